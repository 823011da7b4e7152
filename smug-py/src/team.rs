//! `smug.plan`, `smug.replan` and `smug.Session` on a team config: the team plan's
//! JSON (one entry per robot, the Python `Plan.robots`), the shared world, the run's
//! config and seed.

use crate::{app_to_py, solved, InputError, PyWorld};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use smug_app::team::{plan_team_config, Team, TeamPlanned};
use smug_app::team_replan::replan_team;
use smug_app::team_session::TeamSession;
use smug_core::mission::TeamState;
use smug_core::{LoadedConfig, TeamPlan};
use std::path::Path;
use std::sync::Arc;

/// `(plan.json text, waypoints (0, 4), world, (config TOML, seed))`, as `smug.plan`
/// returns for one robot.
pub(crate) type TeamParts<'py> = (String, Bound<'py, PyArray2<f64>>, PyWorld, (String, u64));

/// A team plan as the parts `smug.plan` returns, with no waypoints of its own (each
/// robot's are in `Plan.robots`); the world and mission are `team`'s.
fn team_parts<'py>(
    py: Python<'py>,
    plan: &TeamPlan,
    team: &Team,
    loaded: &LoadedConfig,
) -> PyResult<TeamParts<'py>> {
    let text = serde_json::to_string_pretty(plan)
        .map_err(|e| InputError::new_err(format!("cannot write the plan as JSON: {e}")))?;
    let world = PyWorld {
        world: team.world.clone(),
        mission: Arc::new(team.mission.mission.clone()),
        invalid_pois: Arc::new(Vec::new()),
    };
    let waypoints = Array2::<f64>::zeros((0, 4)).into_pyarray(py);
    let config_toml = smug_core::toml::to_string(&loaded.config).unwrap_or_default();
    Ok((text, waypoints, world, (config_toml, loaded.config.seed)))
}

/// Plans the team of `loaded`.
pub(crate) fn plan_team<'py>(py: Python<'py>, loaded: LoadedConfig) -> PyResult<TeamParts<'py>> {
    let outcome = py.detach(|| plan_team_config(&loaded)).map_err(app_to_py)?;
    let TeamPlanned { plans, team } = solved(outcome)?;
    team_parts(py, &plans[0], &team, &loaded)
}

/// Replans the team of `loaded` from the team state file `state`.
pub(crate) fn replan_team_file<'py>(
    py: Python<'py>,
    loaded: LoadedConfig,
    state: &Path,
) -> PyResult<TeamParts<'py>> {
    let parsed = TeamState::from_file(state).map_err(|e| InputError::new_err(e.to_string()))?;
    let name = state.display().to_string();
    let outcome = py
        .detach(|| replan_team(&loaded, &parsed, Some(&name)))
        .map_err(app_to_py)?
        .map_no_solution(|no_plan| no_plan.why);
    let TeamPlanned { plans, team } = solved(outcome)?;
    team_parts(py, &plans[0], &team, &loaded)
}

/// A team session for `smug.Session`: the team kept in memory across replans.
pub(crate) struct PyTeamSession {
    /// The session.
    inner: TeamSession,
    /// The config it was made from.
    loaded: LoadedConfig,
}

impl PyTeamSession {
    /// Assembles the team of `loaded` and keeps it.
    pub(crate) fn new(py: Python<'_>, loaded: LoadedConfig) -> PyResult<Self> {
        let inner = py.detach(|| TeamSession::new(&loaded)).map_err(app_to_py)?;
        Ok(Self { inner, loaded })
    }

    /// The obstacles the team's world holds.
    pub(crate) fn obstacles(&self) -> &[smug_core::mission::DiscObstacle] {
        self.inner.obstacles()
    }

    /// Plans the whole mission from the robots' starts.
    pub(crate) fn plan<'py>(&mut self, py: Python<'py>) -> PyResult<TeamParts<'py>> {
        let session = &mut self.inner;
        let plan = solved(py.detach(|| session.plan()).map_err(app_to_py)?)?;
        team_parts(py, &plan, self.inner.team(), &self.loaded)
    }

    /// Replans from a team state given as TOML text (`name` stands for it).
    pub(crate) fn replan<'py>(
        &mut self,
        py: Python<'py>,
        state: &str,
        name: &str,
    ) -> PyResult<TeamParts<'py>> {
        let parsed =
            TeamState::from_toml(state, name).map_err(|e| InputError::new_err(e.to_string()))?;
        let session = &mut self.inner;
        let outcome = py
            .detach(|| session.replan(&parsed, name))
            .map_err(app_to_py)?;
        let plan = solved(outcome)?;
        team_parts(py, &plan, self.inner.team(), &self.loaded)
    }
}
