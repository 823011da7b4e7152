//! The focus of a query: a region around the straight line that grows geometrically
//! (see `LazyPrmStarParams::focus`).

use smug_core::{InformedSet, Pose2};

/// Samples a first-path focus gets at least before it widens.
pub(super) const MIN_FOCUS_PERIOD: u64 = 100;

/// The focus of a query: the informed set of a provisional cost `(1 + excess) ×` the
/// straight-line cost, its excess doubling each `period` samples — a region around
/// the straight line that grows geometrically. While it does not cover the query's
/// informed set (no path yet, or the best path costs more than the provisional cost),
/// every other sample is drawn in it, the others in the informed set (the bounds
/// before a path): a short query on a big map densifies its own neighbourhood first,
/// and a detour found on a sparse roadmap is challenged where better paths lie.
#[derive(Clone, Copy, Debug)]
pub(super) struct Focus {
    /// The excess of the provisional cost over the straight-line cost (0: no focus).
    excess: f64,
    /// The straight-line cost of the query.
    lower_bound: f64,
    /// The provisional cost from which the focus holds the whole bounds.
    whole: f64,
    /// Samples until the focus widens.
    left: u64,
    /// True when the next sample is drawn in the focus.
    focused: bool,
}

impl Focus {
    pub(super) fn new(excess: f64, lower_bound: f64, whole: f64, period: u64) -> Self {
        Self {
            excess,
            lower_bound,
            whole,
            left: period,
            focused: true,
        }
    }

    /// The set of the next sample: the focus every other sample, else the bounds.
    pub(super) fn next_set(&mut self, start: &Pose2, goal: &Pose2) -> Option<InformedSet> {
        self.focused = !self.focused;
        let active =
            !self.focused && self.excess > 0.0 && self.lower_bound > 0.0 && self.excess.is_finite();
        active.then_some(InformedSet {
            start: *start,
            goal: *goal,
            best_cost: (1.0 + self.excess) * self.lower_bound,
        })
    }

    /// Counts a sample; true when the focus is due to widen.
    pub(super) fn tick(&mut self) -> bool {
        self.left = self.left.saturating_sub(1);
        self.left == 0
    }

    /// True when the focus covers the informed set of a path of cost `cost` (or the
    /// whole bounds): its provisional cost is at least `cost` (always with no focus).
    pub(super) fn covers(&self, cost: f64) -> bool {
        !(self.excess > 0.0 && self.excess.is_finite() && self.lower_bound > 0.0)
            || (1.0 + self.excess) * self.lower_bound >= cost.min(self.whole)
    }

    /// Doubles the excess and restarts the count.
    pub(super) fn widen(&mut self, period: u64) {
        self.excess *= 2.0;
        self.left = period;
    }
}
