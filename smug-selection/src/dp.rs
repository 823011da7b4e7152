//! `dp`: plans every leg between PoIs of consecutive targets, then dynamic programming.

use crate::error::{check_groups, unreachable_error};
use serde::{Deserialize, Serialize};
use smug_core::{PathCosts, PoiSelector, Result, Selection, SelectionProblem};

/// Parameters of the DP selector (none).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DpParams {}

/// Plans every path between PoIs of consecutive groups (`M²(N−1) + 2M` paths for N
/// groups of M PoIs), then solves the layered DP: globally optimal for those paths.
#[derive(Clone, Copy, Debug, Default)]
pub struct DpSelector {
    _params: DpParams,
}

impl DpSelector {
    /// A selector with `params`.
    pub fn new(params: DpParams) -> Self {
        Self { _params: params }
    }
}

impl PoiSelector for DpSelector {
    fn select(&self, oracle: &mut dyn PathCosts, problem: &SelectionProblem) -> Result<Selection> {
        check_groups(problem)?;
        if oracle.answers_many() {
            // Every leg DP needs, one call per pose of a layer.
            let mut layers = vec![vec![problem.start]];
            layers.extend(problem.groups.iter().cloned());
            layers.push(vec![problem.end]);
            for pair in layers.windows(2) {
                let rows: Vec<(usize, Vec<usize>)> =
                    pair[0].iter().map(|&p| (p, pair[1].clone())).collect();
                oracle.plan_rows(&rows)?;
            }
        }
        let (chosen, cost) = problem.solve_layers(|i, j| oracle.cost(i, j))?;
        if !cost.is_finite() {
            return Err(unreachable_error(oracle, problem));
        }
        let cost = problem.route_cost(&chosen, |i, j| oracle.cost(i, j))?;
        Ok(Selection { chosen, cost })
    }
}

smug_core::register_plugin!(
    smug_core::registry::SelectorStage,
    name = "dp",
    summary = "dynamic programming over every path between consecutive targets' PoIs (optimal)",
    params = DpParams,
    build = |params, _ctx| Ok(Box::new(DpSelector::new(params))),
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{detour_oracle, selection_error, straight_oracle};
    use crate::SelectionError;

    #[test]
    fn picks_the_optimum_and_plans_every_consecutive_pair() {
        // start 0 at origin; group A = {1: (5, 5), 2: (1, 1)}; group B = {3: (2, 0), 4: (4, 4)}.
        let mut o = straight_oracle(&[(0.0, 0.0), (5.0, 5.0), (1.0, 1.0), (2.0, 0.0), (4.0, 4.0)]);
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 2], vec![3, 4]],
            end: 0,
        };
        let s = DpSelector::default().select(&mut o, &problem).unwrap();
        assert_eq!(s.chosen, vec![2, 3]);
        let expected = 2f64.sqrt() + 2f64.sqrt() + 2.0;
        assert!((s.cost - expected).abs() < 1e-12);
        // M²(N−1) + 2M = 4 + 4 = 8.
        assert_eq!(o.stats().paths_planned, 8);
    }

    #[test]
    fn true_costs_decide_not_straight_lines() {
        // (7, 0) is close in a straight line but every path to it detours.
        let mut o = detour_oracle(&[(0.0, 0.0), (7.0, 0.0), (0.0, 8.0)]);
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 2]],
            end: 0,
        };
        let s = DpSelector::default().select(&mut o, &problem).unwrap();
        assert_eq!(s.chosen, vec![2]);
        assert!((s.cost - 16.0).abs() < 1e-12);
    }

    #[test]
    fn reports_the_unreachable_group() {
        // Nothing reaches x = 9: group 1 = {(9, 0), (9, 1)}.
        let mut o = straight_oracle(&[(0.0, 0.0), (1.0, 0.0), (9.0, 0.0), (9.0, 1.0), (2.0, 2.0)]);
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1], vec![2, 3], vec![4]],
            end: 0,
        };
        let err = DpSelector::default().select(&mut o, &problem).unwrap_err();
        assert_eq!(
            selection_error(&err),
            Some(SelectionError::Unreachable { group: 1 })
        );
    }
}
