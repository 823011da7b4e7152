//! The joint mode: visiting order and PoIs chosen together, as one generalized TSP
//! (GTSP) over every PoI (clusters: the start, one per target, the end of an open
//! mission) with lazy path costs — solve on planned costs where known and admissible
//! lower bounds elsewhere, plan the legs the tour uses, re-solve until the tour uses
//! planned legs only. With an exact GTSP solver the result is optimal for the planned
//! costs (IDP's argument applied to the whole problem).

use crate::lazy::{lazy_solve, tour_legs as legs, LazyRules};
use crate::oracle::PathOracle;
use smug_core::error::Result;
use smug_core::stages::{Clusters, Selection, Sequencer, TourKind};

/// The joint problem over oracle indices: the start, the PoIs of each target, and the
/// end of an open tour (`None`: back to the start).
pub(super) struct JointProblem {
    /// Oracle index of the start.
    pub(super) start: usize,
    /// Oracle indices of each target's PoIs.
    pub(super) groups: Vec<Vec<usize>>,
    /// Oracle index of the end of an open tour.
    pub(super) end: Option<usize>,
}

/// The best tour the sequencer finds: the visiting order (positions in `groups`) and
/// the chosen PoI of each visited group with the route's planned cost (`INFINITY` when
/// a leg it needs has no path).
pub(super) fn joint_tour(
    sequencer: &dyn Sequencer,
    oracle: &mut PathOracle,
    problem: &JointProblem,
) -> Result<(Vec<usize>, Selection)> {
    let (nodes, clusters) = layout(problem)?;
    let kind = match problem.end {
        Some(_) => TourKind::OpenTo(clusters.len() - 1),
        None => TourKind::Closed,
    };
    // Each round warm-starts from the previous round's tour: the matrices differ only
    // where bounds were replaced by planned costs.
    let tour = lazy_solve(
        oracle,
        &nodes,
        &clusters,
        kind,
        LazyRules {
            warm: true,
            settle: false,
            order_only: false,
        },
        |matrix, warm| match warm {
            Some(warm) => sequencer.solve_clusters_from(matrix, &clusters, kind, warm.tour),
            None => sequencer.solve_clusters(matrix, &clusters, kind),
        },
    )?;
    let visits: Vec<usize> = tour
        .order
        .iter()
        .copied()
        .filter(|&v| (1..=problem.groups.len()).contains(&clusters.of(v)))
        .collect();
    let order = visits.iter().map(|&v| clusters.of(v) - 1).collect();
    let chosen = visits.iter().map(|&v| nodes[v]).collect();
    let mut cost = 0.0;
    for (a, b) in legs(&tour, kind) {
        cost += oracle.cost(nodes[a], nodes[b])?;
    }
    Ok((order, Selection { chosen, cost }))
}

