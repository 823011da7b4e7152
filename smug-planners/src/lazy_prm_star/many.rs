//! One-to-many queries of LazyPRM* (`one_to_many`): the goals a source needs are
//! answered by one lazy Dijkstra search on the shared roadmap (each settled vertex's
//! edge checked as it is settled), instead of one query per goal. Many sources (a
//! cost matrix's rows, a DP layer) are searched side by side on the roadmap held
//! still, their checks shared through a memo and written into the roadmap after
//! (see [`crate::roadmap::memo`]): the answers are those of one search after another
//! on that roadmap, for any number of threads.

use super::checks::{MemoChecks, Tally};
use super::LazyPrmStar;
use crate::roadmap::memo::CheckMemo;
use crate::roadmap::{AStar, GraphPath};
use rayon::prelude::*;
use smug_core::{Budget, NoPathReason, Path, PlannerOutcome, Pose2, Proof};
use std::sync::Mutex;
use std::time::Instant;

/// One source's goals while its row is answered.
struct Row {
    /// The source's vertex (`None`: the start is invalid).
    source: Option<u32>,
    outcomes: Vec<Option<PlannerOutcome>>,
    /// (goal index, its vertex) of the goals still to search.
    pending: Vec<(usize, u32)>,
}

impl LazyPrmStar {
    /// Answers every row `start → goals`: the endpoints join the roadmap row by row,
    /// then every row's goals are searched side by side (one search per row) on the
    /// roadmap as it is; a goal the roadmap does not connect is planned as a query of
    /// its own (which grows the roadmap), after which its row's goals still
    /// unanswered are searched again, row by row.
    pub(super) fn plan_rows_on_roadmap(
        &mut self,
        rows: &[(Pose2, Vec<Pose2>)],
    ) -> Vec<Vec<PlannerOutcome>> {
        let started = Instant::now();
        let before = self.counts.breakdown;
        self.ensure_grown();
        self.ensure_grown_for_many();
        let mut prepared: Vec<Row> = rows
            .iter()
            .map(|(start, goals)| self.prepare_row(start, goals))
            .collect();
        let searched: Vec<usize> = (0..prepared.len())
            .filter(|&r| self.ready_to_search(&mut prepared[r]))
            .collect();
        let jobs: Vec<(u32, Vec<u32>)> = searched.iter().map(|&r| job_of(&prepared[r])).collect();
        let found = self.search_in_doubling_batches(&jobs);
        let mut unconnected: Vec<Vec<(usize, u32)>> = prepared.iter().map(|_| Vec::new()).collect();
        let mut connected: Vec<(usize, usize, GraphPath)> = Vec::new();
        for (&r, paths) in searched.iter().zip(found) {
            unconnected[r] = take_found(&mut prepared[r], r, paths, &mut connected);
        }
        self.answer_connected(&mut prepared, connected);
        for ((row, (start, goals)), unconnected) in prepared.iter_mut().zip(rows).zip(unconnected) {
            self.finish_row(row, start, goals, unconnected);
            self.progress.answer(goals.len() as u64);
        }
        let outcomes: Vec<Vec<PlannerOutcome>> = prepared
            .into_iter()
            .map(|row| {
                row.outcomes
                    .into_iter()
                    .map(unanswered_is_earlier_query)
                    .collect()
            })
            .collect();
        for ((start, goals), row) in rows.iter().zip(&outcomes) {
            for (goal, outcome) in goals.iter().zip(row) {
                self.warm.record(start, goal, outcome);
            }
        }
        let accounted = self.counts.breakdown.total_s() - before.total_s();
        self.counts.breakdown.misc_s += (started.elapsed().as_secs_f64() - accounted).max(0.0);
        outcomes
    }

    /// The row of `start → goals` with its endpoints on the roadmap and every goal
    /// that needs no search answered.
    fn prepare_row(&mut self, start: &Pose2, goals: &[Pose2]) -> Row {
        self.counts.queries += goals.len() as u64;
        let Some(s) = self.terminal(start) else {
            return Row {
                source: None,
                outcomes: goals
                    .iter()
                    .map(|_| Some(PlannerOutcome::InvalidStart))
                    .collect(),
                pending: Vec::new(),
            };
        };
        let mut row = Row {
            source: Some(s),
            outcomes: goals.iter().map(|_| None).collect(),
            pending: Vec::new(),
        };
        for (i, goal) in goals.iter().enumerate() {
            match self.answer_without_search(start, goal, s) {
                Ok(outcome) => row.outcomes[i] = Some(outcome),
                Err(g) => row.pending.push((i, g)),
            }
        }
        row
    }

    /// True when `row` has goals to search from a source that is not cut off (a
    /// cut-off source leaves them unanswered, counted).
    fn ready_to_search(&mut self, row: &mut Row) -> bool {
        let Some(s) = row.source else {
            return false;
        };
        if row.pending.is_empty() {
            return false;
        }
        let before = row.pending.len();
        row.pending.retain(|&(_, g)| !self.cut_off_from(s, g));
        self.counts.cut_off_queries += (before - row.pending.len()) as u64;
        !row.pending.is_empty()
    }

    /// [`search_side_by_side`](Self::search_side_by_side) in batches of 1, 1, 2, 4, 8, …
    /// jobs: a search prunes its open list with the edges the roadmap knows valid, and
    /// the batches after the first few know what the earlier ones checked (one batch
    /// of every row on a fresh roadmap pushed 3× the entries). The batches depend on
    /// the number of jobs alone, never on the threads.
    fn search_in_doubling_batches(
        &mut self,
        jobs: &[(u32, Vec<u32>)],
    ) -> Vec<Vec<Option<GraphPath>>> {
        let mut found = Vec::with_capacity(jobs.len());
        let mut batch = 1;
        while found.len() < jobs.len() {
            let from = found.len();
            let to = (from + batch).min(jobs.len());
            found.extend(self.search_side_by_side(&jobs[from..to]));
            batch = to.max(1);
        }
        found
    }

