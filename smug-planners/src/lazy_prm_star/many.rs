//! One-to-many queries of LazyPRM* (`one_to_many`): the goals a source needs are
//! answered by one lazy Dijkstra search on the shared roadmap (each settled vertex's
//! edge checked as it is settled), instead of one query per goal.

use super::LazyPrmStar;
use crate::roadmap::GraphPath;
use smug_core::{Budget, NoPathReason, Path, PlannerOutcome, Pose2, Proof};
use std::time::Instant;

impl LazyPrmStar {
    /// Answers `start → goals`: every goal the roadmap connects to `start` from one
    /// shared search (its path checked lazily, as a query's attempt would); a goal
    /// it does not connect is planned as a query of its own (which grows the
    /// roadmap), after which the goals still unanswered are searched again.
    pub(super) fn plan_many_on_roadmap(
        &mut self,
        start: &Pose2,
        goals: &[Pose2],
    ) -> Vec<PlannerOutcome> {
        let started = Instant::now();
        let before = self.counts.breakdown;
        self.counts.queries += goals.len() as u64;
        self.ensure_grown();
        self.ensure_grown_for_many();
        let Some(s) = self.terminal(start) else {
            return goals.iter().map(|_| PlannerOutcome::InvalidStart).collect();
        };
        let mut outcomes: Vec<Option<PlannerOutcome>> = goals.iter().map(|_| None).collect();
        // (goal index, its vertex) of the goals to search.
        let mut pending = Vec::new();
        for (i, goal) in goals.iter().enumerate() {
            match self.answer_without_search(start, goal, s) {
                Ok(outcome) => outcomes[i] = Some(outcome),
                Err(g) => pending.push((i, g)),
            }
        }
        while !pending.is_empty() {
            if self.cut_off.contains(&s) {
                self.counts.cut_off_queries += pending.len() as u64;
                break; // unanswered: no path
            }
            let vertices: Vec<u32> = pending.iter().map(|&(_, g)| g).collect();
            let found = self.lazy_search_many(s, &vertices);
            let mut unconnected = Vec::new();
            let mut connected = Vec::new();
            for (&(i, g), path) in pending.iter().zip(found) {
                match path {
                    Some(path) => connected.push((i, path)),
                    None => unconnected.push((i, g)),
                }
            }
            let (indices, graph_paths): (Vec<usize>, Vec<GraphPath>) =
                connected.into_iter().unzip();
            let paths = self.post_processed_all(&graph_paths);
            for (i, path) in indices.into_iter().zip(paths) {
                outcomes[i] = Some(PlannerOutcome::Exact(path));
            }
            // The first goal the roadmap does not connect is planned alone (it grows
            // the roadmap); the others are searched again on the grown roadmap.
            let mut unconnected = unconnected.into_iter();
            if let Some((i, g)) = unconnected.next() {
                outcomes[i] = Some(self.solve_query(start, &goals[i], s, g));
            }
            pending = unconnected.collect();
        }
        let outcomes: Vec<PlannerOutcome> = outcomes
            .into_iter()
            .map(|outcome| {
                outcome.unwrap_or(PlannerOutcome::NoPath(NoPathReason::BudgetSpent(
                    Budget::EarlierQuery,
                )))
            })
            .collect();
        for (goal, outcome) in goals.iter().zip(&outcomes) {
            self.warm.record(start, goal, outcome);
        }
        let accounted = self.counts.breakdown.total_s() - before.total_s();
        self.counts.breakdown.misc_s += (started.elapsed().as_secs_f64() - accounted).max(0.0);
        outcomes
    }

    /// Grows the roadmap once by `one_to_many_density` uniform samples per square
    /// metre of the bounds (at most `max_samples`).
    fn ensure_grown_for_many(&mut self) {
        if self.grown_for_many {
            return;
        }
        self.grown_for_many = true;
        let [x0, y0] = self.bounds.min;
        let [x1, y1] = self.bounds.max;
        let area = (x1 - x0).max(0.0) * (y1 - y0).max(0.0);
        let samples = (self.params.one_to_many_density * area).ceil();
        self.grow((samples as u64).min(self.params.max_samples));
    }

