//! The plugins core registers itself: the default space (`se2`) and objective
//! (`path-length`), registered here, above the registry, so that the space and the
//! objective do not import the registry.

use crate::objective::PathLength;
use crate::registry::{ObjectiveStage, SpaceStage};
use crate::space::{Se2Space, Se2SpaceParams};

crate::register_plugin!(
    SpaceStage,
    name = "se2",
    summary =
        "holonomic SE(2) (legged robots): straight lines, OMPL's distance w_t·‖Δxy‖ + w_r·d(Δyaw)",
    params = Se2SpaceParams,
    build = |params, _ctx| {
        let metric = Se2Space::from_params(params)
            .map_err(|message| crate::Error::invalid_param("space", message.to_string()))?;
        Ok(Box::new(metric))
    }
);

crate::register_plugin!(
    ObjectiveStage,
    name = "path-length",
    summary = "SE(2) length w_t·‖Δxy‖ + w_r·d(Δyaw) (today's cost); bound = the cost",
    params = crate::objective::PathLengthParams,
    build = |params, ctx| Ok(Box::new(PathLength::from_params(params)?.on(ctx.space()))),
);
