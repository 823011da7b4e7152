//! DP layers answered by one search: the oracle hands the planner a layer's sources
//! with their DP values and caches each goal's path from its best source.

use super::{refuse_after_deadline, PathOracle, PlannedPath};
use smug_core::error::Result;
use smug_core::pose::Pose2;
use smug_core::stages::LayerOutcome;
use std::sync::Arc;

impl PathOracle {
    /// True when the planner answers a DP layer with one search
    /// ([`PointToPointPlanner::answers_layers`](smug_core::stages::PointToPointPlanner::answers_layers)).
    pub fn answers_layers(&self) -> bool {
        self.planner.answers_layers()
    }

    /// For each of `goals`, the `i` of `sources` (each `(i, offset)`, the cost already
    /// paid to be at `i`) the planner's one search of the layer reached it from most
    /// cheaply, offset included ([`PointToPointPlanner::plan_layer`](smug_core::stages::PointToPointPlanner::plan_layer)); `None` when no
    /// source reaches it. The pair `i → goal` is cached as planned (a pair planned
    /// before keeps the cheaper path); a goal without a path is cached as unreachable
    /// from the first source. `next`: the following layer's goals, which the planner
    /// may start on early.
    pub fn plan_layer(
        &mut self,
        sources: &[(usize, f64)],
        goals: &[usize],
        next: &[usize],
    ) -> Result<Vec<Option<usize>>> {
        refuse_after_deadline(&self.run.deadline)?;
        let from: Vec<(Pose2, f64)> = sources.iter().map(|&(i, o)| (self.poses[i], o)).collect();
        let to: Vec<Pose2> = goals.iter().map(|&j| self.poses[j]).collect();
        let after: Vec<Pose2> = next.iter().map(|&j| self.poses[j]).collect();
        let asked_so_far = self.run.progress.ask(goals.len() as u64);
        let answers = self.planner.plan_layer(&from, &to, &after);
        self.run.progress.answered_up_to(asked_so_far);
        Ok(goals
            .iter()
            .zip(answers?)
            .map(|(&j, answer)| self.keep_layer_answer(sources, j, answer))
            .collect())
    }

    /// Caches a layer search's answer for goal `j` as the pair from its source (unless
    /// that pair is planned already at no higher cost); the source's index when it
    /// reached `j`.
    fn keep_layer_answer(
        &mut self,
        sources: &[(usize, f64)],
        j: usize,
        answer: LayerOutcome,
    ) -> Option<usize> {
        let i = sources.get(answer.source).map_or(j, |s| s.0);
        let planned = PlannedPath::new(answer.outcome);
        let reached = planned.path().is_some();
        let cheaper = self
            .cache
            .get(&(i, j))
            .is_none_or(|known| planned.cost < known.cost);
        if i != j && cheaper {
            self.stats.paths_planned += 1;
            self.store_both_ways(i, j, Arc::new(planned));
        }
        reached.then_some(i)
    }
}
