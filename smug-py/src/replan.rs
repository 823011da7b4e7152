//! `smug.plan` (with `save_roadmap=`: the roadmap file `smug plan --save-roadmap`
//! writes), `smug.replan`: the rest of a mission from a mission state, as `smug replan`
//! (with `roadmap=`: on a saved roadmap), and `smug.Session`: a mission session kept in
//! memory across replans.

use crate::{load, one_line, raise, to_py, ConfigError, InputError, PyEstimator, PyWorld};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use smug_core::mission::{
    assemble_replan_fingerprinted, changed_discs, replan_mission, MissionSession, MissionState,
};
use smug_core::{
    plan_mission, Error, Fingerprint, LoadedConfig, Pipeline, Plan, TraversabilityEstimator, World,
};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// What the Python side gets for a plan: `(plan.json text, waypoints (n, 4), world)`.
type PlanParts<'py> = (String, Bound<'py, PyArray2<f64>>, PyWorld);

/// The plan as Python parts.
fn parts<'py>(py: Python<'py>, plan: &Plan, world: Arc<World>) -> PyResult<PlanParts<'py>> {
    let text = serde_json::to_string_pretty(plan)
        .map_err(|e| InputError::new_err(format!("cannot write the plan as JSON: {e}")))?;
    let waypoints = Array2::from_shape_fn((plan.waypoints.len(), 4), |(k, c)| {
        let w = &plan.waypoints[k];
        [w.x, w.y, w.z, w.yaw][c]
    })
    .into_pyarray(py);
    Ok((text, waypoints, PyWorld { inner: world }))
}

/// Why a roadmap could not be saved or loaded (a Python `InputError`, the CLI's exit 2).
#[derive(Debug)]
pub(crate) struct RoadmapError(pub String);

impl From<RoadmapError> for PyErr {
    fn from(e: RoadmapError) -> Self {
        InputError::new_err(e.0)
    }
}

/// Writes the planner's roadmap after a mission to `file`, fingerprinted for `loaded`
/// on `world` (the world the plan was made in), as `smug plan --save-roadmap` does.
pub(crate) fn write_roadmap(
    pipeline: &Pipeline,
    loaded: &LoadedConfig,
    world: &World,
    file: &Path,
) -> Result<(), RoadmapError> {
    let snapshot = pipeline
        .planner
        .as_ref()
        .and_then(|p| p.save_roadmap())
        .ok_or_else(|| {
            RoadmapError(format!(
                "{}: cannot save a roadmap: the configured planner keeps none",
                file.display()
            ))
        })?;
    smug_core::write_roadmap(file, &snapshot, &Fingerprint::of(loaded, world))
        .map_err(|e| RoadmapError(one_line(&e)))
}

/// Plans a mission (saving the planner's roadmap to `save_roadmap` when given);
/// returns `(plan.json text, waypoints (n, 4), world)`.
#[pyfunction]
#[pyo3(signature = (config, set=Vec::new(), seed=None, world=None, traversability=None, save_roadmap=None))]
pub fn plan<'py>(
    py: Python<'py>,
    config: PathBuf,
    set: Vec<String>,
    seed: Option<u64>,
    world: Option<PyRef<'py, PyWorld>>,
    traversability: Option<Py<PyAny>>,
    save_roadmap: Option<PathBuf>,
) -> PyResult<PlanParts<'py>> {
    let loaded = load(&config, set, seed)?;
    let given_world = world.map(|w| (*w.inner).clone());
    let raised = Arc::new(Mutex::new(None));
    let estimator = traversability.map(|function| {
        let estimator: Box<dyn TraversabilityEstimator> = Box::new(PyEstimator {
            function,
            raised: raised.clone(),
        });
        ("python", estimator)
    });
    let planned = py.detach(move || {
        let mut pipeline = Pipeline::assemble_with(&loaded, given_world, estimator)?;
        let options = pipeline.config.plan;
        let plan = plan_mission(&mut pipeline, options)?;
        let world = pipeline.world.clone();
        let saved = match (&save_roadmap, &world) {
            (Some(file), Some(world)) => write_roadmap(&pipeline, &loaded, world, file).err(),
            _ => None,
        };
        Ok::<_, Error>((plan, world, saved))
    });
    let (plan, world, saved) = planned.map_err(|err| raise(&raised, err))?;
    if let Some(refused) = saved {
        return Err(refused.into());
    }
    let world = world.ok_or_else(|| ConfigError::new_err("the config has no [world] section"))?;
    parts(py, &plan, world)
}

