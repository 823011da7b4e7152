//! `brute-force`: tries every combination of PoIs. Exponential; for tests and tiny missions.

use serde::{Deserialize, Serialize};
use smug_core::{Error, PathCosts, PoiSelector, Result, Selection, SelectionProblem};

/// Parameters of the brute-force selector.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BruteForceParams {
    /// Refuse problems with more combinations than this.
    pub max_combinations: u64,
}

impl Default for BruteForceParams {
    fn default() -> Self {
        Self {
            max_combinations: 1_000_000,
        }
    }
}

/// Enumerates every PoI combination and keeps the cheapest (first in lexicographic
/// order among equals).
#[derive(Clone, Copy, Debug, Default)]
pub struct BruteForceSelector {
    params: BruteForceParams,
}

impl BruteForceSelector {
    /// A selector with `params`.
    pub fn new(params: BruteForceParams) -> Self {
        Self { params }
    }

    fn combination_count(&self, problem: &SelectionProblem) -> Result<u64> {
        let count = problem
            .groups
            .iter()
            .try_fold(1u64, |acc, g| acc.checked_mul(g.len() as u64))
            .unwrap_or(u64::MAX);
        if let Some(g) = problem.groups.iter().position(Vec::is_empty) {
            return Err(Error::InvalidInput(format!(
                "target {g} of the sequence has no PoI"
            )));
        }
        if count > self.params.max_combinations {
            return Err(Error::invalid_param(
                "selector",
                format!(
                    "brute force would try {count} combinations (max_combinations = {})",
                    self.params.max_combinations
                ),
            ));
        }
        Ok(count)
    }
}

/// Advances `digits` like an odometer with per-position bases `sizes`; false when done.
fn next_combination(digits: &mut [usize], sizes: &[usize]) -> bool {
    for (d, &size) in digits.iter_mut().zip(sizes).rev() {
        *d += 1;
        if *d < size {
            return true;
        }
        *d = 0;
    }
    false
}

impl PoiSelector for BruteForceSelector {
    fn select(&self, oracle: &mut dyn PathCosts, problem: &SelectionProblem) -> Result<Selection> {
        self.combination_count(problem)?;
        let sizes: Vec<usize> = problem.groups.iter().map(Vec::len).collect();
        let mut digits = vec![0usize; sizes.len()];
        let mut best: Option<Selection> = None;
        loop {
            let chosen: Vec<usize> = digits
                .iter()
                .zip(&problem.groups)
                .map(|(&d, g)| g[d])
                .collect();
            let cost = problem.route_cost(&chosen, |i, j| oracle.cost(i, j))?;
            if best.as_ref().is_none_or(|b| cost < b.cost) {
                best = Some(Selection { chosen, cost });
            }
            if !next_combination(&mut digits, &sizes) {
                break;
            }
        }
        Ok(best.expect("at least one combination exists"))
    }
}

smug_core::register_plugin!(
    smug_core::registry::SelectorStage,
    name = "brute-force",
    summary = "every PoI combination (exponential; reference for tests)",
    params = BruteForceParams,
    build = |params, _ctx| Ok(Box::new(BruteForceSelector::new(params))),
);

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::{Path, PathLength, PlannerOutcome, PlannerStats, PointToPointPlanner, Pose2};
    use std::sync::Arc;

    /// Straight lines, except that nothing reaches x = 9.
    struct StraightLine;

    impl PointToPointPlanner for StraightLine {
        fn plan(&mut self, a: &Pose2, b: &Pose2) -> Result<PlannerOutcome> {
            if a.x == 9.0 || b.x == 9.0 {
                return Ok(PlannerOutcome::NoPath(smug_core::NoPathReason::Proved(
                    smug_core::Proof::Disconnected,
                )));
            }
            Ok(PlannerOutcome::Exact(Path::new(
                vec![*a, *b],
                &PathLength::default(),
            )))
        }

        fn stats(&self) -> PlannerStats {
            PlannerStats::default()
        }
    }

    fn oracle(poses: &[(f64, f64)]) -> smug_mission::PathOracle {
        let mut o = smug_mission::PathOracle::new(
            Arc::new(PathLength::new(1.0, 0.0).unwrap()),
            Box::new(StraightLine),
        );
        for &(x, y) in poses {
            o.add_pose(Pose2::new(x, y, 0.0));
        }
        o
    }

    #[test]
    fn picks_the_cheapest_combination() {
        // start 0 at origin; group A = {1: (5, 5), 2: (1, 1)}; group B = {3: (2, 0), 4: (9, 0)}.
        let mut o = oracle(&[(0.0, 0.0), (5.0, 5.0), (1.0, 1.0), (2.0, 0.0), (9.0, 0.0)]);
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 2], vec![3, 4]],
            end: 0,
        };
        let s = BruteForceSelector::default()
            .select(&mut o, &problem)
            .unwrap();
        assert_eq!(s.chosen, vec![2, 3]);
        let expected = 2f64.sqrt() + 2f64.sqrt() + 2.0;
        assert!((s.cost - expected).abs() < 1e-12);
    }

    #[test]
    fn unreachable_everywhere_costs_infinity_and_big_problems_are_refused() {
        let mut o = oracle(&[(0.0, 0.0), (9.0, 0.0)]);
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1]],
            end: 0,
        };
        assert_eq!(
            BruteForceSelector::default()
                .select(&mut o, &problem)
                .unwrap()
                .cost,
            f64::INFINITY
        );
        let small = BruteForceSelector::new(BruteForceParams {
            max_combinations: 3,
        });
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 0], vec![1, 0]],
            end: 0,
        };
        assert!(small.select(&mut o, &problem).is_err());
    }

    #[test]
    fn odometer_enumerates_all() {
        let sizes = [2, 3];
        let mut digits = vec![0, 0];
        let mut n = 1;
        while next_combination(&mut digits, &sizes) {
            n += 1;
        }
        assert_eq!(n, 6);
    }
}
