//! The planner's roadmap file: saved after a mission (`smug plan --save-roadmap`),
//! loaded before a replan (`smug replan --roadmap`).

use crate::{one_line, AppError, Result};
use smug_core::mission::MissionState;
use smug_core::{Fingerprint, LoadedConfig, Pipeline, World};
use smug_mission::{changed_discs, fingerprint};
use smug_planners::{read_roadmap, write_roadmap};
use std::path::Path;

/// Writes the planner's roadmap after a mission to `file`, fingerprinted for `loaded`
/// on `world` (the world the plan was made in).
pub fn save_roadmap(
    pipeline: &Pipeline,
    loaded: &LoadedConfig,
    world: &World,
    file: &Path,
) -> Result<()> {
    let saved = pipeline
        .planner
        .as_ref()
        .and_then(|p| p.save_roadmap())
        .ok_or_else(|| AppError::NoRoadmapToSave {
            file: file.to_path_buf(),
        })?;
    write_roadmap(file, &saved, &fingerprint(loaded, world))?;
    Ok(())
}

/// Loads the roadmap `file` into the pipeline's planner; the file must carry
/// `fingerprint` (the replan's world, robot and config), and the obstacles of `state`
/// are re-checked.
pub fn load_roadmap(
    pipeline: &mut Pipeline,
    loaded: &LoadedConfig,
    state: &MissionState,
    fingerprint: &Fingerprint,
    file: &Path,
) -> Result<()> {
    let saved = read_roadmap(file, fingerprint)?;
    let changed = changed_discs(state, &loaded.config.robot);
    let planner = pipeline
        .planner
        .as_mut()
        .ok_or_else(|| AppError::NoPlannerForRoadmap {
            file: file.to_path_buf(),
        })?;
    planner
        .load_roadmap(&saved, &changed)
        .map_err(|e| AppError::RoadmapRefused {
            file: file.to_path_buf(),
            message: one_line(&e),
        })
}
