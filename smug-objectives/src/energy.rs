//! `energy`: mechanical work on the terrain. A motion costs
//! `μ·m·g·length + m·g·Σ max(0, Δz)` along the space's motion (uphill work counted,
//! downhill not recovered), so it is asymmetric; the bound is
//! `μ·m·g·‖Δxy‖ + m·g·max(0, z_b − z_a)` (consistent: heights telescope).

use crate::terrain::Terrain;
use serde::{Deserialize, Serialize};
use smug_core::objective::{check_non_negative, check_positive, integrate_motion};
use smug_core::{BuildContext, Objective, Pose2, Result, StateSpace};
use std::sync::Arc;

/// Parameters of `energy` (SI units: joules).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EnergyParams {
    /// Robot mass, kg (ANYmal: 50).
    pub mass: f64,
    /// Cost of transport on flat ground `μ` (walking/rolling resistance, dimensionless).
    pub friction: f64,
    /// Gravity, m/s².
    pub gravity: f64,
    /// Integration step along a motion (space distance).
    pub step: f64,
}

impl Default for EnergyParams {
    fn default() -> Self {
        Self {
            mass: 50.0,
            friction: 0.3,
            gravity: 9.81,
            step: 0.2,
        }
    }
}

/// Flat-ground work plus uphill work.
#[derive(Debug)]
pub struct Energy {
    params: EnergyParams,
    terrain: Terrain,
    space: Arc<dyn StateSpace>,
}

impl Energy {
    /// The objective on `terrain` along the motions of `space`.
    pub fn new(params: EnergyParams, terrain: Terrain, space: Arc<dyn StateSpace>) -> Result<Self> {
        check_positive("objective", "mass", params.mass)?;
        check_positive("objective", "friction", params.friction)?;
        check_positive("objective", "gravity", params.gravity)?;
        check_positive("objective", "step", params.step)?;
        check_non_negative("objective", "mass × gravity", params.mass * params.gravity)?;
        Ok(Self {
            params,
            terrain,
            space,
        })
    }

    fn weight(&self) -> f64 {
        self.params.mass * self.params.gravity
    }
}

impl Objective for Energy {
    fn motion_cost(&self, a: &Pose2, b: &Pose2) -> f64 {
        let (mg, mu) = (self.weight(), self.params.friction);
        // Climbs between consecutive known heights: where a curve leaves the known
        // ground (off the map), the climb resumes from the last height known, so the
        // total is never below the net rise of the bound.
        let mut last = self.terrain.height(a.x, a.y);
        integrate_motion(self.space.as_ref(), a, b, self.params.step, |piece| {
            let to = self.terrain.height(piece.to.x, piece.to.y);
            let climb = match (last, to) {
                (Some(z0), Some(z1)) => (z1 - z0).max(0.0),
                _ => 0.0,
            };
            last = to.or(last);
            mu * mg * piece.length + mg * climb
        })
    }

    fn cost_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        let (mg, mu) = (self.weight(), self.params.friction);
        let climb = self.terrain.rise((a.x, a.y), (b.x, b.y)).max(0.0);
        mu * mg * self.space.length_bound(a, b) + mg * climb
    }

    fn bound_weights(&self) -> (f64, f64) {
        (self.params.friction * self.weight(), 0.0)
    }

    fn is_symmetric(&self) -> bool {
        false
    }
}

fn build(params: EnergyParams, ctx: &BuildContext) -> Result<Energy> {
    let terrain = Terrain::new(ctx.world()?, "energy", false)?;
    Energy::new(params, terrain, ctx.space())
}

smug_core::register_plugin!(
    smug_core::registry::ObjectiveStage,
    name = "energy",
    summary = "work μ·m·g·length + m·g·Σ max(0, Δz) (climbing costs; asymmetric); bound μmg‖Δxy‖ + mg·max(0, Δz)",
    params = EnergyParams,
    build = |params, ctx| Ok(Box::new(build(params, ctx)?)),
);
