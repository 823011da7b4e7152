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
        if oracle.answers_layers() {
            return crate::layered::dp_by_layers(oracle, problem, &layers(problem));
        }
        if oracle.answers_many() {
            // Every leg DP needs, one call per pose of a layer.
            for pair in layers(problem).windows(2) {
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

/// The start, the groups in order, and the end: the DP's layers.
pub(crate) fn layers(problem: &SelectionProblem) -> Vec<Vec<usize>> {
    let mut layers = vec![vec![problem.start]];
    layers.extend(problem.groups.iter().cloned());
    layers.push(vec![problem.end]);
    layers
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
    use crate::test_support::{detour_oracle, radius_oracle_by, selection_error, straight_oracle};
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

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

        /// Asked layer by layer (one call per layer, each PoI at its DP value), the DP
        /// chooses a route as cheap as the DP over every pair, or names the same
        /// unreachable group (legs longer than 10 m have no path).
        #[test]
        fn layer_by_layer_equals_every_pair(
            points in proptest::collection::vec((0.0f64..24.0, 0.0f64..24.0), 7..16),
            sizes in proptest::collection::vec(1usize..4, 2..5),
        ) {
            let groups = groups_of(&sizes, points.len() - 1);
            let problem = SelectionProblem { start: 0, groups, end: 0 };
            let mut pairs = radius_oracle_by(false, &points);
            let mut layers = radius_oracle_by(true, &points);
            let by_pairs = DpSelector::default().select(&mut pairs, &problem);
            let by_layers = DpSelector::default().select(&mut layers, &problem);
            match (by_pairs, by_layers) {
                (Ok(a), Ok(b)) => {
                    proptest::prop_assert!((a.cost - b.cost).abs() <= 1e-9 * a.cost.max(1.0));
                    let cost = problem.route_cost(&b.chosen, |i, j| layers.cost(i, j)).unwrap();
                    proptest::prop_assert!((cost - b.cost).abs() <= 1e-9 * cost.max(1.0));
                }
                (Err(a), Err(b)) => {
                    proptest::prop_assert_eq!(selection_error(&a), selection_error(&b));
                }
                (a, b) => proptest::prop_assert!(false, "{a:?} by pairs, {b:?} by layers"),
            }
        }
    }

    /// Groups of the given sizes over poses `1..=poses` (wrapping round).
    fn groups_of(sizes: &[usize], poses: usize) -> Vec<Vec<usize>> {
        let mut next = 0;
        sizes
            .iter()
            .map(|&n| {
                (0..n)
                    .map(|_| {
                        next += 1;
                        (next - 1) % poses + 1
                    })
                    .collect()
            })
            .collect()
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
