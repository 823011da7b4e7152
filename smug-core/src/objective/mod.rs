//! Objectives: what a motion costs, separate from how the robot moves.
//!
//! An [`Objective`] gives the cost of the space's local motion between two states
//! (integrated along the motion over the world's layers), the cost of a path as the sum
//! of its motions, and an admissible lower bound between two states. Every place that
//! needs a lower bound (A*'s heuristic, the informed set, IDP's `l(p, q)`, lazy
//! sequencing) uses the objective's bound; the space keeps the k-NN distance.

mod path_length;

pub use path_length::{PathLength, PathLengthParams};

use crate::pose::Pose2;
use crate::space::StateSpace;
use std::fmt::Debug;

/// A cost function over motions, with an admissible lower bound.
///
/// Contract (checked by `smug_core::testing::check_objective`):
/// - `motion_cost(a, b) ≥ w_t·‖Δxy‖ + w_r·d(yaw_a, yaw_b) ≥ 0` with
///   `(w_t, w_r) = bound_weights()` (the informed sampler's ellipse relies on it);
/// - `cost_bound(a, b)` is never above the cost of any path from `a` to `b`, and is
///   consistent: `cost_bound(a, c) ≤ motion_cost(a, b) + cost_bound(b, c)` (A* relies on
///   it); it is also ≥ `w_t·‖Δxy‖ + w_r·d(yaw)`;
/// - the cost of a path is the sum of its motions' costs.
pub trait Objective: Send + Sync + Debug {
    /// The cost of the space's local motion from `a` to `b`.
    fn motion_cost(&self, a: &Pose2, b: &Pose2) -> f64;

    /// An admissible, consistent lower bound of the cost of any path from `a` to `b`.
    fn cost_bound(&self, a: &Pose2, b: &Pose2) -> f64;

    /// Weights `(w_t, w_r)` of the additive bound every motion cost respects:
    /// `motion_cost(a, b) ≥ w_t·‖Δxy‖ + w_r·d(yaw_a, yaw_b)`.
    fn bound_weights(&self) -> (f64, f64);

    /// True when `motion_cost(a, b) == motion_cost(b, a)` for every pair (then a path
    /// reversed costs the same, and cost matrices may be symmetric).
    fn is_symmetric(&self) -> bool {
        true
    }

    /// `Some((w_t, w_r))` when every motion costs exactly the SE(2) length
    /// `w_t·‖Δxy‖ + w_r·d(yaw_a, yaw_b)` of a straight motion (`path-length` on a
    /// holonomic space); `None` (the default) for any other cost. Exact geometric
    /// planners serve only this objective.
    fn se2_length_weights(&self) -> Option<(f64, f64)> {
        None
    }

    /// True when `motion_cost(a, b)` depends only on where `b` lies relative to `a`
    /// (the same motion costs the same anywhere on the map: a planner may cost its
    /// motion primitives once); false (the default) for costs that look at the terrain.
    fn is_translation_invariant(&self) -> bool {
        false
    }

    /// The cost of the path through `states`: the sum of its motions' costs.
    fn path_cost(&self, states: &[Pose2]) -> f64 {
        states
            .windows(2)
            .map(|w| self.motion_cost(&w[0], &w[1]))
            .sum()
    }
}

/// Most pieces one motion is split into by [`integrate_motion`] (a bound on the work
/// per motion whatever its length).
pub const MAX_PIECES: usize = 100_000;

/// One piece of a motion, as [`integrate_motion`] hands it out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    /// The state the piece starts at.
    pub from: Pose2,
    /// The state it ends at.
    pub to: Pose2,
    /// The state halfway along it.
    pub middle: Pose2,
    /// Its length in the plane, metres, along the motion: `‖Δxy‖` for straight
    /// (holonomic) motions, the arc length for curves (the chord would be shorter, and
    /// a cost summed over chords would fall below `length_bound`).
    pub length: f64,
}

/// Integrates `f` along the space's motion from `a` to `b`, split into pieces of space
/// distance at most `step` (at most [`MAX_PIECES`]): `f` gets each [`Piece`] (its end
/// states, middle state and length) and returns the piece's cost.
pub fn integrate_motion(
    space: &dyn StateSpace,
    a: &Pose2,
    b: &Pose2,
    step: f64,
    mut f: impl FnMut(&Piece) -> f64,
) -> f64 {
    let pieces = (space.distance(a, b) / step).ceil();
    let n = if pieces.is_finite() && pieces >= 1.0 {
        (pieces as usize).min(MAX_PIECES)
    } else {
        1
    };
    // Curves are interpolated uniformly in arc length: every piece is 1/n of it.
    let arc = (!space.is_holonomic()).then(|| space.motion_extent(a, b).length / n as f64);
    let at = |k: f64| space.interpolate(a, b, k / n as f64);
    let mut from = *a;
    let mut total = 0.0;
    for k in 1..=n {
        let to = if k == n { *b } else { at(k as f64) };
        let piece = Piece {
            from,
            to,
            middle: at(k as f64 - 0.5),
            length: arc.unwrap_or_else(|| from.xy_distance(&to)),
        };
        total += f(&piece);
        from = to;
    }
    total
}

/// Checks an integration step from config: finite and > 0.
pub fn check_step(stage: &str, step: f64) -> crate::Result<f64> {
    if step.is_finite() && step > 0.0 {
        Ok(step)
    } else {
        Err(crate::Error::invalid_param(
            stage,
            format!("step must be finite and > 0, got {step}"),
        ))
    }
}

/// Checks a non-negative finite parameter from config, naming it in the error.
pub fn check_non_negative(stage: &str, key: &str, value: f64) -> crate::Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(crate::Error::invalid_param(
            stage,
            format!("{key} must be finite and ≥ 0, got {value}"),
        ))
    }
}

/// Checks a positive finite parameter from config, naming it in the error.
pub fn check_positive(stage: &str, key: &str, value: f64) -> crate::Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(crate::Error::invalid_param(
            stage,
            format!("{key} must be finite and > 0, got {value}"),
        ))
    }
}
