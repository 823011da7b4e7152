//! Focusing a one-to-many search: as goals settle, its heuristic is re-aimed at the
//! goals left and its queue re-keyed, so it stops expanding towards settled goals.

use super::queue::{Entry, Item};
use super::search::{Run, Worker};
use super::sources::is_source;

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

    /// Once a goal is settled, aims the heuristic at the goals left (the search would
    /// otherwise keep expanding towards settled goals). The queue is re-keyed lazily:
    /// an entry keyed with an older focus gets its key again when popped
    /// ([`Self::rekeyed`]). The new heuristic is consistent too, so every pose still
    /// closes at its optimal cost.
    pub(super) fn refocus(&mut self, run: &mut Run) {
        self.aim(run);
        run.focus = run.focus.wrapping_add(1);
    }

    /// A popped node entry keyed with an older focus: true when it is done with
    /// (dropped, as no goal left is reachable from it, or queued again at its key under
    /// the current focus), false when its key stands (then it pops now, as it would
    /// from a queue re-keyed at once). The heuristic aims at fewer goals each time, so
    /// keys only grow: an entry pops at its current key after every entry whose
    /// current key is below it, ties in the same order, as from a queue re-keyed at
    /// every refocus.
    pub(super) fn rekeyed(&mut self, run: &mut Run, entry: Entry) -> bool {
        let Item::Node { id, g, .. } = entry.item else {
            return false;
        };
        if is_source(id) {
            return false; // keyed at its offset alone, under any focus
        }
        let h = self.heuristic(id, &run.aimed, run.h2d.as_deref());
        if h.is_infinite() {
            return true;
        }
        let key = g + self.weight * h;
        debug_assert!(key >= entry.key, "a refocused key never falls");
        let mut item = entry.item;
        if let Item::Node { focus, .. } = &mut item {
            *focus = run.focus;
        }
        if key == entry.key {
            return false;
        }
        run.heap.push(Entry { key, item });
        true
    }
}
