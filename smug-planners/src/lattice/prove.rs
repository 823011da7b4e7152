//! Proofs of unreachable goals: proving searches (a lattice search of a small budget
//! that builds no path, only the proofs of the goals it cannot reach: the mission's
//! early probes of its start and end poses), and the proofs every exhausted search
//! keeps for later ones, which use them to stop sooner and to stay out of what is
//! proved.

use super::caches::insert;
use super::search::{End, Run, Until, Worker};
use super::sources::source_id;
use smug_core::{NoPathReason, Pose2, Proof};
use std::sync::Arc;
use std::time::Instant;

impl Worker<'_> {
    /// One search from `start` to `goals` of at most `max_expansions` expansions that
    /// only proves: for each goal, the proof that it cannot be reached when the search
    /// exhausted the lattice poses it could reach without it (`None`: reached, invalid,
    /// or the budget ran out). No path is built. The search ends at the first goal it
    /// reaches: a start that reaches one is not boxed in, and a search on to the others
    /// would only prove them out by exhausting a region that holds a goal (on lunar,
    /// the start's probe ran its whole budget of 20,000 expansions every time).
    pub(super) fn prove(
        &mut self,
        start: &Pose2,
        goals: &[Pose2],
        max_expansions: u64,
    ) -> Vec<Option<NoPathReason>> {
        let started = Instant::now();
        self.me.counts.searches += 1;
        let mut proofs = vec![None; goals.len()];
        if !self.sh.states.is_valid(start) {
            return proofs;
        }
        let (asked, index) = self.asked_goals(start, goals, |_, _| {});
        if !asked.is_empty() {
            let (reached, end) =
                self.run(&[(*start, 0.0)], asked, max_expansions, Until::FirstGoal);
            let exhausted = matches!(end, End::Exhausted);
            for (goal, k) in reached.into_iter().zip(index) {
                if goal.reached.is_none() && (exhausted || goal.proved_out) {
                    proofs[k] = Some(NoPathReason::Proved(Proof::Exhausted));
                }
            }
        }
        self.me.counts.breakdown.astar_s += started.elapsed().as_secs_f64();
        proofs
    }

    /// Marks the goals an earlier exhausted search proved unreachable from every
    /// lattice pose the sources join (and that no direct shot from a source reaches):
    /// everything this search can reach, that one reached, and it found no way to
    /// them. The search still orders its expansions by every goal (so its answers for
    /// the others are the same), it only stops without waiting for these.
    pub(super) fn apply_kept_proofs(&mut self, run: &mut Run) {
        let joined: Vec<u32> = run
            .sources
            .iter()
            .flat_map(|s| s.joins.iter().map(|j| j.0))
            .collect();
        if joined.is_empty() {
            return;
        }
        for k in 0..run.goals.len() {
            let pose = run.goals[k].pose;
            if !self.sh.caches.proved_unreachable(&joined, &pose) {
                continue;
            }
            let direct = (0..run.sources.len()).any(|s| {
                let from = run.sources[s].pose;
                from.xy_distance(&pose) <= self.sh.shot_radius
                    && self.shot_valid(source_id(s), &from, &pose, &run.goals[k].shots)
            });
            if !direct {
                run.goals[k].proved_out = true;
                run.open_goals -= 1;
            }
        }
    }

    /// The poses of a kept proof that shows every goal the search waits for unreachable
    /// from them: the search need not go there. (Its answers stay the same: no path to
    /// those goals passes through such a pose, and the poses it does go to pop in the
    /// same order.) A start beside an earlier start's dead end then proves the same
    /// dead end by a search of the few poses its curves join outside that proof.
    pub(super) fn proof_bound(&self, run: &Run) -> Option<Arc<Vec<u64>>> {
        let awaited = run.awaited();
        if awaited.is_empty() {
            return None;
        }
        self.sh.caches.proof_covering(&awaited)
    }

    /// After an exhausted search: keeps the proof that its unreached goals cannot be
    /// reached from any lattice pose it closed, nor from the poses of the proof it
    /// was bounded by.
    pub(super) fn keep_proof(&self, run: &Run) {
        let unreached = run.awaited();
        // A search that closed no lattice pose (a start whose curves join none) proves
        // nothing for any other start.
        if unreached.is_empty() || run.closed.is_empty() {
            return;
        }
        let mut closed = match &run.pruned {
            Some(pruned) => pruned.as_ref().clone(),
            None => vec![0u64; self.sh.lattice.len().div_ceil(64)],
        };
        for &id in &run.closed {
            insert(&mut closed, id);
        }
        self.sh.caches.keep_proof(closed, &unreached);
    }
}
