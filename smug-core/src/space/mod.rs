//! State spaces (motion models): the distance for nearest neighbours, the local motion
//! between two states, and the OMPL SE(2) default.
//!
//! A space says how the robot moves; what a motion costs is the objective's business
//! (see [`crate::objective`]).

use crate::pose::{angle_distance, wrap_angle, Pose2};
use serde::{Deserialize, Serialize};
use std::fmt::Debug;

/// A motion model on SE(2): the k-NN distance and the local motion between two states.
///
/// Implementations satisfy the triangle inequality (and symmetry when
/// [`StateSpace::is_symmetric`]), checked by `smug_core::testing::check_metric_axioms`,
/// and the additive lower bound `distance(a, b) ≥ w_t·‖Δxy‖ + w_r·d(yaw_a, yaw_b)` with
/// `(w_t, w_r) = lower_bound_weights()`: spatial indices rely on it.
pub trait StateSpace: Send + Sync + Debug {
    /// The length of the local motion from `a` to `b` (the k-NN distance).
    fn distance(&self, a: &Pose2, b: &Pose2) -> f64;

    /// The state a fraction `t ∈ [0, 1]` of the way from `a` to `b`
    /// (along the shortest yaw arc); `t = 0` gives `a`, `t = 1` gives `b`.
    fn interpolate(&self, a: &Pose2, b: &Pose2, t: f64) -> Pose2;

    /// Weights `(w_t, w_r)` of an additive lower bound of [`StateSpace::distance`]:
    /// `distance(a, b) ≥ w_t·‖Δxy‖ + w_r·d(yaw_a, yaw_b)`.
    fn lower_bound_weights(&self) -> (f64, f64);

    /// True when `distance(a, b) == distance(b, a)` and the motion `b → a` is the motion
    /// `a → b` reversed (then roadmaps, path caches and cost matrices may be undirected).
    fn is_symmetric(&self) -> bool {
        true
    }

    /// The local motion's length in the plane and how far its heading turns in all
    /// (a straight SE(2) motion: `‖Δxy‖` and `d(yaw_a, yaw_b)`); objectives cost by it.
    fn motion_extent(&self, a: &Pose2, b: &Pose2) -> MotionExtent {
        MotionExtent {
            length: a.xy_distance(b),
            turning: angle_distance(a.yaw, b.yaw),
        }
    }

    /// A lower bound of the planar length of every feasible path from `a` to `b` that
    /// is also the length of the shortest one where the model knows it (a curve of
    /// bounded curvature: the Dubins or Reeds–Shepp length); at least `‖Δxy‖`.
    /// Objectives build their admissible bounds on it.
    fn length_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        a.xy_distance(b)
    }

    /// A lower bound of `distance(a, b)` cheaper than the distance itself, for nearest
    /// neighbour searches of non-holonomic models (default: the additive bound of
    /// `lower_bound_weights`). Curvature-limited models: `max(‖Δxy‖, r·d(yaw))`.
    fn distance_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        let (w_t, w_r) = self.lower_bound_weights();
        w_t * a.xy_distance(b) + w_r * angle_distance(a.yaw, b.yaw)
    }

    /// `distance(a, b)` when it is at most `bound`, else `None`; models whose distance
    /// is costly skip the work a farther answer would need (nearest-neighbour searches
    /// ask with the k-th nearest distance found so far). The answer is bit-identical to
    /// `distance`.
    fn distance_within(&self, a: &Pose2, b: &Pose2, bound: f64) -> Option<f64> {
        let d = self.distance(a, b);
        (d <= bound).then_some(d)
    }

    /// True when the robot drives backwards at fraction `t` of the motion `a → b`
    /// (a Reeds–Shepp gear change); forward-only models never do.
    fn is_reversing(&self, _a: &Pose2, _b: &Pose2, _t: f64) -> bool {
        false
    }

    /// True for holonomic models: straight SE(2) motions (the default
    /// `motion_extent` and `length_bound`) with the heading free of the direction of
    /// travel (legged robots: a waypoint may be turned to face the next one); false for
    /// car-like models, whose plans are their curves sampled, headings untouched.
    fn is_holonomic(&self) -> bool {
        true
    }

    /// The minimum turning radius of a curvature-limited model (metres), `None` for
    /// models that turn on the spot (the default).
    fn turning_radius(&self) -> Option<f64> {
        None
    }

    /// True when the model may drive backwards (Reeds–Shepp); forward-only models and
    /// holonomic ones (the default) say false.
    fn has_reverse_gear(&self) -> bool {
        false
    }

    /// True when a motion's curve, length and turning depend only on where `b` lies
    /// relative to `a` (the motion moved anywhere in the plane is the same motion):
    /// the free-space models; false (the default) for any space that looks at the map.
    fn is_translation_invariant(&self) -> bool {
        false
    }
}

