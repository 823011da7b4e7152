//! `irba`: iterative rubber band — local sweeps over the groups (docs/algorithms.md).

use crate::error::check_groups;
use crate::idp::idp;
use serde::{Deserialize, Serialize};
use smug_core::{Error, PathCosts, PoiSelector, Result, Selection, SelectionProblem};

/// Parameters of the iterative rubber band selector.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IrbaParams {
    /// Stop after this many sweeps over the groups even if the route still changes (≥ 1).
    pub max_sweeps: usize,
}

impl Default for IrbaParams {
    fn default() -> Self {
        Self { max_sweeps: 100 }
    }
}

/// Iterative rubber band (after Gao et al. 2021 / Pan et al. 2010): start from the PoIs
/// nearest (straight line) to their neighbours, then sweep the groups in order, the last
/// one included, moving each to the PoI minimising the planned cost `c(prev, p) + c(p,
/// next)`, until a sweep changes nothing. Each local choice plans lazily: candidates are
/// ranked by planned cost where planned, else by lower bound, and the best one's legs are
/// planned until the best is fully planned. No optimality guarantee. If the band ends on
/// an infinite route, falls back to iterative DP, which finds a finite route or reports
/// the unreachable group.
#[derive(Clone, Copy, Debug, Default)]
pub struct IrbaSelector {
    params: IrbaParams,
}

impl IrbaSelector {
    /// A selector with `params`.
    pub fn new(params: IrbaParams) -> Self {
        Self { params }
    }
}

/// The initial band: group by group, the PoI minimising the straight-line cost from the
/// previous choice (the start for group 0) plus the mean straight-line cost to the next
/// group's PoIs (the end for the last group). First among equals.
pub(crate) fn initial_band(oracle: &dyn PathCosts, problem: &SelectionProblem) -> Vec<usize> {
    let mut chosen = Vec::with_capacity(problem.groups.len());
    let mut prev = problem.start;
    for (g, group) in problem.groups.iter().enumerate() {
        let next: &[usize] = problem
            .groups
            .get(g + 1)
            .map_or(std::slice::from_ref(&problem.end), Vec::as_slice);
        let score = |p: usize| {
            let to_next: f64 = next.iter().map(|&q| oracle.lower_bound(p, q)).sum();
            oracle.lower_bound(prev, p) + to_next / next.len() as f64
        };
        let mut best = (group[0], score(group[0]));
        for &p in &group[1..] {
            let s = score(p);
            if s < best.1 {
                best = (p, s);
            }
        }
        chosen.push(best.0);
        prev = best.0;
    }
    chosen
}

/// The PoI of `group` minimising the true cost `c(prev, p) + c(p, next)`, planning lazily,
/// and that cost. Prefers `current` among equals (so sweeps terminate), then the first.
fn best_between(
    oracle: &mut dyn PathCosts,
    prev: usize,
    group: &[usize],
    next: usize,
    current: usize,
) -> Result<(usize, f64)> {
    loop {
        let mut best = (current, estimate(oracle, prev, current, next));
        for &p in group {
            let e = estimate(oracle, prev, p, next);
            if e < best.1 {
                best = (p, e);
            }
        }
        let p = best.0;
        if oracle.is_planned(prev, p) && oracle.is_planned(p, next) {
            return Ok(best);
        }
        // Plans at least one new leg: the loop ends after at most 2·|group| rounds.
        oracle.cost(prev, p)?;
        oracle.cost(p, next)?;
    }
}

/// `c(prev, p) + c(p, next)` with planned costs where planned, else lower bounds.
fn estimate(oracle: &dyn PathCosts, prev: usize, p: usize, next: usize) -> f64 {
    oracle.cost_or_bound(prev, p) + oracle.cost_or_bound(p, next)
}

