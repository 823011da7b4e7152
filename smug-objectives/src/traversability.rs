//! `traversability`: risk-aware length. A motion costs
//! `∫ w_t·(1 + w·(1 − τ)^p) ds + w_r·Σ d(Δyaw)` along the space's motion, with τ the
//! traversability under the robot; the bound is the SE(2) length (the factor is ≥ 1).

use crate::terrain::Terrain;
use serde::{Deserialize, Serialize};
use smug_core::objective::{check_non_negative, check_positive, integrate_motion};
use smug_core::pose::angle_distance;
use smug_core::{BuildContext, Objective, Pose2, Result, StateSpace};
use std::sync::Arc;

/// Parameters of `traversability`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RiskAwareParams {
    /// Cost per metre on perfect ground (τ = 1).
    pub translation_weight: f64,
    /// Cost per radian of yaw change.
    pub rotation_weight: f64,
    /// `w`: extra cost per metre at τ = 0, relative to perfect ground.
    pub risk_weight: f64,
    /// `p`: how sharply the extra cost grows as τ falls (1 = linear).
    pub exponent: f64,
    /// Integration step along a motion (space distance).
    pub step: f64,
}

impl Default for RiskAwareParams {
    fn default() -> Self {
        Self {
            translation_weight: 1.0,
            rotation_weight: 0.5,
            risk_weight: 4.0,
            exponent: 2.0,
            step: 0.2,
        }
    }
}

/// Length weighted by `1 + w·(1 − τ)^p`.
#[derive(Debug)]
pub struct RiskAware {
    params: RiskAwareParams,
    terrain: Terrain,
    space: Arc<dyn StateSpace>,
}

impl RiskAware {
    /// The objective on `terrain` along the motions of `space`.
    pub fn new(
        params: RiskAwareParams,
        terrain: Terrain,
        space: Arc<dyn StateSpace>,
    ) -> Result<Self> {
        check_positive("objective", "translation_weight", params.translation_weight)?;
        check_non_negative("objective", "rotation_weight", params.rotation_weight)?;
        check_non_negative("objective", "risk_weight", params.risk_weight)?;
        check_positive("objective", "exponent", params.exponent)?;
        check_positive("objective", "step", params.step)?;
        Ok(Self {
            params,
            terrain,
            space,
        })
    }

    /// The cost factor at `(x, y)`: `1 + w·(1 − τ)^p`.
    fn factor(&self, x: f64, y: f64) -> f64 {
        let risk = 1.0 - self.terrain.traversability(x, y);
        1.0 + self.params.risk_weight * risk.powf(self.params.exponent)
    }
}

impl Objective for RiskAware {
    fn motion_cost(&self, a: &Pose2, b: &Pose2) -> f64 {
        let p = &self.params;
        integrate_motion(self.space.as_ref(), a, b, p.step, |piece| {
            p.translation_weight * piece.length * self.factor(piece.middle.x, piece.middle.y)
                + p.rotation_weight * angle_distance(piece.from.yaw, piece.to.yaw)
        })
    }

    fn cost_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        let p = &self.params;
        p.translation_weight * self.space.length_bound(a, b)
            + p.rotation_weight * angle_distance(a.yaw, b.yaw)
    }

    fn bound_weights(&self) -> (f64, f64) {
        (self.params.translation_weight, self.params.rotation_weight)
    }

    fn is_symmetric(&self) -> bool {
        // The motion b → a is a → b reversed only on symmetric spaces.
        self.space.is_symmetric()
    }
}

fn build(params: RiskAwareParams, ctx: &BuildContext) -> Result<RiskAware> {
    let terrain = Terrain::new(ctx.world()?, "traversability", true)?;
    RiskAware::new(params, terrain, ctx.space())
}

smug_core::register_plugin!(
    smug_core::registry::ObjectiveStage,
    name = "traversability",
    summary = "risk-aware length ∫ 1 + w·(1 − τ)^p ds (keeps to safer ground); bound = length",
    params = RiskAwareParams,
    build = |params, ctx| Ok(Box::new(build(params, ctx)?)),
);
