//! Proving searches: a lattice search of a small budget that builds no path, only
//! the proofs of the goals it cannot reach (the mission's early probes of its start
//! and end poses).

use super::search::{End, Worker};
use smug_core::{NoPathReason, Pose2, Proof};
use std::time::Instant;

impl Worker<'_> {
    /// One search from `start` to `goals` of at most `max_expansions` expansions that
    /// only proves: for each goal, the proof that it cannot be reached when the search
    /// exhausted the lattice poses it could reach without it (`None`: reached, invalid,
    /// or the budget ran out). No path is built.
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
            let (reached, end) = self.run(start, asked, max_expansions);
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
}
