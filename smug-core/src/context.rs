//! What a plugin's builder may use ([`BuildContext`]): the seed, the robot, the run
//! context, and the stages built before it; and what changed since the world the
//! stages were built for ([`WorldChange`]). Building a stage by name through the
//! registry is [`BuildContext::build`], beside the registry.

use crate::config::{KeyPath, PluginSection, RobotConfig, SourceMap};
use crate::deadline::Deadline;
use crate::error::{Error, Result};
use crate::limits::MemoryLimit;
use crate::mission::DiscObstacle;
use crate::objective::{Objective, PathLength};
use crate::rng::{stage_rng, StageRng};
use crate::run_context::RunContext;
use crate::space::{Se2Space, StateSpace};
use crate::stages::{MotionValidator, StateValidityChecker};
use crate::world::World;
use serde::de::DeserializeOwned;
use std::sync::Arc;

/// How the context's world came from the one the stages were built for before: that
/// world with obstacles added (set while a
/// `smug_mission::MissionSession` rebuilds the stages). A plugin may
/// update what it derived from the previous world instead of deriving it again, as
/// long as the result is the same.
#[derive(Clone, Debug)]
pub struct WorldChange {
    /// The world before.
    pub previous: Arc<World>,
    /// The obstacles added to it, in order.
    pub obstacles: Vec<DiscObstacle>,
}

/// What a plugin's builder may use: the seed, the robot, and the stages built before it.
#[derive(Clone)]
pub struct BuildContext {
    seed: u64,
    robot: RobotConfig,
    pub(crate) sources: Arc<SourceMap>,
    space: Arc<dyn StateSpace>,
    objective: Arc<dyn Objective>,
    world: Option<Arc<World>>,
    state_validity: Option<Arc<dyn StateValidityChecker>>,
    motion_validator: Option<Arc<dyn MotionValidator>>,
    pub(crate) sampler: Option<PluginSection>,
    world_change: Option<Arc<WorldChange>>,
    run: RunContext,
    pub(crate) building: String,
}

impl BuildContext {
    /// A context with the default space (`se2`) and objective (`path-length`) and
    /// nothing else built (for tests and programmatic assembly; add stages with the
    /// `with_*` methods).
    pub fn new(seed: u64, robot: RobotConfig) -> Self {
        Self {
            seed,
            robot,
            sources: Arc::new(SourceMap::default()),
            space: Arc::new(Se2Space::default()),
            objective: Arc::new(PathLength::default()),
            world: None,
            state_validity: None,
            motion_validator: None,
            sampler: None,
            world_change: None,
            run: RunContext::default(),
            building: String::new(),
        }
    }

    /// Sets the state space (motion model).
    pub fn with_space(mut self, space: Arc<dyn StateSpace>) -> Self {
        self.space = space;
        self
    }

    /// Sets the objective.
    pub fn with_objective(mut self, objective: Arc<dyn Objective>) -> Self {
        self.objective = objective;
        self
    }

    /// Sets the world.
    pub fn with_world(mut self, world: Arc<World>) -> Self {
        self.world = Some(world);
        self
    }

    /// Sets the state validity checker.
    pub fn with_state_validity(mut self, checker: Arc<dyn StateValidityChecker>) -> Self {
        self.state_validity = Some(checker);
        self
    }

    /// Sets the motion validator.
    pub fn with_motion_validator(mut self, validator: Arc<dyn MotionValidator>) -> Self {
        self.motion_validator = Some(validator);
        self
    }

    /// Sets the sampler section planners build their samplers from.
    pub fn with_sampler(mut self, section: PluginSection) -> Self {
        self.sampler = Some(section);
        self
    }

    /// Sets the run context (deadline and memory limit) handed to the stages.
    pub fn with_run(mut self, run: RunContext) -> Self {
        self.run = run;
        self
    }

    /// The run context: the deadline stages stop at, the memory limit they allocate
    /// within.
    pub fn run(&self) -> &RunContext {
        &self.run
    }

    /// The run's deadline (a handle the stages keep; armed while a run with a
    /// deadline plans).
    pub fn deadline(&self) -> Deadline {
        self.run.deadline.clone()
    }

    /// The run's progress (planners answering many legs at once count their rows).
    pub fn progress(&self) -> crate::run_context::RunProgress {
        self.run.progress.clone()
    }

    /// The run's memory limit.
    pub fn memory(&self) -> MemoryLimit {
        self.run.memory
    }

    /// Sets (or clears) what changed since the previous world.
    pub fn with_world_change(mut self, change: Option<Arc<WorldChange>>) -> Self {
        self.world_change = change;
        self
    }

    /// What changed since the world the stages were built for before, if the context
    /// rebuilds them after a change.
    pub fn world_change(&self) -> Option<&WorldChange> {
        self.world_change.as_deref()
    }

    /// The run's seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The robot's base box.
    pub fn robot(&self) -> &RobotConfig {
        &self.robot
    }

    /// `path` resolved against the main config file's directory (absolute paths stay).
    pub fn resolve_path(&self, path: &std::path::Path) -> std::path::PathBuf {
        self.sources.base_dir().join(path)
    }

    /// A reproducible RNG for `stream`, derived from the seed.
    pub fn rng(&self, stream: &str) -> StageRng {
        stage_rng(self.seed, stream)
    }

    /// The state space (motion model).
    pub fn space(&self) -> Arc<dyn StateSpace> {
        self.space.clone()
    }

    /// The objective.
    pub fn objective(&self) -> Arc<dyn Objective> {
        self.objective.clone()
    }

    /// The world, or an error naming the stage that needs it.
    pub fn world(&self) -> Result<Arc<World>> {
        self.world.clone().ok_or_else(|| self.missing("world"))
    }

    /// The state validity checker, or an error naming the stage that needs it.
    pub fn state_validity(&self) -> Result<Arc<dyn StateValidityChecker>> {
        self.state_validity
            .clone()
            .ok_or_else(|| self.missing("validity"))
    }

    /// The motion validator, or an error naming the stage that needs it.
    pub fn motion_validator(&self) -> Result<Arc<dyn MotionValidator>> {
        self.motion_validator
            .clone()
            .ok_or_else(|| self.missing("motion"))
    }

    /// The typed parameters of `section`; errors name the key and its line.
    pub fn params<P: DeserializeOwned>(&self, section: &PluginSection) -> Result<P> {
        let prefix = KeyPath::dotted(&section.key).join("params");
        Ok(self
            .sources
            .deserialize(&prefix, toml::Value::Table(section.params.clone()))?)
    }

    /// An error naming the stage being built and the stage it needs.
    pub(crate) fn missing(&self, needed: &'static str) -> Error {
        Error::MissingStage {
            stage: if self.building.is_empty() {
                "this command".into()
            } else {
                format!("[{}]", self.building)
            },
            needed,
        }
    }
}
