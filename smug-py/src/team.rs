//! `smug.plan` on a team config: the team plan's JSON (one entry per robot, the
//! Python `Plan.robots`), the shared world, the run's config and seed.

use crate::{app_to_py, solved, InputError, PyWorld};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use smug_app::team::{plan_team_config, TeamPlanned};
use smug_core::LoadedConfig;
use std::sync::Arc;

/// `(plan.json text, waypoints (0, 4), world, (config TOML, seed))`, as `smug.plan`
/// returns for one robot.
type TeamParts<'py> = (String, Bound<'py, PyArray2<f64>>, PyWorld, (String, u64));

/// Plans the team of `loaded`; the parts `smug.plan` returns, with no waypoints of
/// its own (each robot's are in `Plan.robots`).
pub(crate) fn plan_team<'py>(py: Python<'py>, loaded: LoadedConfig) -> PyResult<TeamParts<'py>> {
    let seed = loaded.config.seed;
    let config_toml = smug_core::toml::to_string(&loaded.config).unwrap_or_default();
    let outcome = py
        .detach(move || plan_team_config(&loaded))
        .map_err(app_to_py)?;
    let TeamPlanned { plans, team } = solved(outcome)?;
    let text = serde_json::to_string_pretty(&plans[0])
        .map_err(|e| InputError::new_err(format!("cannot write the plan as JSON: {e}")))?;
    let world = PyWorld {
        world: team.world.clone(),
        mission: Arc::new(team.mission.mission.clone()),
        invalid_pois: Arc::new(Vec::new()),
    };
    let waypoints = Array2::<f64>::zeros((0, 4)).into_pyarray(py);
    Ok((text, waypoints, world, (config_toml, seed)))
}
