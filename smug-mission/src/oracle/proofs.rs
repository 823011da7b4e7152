//! The planner's proofs that no path exists, asked by oracle index: the mission's
//! probes of its start and end poses and of its PoIs (nothing is cached).

use super::PathOracle;
use smug_core::error::Result;
use smug_core::pose::Pose2;
use smug_core::stages::NoPathReason;

impl PathOracle {
    /// Whether the planner proves dead ends cheaply ([`PointToPointPlanner::proves_dead_ends`](smug_core::stages::PointToPointPlanner::proves_dead_ends)).
    pub fn proves_dead_ends(&self) -> bool {
        self.planner.proves_dead_ends()
    }

    /// Asks the planner to prove, within `effort`, that no path leads from pose `i` to
    /// pose `j` ([`PointToPointPlanner::prove_unreachable`](smug_core::stages::PointToPointPlanner::prove_unreachable)); nothing is cached.
    pub fn prove_unreachable(
        &mut self,
        i: usize,
        j: usize,
        effort: u64,
    ) -> Result<Option<NoPathReason>> {
        let (a, b) = (self.poses[i], self.poses[j]);
        self.planner.prove_unreachable(&a, &b, effort)
    }

    /// [`prove_unreachable`](Self::prove_unreachable) for each pair `(i, j)` of
    /// `pairs`, side by side where the planner can
    /// ([`PointToPointPlanner::prove_each_unreachable`](smug_core::stages::PointToPointPlanner::prove_each_unreachable)); nothing is cached.
    pub fn prove_each_unreachable(
        &mut self,
        pairs: &[(usize, usize)],
        effort: u64,
    ) -> Result<Vec<Option<NoPathReason>>> {
        let poses: Vec<(Pose2, Pose2)> = pairs
            .iter()
            .map(|&(i, j)| (self.poses[i], self.poses[j]))
            .collect();
        self.planner.prove_each_unreachable(&poses, effort)
    }

    /// Asks the planner to prove, within `effort`, for each pose of `js` that no path
    /// leads from pose `i` to it, with one search
    /// ([`PointToPointPlanner::prove_unreachable_from`](smug_core::stages::PointToPointPlanner::prove_unreachable_from)); nothing is cached.
    pub fn prove_unreachable_from(
        &mut self,
        i: usize,
        js: &[usize],
        effort: u64,
    ) -> Result<Vec<Option<NoPathReason>>> {
        let goals: Vec<Pose2> = js.iter().map(|&j| self.poses[j]).collect();
        let start = self.poses[i];
        self.planner.prove_unreachable_from(&start, &goals, effort)
    }

    /// Asks the planner to prove, within `effort`, for each pose of `is` that no path
    /// leads from it to pose `j`, with one backward search
    /// ([`PointToPointPlanner::prove_unenterable`](smug_core::stages::PointToPointPlanner::prove_unenterable)); nothing is cached.
    pub fn prove_unenterable(
        &mut self,
        j: usize,
        is: &[usize],
        effort: u64,
    ) -> Result<Vec<Option<NoPathReason>>> {
        let starts: Vec<Pose2> = is.iter().map(|&i| self.poses[i]).collect();
        let goal = self.poses[j];
        self.planner.prove_unenterable(&goal, &starts, effort)
    }
}