/// How long a local motion is in the plane, and how far its heading turns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionExtent {
    /// Planar length, metres.
    pub length: f64,
    /// Total heading change along the motion, radians (≥ `d(yaw_a, yaw_b)`).
    pub turning: f64,
}

/// Parameters of the OMPL SE(2) space (the weights of its distance).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Se2SpaceParams {
    /// Weight of the Euclidean distance in the plane (OMPL: 1.0).
    pub translation_weight: f64,
    /// Weight of the shortest yaw distance (OMPL: 0.5).
    pub rotation_weight: f64,
}

impl Default for Se2SpaceParams {
    fn default() -> Self {
        Self {
            translation_weight: 1.0,
            rotation_weight: 0.5,
        }
    }
}

/// OMPL's `SE2StateSpace` distance: `w_t·‖Δxy‖₂ + w_r·d(Δyaw)` (Euclidean, not squared).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Se2Space {
    w_t: f64,
    w_r: f64,
}

impl Default for Se2Space {
    fn default() -> Self {
        Self::from_params(Se2SpaceParams::default()).expect("default weights are valid")
    }
}

/// Why SE(2) metric weights are invalid.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum SpaceError {
    /// The translation weight is not finite and > 0.
    #[error("translation_weight must be finite and > 0, got {0}")]
    TranslationWeight(f64),
    /// The rotation weight is not finite and ≥ 0.
    #[error("rotation_weight must be finite and ≥ 0, got {0}")]
    RotationWeight(f64),
}

impl Se2Space {
    /// A metric with the given weights; both must be finite and ≥ 0, `w_t` > 0.
    pub fn new(translation_weight: f64, rotation_weight: f64) -> Result<Self, SpaceError> {
        if !(translation_weight.is_finite() && translation_weight > 0.0) {
            return Err(SpaceError::TranslationWeight(translation_weight));
        }
        if !(rotation_weight.is_finite() && rotation_weight >= 0.0) {
            return Err(SpaceError::RotationWeight(rotation_weight));
        }
        Ok(Self {
            w_t: translation_weight,
            w_r: rotation_weight,
        })
    }

    /// A metric from its config parameters.
    pub fn from_params(p: Se2SpaceParams) -> Result<Self, SpaceError> {
        Self::new(p.translation_weight, p.rotation_weight)
    }
}

impl StateSpace for Se2Space {
    fn is_translation_invariant(&self) -> bool {
        true
    }

    fn distance(&self, a: &Pose2, b: &Pose2) -> f64 {
        self.w_t * a.xy_distance(b) + self.w_r * angle_distance(a.yaw, b.yaw)
    }

    fn interpolate(&self, a: &Pose2, b: &Pose2, t: f64) -> Pose2 {
        if t <= 0.0 {
            return *a;
        }
        if t >= 1.0 {
            return *b;
        }
        let dyaw = wrap_angle(b.yaw - a.yaw);
        Pose2::new(
            a.x + (b.x - a.x) * t,
            a.y + (b.y - a.y) * t,
            a.yaw + dyaw * t,
        )
    }

    fn lower_bound_weights(&self) -> (f64, f64) {
        (self.w_t, self.w_r)
    }
}

#[cfg(test)]
mod tests;
