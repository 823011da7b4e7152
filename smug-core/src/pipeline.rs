//! Assembling a pipeline from config: each stage is built by its registered plugin,
//! in dependency order, through a [`BuildContext`] that hands out what earlier stages built.

use crate::config::{KeyPath, LoadedConfig, PipelineConfig, PluginSection};
use crate::error::{Error, Result};
use crate::mission::Mission;
use crate::objective::Objective;
use crate::pose::Pose2;
use crate::registry::{
    MotionStage, ObjectiveStage, PlannerStage, SamplerStage, SelectorStage, SequencerStage,
    SpaceStage, Stage, TraversabilityStage, ValidityStage, WorldStage,
};
use crate::run_context::RunContext;
use crate::space::StateSpace;
use crate::stages::{
    MotionValidator, PoiSelector, PointToPointPlanner, Sequencer, StateValidityChecker,
    TraversabilityEstimator,
};
use crate::world::{Scenario, World};
use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

#[path = "pipeline_rebuild.rs"]
mod rebuild;
pub use crate::context::{BuildContext, WorldChange};

/// The message for a config that still has the `[cost]` section of earlier versions.
const REMOVED_COST: &str =
    "`[cost]` was split into `[space]` (the motion model and k-NN distance, \
     e.g. type = \"se2\") and `[objective]` (what a path costs, e.g. type = \"path-length\"); \
     both take the weights `translation_weight` and `rotation_weight`: move the section there";

/// A robot whose base box is longer or wider than the world cannot stand anywhere in it:
/// an error naming the key and both sizes.
fn check_robot_fits(loaded: &LoadedConfig, world: &World) -> Result<()> {
    let robot = &loaded.config.robot;
    let [w, h] = world.bounds().extent();
    let room = w.min(h);
    for (key, size) in [("robot.length", robot.length), ("robot.width", robot.width)] {
        if size > room {
            let message = format!(
                "the robot ({size} m) is larger than world `{}` ({w} × {h} m)",
                world.name
            );
            return Err(loaded
                .sources
                .key_error(&KeyPath::dotted(key), message)
                .into());
        }
    }
    Ok(())
}

/// One assembled stage: which plugin, with which resolved parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct ResolvedStage {
    /// Config section.
    pub key: String,
    /// Plugin name.
    pub plugin: String,
    /// Parameters with defaults filled in.
    pub params: toml::Table,
}

/// Every stage the config names, built and wired together.
pub struct Pipeline {
    /// The config it was built from.
    pub config: PipelineConfig,
    /// The world (with its traversability layer), if configured.
    pub world: Option<Arc<World>>,
    /// The mission as the world plugin (or the caller) gave it; `None` for a world of
    /// maps only (point-to-point queries).
    pub given_mission: Option<Mission>,
    /// The given mission without the PoIs the validity checker rejects (once both
    /// a mission and a validity checker are configured; else the given mission).
    pub mission: Option<Mission>,
    /// PoIs left out because they are not valid for the robot.
    pub dropped_pois: Vec<DroppedPoi>,
    /// The state space (motion model).
    pub space: Arc<dyn StateSpace>,
    /// The objective (what paths cost).
    pub objective: Arc<dyn Objective>,
    /// The state validity checker, if configured.
    pub state_validity: Option<Arc<dyn StateValidityChecker>>,
    /// The motion validator, if configured.
    pub motion_validator: Option<Arc<dyn MotionValidator>>,
    /// The point-to-point planner, if configured.
    pub planner: Option<Box<dyn PointToPointPlanner>>,
    /// The sequencer, if configured.
    pub sequencer: Option<Box<dyn Sequencer>>,
    /// The PoI selector, if configured.
    pub selector: Option<Box<dyn PoiSelector>>,
    /// Each stage's plugin and resolved parameters, in build order.
    pub resolved: Vec<ResolvedStage>,
    /// Build time per stage, seconds.
    pub build_times_s: BTreeMap<String, f64>,
    /// Told the number of paths planned so far after each plan of
    /// `smug_mission::plan_mission` (a progress display; `None`: nothing told).
    pub progress: Option<crate::run_context::ProgressFn>,
    context: BuildContext,
}

impl Pipeline {
    /// Builds every stage the config names.
    pub fn assemble(loaded: &LoadedConfig) -> Result<Self> {
        Self::assemble_inner(loaded, None, None)
    }

    /// Builds every stage, using `world` (maps only, no mission: point-to-point
    /// queries) instead of the config's `[world]` section.
    pub fn assemble_with_world(loaded: &LoadedConfig, world: World) -> Result<Self> {
        Self::assemble_inner(loaded, Some((world, None)), None)
    }

