//! Sampler stage: draws SE(2) states for the roadmap.

use crate::pose::{Bounds2, Pose2};

/// The informed set of a query: states that could improve a path from `start` to
/// `goal` whose best cost so far is `best_cost`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InformedSet {
    /// Query start.
    pub start: Pose2,
    /// Query goal.
    pub goal: Pose2,
    /// Cost of the best path found so far.
    pub best_cost: f64,
}

/// Draws states; owns its seeded RNG so runs are reproducible.
pub trait Sampler: Send + Sync {
    /// A state inside `bounds`, and inside `informed` when given and the sampler uses
    /// it; `None` when the requested region is empty.
    fn sample(&mut self, bounds: &Bounds2, informed: Option<&InformedSet>) -> Option<Pose2>;
}
