//! `path-length`: `w_t·length + w_r·turning` of the space's motions; for straight SE(2)
//! motions that is `w_t·‖Δxy‖ + w_r·d(Δyaw)` (OMPL's path length under its SE(2)
//! distance) and the bound is the cost itself; for curved models the bound is
//! `w_t·length_bound + w_r·d(Δyaw)` (the shortest feasible curve).

use super::{check_non_negative, check_positive, Objective};
use crate::pose::{angle_distance, Pose2};
use crate::space::StateSpace;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Parameters of `path-length`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PathLengthParams {
    /// Cost per metre in the plane (OMPL: 1.0).
    pub translation_weight: f64,
    /// Cost per radian of yaw change (OMPL: 0.5).
    pub rotation_weight: f64,
}

impl Default for PathLengthParams {
    fn default() -> Self {
        Self {
            translation_weight: 1.0,
            rotation_weight: 0.5,
        }
    }
}

/// `w_t·length + w_r·turning` per motion of the space (on `se2`: a metric, so the bound
/// equals the cost).
#[derive(Clone, Debug)]
pub struct PathLength {
    w_t: f64,
    w_r: f64,
    /// The space's motions, when they are not straight SE(2) lines.
    curved: Option<Arc<dyn StateSpace>>,
}

impl Default for PathLength {
    fn default() -> Self {
        Self::from_params(PathLengthParams::default()).expect("default weights are valid")
    }
}

impl PathLength {
    /// The objective with the given weights: `translation_weight` > 0, `rotation_weight` ≥ 0.
    pub fn new(translation_weight: f64, rotation_weight: f64) -> crate::Result<Self> {
        Self::from_params(PathLengthParams {
            translation_weight,
            rotation_weight,
        })
    }

    /// The objective from its parameters on straight SE(2) motions:
    /// `translation_weight` > 0, `rotation_weight` ≥ 0.
    pub fn from_params(p: PathLengthParams) -> crate::Result<Self> {
        Ok(Self {
            w_t: check_positive("objective", "translation_weight", p.translation_weight)?,
            w_r: check_non_negative("objective", "rotation_weight", p.rotation_weight)?,
            curved: None,
        })
    }

    /// The same objective along the motions of `space` (holonomic spaces move in
    /// straight lines: their length and turning need no call through the space).
    pub fn on(mut self, space: Arc<dyn StateSpace>) -> Self {
        self.curved = (!space.is_holonomic()).then_some(space);
        self
    }
}

impl Objective for PathLength {
    fn motion_cost(&self, a: &Pose2, b: &Pose2) -> f64 {
        match &self.curved {
            None => self.w_t * a.xy_distance(b) + self.w_r * angle_distance(a.yaw, b.yaw),
            Some(space) => {
                let extent = space.motion_extent(a, b);
                self.w_t * extent.length + self.w_r * extent.turning
            }
        }
    }

    fn cost_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        match &self.curved {
            None => self.motion_cost(a, b),
            Some(space) => {
                self.w_t * space.length_bound(a, b) + self.w_r * angle_distance(a.yaw, b.yaw)
            }
        }
    }

    fn is_symmetric(&self) -> bool {
        self.curved
            .as_ref()
            .is_none_or(|space| space.is_symmetric())
    }

    fn is_translation_invariant(&self) -> bool {
        self.curved
            .as_ref()
            .is_none_or(|space| space.is_translation_invariant())
    }

    fn bound_weights(&self) -> (f64, f64) {
        (self.w_t, self.w_r)
    }

    fn se2_length_weights(&self) -> Option<(f64, f64)> {
        self.curved.is_none().then_some((self.w_t, self.w_r))
    }
}

#[cfg(test)]
mod tests;