/// Replans a mission from a state file (on the roadmap file `roadmap` when given);
/// returns `(plan.json text, waypoints (n, 4), world)`.
#[pyfunction]
#[pyo3(signature = (config, state, set=Vec::new(), seed=None, roadmap=None))]
pub fn replan<'py>(
    py: Python<'py>,
    config: PathBuf,
    state: PathBuf,
    set: Vec<String>,
    seed: Option<u64>,
    roadmap: Option<PathBuf>,
) -> PyResult<PlanParts<'py>> {
    let loaded = load(&config, set, seed)?;
    let parsed = MissionState::from_file(&state).map_err(|e| InputError::new_err(e.to_string()))?;
    let name = state.display().to_string();
    let planned = py.detach(|| {
        let (mut pipeline, fingerprint) =
            assemble_replan_fingerprinted(&loaded, &parsed, &name).map_err(to_py)?;
        if let Some(file) = &roadmap {
            let snapshot = smug_core::read_roadmap(file, &fingerprint)
                .map_err(|e| RoadmapError(one_line(&e)))?;
            let changed = changed_discs(&parsed, &loaded.config.robot);
            let planner = pipeline.planner.as_mut().ok_or_else(|| {
                RoadmapError(format!("{}: the config has no planner", file.display()))
            })?;
            planner
                .load_roadmap(snapshot, &changed)
                .map_err(|e| RoadmapError(format!("{}: {}", file.display(), one_line(&e))))?;
        }
        let options = pipeline.config.plan;
        let plan = replan_mission(&mut pipeline, options, &parsed).map_err(to_py)?;
        Ok::<_, PyErr>((plan, pipeline.world.clone()))
    });
    let (mut plan, world) = planned?;
    if let Some(info) = plan.replan.as_mut() {
        info.state_file = Some(name);
    }
    let world = world.ok_or_else(|| InputError::new_err("the config has no [world] section"))?;
    parts(py, &plan, world)
}

/// A mission session: the pipeline assembled once and kept in memory, the mission
/// planned, then replanned in place for each mission state (see `MissionSession`).
#[pyclass(name = "Session", module = "smug")]
pub struct PySession {
    inner: MissionSession,
}

#[pymethods]
impl PySession {
    /// Assembles the pipeline of `config` (with overrides and seed) and keeps it.
    #[new]
    #[pyo3(signature = (config, set=Vec::new(), seed=None))]
    fn new(py: Python<'_>, config: PathBuf, set: Vec<String>, seed: Option<u64>) -> PyResult<Self> {
        let loaded = load(&config, set, seed)?;
        let inner = py.detach(|| MissionSession::new(&loaded)).map_err(to_py)?;
        Ok(Self { inner })
    }

    /// Plans the whole mission (as `smug plan`); returns the plan's parts.
    fn plan<'py>(&mut self, py: Python<'py>) -> PyResult<PlanParts<'py>> {
        let session = &mut self.inner;
        let plan = py.detach(|| session.plan()).map_err(to_py)?;
        let world = self.inner.world().map_err(to_py)?.clone();
        parts(py, &plan, world)
    }

    /// Replans from a mission state given as TOML text (`name` stands for it in
    /// errors); returns the plan's parts.
    fn replan<'py>(
        &mut self,
        py: Python<'py>,
        state: &str,
        name: &str,
    ) -> PyResult<PlanParts<'py>> {
        let parsed =
            MissionState::from_toml(state, name).map_err(|e| InputError::new_err(e.to_string()))?;
        let session = &mut self.inner;
        let plan = py.detach(|| session.replan(&parsed)).map_err(to_py)?;
        let world = self.inner.world().map_err(to_py)?.clone();
        parts(py, &plan, world)
    }

    /// The obstacles applied so far, as `(x, y, radius, height)` tuples.
    fn obstacles(&self) -> Vec<(f64, f64, f64, f64)> {
        self.inner
            .obstacles()
            .iter()
            .map(|o| (o.center[0], o.center[1], o.radius, o.height))
            .collect()
    }

    /// The number of paths kept from earlier plans (each direction counts).
    fn known_paths(&self) -> usize {
        self.inner.known_paths()
    }
}