    /// The cheapest valid path on the roadmap from each job's source to each of its
    /// goals (`None` where none is left), one lazy Dijkstra search per job, side by
    /// side on the roadmap held still; what they found is written into the roadmap
    /// after. Checking time is booked as checking, the rest as A*.
    fn search_side_by_side(&mut self, jobs: &[(u32, Vec<u32>)]) -> Vec<Vec<Option<GraphPath>>> {
        if jobs.is_empty() {
            return Vec::new();
        }
        let started = Instant::now();
        let memo = CheckMemo::new(&self.roadmap);
        let tally = Tally::default();
        let spare = Mutex::new(std::mem::take(&mut self.row_searches));
        let found: Vec<Vec<Option<GraphPath>>> = {
            let (roadmap, states, motions) =
                (&self.roadmap, self.states.as_ref(), self.motions.as_ref());
            jobs.par_iter()
                .map(|(s, goals)| {
                    let mut astar = take_search(&spare);
                    let mut checks = MemoChecks {
                        memo: &memo,
                        states,
                        motions,
                        tally: &tally,
                    };
                    let found = astar.search_many_lazy(roadmap, *s, goals, &mut checks);
                    put_back(&spare, astar);
                    found
                })
                .collect()
        };
        self.row_searches = spare.into_inner().unwrap_or_else(|e| e.into_inner());
        memo.apply(&mut self.roadmap);
        let checking = tally.book(&mut self.counts);
        self.counts.searches += jobs.len() as u64;
        self.counts.breakdown.astar_s += (started.elapsed().as_secs_f64() - checking).max(0.0);
        if found.iter().flatten().any(Option::is_none) {
            self.roadmap.refresh_components();
        }
        found
    }

    /// Post-processes the `(row, goal index, path)` found (side by side) and answers them.
    fn answer_connected(&mut self, rows: &mut [Row], connected: Vec<(usize, usize, GraphPath)>) {
        let (places, graph_paths): (Vec<(usize, usize)>, Vec<GraphPath>) = connected
            .into_iter()
            .map(|(r, i, path)| ((r, i), path))
            .unzip();
        let paths = self.post_processed_all(&graph_paths);
        for ((r, i), path) in places.into_iter().zip(paths) {
            rows[r].outcomes[i] = Some(PlannerOutcome::Exact(path));
        }
    }

    /// Answers the goals of `row` its search left `unconnected`: the first is planned
    /// alone (it grows the roadmap), the others searched again on the grown roadmap,
    /// until none is left.
    fn finish_row(
        &mut self,
        row: &mut Row,
        start: &Pose2,
        goals: &[Pose2],
        mut unconnected: Vec<(usize, u32)>,
    ) {
        let Some(s) = row.source else {
            return;
        };
        while let Some(&(i, g)) = unconnected.first() {
            row.outcomes[i] = Some(self.solve_query(start, &goals[i], s, g));
            row.pending = unconnected.split_off(1);
            if row.pending.is_empty() || !self.ready_to_search(row) {
                return;
            }
            let found = self.search_side_by_side(&[job_of(row)]);
            let mut connected = Vec::new();
            let paths = found.into_iter().flatten().collect();
            unconnected = take_found(row, 0, paths, &mut connected);
            self.answer_connected(std::slice::from_mut(row), connected);
        }
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
            Some(g) if self.cut_off_from(g, s) => {
                self.counts.cut_off_queries += 1;
                Ok(PlannerOutcome::NoPath(NoPathReason::BudgetSpent(
                    Budget::EarlierQuery,
                )))
            }
            Some(g) => Err(g),
        }
    }
}

/// Takes the search's `paths` for `row`'s pending goals (the row is `r` in its
/// batch): each path found joins `connected` as `(r, goal index, path)`; the goals
/// without one are returned. The row has no pending goal after.
fn take_found(
    row: &mut Row,
    r: usize,
    paths: Vec<Option<GraphPath>>,
    connected: &mut Vec<(usize, usize, GraphPath)>,
) -> Vec<(usize, u32)> {
    let mut unconnected = Vec::new();
    for ((i, g), path) in row.pending.drain(..).zip(paths) {
        match path {
            Some(path) => connected.push((r, i, path)),
            None => unconnected.push((i, g)),
        }
    }
    unconnected
}

/// The search a row asks for: its source and pending goals.
fn job_of(row: &Row) -> (u32, Vec<u32>) {
    let s = row.source.unwrap_or(u32::MAX);
    (s, row.pending.iter().map(|&(_, g)| g).collect())
}

/// A search's buffers from the spares (or new ones).
fn take_search(spare: &Mutex<Vec<AStar>>) -> AStar {
    spare
        .lock()
        .map(|mut spare| spare.pop())
        .unwrap_or_default()
        .unwrap_or_default()
}

/// Returns a search's buffers to the spares.
fn put_back(spare: &Mutex<Vec<AStar>>, astar: AStar) {
    if let Ok(mut spare) = spare.lock() {
        spare.push(astar);
    }
}

/// A goal left unanswered: its source was cut off after an earlier query spent its budget.
fn unanswered_is_earlier_query(outcome: Option<PlannerOutcome>) -> PlannerOutcome {
    outcome.unwrap_or(PlannerOutcome::NoPath(NoPathReason::BudgetSpent(
        Budget::EarlierQuery,
    )))
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
