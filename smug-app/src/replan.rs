//! Replanning the rest of a mission from a mission state file, as `smug replan` and
//! `smug.replan` do.

use crate::no_plan::NoPlan;
use crate::plan::Planned;
use crate::{AppError, Outcome, Result};
use smug_core::mission::MissionState;
use smug_core::LoadedConfig;
use smug_mission::{assemble_replan_fingerprinted, replan_mission_reporting, MissionFailed};
use std::path::Path;

/// What to replan from.
pub struct ReplanRequest<'a> {
    /// The mission state file (TOML): `pose`, `visited`, `failed_pois`, `[[obstacles]]`.
    pub state: &'a Path,
    /// A roadmap file saved after the mission to start from.
    pub roadmap: Option<&'a Path>,
}

/// The stages [`replan`] reports, in order, for a progress display.
pub mod stages {
    /// Building the world with the state's changes, and the checkers.
    pub const ASSEMBLING: &str = "building the updated world and the checkers";
    /// Loading the roadmap file.
    pub const LOADING_ROADMAP: &str = "loading the roadmap";
    /// Replanning.
    pub const REPLANNING: &str = "replanning the remaining targets";
}

/// Replans the targets left in the state file on `loaded`'s pipeline (the plan is
/// marked as a replan of that file); `progress` hears each of [`stages`] as it starts.
pub fn replan(
    loaded: &LoadedConfig,
    request: &ReplanRequest<'_>,
    progress: &mut dyn FnMut(&'static str),
) -> Result<Outcome<Planned>> {
    let state = MissionState::from_file(request.state)?;
    Ok(replan_from(loaded, &state, request, progress)?.map_no_solution(|no_plan| no_plan.why))
}

/// [`replan`] with the state already read from `request.state`; without a plan, also
/// what plan.json reports (what could not be reached, the run's statistics).
pub fn replan_from(
    loaded: &LoadedConfig,
    state: &MissionState,
    request: &ReplanRequest<'_>,
    progress: &mut dyn FnMut(&'static str),
) -> Result<Outcome<Planned, NoPlan>> {
    progress(stages::ASSEMBLING);
    let state_name = request.state.display().to_string();
    let (mut pipeline, fingerprint) = assemble_replan_fingerprinted(loaded, state, &state_name)?;
    if let Some(file) = request.roadmap {
        progress(stages::LOADING_ROADMAP);
        crate::load_roadmap(&mut pipeline, loaded, state, &fingerprint, file)?;
    }
    progress(stages::REPLANNING);
    let options = pipeline.config.plan;
    let mut plan = match replan_mission_reporting(&mut pipeline, options, state) {
        Ok(plan) => plan,
        Err(MissionFailed { error, stats }) => {
            return match NoPlan::of(&error, *stats) {
                Some(why) => Ok(Outcome::NoSolution { why }),
                None => Err(error.into()),
            }
        }
    };
    plan.traversability_files = smug_mission::traversability_files(loaded);
    if let Some(info) = plan.replan.as_mut() {
        info.state_file = Some(state_name);
    }
    let world = pipeline.world.clone().ok_or(AppError::NoWorld)?;
    Ok(Outcome::Solved(Planned {
        plan,
        pipeline,
        world,
    }))
}
