//! `smug.plan` (with `save_roadmap=`: the roadmap file `smug plan --save-roadmap`
//! writes), `smug.replan`: the rest of a mission from a mission state, as `smug replan`
//! (with `roadmap=`: on a saved roadmap), and `smug.Session`: a mission session kept in
//! memory across replans.

use crate::team::PyTeamSession;
use crate::{app_to_py, load, raise, solved, to_py, InputError, PyEstimator, PyWorld};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use smug_app::replan::ReplanRequest;
use smug_app::MissionSession;
use smug_core::mission::MissionState;
use smug_core::{Pipeline, Plan, TraversabilityEstimator};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// What the Python side gets for a plan: `(plan.json text, waypoints (n, 4), world,
/// (config TOML, seed))`.
type PlanParts<'py> = (String, Bound<'py, PyArray2<f64>>, PyWorld, (String, u64));

/// The plan as Python parts.
fn parts<'py>(py: Python<'py>, plan: &Plan, pipeline: &Pipeline) -> PyResult<PlanParts<'py>> {
    let text = smug_app::outputs::plan_json(plan)
        .map_err(|e| InputError::new_err(format!("cannot write the plan as JSON: {e}")))?;
    let waypoints = Array2::from_shape_fn((plan.waypoints.len(), 4), |(k, c)| {
        let w = &plan.waypoints[k];
        [w.x, w.y, w.z, w.yaw][c]
    })
    .into_pyarray(py);
    let run = smug_app::outputs::run_info(pipeline, smug_app::plan_mcap::WriteMode::Replace);
    Ok((
        text,
        waypoints,
        PyWorld::of(pipeline)?,
        (run.config_toml, run.seed),
    ))
}

/// Plans a mission (saving the planner's roadmap to `save_roadmap` when given);
/// returns `(plan.json text, waypoints (n, 4), world, (config TOML, seed))`.
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
    if smug_app::team::is_team(&loaded) && world.is_none() && traversability.is_none() {
        return crate::team::plan_team(py, loaded);
    }
    let given_world = world.map(|w| ((*w.world).clone(), Some((*w.mission).clone())));
    let raised = Arc::new(Mutex::new(None));
    let estimator = traversability.map(|function| {
        let estimator: Box<dyn TraversabilityEstimator> = Box::new(PyEstimator {
            function,
            raised: raised.clone(),
        });
        ("python", estimator)
    });
    let planned = py.detach(move || -> smug_app::Result<_> {
        let outcome = smug_app::plan(&loaded, given_world, estimator)?;
        let smug_app::Outcome::Solved(planned) = &outcome else {
            return Ok((outcome, None));
        };
        let saved = save_roadmap
            .as_deref()
            .map(|file| smug_app::save_roadmap(&planned.pipeline, &loaded, &planned.world, file))
            .and_then(Result::err);
        Ok((outcome, saved))
    });
    let (outcome, saved) = planned.map_err(|err| raise(&raised, app_to_py(err)))?;
    let planned = solved(outcome).map_err(|err| raise(&raised, err))?;
    if let Some(refused) = saved {
        return Err(app_to_py(refused));
    }
    parts(py, &planned.plan, &planned.pipeline)
}

/// Replans a mission from a state file (on the roadmap file `roadmap` when given);
/// returns `(plan.json text, waypoints (n, 4), world, (config TOML, seed))`.
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
    if smug_app::team::is_team(&loaded) {
        if roadmap.is_some() {
            return Err(InputError::new_err(
                "roadmap: a team has one roadmap per robot; not supported yet",
            ));
        }
        return crate::team::replan_team_file(py, loaded, &state);
    }
    let request = ReplanRequest {
        state: &state,
        roadmap: roadmap.as_deref(),
    };
    let planned = py
        .detach(|| smug_app::replan(&loaded, &request, &mut |_| {}))
        .map_err(app_to_py)?;
    let planned = solved(planned)?;
    parts(py, &planned.plan, &planned.pipeline)
}

/// What a session keeps: one robot's pipeline, or a team's.
enum Kept {
    /// One robot.
    One(Box<MissionSession>),
    /// A team config.
    Team(Box<PyTeamSession>),
}

/// A mission session: the pipeline assembled once and kept in memory, the mission
/// planned, then replanned in place for each mission state (see `MissionSession`); on
/// a team config, every robot's pipeline (see `TeamSession`).
#[pyclass(name = "Session", module = "smug")]
pub struct PySession {
    inner: Kept,
}

#[pymethods]
impl PySession {
    /// Assembles the pipeline of `config` (with overrides and seed) and keeps it.
    #[new]
    #[pyo3(signature = (config, set=Vec::new(), seed=None))]
    fn new(py: Python<'_>, config: PathBuf, set: Vec<String>, seed: Option<u64>) -> PyResult<Self> {
        let loaded = load(&config, set, seed)?;
        let inner = if smug_app::team::is_team(&loaded) {
            Kept::Team(Box::new(PyTeamSession::new(py, loaded)?))
        } else {
            Kept::One(Box::new(
                py.detach(|| MissionSession::new(&loaded)).map_err(to_py)?,
            ))
        };
        Ok(Self { inner })
    }

    /// Plans the whole mission (as `smug plan`); returns the plan's parts.
    fn plan<'py>(&mut self, py: Python<'py>) -> PyResult<PlanParts<'py>> {
        match &mut self.inner {
            Kept::One(session) => {
                let plan = py.detach(|| session.plan()).map_err(to_py)?;
                parts(py, &plan, session.pipeline())
            }
            Kept::Team(team) => team.plan(py),
        }
    }

    /// Replans from a mission state given as TOML text (`name` stands for it in
    /// errors; a team state on a team config); returns the plan's parts.
    fn replan<'py>(
        &mut self,
        py: Python<'py>,
        state: &str,
        name: &str,
    ) -> PyResult<PlanParts<'py>> {
        let session = match &mut self.inner {
            Kept::One(session) => session,
            Kept::Team(team) => return team.replan(py, state, name),
        };
        let parsed =
            MissionState::from_toml(state, name).map_err(|e| InputError::new_err(e.to_string()))?;
        let plan = py.detach(|| session.replan(&parsed)).map_err(to_py)?;
        parts(py, &plan, session.pipeline())
    }

    /// The obstacles applied so far, as `(x, y, radius, height)` tuples.
    fn obstacles(&self) -> Vec<(f64, f64, f64, f64)> {
        let obstacles = match &self.inner {
            Kept::One(session) => session.obstacles(),
            Kept::Team(team) => team.obstacles(),
        };
        obstacles
            .iter()
            .map(|o| (o.center[0], o.center[1], o.radius, o.height))
            .collect()
    }

    /// The number of paths kept from earlier plans (each direction counts; 0 for a
    /// team, which keeps its robots' roadmaps, not their paths).
    fn known_paths(&self) -> usize {
        match &self.inner {
            Kept::One(session) => session.known_paths(),
            Kept::Team(_) => 0,
        }
    }
}
