//! A pipeline assembled from config: each stage built by its registered plugin, in the
//! stage table's order (`assemble.rs`: the steps of `steps.rs` around the world's of
//! `world.rs`), through a [`BuildContext`] that hands out what earlier stages built
//! ([`Pipeline::context`], composed from the stages the pipeline holds, once each).

use crate::config::{LoadedConfig, PipelineConfig, PluginSection, SourceMap};
use crate::error::Result;
use crate::mission::Mission;
use crate::objective::Objective;
use crate::registry::Stage;
use crate::run_context::RunContext;
use crate::space::StateSpace;
use crate::stages::{
    MotionValidator, PoiSelector, PointToPointPlanner, Sequencer, StateValidityChecker,
};
use crate::world::World;
use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

mod assemble;
mod prune;
mod rebuild;
mod steps;
mod world;
pub use crate::context::{BuildContext, WorldChange};
pub use prune::{prune_mission, DroppedPoi};

/// Whether a stage step builds the pipeline for the first time or again on a changed
/// world ([`Pipeline::rebuild_on_world`]: nothing recorded again, the mission kept).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    Assemble,
    Rebuild,
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
    /// The team sequencer, if configured.
    pub team_sequencer: Option<Box<dyn crate::stages::TeamSequencer>>,
    /// Each stage's plugin and resolved parameters, in build order.
    pub resolved: Vec<ResolvedStage>,
    /// Build time per stage, seconds.
    pub build_times_s: BTreeMap<String, f64>,
    /// The deadline and memory limit every stage was handed.
    run: RunContext,
    /// Where each config key was written (for the stages' error messages).
    sources: Arc<SourceMap>,
    /// The sampler section the planners build their samplers from, once checked.
    sampler: Option<PluginSection>,
}

impl Pipeline {
    /// A pipeline of `loaded`'s config with nothing built yet (the default space and
    /// objective).
    pub(super) fn empty(loaded: &LoadedConfig) -> Self {
        let config = loaded.config.clone();
        let ctx = BuildContext::new(config.seed, config.robot);
        Pipeline {
            run: RunContext::new(config.limits.memory()),
            config,
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
            team_sequencer: None,
            resolved: Vec::new(),
            build_times_s: BTreeMap::new(),
            sources: loaded.sources.clone(),
            sampler: None,
        }
    }

    /// Builds `section` with its plugin in `ctx`, timed; recorded in
    /// [`resolved`](Self::resolved) when assembling.
    fn build_stage<S: Stage>(
        &mut self,
        ctx: &BuildContext,
        section: &PluginSection,
    ) -> Result<Box<S::Object>> {
        self.build_stage_in::<S>(ctx, section, Phase::Assemble)
    }

    /// [`build_stage`](Self::build_stage) in `phase` (a rebuild records nothing again).
    fn build_stage_in<S: Stage>(
        &mut self,
        ctx: &BuildContext,
        section: &PluginSection,
        phase: Phase,
    ) -> Result<Box<S::Object>> {
        let started = Instant::now();
        let built = ctx.build::<S>(section)?;
        self.add_time(&section.key, started);
        if phase == Phase::Assemble {
            self.resolved.push(ResolvedStage {
                key: section.key.clone(),
                plugin: section.kind.clone(),
                params: built.params,
            });
        }
        Ok(built.object)
    }

    fn add_time(&mut self, key: &str, started: Instant) {
        *self.build_times_s.entry(key.to_string()).or_default() += started.elapsed().as_secs_f64();
    }

    /// Checks `loaded`'s stage sections without building anything: every plugin
    /// name registered, every parameter one its plugin reads (errors name the key and
    /// where it was written).
    pub fn check_params(loaded: &LoadedConfig) -> Result<()> {
        let pipeline = Pipeline::empty(loaded);
        crate::registry::check_sections(&pipeline.config, &pipeline.context())
    }

    /// A context holding this pipeline's stages (to build more, e.g. a fresh planner):
    /// composed from them on demand, so it always sees the current ones.
    pub fn context(&self) -> BuildContext {
        let mut ctx = BuildContext::new(self.config.seed, self.config.robot)
            .with_run(self.run.clone())
            .with_space(self.space.clone())
            .with_objective(self.objective.clone());
        ctx.sources = self.sources.clone();
        if let Some(world) = &self.world {
            ctx = ctx.with_world(world.clone());
        }
        if let Some(checker) = &self.state_validity {
            ctx = ctx.with_state_validity(checker.clone());
        }
        if let Some(validator) = &self.motion_validator {
            ctx = ctx.with_motion_validator(validator.clone());
        }
        if let Some(section) = &self.sampler {
            ctx = ctx.with_sampler(section.clone());
        }
        ctx
    }

    /// The run context every stage was handed: this pipeline's deadline and memory
    /// limit (its own; other pipelines have theirs).
    pub fn run(&self) -> &RunContext {
        &self.run
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