    /// The answer to `start → goal` when no search is needed (a loaded answer, an
    /// invalid goal, the start itself, a cut-off goal), else the goal's vertex.
    fn answer_without_search(
        &mut self,
        start: &Pose2,
        goal: &Pose2,
        s: u32,
    ) -> Result<PlannerOutcome, u32> {
        if let Some(outcome) = self.warm.reuse(start, goal) {
            return Ok(outcome);
        }
        match self.terminal(goal) {
            None => Ok(PlannerOutcome::InvalidGoal),
            Some(g) if g == s => Ok(PlannerOutcome::Exact(Path {
                states: vec![*start],
                cost: 0.0,
            })),
            Some(_) if self.proved_disconnected(start, goal) => Ok(PlannerOutcome::NoPath(
                NoPathReason::Proved(Proof::Disconnected),
            )),
            Some(g) if self.cut_off.contains(&g) => {
                self.counts.cut_off_queries += 1;
                Ok(PlannerOutcome::NoPath(NoPathReason::BudgetSpent(
                    Budget::EarlierQuery,
                )))
            }
            Some(g) => Err(g),
        }
    }

    /// The cheapest valid path on the roadmap from `s` to each of `goals` (`None`
    /// where none is left), by one lazy Dijkstra search (see
    /// [`crate::roadmap::AStar::search_many_lazy`]); its checking time is booked as checking.
    fn lazy_search_many(&mut self, s: u32, goals: &[u32]) -> Vec<Option<GraphPath>> {
        let found = self.timed_lazy_search(|astar, roadmap, _, checks| {
            astar.search_many_lazy(roadmap, s, goals, checks)
        });
        if found.iter().any(Option::is_none) {
            self.roadmap.refresh_components();
        }
        found
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{planner_on, Discs};
    use super::super::{LazyPrmStar, LazyPrmStarParams};
    use proptest::prelude::*;
    use smug_core::{PlannerOutcome, PointToPointPlanner, Pose2};

    /// A planner on a fixed roadmap of 150 samples (queries draw none).
    fn fixed_roadmap_planner(
        discs: &[(f64, f64, f64)],
        seed: u64,
        one_to_many: bool,
        smooth: bool,
    ) -> LazyPrmStar {
        let params = LazyPrmStarParams {
            initial_samples: 150,
            max_samples: 0,
            one_to_many,
            one_to_many_density: 0.0,
            smooth,
            retry_cut_off: true,
            ..LazyPrmStarParams::default()
        };
        planner_on(params, seed, Discs(discs.to_vec())).unwrap()
    }

    fn pose((x, y): (f64, f64)) -> Pose2 {
        Pose2::new(x, y, 0.0)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(96))]
        #[test]
        fn one_search_gives_each_goal_the_plan_of_its_own_query_on_a_fixed_roadmap(
            discs in proptest::collection::vec((1.0f64..9.0, 1.0f64..9.0, 0.3f64..1.8), 0..7),
            seed in any::<u64>(),
            start in (0.0f64..10.0, 0.0f64..10.0),
            goals in proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0), 1..10),
            smooth in any::<bool>(),
        ) {
            let start = pose(start);
            let goals: Vec<Pose2> = goals.into_iter().map(pose).collect();
            let mut alone = fixed_roadmap_planner(&discs, seed, false, smooth);
            // The goals' vertices join the roadmap first, as in the one-to-many search.
            for goal in &goals {
                alone.plan(&start, goal).unwrap();
            }
            let expected: Vec<PlannerOutcome> =
                goals.iter().map(|goal| alone.plan(&start, goal).unwrap()).collect();
            let mut many = fixed_roadmap_planner(&discs, seed, true, smooth);
            prop_assert!(many.answers_many());
            let found = many.plan_many(&start, &goals).unwrap();
            prop_assert_eq!(found.len(), goals.len());
            let mut paths = 0;
            for (want, got) in expected.iter().zip(&found) {
                match (want, got) {
                    (PlannerOutcome::Exact(a), PlannerOutcome::Exact(b)) => {
                        paths += 1;
                        prop_assert_eq!(&a.states, &b.states);
                        prop_assert!((a.cost - b.cost).abs() <= 1e-9 * (1.0 + a.cost));
                    }
                    (a, b) => prop_assert_eq!(a, b),
                }
            }
            // Solvable queries are the common case: make sure the test compares paths.
            prop_assume!(paths > 0);
        }
    }
}
