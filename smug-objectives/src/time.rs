//! `time`: travel time. A motion costs `∫ ds / v(τ, slope) + Σ d(Δyaw) / ω` along the
//! space's motion, with a speed that falls on poor and steep ground:
//! `v = v_max · (f + (1 − f)·τ) · max(f, 1 − |slope| / max_slope)`, `f` the slowest
//! fraction of `v_max`; the bound is `‖Δxy‖ / v_max + d(Δyaw) / ω`.

use crate::terrain::Terrain;
use serde::{Deserialize, Serialize};
use smug_core::objective::{check_positive, integrate_motion};
use smug_core::pose::angle_distance;
use smug_core::{BuildContext, Error, Objective, Pose2, Result, StateSpace};
use std::sync::Arc;

/// Parameters of `time` (seconds, metres, radians).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TravelTimeParams {
    /// Top speed on perfect flat ground, m/s.
    pub max_speed: f64,
    /// Turning rate, rad/s.
    pub turn_rate: f64,
    /// The slowest speed as a fraction of `max_speed` (at τ = 0, or at `max_slope`), in (0, 1].
    pub min_speed_fraction: f64,
    /// Slope (rise over run) at which the slope alone slows to `min_speed_fraction`.
    pub max_slope: f64,
    /// Integration step along a motion (space distance).
    pub step: f64,
}

impl Default for TravelTimeParams {
    fn default() -> Self {
        Self {
            max_speed: 1.0,
            turn_rate: 1.0,
            min_speed_fraction: 0.2,
            max_slope: 0.6,
            step: 0.2,
        }
    }
}

/// Travel time with a terrain-dependent speed.
#[derive(Debug)]
pub struct TravelTime {
    params: TravelTimeParams,
    terrain: Terrain,
    space: Arc<dyn StateSpace>,
}

impl TravelTime {
    /// The objective on `terrain` along the motions of `space`.
    pub fn new(
        params: TravelTimeParams,
        terrain: Terrain,
        space: Arc<dyn StateSpace>,
    ) -> Result<Self> {
        check_positive("objective", "max_speed", params.max_speed)?;
        check_positive("objective", "turn_rate", params.turn_rate)?;
        check_positive("objective", "max_slope", params.max_slope)?;
        check_positive("objective", "step", params.step)?;
        let f = params.min_speed_fraction;
        if !(f.is_finite() && f > 0.0 && f <= 1.0) {
            return Err(Error::invalid_param(
                "objective",
                format!("min_speed_fraction must be in (0, 1], got {f}"),
            ));
        }
        Ok(Self {
            params,
            terrain,
            space,
        })
    }

    /// Speed at `mid` heading from `from` to `to`; the slope is measured over a fixed
    /// baseline of one `step` along the heading, whatever the piece's length (so the
    /// cost is a line integral, additive over split motions up to discretisation).
    fn speed(&self, from: &Pose2, to: &Pose2, mid: &Pose2) -> f64 {
        let p = &self.params;
        let f = p.min_speed_fraction;
        let tau = self.terrain.traversability(mid.x, mid.y);
        let run = from.xy_distance(to);
        let slope = if run > 0.0 {
            let h = 0.5 * p.step / run;
            let (dx, dy) = ((to.x - from.x) * h, (to.y - from.y) * h);
            let rise = self
                .terrain
                .rise((mid.x - dx, mid.y - dy), (mid.x + dx, mid.y + dy));
            rise.abs() / p.step
        } else {
            0.0
        };
        let ground = f + (1.0 - f) * tau;
        let steepness = (1.0 - slope / p.max_slope).max(f);
        p.max_speed * ground * steepness
    }
}

impl Objective for TravelTime {
    fn motion_cost(&self, a: &Pose2, b: &Pose2) -> f64 {
        let p = &self.params;
        integrate_motion(self.space.as_ref(), a, b, p.step, |piece| {
            piece.length / self.speed(&piece.from, &piece.to, &piece.middle)
                + angle_distance(piece.from.yaw, piece.to.yaw) / p.turn_rate
        })
    }

    fn cost_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        let p = &self.params;
        self.space.length_bound(a, b) / p.max_speed + angle_distance(a.yaw, b.yaw) / p.turn_rate
    }

    fn bound_weights(&self) -> (f64, f64) {
        (1.0 / self.params.max_speed, 1.0 / self.params.turn_rate)
    }

    fn is_symmetric(&self) -> bool {
        // The motion b → a is a → b reversed only on symmetric spaces.
        self.space.is_symmetric()
    }
}

fn build(params: TravelTimeParams, ctx: &BuildContext) -> Result<TravelTime> {
    let terrain = Terrain::new(ctx.world()?, "time", true)?;
    TravelTime::new(params, terrain, ctx.space())
}

smug_core::register_plugin!(
    smug_core::registry::ObjectiveStage,
    name = "time",
    summary = "travel time ∫ ds / v(τ, slope) + turning, v ≤ max_speed; bound ‖Δxy‖ / max_speed",
    params = TravelTimeParams,
    build = |params, ctx| Ok(Box::new(build(params, ctx)?)),
);