    /// Builds every stage, with `world` and its mission (when given) instead of the
    /// config's `[world]` section and `estimator` (when given) instead of its
    /// `[traversability]` section. The estimator is recorded as stage
    /// `traversability`, plugin `name`.
    pub fn assemble_with(
        loaded: &LoadedConfig,
        world: Option<(World, Option<Mission>)>,
        estimator: Option<(&str, Box<dyn TraversabilityEstimator>)>,
    ) -> Result<Self> {
        Self::assemble_inner(loaded, world, estimator)
    }

    fn assemble_inner(
        loaded: &LoadedConfig,
        given_world: Option<(World, Option<Mission>)>,
        given_estimator: Option<(&str, Box<dyn TraversabilityEstimator>)>,
    ) -> Result<Self> {
        let config = loaded.config.clone();
        let mut ctx = BuildContext::new(config.seed, config.robot)
            .with_run(RunContext::new(config.limits.memory()));
        ctx.sources = loaded.sources.clone();
        let mut pipeline = Pipeline {
            config: config.clone(),
            world: None,
            given_mission: None,
            mission: None,
            dropped_pois: Vec::new(),
            space: ctx.space(),
            objective: ctx.objective(),
            state_validity: None,
            motion_validator: None,
            planner: None,
            sequencer: None,
            selector: None,
            resolved: Vec::new(),
            build_times_s: BTreeMap::new(),
            progress: None,
            context: ctx.clone(),
        };
        if config.cost.is_some() {
            let key = KeyPath::dotted("cost");
            return Err(loaded.sources.key_error(&key, REMOVED_COST).into());
        }
        let space_section = config
            .space
            .clone()
            .unwrap_or_else(|| PluginSection::new("space", "se2"));
        let space: Arc<dyn StateSpace> = pipeline
            .build_stage::<SpaceStage>(&ctx, &space_section)?
            .into();
        ctx = ctx.with_space(space.clone());
        pipeline.space = space;

        let world = match (given_world, &config.world) {
            (Some(given), _) => Some(given),
            (None, Some(section)) => {
                let Scenario { world, mission } =
                    *pipeline.build_stage::<WorldStage>(&ctx, section)?;
                Some((world, Some(mission)))
            }
            (None, None) => None,
        };
        if let Some((mut world, mission)) = world {
            if let Some(mission) = &mission {
                mission.validate()?;
            }
            check_robot_fits(loaded, &world)?;
            let estimator = match (given_estimator, &config.traversability) {
                (Some((name, estimator)), _) => {
                    let section = PluginSection::new("traversability", name);
                    pipeline.resolved.push(ResolvedStage {
                        key: section.key.clone(),
                        plugin: section.kind.clone(),
                        params: toml::Table::new(),
                    });
                    Some((section, estimator))
                }
                (None, Some(section)) => Some((
                    section.clone(),
                    pipeline.build_stage::<TraversabilityStage>(&ctx, section)?,
                )),
                (None, None) => None,
            };
            if let Some((section, estimator)) = estimator {
                let section = &section;
                let started = Instant::now();
                world.traversability = Some(check_layer_fits(
                    estimator.estimate(&world)?,
                    &world,
                    section,
                )?);
                pipeline.add_time(&section.key, started);
            }
            pipeline.given_mission = mission.clone();
            pipeline.mission = mission;
            let world = Arc::new(world);
            ctx = ctx.with_world(world.clone());
            pipeline.world = Some(world);
        }
        let objective_section = config
            .objective
            .clone()
            .unwrap_or_else(|| PluginSection::new("objective", "path-length"));
        let objective: Arc<dyn Objective> = pipeline
            .build_stage::<ObjectiveStage>(&ctx, &objective_section)?
            .into();
        ctx = ctx.with_objective(objective.clone());
        pipeline.objective = objective;
        if let Some(section) = &config.validity {
            let checker: Arc<dyn StateValidityChecker> =
                pipeline.build_stage::<ValidityStage>(&ctx, section)?.into();
            // A mission without targets has nothing to prune.
            if let Some(mission) = pipeline.mission.as_ref().filter(|m| !m.targets.is_empty()) {
                let (pruned, dropped) = prune_mission(mission, checker.as_ref())?;
                pipeline.mission = Some(pruned);
                pipeline.dropped_pois = dropped;
            }
            ctx = ctx.with_state_validity(checker.clone());
            pipeline.state_validity = Some(checker);
        }
        if let Some(section) = &config.motion {
            let validator: Arc<dyn MotionValidator> =
                pipeline.build_stage::<MotionStage>(&ctx, section)?.into();
            ctx = ctx.with_motion_validator(validator.clone());
            pipeline.motion_validator = Some(validator);
        }
        if let Some(section) = &config.sampler {
            // Built once here to check it and record its parameters; planners build their own.
            pipeline.build_stage::<SamplerStage>(&ctx, section)?;
            ctx = ctx.with_sampler(section.clone());
        }
        if let Some(section) = &config.planner {
            pipeline.planner = Some(pipeline.build_stage::<PlannerStage>(&ctx, section)?);
        }
        if let Some(section) = &config.sequencer {
            pipeline.sequencer = Some(pipeline.build_stage::<SequencerStage>(&ctx, section)?);
        }
        if let Some(section) = &config.selector {
            pipeline.selector = Some(pipeline.build_stage::<SelectorStage>(&ctx, section)?);
        }
        pipeline.context = ctx;
        Ok(pipeline)
    }

