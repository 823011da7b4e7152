//! An out-of-tree SMUG objective, one file: length with a penalty for steep ground,
//! registered by name, selectable from any config:
//!
//! ```toml
//! [objective]
//! type = "example-steepness"
//! params = { penalty = 2.0 }
//! ```
//!
//! A motion costs `∫ (1 + penalty·|slope|) ds` along the space's motion; every piece
//! costs at least its length, so the space's `length_bound` is an admissible and
//! consistent bound. A binary picks it up by linking this crate
//! (`use smug_example_objective as _;`).

#![warn(missing_docs)]

use serde::{Deserialize, Serialize};
use smug_core::objective::{check_non_negative, check_positive, integrate_motion};
use smug_core::{BuildContext, Objective, Pose2, Result, StateSpace, World};
use std::sync::Arc;

/// Parameters of `example-steepness`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SteepnessParams {
    /// Extra cost per metre per unit of slope (rise over run).
    pub penalty: f64,
    /// Integration step along a motion (space distance).
    pub step: f64,
}

impl Default for SteepnessParams {
    fn default() -> Self {
        Self {
            penalty: 2.0,
            step: 0.25,
        }
    }
}

/// Length weighted by `1 + penalty·|slope|`.
#[derive(Debug)]
pub struct Steepness {
    params: SteepnessParams,
    world: Arc<World>,
    space: Arc<dyn StateSpace>,
}

impl Steepness {
    /// The objective on `world`'s elevation along the motions of `space`.
    pub fn new(
        params: SteepnessParams,
        world: Arc<World>,
        space: Arc<dyn StateSpace>,
    ) -> Result<Self> {
        check_non_negative("objective", "penalty", params.penalty)?;
        check_positive("objective", "step", params.step)?;
        Ok(Self {
            params,
            world,
            space,
        })
    }

    /// `|Δz| / run` between two states (0 where a height is unknown or they coincide).
    fn slope(&self, from: &Pose2, to: &Pose2) -> f64 {
        let run = from.xy_distance(to);
        match (
            self.world.height_at(from.x, from.y),
            self.world.height_at(to.x, to.y),
        ) {
            (Some(a), Some(b)) if run > 0.0 => (b - a).abs() / run,
            _ => 0.0,
        }
    }
}

impl Objective for Steepness {
    fn motion_cost(&self, a: &Pose2, b: &Pose2) -> f64 {
        let penalty = self.params.penalty;
        integrate_motion(self.space.as_ref(), a, b, self.params.step, |piece| {
            piece.length * (1.0 + penalty * self.slope(&piece.from, &piece.to))
        })
    }

    fn cost_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        self.space.length_bound(a, b)
    }

    fn bound_weights(&self) -> (f64, f64) {
        (1.0, 0.0)
    }

    fn is_symmetric(&self) -> bool {
        // The motion b → a is a → b reversed only on symmetric spaces.
        self.space.is_symmetric()
    }
}

fn build(params: SteepnessParams, ctx: &BuildContext) -> Result<Steepness> {
    Steepness::new(params, ctx.world()?, ctx.space())
}

smug_core::register_plugin!(
    smug_core::registry::ObjectiveStage,
    name = "example-steepness",
    summary = "length with a penalty for steep ground, ∫ 1 + penalty·|slope| ds (example)",
    params = SteepnessParams,
    build = |params, ctx| Ok(Box::new(build(params, ctx)?)),
);

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use smug_core::testing::{arb_pose, check_objective, check_objective_path};
    use smug_core::{GridGeometry, GridLayer, Mission, Se2Space};

    /// A 20 × 20 m world of rolling hills.
    fn hills() -> Arc<World> {
        let geometry = GridGeometry::new([-10.0, -10.0], 0.5, [40, 40]).unwrap();
        let elevation = GridLayer::from_fn(geometry, |i, j| {
            ((i as f32 * 0.3).sin() + (j as f32 * 0.2).cos()) * 0.8
        });
        let _mission = Mission {
            start: Pose2::new(0.0, 0.0, 0.0),
            end: None,
            targets: Vec::new(),
        };
        Arc::new(World::new("hills", elevation))
    }

    proptest! {
        #[test]
        fn keeps_the_objective_contract(a in arb_pose(9.0), b in arb_pose(9.0), c in arb_pose(9.0), t in 0.0..1.0f64) {
            let space: Arc<dyn StateSpace> = Arc::new(Se2Space::default());
            let params = SteepnessParams { step: 0.01, ..SteepnessParams::default() };
            let objective = Steepness::new(params, hills(), space.clone()).unwrap();
            check_objective(&objective, space.as_ref(), (&a, &b, &c), t, 0.02)?;
            check_objective_path(&objective, &[a, b, c])?;
        }
    }
}