/// The GTSP's nodes (oracle indices) and clusters: start, each group, end.
fn layout(problem: &JointProblem) -> Result<(Vec<usize>, Clusters)> {
    let mut nodes = vec![problem.start];
    let mut members = vec![vec![0]];
    for group in &problem.groups {
        members.push((nodes.len()..nodes.len() + group.len()).collect());
        nodes.extend(group);
    }
    if let Some(end) = problem.end {
        members.push(vec![nodes.len()]);
        nodes.push(end);
    }
    let clusters = Clusters::new(nodes.len(), members)?;
    Ok((nodes, clusters))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::matrix::full_matrix;
    use crate::test_support::{oracle, oracle_with_dead_pair, Exhaustive};
    use proptest::prelude::*;
    use smug_core::pose::Pose2;

    /// A symmetric model whose planner proves no path between the two nearest PoIs of
    /// two targets (a lattice's proof at its resolution): the tour goes round that
    /// leg through another PoI instead of ending without a plan.
    #[test]
    fn a_proved_dead_leg_between_pois_is_routed_round() {
        // Start (0, 0); target A = {1}; target B = {2 (near A), 3 (farther)}.
        let poses =
            [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (2.0, 3.0)].map(|(x, y)| Pose2::new(x, y, 0.0));
        let (mut oracle, nodes) = oracle_with_dead_pair(&poses, vec![1.0; 16], (1, 2));
        let problem = JointProblem {
            start: nodes[0],
            groups: vec![vec![nodes[1]], vec![nodes[2], nodes[3]]],
            end: None,
        };
        let (_, joint) = joint_tour(&Exhaustive, &mut oracle, &problem).unwrap();
        assert_eq!(joint.chosen.len(), 2);
        assert!(joint.chosen.contains(&nodes[3]), "{joint:?}");
        let expected = 1.0 + 10f64.sqrt() + 13f64.sqrt();
        assert!((joint.cost - expected).abs() < 1e-9, "{joint:?}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        /// Joint mode with an exact GTSP solver on a fixed roadmap: never more than the
        /// sequential mode (order from representatives, then the DP selection), and
        /// exactly the best one-PoI-per-target tour over all planned paths.
        #[test]
        fn joint_with_an_exact_solver_never_costs_more_than_sequential_dp(
            points in prop::collection::vec((0.0..20.0f64, 0.0..20.0f64, -3.0..3.0f64), 14),
            detours in prop::collection::vec(1.0..2.0f64, 196),
            sizes in prop::collection::vec(1usize..=3, 2..=4),
            open in any::<bool>(),
        ) {
            let total: usize = sizes.iter().sum::<usize>() + 2;
            let poses: Vec<Pose2> = points[..total].iter().map(|&(x, y, yaw)| Pose2::new(x, y, yaw)).collect();
            let padded: Vec<f64> = (0..total * total).map(|k| detours[(k / total) * 14 + k % total]).collect();
            let (mut seq_oracle, nodes) = oracle(&poses, padded.clone());
            let mut groups = Vec::new();
            let mut next = 1;
            for &size in &sizes {
                groups.push(nodes[next..next + size].to_vec());
                next += size;
            }
            let end = if open { nodes[total - 1] } else { nodes[0] };
            // Sequential: representatives are the first PoIs; DP selection along the order.
            let mut reps = vec![nodes[0]];
            reps.extend(groups.iter().map(|g| g[0]));
            let kind = if open { reps.push(end); TourKind::OpenTo(reps.len() - 1) } else { TourKind::Closed };
            let tour = Exhaustive.solve(&full_matrix(&mut seq_oracle, &reps).unwrap(), kind).unwrap();
            let order: Vec<usize> = tour.order.iter().copied().filter(|&v| v != 0 && v <= groups.len()).map(|v| v - 1).collect();
            let selection = smug_core::stages::SelectionProblem {
                start: nodes[0],
                groups: order.iter().map(|&g| groups[g].clone()).collect(),
                end,
            };
            let (_, sequential) = selection.solve_layers(|i, j| seq_oracle.cost(i, j)).unwrap();
            let (mut joint_oracle, _) = oracle(&poses, padded);
            let problem = JointProblem {
                start: nodes[0],
                groups: groups.clone(),
                end: open.then_some(end),
            };
            let (joint_order, joint) = joint_tour(&Exhaustive, &mut joint_oracle, &problem).unwrap();
            prop_assert!(joint.cost <= sequential + 1e-9, "joint {} vs sequential {sequential}", joint.cost);
            let mut sorted = joint_order.clone();
            sorted.sort_unstable();
            prop_assert_eq!(sorted, (0..groups.len()).collect::<Vec<_>>());
            for (&g, &p) in joint_order.iter().zip(&joint.chosen) {
                prop_assert!(groups[g].contains(&p));
            }
            // The best tour over every planned path: the GTSP on the full matrix.
            let mut all = vec![nodes[0]];
            all.extend(groups.iter().flatten());
            let mut members = vec![vec![0]];
            let mut k = 1;
            for g in &groups {
                members.push((k..k + g.len()).collect());
                k += g.len();
            }
            if open {
                members.push(vec![all.len()]);
                all.push(end);
            }
            let clusters = Clusters::new(all.len(), members).unwrap();
            let kind = if open { TourKind::OpenTo(clusters.len() - 1) } else { TourKind::Closed };
            let best = Exhaustive.solve_clusters(&full_matrix(&mut seq_oracle, &all).unwrap(), &clusters, kind).unwrap();
            prop_assert!((joint.cost - best.cost).abs() < 1e-9, "joint {} vs optimum {}", joint.cost, best.cost);
        }
    }
}
