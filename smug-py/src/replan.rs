//! `smug.replan`: the rest of a mission from a mission state file, as `smug replan`.

use crate::{load, to_py, InputError, PyWorld};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use smug_core::mission::{assemble_replan, replan_mission, MissionState};
use smug_core::Error;
use std::path::PathBuf;

/// Replans a mission from a state file; returns `(plan.json text, waypoints (n, 4), world)`.
#[pyfunction]
#[pyo3(signature = (config, state, set=Vec::new(), seed=None))]
pub(crate) fn replan<'py>(
    py: Python<'py>,
    config: PathBuf,
    state: PathBuf,
    set: Vec<String>,
    seed: Option<u64>,
) -> PyResult<(String, Bound<'py, PyArray2<f64>>, PyWorld)> {
    let loaded = load(&config, set, seed)?;
    let parsed = MissionState::from_file(&state).map_err(|e| InputError::new_err(e.to_string()))?;
    let name = state.display().to_string();
    let planned = py.detach(|| {
        let mut pipeline = assemble_replan(&loaded, &parsed, &name)?;
        let options = pipeline.config.plan;
        let plan = replan_mission(&mut pipeline, options, &parsed)?;
        Ok::<_, Error>((plan, pipeline.world.clone()))
    });
    let (mut plan, world) = planned.map_err(to_py)?;
    if let Some(info) = plan.replan.as_mut() {
        info.state_file = Some(name);
    }
    let world = world.ok_or_else(|| InputError::new_err("the config has no [world] section"))?;
    let text = serde_json::to_string_pretty(&plan)
        .map_err(|e| InputError::new_err(format!("cannot write the plan as JSON: {e}")))?;
    let waypoints = Array2::from_shape_fn((plan.waypoints.len(), 4), |(k, c)| {
        let w = &plan.waypoints[k];
        [w.x, w.y, w.z, w.yaw][c]
    })
    .into_pyarray(py);
    Ok((text, waypoints, PyWorld { inner: world }))
}
