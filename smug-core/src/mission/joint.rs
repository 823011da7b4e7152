//! The joint mode: visiting order and PoIs chosen together, as one generalized TSP
//! (GTSP) over every PoI (clusters: the start, one per target, the end of an open
//! mission) with lazy path costs — solve on planned costs where known and admissible
//! lower bounds elsewhere, plan the legs the tour uses, re-solve until the tour uses
//! planned legs only. With an exact GTSP solver the result is optimal for the planned
//! costs (IDP's argument applied to the whole problem).

use super::sequential::{lazy_solve, tour_legs as legs};
use crate::error::Result;
use crate::oracle::PathOracle;
use crate::stages::{Clusters, Selection, Sequencer, TourKind};

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
        kind,
        true,
        |matrix, previous| match previous {
            Some(previous) => sequencer.solve_clusters_from(matrix, &clusters, kind, previous),
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
