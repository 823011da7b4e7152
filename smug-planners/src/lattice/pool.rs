//! Running the planner's searches: each on a searcher taken from the pool of idle
//! ones (their buffers are large, so they are kept between searches), with the
//! heuristic's weight of its kind, stoppable, and batches side by side on rayon's
//! threads.

use super::{buffers, search, Counts, LatticePlanner, Shared};
use rayon::prelude::*;
use smug_core::{NoPathReason, PlannerOutcome, PointToPointPlanner, Pose2, Result};
use std::sync::atomic::AtomicBool;
use std::sync::Mutex;

impl LatticePlanner {
    /// Runs `work` on a worker with an idle searcher of `pool` (a new one when none is
    /// idle) and the configured `heuristic_weight`, then returns the searcher to the
    /// pool; gives `work`'s result and the searcher's counts of it.
    pub(super) fn with_searcher<R>(
        shared: &Shared,
        pool: &Mutex<Vec<buffers::Searcher>>,
        work: impl FnOnce(&mut search::Worker<'_>) -> R,
    ) -> (R, Counts) {
        Self::with_searcher_as(shared, pool, shared.params.heuristic_weight, None, work)
    }

    /// [`Self::with_searcher`] with the heuristic weighted by `weight`, the search
    /// stopping once `stop` (if any) is set.
    pub(super) fn with_searcher_as<R>(
        shared: &Shared,
        pool: &Mutex<Vec<buffers::Searcher>>,
        weight: f64,
        stop: Option<&AtomicBool>,
        work: impl FnOnce(&mut search::Worker<'_>) -> R,
    ) -> (R, Counts) {
        let idle = pool.lock().expect("searcher pool").pop();
        let mut searcher = idle.unwrap_or_else(|| buffers::Searcher::new(shared.lattice.len()));
        let result = work(&mut search::Worker {
            sh: shared,
            me: &mut searcher,
            weight,
            stop,
        });
        let counts = std::mem::take(&mut searcher.counts);
        pool.lock().expect("searcher pool").push(searcher);
        (result, counts)
    }

    /// Searches from `start` to `goals` with an idle searcher, the heuristic weighted
    /// by `weight`; gives the answers and the search's counts.
    pub(super) fn search_with_pool(
        shared: &Shared,
        pool: &Mutex<Vec<buffers::Searcher>>,
        weight: f64,
        start: &Pose2,
        goals: &[Pose2],
        max_expansions: u64,
    ) -> (search::Answers, Counts) {
        Self::with_searcher_as(shared, pool, weight, None, |worker| {
            worker.search(start, goals, max_expansions)
        })
    }

    /// One search on this thread; its path costs become [`Self::last_costs`].
    pub(super) fn search(
        &mut self,
        start: &Pose2,
        goals: &[Pose2],
        max_expansions: u64,
    ) -> Vec<PlannerOutcome> {
        let (shared, pool) = (&self.shared, &self.searchers);
        let weight = shared.params.heuristic_weight;
        let answered = Self::search_with_pool(shared, pool, weight, start, goals, max_expansions);
        self.record(answered)
    }

    /// One proving search on this thread ([`search::Worker::prove`]); its counts are
    /// added to the planner's.
    pub(super) fn prove(
        &mut self,
        start: &Pose2,
        goals: &[Pose2],
        effort: u64,
    ) -> Vec<Option<NoPathReason>> {
        let (proofs, counts) = Self::with_searcher(&self.shared, &self.searchers, |worker| {
            worker.prove(start, goals, effort)
        });
        self.counts.add(&counts);
        proofs
    }

    /// Adds a search's counts to the planner's and keeps its path costs as
    /// [`Self::last_costs`]; returns its outcomes.
    pub(super) fn record(
        &mut self,
        (answers, counts): (search::Answers, Counts),
    ) -> Vec<PlannerOutcome> {
        self.counts.add(&counts);
        self.last_costs = answers.costs;
        answers.outcomes
    }

    /// The rows' searches, the heuristic weighted by `weight`: side by side on rayon's
    /// threads where the lattice allows, sharing the caches; each search's answer is
    /// the same as alone (see module `caches`).
    pub(super) fn plan_rows_weighted(
        &mut self,
        rows: &[(Pose2, Vec<Pose2>)],
        weight: f64,
    ) -> Result<Vec<Vec<PlannerOutcome>>> {
        let (shared, pool) = (&self.shared, &self.searchers);
        let max = shared.params.max_expansions;
        let answered = self.side_by_side(rows, |(start, goals)| {
            let answered = Self::search_with_pool(shared, pool, weight, start, goals, max);
            shared.progress.answer(goals.len() as u64);
            answered
        });
        self.counts.queries += rows
            .iter()
            .map(|(_, goals)| goals.len() as u64)
            .sum::<u64>();
        Ok(answered.into_iter().map(|a| self.record(a)).collect())
    }

    /// `work` on each of `items`, side by side on rayon's threads when there are two or
    /// more and the lattice allows (see `MAX_PARALLEL_STATES`), the results in order.
    pub(super) fn side_by_side<T: Sync, R: Send>(
        &self,
        items: &[T],
        work: impl Fn(&T) -> R + Sync + Send,
    ) -> Vec<R> {
        if items.len() < 2 || !self.plans_rows_side_by_side() {
            items.iter().map(work).collect()
        } else {
            items.par_iter().with_max_len(1).map(work).collect()
        }
    }
}
