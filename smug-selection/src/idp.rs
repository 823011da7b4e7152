//! `idp`: Iterative DP — DP over lower bounds, planning only the legs it chooses.

use crate::error::{check_groups, unreachable_error};
use serde::{Deserialize, Serialize};
use smug_core::{PathCosts, PoiSelector, Result, Selection, SelectionProblem};
use std::collections::HashSet;

/// Parameters of the iterative DP selector (none).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IdpParams {}

/// Iterative DP: leg costs are the planned cost when planned, else the straight-line
/// lower bound; repeat the DP and plan the chosen route's unplanned legs until the DP
/// chooses a route whose legs are all planned. That route is optimal for the paths the
/// oracle gives (lower bounds never exceed true costs), so on a shared, fixed roadmap IDP
/// returns DP's cost while planning far fewer paths.
#[derive(Clone, Copy, Debug, Default)]
pub struct IdpSelector {
    _params: IdpParams,
}

impl IdpSelector {
    /// A selector with `params`.
    pub fn new(params: IdpParams) -> Self {
        Self { _params: params }
    }
}

impl PoiSelector for IdpSelector {
    fn select(&self, oracle: &mut dyn PathCosts, problem: &SelectionProblem) -> Result<Selection> {
        check_groups(problem)?;
        idp(oracle, problem)
    }
}

/// Runs iterative DP (groups must be non-empty). Terminates: every iteration but the
/// last plans at least one new leg between consecutive layers, and there are finitely many.
pub(crate) fn idp(oracle: &mut dyn PathCosts, problem: &SelectionProblem) -> Result<Selection> {
    let mut best: Option<Selection> = None;
    let mut searched = HashSet::new();
    loop {
        let (chosen, _) = problem.solve_layers(|i, j| Ok(oracle.cost_or_bound(i, j)))?;
        let unplanned = legs_to_plan(oracle, problem, &chosen, &mut searched);
        let planned_new = !unplanned.is_empty();
        oracle.plan_pairs(&unplanned)?;
        // Every leg is planned now: this is the route's true cost.
        let cost = problem.route_cost(&chosen, |i, j| oracle.cost(i, j))?;
        // `<=`: among equals keep the latest, the DP's final (provably optimal) choice.
        if best.as_ref().is_none_or(|b| cost <= b.cost) {
            best = Some(Selection { chosen, cost });
        }
        if !planned_new {
            break;
        }
    }
    match best {
        Some(s) if s.cost.is_finite() => Ok(s),
        _ => Err(unreachable_error(oracle, problem)),
    }
}

/// The legs of the route through `chosen` not planned yet. A leg from a pose already
/// searched from towards the same layer (in `searched`: leg position and pose) asks,
/// when the oracle answers many goals with one search, for every PoI of that layer
/// from the pose: a pose IDP comes back to once tends to come back again (on lunar
/// with the rover, 55 of 77 poses searched from were searched from 3–7 times, each
/// time for one or two PoIs of the same target).
fn legs_to_plan(
    oracle: &dyn PathCosts,
    problem: &SelectionProblem,
    chosen: &[usize],
    searched: &mut HashSet<(usize, usize)>,
) -> Vec<(usize, usize)> {
    let mut legs = Vec::new();
    for (w, leg) in problem.route(chosen).windows(2).enumerate() {
        let (from, to) = (leg[0], leg[1]);
        if oracle.is_planned(from, to) {
            continue;
        }
        let again = !searched.insert((w, from));
        match problem.groups.get(w) {
            Some(layer) if again && oracle.answers_many() => legs.extend(
                layer
                    .iter()
                    .filter(|&&j| !oracle.is_planned(from, j))
                    .map(|&j| (from, j)),
            ),
            _ => legs.push((from, to)),
        }
    }
    legs
}

