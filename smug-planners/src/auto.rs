//! `auto`: the exact `visibility` planner where it applies (a disc on a flat occupancy
//! grid, straight holonomic motions, the path-length objective), the `lattice` planner
//! (its default parameters) for curvature-limited models (Dubins, Reeds–Shepp), else
//! LazyPRM* with the given parameters (LazyPRM*'s own: a config switches by its `type`
//! alone). A config that pins LazyPRM*'s parameters for a holonomic robot keeps its
//! plans, and swapping the robot for a car by its `space` alone gets a planner for cars.

use crate::lattice::{self, LatticeParams};
use crate::lazy_prm_star::{self, LazyPrmStarParams};
use crate::visibility::{build_exact, VisibilityParams};
use serde::{Deserialize, Serialize};
use smug_core::{BuildContext, PointToPointPlanner, Result};

/// Parameters of `auto`: LazyPRM*'s, used where the exact planner does not apply.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct AutoParams(pub LazyPrmStarParams);

/// The exact planner if it applies to the pipeline of `ctx`, the lattice for a
/// curvature-limited model, else LazyPRM*.
pub fn build_auto(params: AutoParams, ctx: &BuildContext) -> Result<Box<dyn PointToPointPlanner>> {
    if ctx.space().turning_radius().is_some() {
        return Ok(Box::new(lattice::build_planner(
            LatticeParams::default(),
            ctx,
        )?));
    }
    Ok(match build_exact(VisibilityParams::default(), ctx)? {
        Ok(exact) => Box::new(exact),
        Err(_) => Box::new(lazy_prm_star::build_planner(params.0, ctx)?),
    })
}

smug_core::register_plugin!(
    smug_core::registry::PlannerStage,
    name = "auto",
    summary = "exact `visibility` where it applies (disc on a grid, straight motions, path length), `lattice` for cars (dubins, reeds-shepp), else LazyPRM* (its params)",
    params = AutoParams,
    build = |params, ctx| build_auto(params, ctx),
);
