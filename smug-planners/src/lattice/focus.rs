//! Focusing a one-to-many search: as goals settle, its heuristic is re-aimed at the
//! goals left and its queue re-keyed, so it stops expanding towards settled goals.

use super::search::{Entry, Item, Run, Worker};
use dary_heap::OctonaryHeap as BinaryHeap;

/// A search with goals left re-aims its heuristic at them whenever at most this
/// many are left (and whenever half of those aimed at are settled).
const REFOCUS_BELOW: usize = 8;

impl Worker<'_> {
    /// Aims the heuristic at the goals not settled yet (those proved unreachable
    /// included, so that they order the search as if they were not).
    pub(super) fn aim(&mut self, run: &mut Run) {
        run.aimed = run
            .goals
            .iter()
            .filter(|g| g.reached.is_none())
            .map(|g| g.pose)
            .collect();
        run.h2d = self
            .sh
            .params
            .obstacle_heuristic
            .then(|| self.goal_heuristic(&run.aimed));
    }

    /// Whether the goals left are few enough, against those the heuristic aims at, for
    /// a sharper heuristic to pay for re-keying the heap: at most [`REFOCUS_BELOW`],
    /// or half of those aimed at.
    pub(super) fn worth_refocusing(&self, run: &Run) -> bool {
        let left = run.goals.iter().filter(|g| g.reached.is_none()).count();
        left < run.aimed.len() && (left <= REFOCUS_BELOW || 2 * left <= run.aimed.len())
    }

    /// Once a goal is settled, aims the heuristic at the goals left and re-keys the
    /// queue with it (the search would otherwise keep expanding towards settled
    /// goals). The new heuristic is consistent too, so every pose still closes at its
    /// optimal cost; shots to settled goals and poses that reach no goal left go.
    pub(super) fn refocus(&mut self, run: &mut Run) {
        self.aim(run);
        let entries = std::mem::take(&mut run.heap).into_vec();
        let weight = self.sh.params.heuristic_weight;
        let mut kept = Vec::with_capacity(entries.len());
        for entry in entries {
            match entry.item {
                Item::Node { id, g, .. } => {
                    let h = self.heuristic(id, &run.aimed, run.h2d.as_deref());
                    if h.is_finite() {
                        kept.push(Entry {
                            key: g + weight * h,
                            item: entry.item,
                        });
                    }
                }
                Item::Shot { goal, .. } => {
                    if run.goals[goal as usize].reached.is_none() {
                        kept.push(entry);
                    }
                }
            }
        }
        run.heap = BinaryHeap::from(kept);
    }
}