smug_core::register_plugin!(
    smug_core::registry::SelectorStage,
    name = "idp",
    summary = "iterative DP over lower bounds, planning only the chosen legs (optimal, lazy)",
    params = IdpParams,
    build = |params, _ctx| Ok(Box::new(IdpSelector::new(params))),
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{detour_oracle, selection_error, straight_oracle};
    use crate::{DpSelector, SelectionError};

    #[test]
    fn matches_dp_with_fewer_plans() {
        let poses = [
            (0.0, 0.0),
            (5.0, 5.0),
            (1.0, 1.0),
            (7.0, 0.5),
            (2.0, 0.0),
            (4.0, 4.0),
            (3.0, -1.0),
            (0.0, 8.0),
            (-2.0, 1.0),
        ];
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 2, 3], vec![4, 5, 6], vec![7, 8]],
            end: 0,
        };
        let mut o_dp = detour_oracle(&poses);
        let mut o_idp = detour_oracle(&poses);
        let dp = DpSelector::default().select(&mut o_dp, &problem).unwrap();
        let idp = IdpSelector::default().select(&mut o_idp, &problem).unwrap();
        assert!((dp.cost - idp.cost).abs() < 1e-9, "{dp:?} vs {idp:?}");
        assert_eq!(o_dp.stats().paths_planned, 3 + 9 + 6 + 2);
        assert!(o_idp.stats().paths_planned < o_dp.stats().paths_planned);
    }

    /// Costs from a table (bounds a tenth of them), planned in calls that are logged.
    struct Logged {
        costs: Vec<Vec<f64>>,
        planned: std::collections::HashSet<(usize, usize)>,
        calls: Vec<Vec<(usize, usize)>>,
    }

    impl PathCosts for Logged {
        fn cost(&mut self, i: usize, j: usize) -> Result<f64> {
            self.plan_pairs(&[(i, j)])?;
            Ok(self.costs[i][j])
        }
        fn lower_bound(&self, i: usize, j: usize) -> f64 {
            0.1 * self.costs[i][j]
        }
        fn is_planned(&self, i: usize, j: usize) -> bool {
            self.planned.contains(&(i, j))
        }
        fn planned_cost(&self, i: usize, j: usize) -> Option<f64> {
            self.is_planned(i, j).then(|| self.costs[i][j])
        }
        fn answers_many(&self) -> bool {
            true
        }
        fn plan_rows(&mut self, rows: &[(usize, Vec<usize>)]) -> Result<()> {
            let pairs: Vec<(usize, usize)> = rows
                .iter()
                .flat_map(|(i, js)| js.iter().map(move |&j| (*i, j)))
                .collect();
            self.plan_pairs(&pairs)
        }
        fn plan_pairs(&mut self, pairs: &[(usize, usize)]) -> Result<()> {
            let new: Vec<(usize, usize)> = pairs
                .iter()
                .copied()
                .filter(|p| !self.planned.contains(p))
                .collect();
            if !new.is_empty() {
                self.planned.extend(new.iter().copied());
                self.calls.push(new);
            }
            Ok(())
        }
    }

    #[test]
    fn a_pose_searched_from_again_towards_a_layer_asks_for_the_whole_layer() {
        // Start 0, one layer {1, 2, 3}, end 0; bounds favour 1 then 2, but both are
        // dear, so IDP comes back to the start for the layer three times.
        let mut costs = vec![vec![1.0; 4]; 4];
        costs[0][1] = 10.0;
        costs[0][2] = 9.0;
        costs[0][3] = 8.0;
        let mut oracle = Logged {
            costs,
            planned: Default::default(),
            calls: Vec::new(),
        };
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 2, 3]],
            end: 0,
        };
        let s = IdpSelector::default()
            .select(&mut oracle, &problem)
            .unwrap();
        assert_eq!(s.chosen, vec![3]);
        let from_start: Vec<Vec<usize>> = oracle
            .calls
            .iter()
            .map(|c| c.iter().filter(|p| p.0 == 0).map(|p| p.1).collect())
            .filter(|js: &Vec<usize>| !js.is_empty())
            .collect();
        // First the chosen PoI alone, then (asked again) every PoI of the layer left.
        assert_eq!(from_start.len(), 2, "{:?}", oracle.calls);
        assert_eq!(from_start[0].len(), 1);
        assert_eq!(from_start[0].len() + from_start[1].len(), 3);
    }

    #[test]
    fn avoids_detours_and_reports_unreachable_groups() {
        let mut o = detour_oracle(&[(0.0, 0.0), (7.0, 0.0), (0.0, 8.0)]);
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 2]],
            end: 0,
        };
        let s = IdpSelector::default().select(&mut o, &problem).unwrap();
        assert_eq!(s.chosen, vec![2]);

        // Group 0 = {(9, 0)} is unreachable from the start.
        let mut o = straight_oracle(&[(0.0, 0.0), (9.0, 0.0), (1.0, 1.0)]);
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1], vec![2]],
            end: 0,
        };
        let err = IdpSelector::default().select(&mut o, &problem).unwrap_err();
        assert_eq!(
            selection_error(&err),
            Some(SelectionError::Unreachable { group: 0 })
        );
    }

    #[test]
    fn open_routes_with_an_unreachable_end() {
        let mut o = straight_oracle(&[(0.0, 0.0), (1.0, 0.0), (9.0, 5.0)]);
        let with_group = SelectionProblem {
            start: 0,
            groups: vec![vec![1]],
            end: 2,
        };
        let err = IdpSelector::default()
            .select(&mut o, &with_group)
            .unwrap_err();
        assert_eq!(
            selection_error(&err),
            Some(SelectionError::Unreachable { group: 0 })
        );
        let direct = SelectionProblem {
            start: 0,
            groups: vec![],
            end: 2,
        };
        let err = IdpSelector::default().select(&mut o, &direct).unwrap_err();
        assert_eq!(selection_error(&err), Some(SelectionError::EndUnreachable));
        let empty_group = SelectionProblem {
            start: 0,
            groups: vec![vec![1], vec![]],
            end: 0,
        };
        assert!(matches!(
            IdpSelector::default().select(&mut o, &empty_group),
            Err(smug_core::Error::InvalidInput(_))
        ));
    }
}