    fn build_stage<S: Stage>(
        &mut self,
        ctx: &BuildContext,
        section: &PluginSection,
    ) -> Result<Box<S::Object>> {
        let started = Instant::now();
        let built = ctx.build::<S>(section)?;
        self.add_time(&section.key, started);
        self.resolved.push(ResolvedStage {
            key: section.key.clone(),
            plugin: section.kind.clone(),
            params: built.params,
        });
        Ok(built.object)
    }

    fn add_time(&mut self, key: &str, started: Instant) {
        *self.build_times_s.entry(key.to_string()).or_default() += started.elapsed().as_secs_f64();
    }

    /// The context the stages were built with (to build more, e.g. a fresh planner).
    pub fn context(&self) -> &BuildContext {
        &self.context
    }

    /// The run context every stage was handed: this pipeline's deadline and memory
    /// limit (its own; other pipelines have theirs).
    pub fn run(&self) -> &RunContext {
        self.context.run()
    }

    /// The resolved pipeline as TOML: seed, robot, every stage with its parameters.
    pub fn resolved_toml(&self) -> String {
        let mut table = toml::Table::new();
        table.insert("seed".into(), toml::Value::Integer(self.config.seed as i64));
        table.insert(
            "robot".into(),
            toml::Value::Table(crate::registry::params_table(&self.config.robot)),
        );
        for stage in &self.resolved {
            let mut section = toml::Table::new();
            section.insert("type".into(), toml::Value::String(stage.plugin.clone()));
            section.insert("params".into(), toml::Value::Table(stage.params.clone()));
            table.insert(stage.key.clone(), toml::Value::Table(section));
        }
        toml::to_string_pretty(&table).unwrap_or_default()
    }
}

/// A PoI left out of the mission.
#[derive(Clone, Debug, PartialEq)]
pub struct DroppedPoi {
    /// Target id.
    pub target: String,
    /// Index of the PoI in the target's list.
    pub index: usize,
    /// The PoI.
    pub pose: Pose2,
}

/// The mission without invalid PoIs. An invalid start or end, or a target left with
/// no valid PoI, is an error that names it.
pub fn prune_mission(
    mission: &Mission,
    checker: &dyn StateValidityChecker,
) -> Result<(Mission, Vec<DroppedPoi>)> {
    let describe = |p: &Pose2| format!("({:.3}, {:.3}, yaw {:.3})", p.x, p.y, p.yaw);
    if !checker.is_valid(&mission.start) {
        return Err(Error::InvalidInput(format!(
            "the start pose {} is not valid for the robot (in collision, untraversable or off the map)",
            describe(&mission.start)
        )));
    }
    if let Some(end) = mission.end.filter(|e| !checker.is_valid(e)) {
        return Err(Error::InvalidInput(format!(
            "the end pose {} is not valid for the robot (in collision, untraversable or off the map)",
            describe(&end)
        )));
    }
    let mut pruned = mission.clone();
    let mut dropped = Vec::new();
    for target in &mut pruned.targets {
        let mut index = 0;
        target.pois.retain(|pose| {
            let keep = checker.is_valid(pose);
            if !keep {
                dropped.push(DroppedPoi {
                    target: target.id.clone(),
                    index,
                    pose: *pose,
                });
            }
            index += 1;
            keep
        });
        if target.pois.is_empty() {
            return Err(Error::InvalidInput(format!(
                "target `{}` has no valid pose of interest: all {index} PoIs are in collision, \
                 untraversable or off the map",
                target.id
            )));
        }
    }
    Ok((pruned, dropped))
}

fn check_layer_fits(
    layer: crate::grid::GridLayer,
    world: &World,
    section: &PluginSection,
) -> Result<crate::grid::GridLayer> {
    let (got, want) = (layer.geometry, world.elevation.geometry);
    let same = got.size == want.size
        && (got.resolution - want.resolution).abs() <= 1e-9 * want.resolution
        && (got.origin[0] - want.origin[0]).abs() <= 1e-6
        && (got.origin[1] - want.origin[1]).abs() <= 1e-6;
    if same && layer.data.len() == want.len() {
        Ok(layer)
    } else {
        Err(Error::invalid_param(
            &section.key,
            format!(
                "plugin `{}` returned a layer of {}×{} cells at {} m from {:?}; the world's \
                 elevation is {}×{} at {} m from {:?}",
                section.kind,
                got.size[0],
                got.size[1],
                got.resolution,
                got.origin,
                want.size[0],
                want.size[1],
                want.resolution,
                want.origin
            ),
        ))
    }
}
