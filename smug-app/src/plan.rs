//! Planning a mission from a config, as `smug plan` and `smug.plan` do.

use crate::no_plan::NoPlan;
use crate::{AppError, Outcome, Result};
use smug_core::registry::{ObjectiveStage, SpaceStage, Stage, TraversabilityStage, WorldStage};
use smug_core::{LoadedConfig, Mission, Pipeline, Plan, TraversabilityEstimator, World};
use smug_mission::{plan_mission_reporting, traversability_files, MissionFailed};
use std::path::Path;
use std::sync::Arc;

/// A plan with the pipeline that made it and the world it was made in.
pub struct Planned {
    /// The plan.
    pub plan: Plan,
    /// The pipeline (its planner keeps the roadmap, see [`crate::save_roadmap`]).
    pub pipeline: Pipeline,
    /// The world the plan was made in.
    pub world: Arc<World>,
}

/// The stages that build a world with its layers, the sections to keep
/// ([`PipelineConfig::keep_sections`](smug_core::PipelineConfig::keep_sections)) to
/// assemble a config's world alone (`smug worlds`, `smug.load_world`).
pub const WORLD_STAGES: [&str; 4] = [
    WorldStage::NAME,
    TraversabilityStage::NAME,
    SpaceStage::NAME,
    ObjectiveStage::NAME,
];

/// Loads a config with `--set` overrides and a seed, as `smug plan --set … --seed N`.
pub fn load_config(config: &Path, set: &[String], seed: Option<u64>) -> Result<LoadedConfig> {
    let mut set = set.to_vec();
    if let Some(seed) = seed {
        set.push(format!("seed={seed}"));
    }
    Ok(LoadedConfig::from_file(config, &set)?)
}

/// Builds every stage of `loaded`, with `world` and its mission (when given) instead
/// of the config's `[world]` and `estimator` (when given) instead of its
/// `[traversability]`.
pub fn assemble(
    loaded: &LoadedConfig,
    world: Option<(World, Option<Mission>)>,
    estimator: Option<(&str, Box<dyn TraversabilityEstimator>)>,
) -> Result<Pipeline> {
    Ok(Pipeline::assemble_with(loaded, world, estimator)?)
}

/// Plans the mission on an assembled pipeline with the config's plan options.
pub fn plan_on(pipeline: Pipeline) -> Result<Outcome<Planned>> {
    Ok(plan_on_reporting(pipeline)?.map_no_solution(|no_plan| no_plan.why))
}

/// [`plan_on`] that, without a plan, also says what plan.json reports: what could not be
/// reached and the run's statistics.
pub fn plan_on_reporting(mut pipeline: Pipeline) -> Result<Outcome<Planned, NoPlan>> {
    let options = pipeline.config.plan;
    let plan = match plan_mission_reporting(&mut pipeline, options) {
        Ok(plan) => plan,
        Err(MissionFailed { error, stats }) => {
            return match NoPlan::of(&error, *stats) {
                Some(why) => Ok(Outcome::NoSolution { why }),
                None => Err(error.into()),
            }
        }
    };
    let world = pipeline.world.clone().ok_or(AppError::NoWorld)?;
    Ok(Outcome::Solved(Planned {
        plan,
        pipeline,
        world,
    }))
}

/// Assembles the pipeline of `loaded` and plans its mission (see [`assemble`]); the
/// plan records the files its traversability came from (a config's estimator only).
pub fn plan(
    loaded: &LoadedConfig,
    world: Option<(World, Option<Mission>)>,
    estimator: Option<(&str, Box<dyn TraversabilityEstimator>)>,
) -> Result<Outcome<Planned>> {
    if estimator.is_some() {
        return plan_on(assemble(loaded, world, estimator)?);
    }
    Ok(
        plan_config_pipeline(loaded, assemble(loaded, world, None)?)?
            .map_no_solution(|no_plan| no_plan.why),
    )
}

/// [`plan_on_reporting`] for a pipeline assembled from `loaded` with the config's own
/// estimator: the plan records the files its traversability came from.
pub fn plan_config_pipeline(
    loaded: &LoadedConfig,
    pipeline: Pipeline,
) -> Result<Outcome<Planned, NoPlan>> {
    let mut outcome = plan_on_reporting(pipeline)?;
    if let Outcome::Solved(planned) = &mut outcome {
        planned.plan.traversability_files = traversability_files(loaded);
    }
    Ok(outcome)
}
