//! SMUG core: the value types, stage traits, plugin registry and TOML
//! pipelines that every other SMUG crate builds on.
//!
//! A pipeline is assembled from a TOML config: each stage (`world`, `traversability`,
//! `space`, `objective`, `validity`, `motion`, `sampler`, `planner`, `sequencer`,
//! `selector`: the stage table in `stage_table.rs`, [`registry::STAGE_KEYS`]) names a
//! registered plugin with `type = "…"` and gives its parameters in `params`.
//! Plugins register themselves with [`register_plugin!`].

#![warn(missing_docs)]

#[macro_use]
mod stage_table;

mod builtins;
pub mod config;
pub mod context;
pub mod counter;
pub mod deadline;
pub mod digest;
pub mod error;
pub mod grid;
pub mod limits;
pub mod mission;
pub mod objective;
pub mod output;
pub mod path;
pub mod pipeline;
pub mod plan;
pub mod pose;
pub mod queries;
pub mod registry;
pub mod rng;
pub mod run_context;
pub mod space;
pub mod stages;
pub mod termination;
#[cfg(feature = "testing")]
pub mod testing;
pub mod timing;
pub mod world;

pub use config::{LoadedConfig, PipelineConfig, PluginSection, RobotConfig};
pub use counter::Counter;
pub use deadline::Deadline;
pub use error::{ConfigError, Error, Origin, RegistryError, Result};
pub use grid::{GridError, GridGeometry, GridLayer, VoxelGeometry, VoxelGrid};
pub use limits::MemoryLimit;
pub use mission::PlanOptions;
pub use mission::{Mission, Target};
pub use objective::{Objective, PathLength};
pub use path::Path;
pub use pipeline::{BuildContext, Pipeline, WorldChange};
pub use plan::{Plan, PlanStats, RobotPlan, TeamPlan, TeamReplanInfo, TimeBreakdown};
pub use pose::{Bounds2, Point3, Pose2, PoseBits, Waypoint};
pub use run_context::{RunContext, RunProgress};
pub use space::{MotionExtent, Se2Space, SpaceError, StateSpace};
pub use stages::*;
pub use termination::Termination;
pub use world::{Scenario, World};

#[doc(hidden)]
pub use inventory;
#[doc(hidden)]
pub use toml;