impl PoiSelector for IrbaSelector {
    fn select(&self, oracle: &mut dyn PathCosts, problem: &SelectionProblem) -> Result<Selection> {
        check_groups(problem)?;
        if self.params.max_sweeps == 0 {
            return Err(Error::invalid_param(
                "selector",
                "irba: max_sweeps must be ≥ 1",
            ));
        }
        let mut chosen = initial_band(oracle, problem);
        let n = chosen.len();
        for _ in 0..self.params.max_sweeps {
            let mut changed = false;
            for g in 0..n {
                let prev = if g == 0 { problem.start } else { chosen[g - 1] };
                let next = if g + 1 == n {
                    problem.end
                } else {
                    chosen[g + 1]
                };
                let (p, _) = best_between(oracle, prev, &problem.groups[g], next, chosen[g])?;
                if p != chosen[g] {
                    chosen[g] = p;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        // Plans any leg left unplanned when the sweep cap is hit.
        let cost = problem.route_cost(&chosen, |i, j| oracle.cost(i, j))?;
        if cost.is_finite() {
            Ok(Selection { chosen, cost })
        } else {
            idp(oracle, problem)
        }
    }
}

smug_core::register_plugin!(
    smug_core::registry::SelectorStage,
    name = "irba",
    summary = "iterative rubber band: local sweeps over the targets (fast, not optimal)",
    params = IrbaParams,
    build = |params, _ctx| {
        if params.max_sweeps == 0 {
            return Err(Error::invalid_param(
                "selector",
                "irba: max_sweeps must be ≥ 1",
            ));
        }
        Ok(Box::new(IrbaSelector::new(params)))
    },
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{detour_oracle, radius_oracle, selection_error, straight_oracle};
    use crate::{DpSelector, SelectionError};

    #[test]
    fn updates_the_last_group() {
        // Group 1's straight-line favourite (7, 0) costs a detour through y = 50.
        let poses = [(0.0, 0.0), (5.0, 0.0), (7.0, 0.0), (5.0, 4.0)];
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1], vec![2, 3]],
            end: 0,
        };
        let mut o = detour_oracle(&poses);
        assert_eq!(initial_band(&o, &problem), vec![1, 2]);
        let s = IrbaSelector::default().select(&mut o, &problem).unwrap();
        assert_eq!(s.chosen, vec![1, 3]);
        let expected = 5.0 + 4.0 + 41f64.sqrt();
        assert!((s.cost - expected).abs() < 1e-12);
        let dp = DpSelector::default()
            .select(&mut detour_oracle(&poses), &problem)
            .unwrap();
        assert_eq!(dp.chosen, s.chosen);
    }

    #[test]
    fn leaves_a_dead_end_or_reports_the_unreachable_group() {
        // Group 1's straight-line favourite (9, 0) is unreachable: the band moves on to
        // (0, -20).
        let mut o = straight_oracle(&[(0.0, 0.0), (1.0, 0.0), (9.0, 0.0), (0.0, -20.0)]);
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1], vec![2, 3]],
            end: 0,
        };
        assert_eq!(initial_band(&o, &problem), vec![1, 2]);
        let s = IrbaSelector::default().select(&mut o, &problem).unwrap();
        assert_eq!(s.chosen, vec![1, 3]);

        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1], vec![2]],
            end: 0,
        };
        let err = IrbaSelector::default()
            .select(&mut o, &problem)
            .unwrap_err();
        assert_eq!(
            selection_error(&err),
            Some(SelectionError::Unreachable { group: 1 })
        );
        let zero = IrbaSelector::new(IrbaParams { max_sweeps: 0 });
        assert!(zero.select(&mut o, &problem).is_err());
    }

    #[test]
    fn a_stuck_band_falls_back_to_iterative_dp() {
        // Paths are at most 10 m long. The band starts at A, C; neither A → D nor B → C
        // exists, so no single move leaves the infinite route; only S → B → D → E works.
        let poses = [
            (0.0, 0.0),    // S
            (5.0, 2.0),    // A
            (-5.0, -8.0),  // B
            (-4.0, 9.0),   // C
            (-14.0, -9.0), // D
            (-8.0, -4.0),  // E
        ];
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 2], vec![3, 4]],
            end: 5,
        };
        let mut o = radius_oracle(&poses);
        assert_eq!(initial_band(&o, &problem), vec![1, 3]);
        let s = IrbaSelector::default().select(&mut o, &problem).unwrap();
        assert_eq!(s.chosen, vec![2, 4]);
        assert!(s.cost.is_finite());
    }
}
