//! Test fixtures the mission modes' tests share: a planner with fixed detours, an
//! exhaustive sequencer and an oracle over given poses.

use crate::oracle::PathOracle;
use smug_core::error::Result;
use smug_core::objective::PathLength;
use smug_core::path::Path;
use smug_core::pose::Pose2;
use smug_core::stages::{
    Clusters, CostMatrix, PlannerOutcome, PlannerStats, PointToPointPlanner, Sequencer, Tour,
    TourKind,
};
use smug_core::{NoPathReason, Proof};
use std::sync::Arc;

/// Answers every query with a straight path whose cost is the objective's cost
/// times a fixed detour factor of the pair (≥ 1, symmetric).
struct DetourPlanner {
    poses: Vec<Pose2>,
    detours: Vec<f64>,
    objective: PathLength,
    /// Directed legs (indices of `poses`) without a path.
    dead: Vec<(usize, usize)>,
}

impl DetourPlanner {
    fn index(&self, pose: &Pose2) -> usize {
        self.poses.iter().position(|p| p == pose).unwrap()
    }
}

impl PointToPointPlanner for DetourPlanner {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        let (i, j) = (self.index(start), self.index(goal));
        if self.dead.contains(&(i, j)) {
            return Ok(PlannerOutcome::NoPath(NoPathReason::Proved(
                Proof::Exhausted,
            )));
        }
        let n = self.poses.len();
        let factor = self.detours[i.min(j) * n + i.max(j)];
        let mut path = Path::new(vec![*start, *goal], &self.objective);
        path.cost *= factor;
        Ok(PlannerOutcome::Exact(path))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

/// The best tour by trying every order (small n only).
pub(crate) struct Exhaustive;

impl Sequencer for Exhaustive {
    fn solve(&self, costs: &CostMatrix, kind: TourKind) -> Result<Tour> {
        let n = costs.len();
        let mut rest: Vec<usize> = (1..n).collect();
        let mut best = Tour {
            order: vec![],
            cost: f64::INFINITY,
        };
        permute(&mut rest, 0, &mut |p| {
            let order: Vec<usize> = std::iter::once(0).chain(p.iter().copied()).collect();
            let cost = costs.tour_cost(&order, kind);
            if cost < best.cost {
                best = Tour { order, cost };
            }
        });
        Ok(best)
    }

    fn solve_clusters(
        &self,
        costs: &CostMatrix,
        clusters: &Clusters,
        kind: TourKind,
    ) -> Result<Tour> {
        let m = clusters.len();
        let end = match kind {
            TourKind::OpenTo(c) => Some(c),
            TourKind::Closed => None,
        };
        let mut middle: Vec<usize> = (1..m).filter(|&c| Some(c) != end).collect();
        let mut best = Tour {
            order: vec![],
            cost: f64::INFINITY,
        };
        permute(&mut middle, 0, &mut |p| {
            let order: Vec<usize> = std::iter::once(0)
                .chain(p.iter().copied())
                .chain(end)
                .collect();
            let mut choices = vec![Vec::new()];
            for &c in &order {
                choices = choices
                    .iter()
                    .flat_map(|prefix: &Vec<usize>| {
                        clusters.members(c).iter().map(move |&v| {
                            let mut next = prefix.clone();
                            next.push(v);
                            next
                        })
                    })
                    .collect();
            }
            for nodes in choices {
                let cost = costs.tour_cost(&nodes, kind);
                if cost < best.cost {
                    best = Tour { order: nodes, cost };
                }
            }
        });
        Ok(best)
    }
}

fn permute(items: &mut [usize], k: usize, visit: &mut impl FnMut(&[usize])) {
    if k == items.len() {
        return visit(items);
    }
    for i in k..items.len() {
        items.swap(k, i);
        permute(items, k + 1, visit);
        items.swap(k, i);
    }
}

pub(crate) fn oracle(poses: &[Pose2], detours: Vec<f64>) -> (PathOracle, Vec<usize>) {
    oracle_with_dead_leg(poses, detours, None)
}

/// [`oracle`] whose planner finds no path for the directed leg `dead` (indices of
/// `poses`), a directed oracle when there is one.
pub(crate) fn oracle_with_dead_leg(
    poses: &[Pose2],
    detours: Vec<f64>,
    dead: Option<(usize, usize)>,
) -> (PathOracle, Vec<usize>) {
    oracle_without(poses, detours, dead.into_iter().collect(), dead.is_none())
}

/// [`oracle`], symmetric, whose planner proves that no path joins the poses `pair`
/// (indices of `poses`), either way: what a lattice may prove at its resolution
/// between two PoIs that other routes reach.
pub(crate) fn oracle_with_dead_pair(
    poses: &[Pose2],
    detours: Vec<f64>,
    (i, j): (usize, usize),
) -> (PathOracle, Vec<usize>) {
    oracle_without(poses, detours, vec![(i, j), (j, i)], true)
}

fn oracle_without(
    poses: &[Pose2],
    detours: Vec<f64>,
    dead: Vec<(usize, usize)>,
    symmetric: bool,
) -> (PathOracle, Vec<usize>) {
    let objective = PathLength::default();
    let planner = DetourPlanner {
        poses: poses.to_vec(),
        detours,
        objective: objective.clone(),
        dead,
    };
    let mut oracle =
        PathOracle::new(Arc::new(objective), Box::new(planner)).with_symmetry(symmetric);
    let nodes = poses.iter().map(|p| oracle.add_pose(*p)).collect();
    (oracle, nodes)
}
