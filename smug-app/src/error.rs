//! The application layer's error type.

use std::path::PathBuf;

/// Why a command could not run (the CLI's exit 2; a Python `ConfigError` or
/// `InputError`).
#[derive(Debug, thiserror::Error)]
pub enum AppError {
    /// A library error (config, plugin, input, planning).
    #[error(transparent)]
    Smug(#[from] smug_core::Error),
    /// A config file could not be read.
    #[error(transparent)]
    Config(#[from] smug_core::ConfigError),
    /// A plugin lookup failed.
    #[error(transparent)]
    Registry(#[from] smug_core::RegistryError),
    /// A mission state file could not be read.
    #[error(transparent)]
    State(#[from] smug_core::mission::StateError),
    /// A map file could not be read.
    #[error(transparent)]
    Map(#[from] smug_worlds::MapFileError),
    /// A roadmap file could not be written or read.
    #[error(transparent)]
    RoadmapFile(#[from] smug_planners::RoadmapFileError),
    /// The configured planner keeps no roadmap to save.
    #[error("{}: cannot save a roadmap: the configured planner keeps none", file.display())]
    NoRoadmapToSave {
        /// The roadmap file asked for.
        file: PathBuf,
    },
    /// A roadmap file was given but the config has no planner.
    #[error("{}: the config has no planner", file.display())]
    NoPlannerForRoadmap {
        /// The roadmap file.
        file: PathBuf,
    },
    /// The planner refused a roadmap file.
    #[error("{}: {message}", file.display())]
    RoadmapRefused {
        /// The roadmap file.
        file: PathBuf,
        /// Why, on one line.
        message: String,
    },
    /// The config has no `[planner]` section (p2p).
    #[error("the config has no [planner] section")]
    NoPlanner,
    /// A team command was given a config without `[team]`.
    #[error("the config has no [team] section (a team names its robots in [[team.robots]])")]
    NotATeam,
    /// Building one robot of a team failed.
    #[error("robot `{robot}`: {source}")]
    Robot {
        /// The robot's name.
        robot: String,
        /// Why.
        source: Box<smug_core::Error>,
    },
    /// The config has no `[world]` section.
    #[error("the config has no [world] section")]
    NoWorld,
    /// An output file would overwrite one of the run's inputs.
    #[error("{}: is an input of this run; choose another --out (or [output] dir)", path.display())]
    OutputOverInput {
        /// The output (and input) file.
        path: PathBuf,
    },
    /// An output directory could not be created or a file written.
    #[error("{}: {what}: {source}", path.display())]
    Write {
        /// The directory or file.
        path: PathBuf,
        /// `cannot create`, `cannot write` or `cannot remove`.
        what: &'static str,
        /// The cause.
        source: std::io::Error,
    },
    /// plan.mcap could not be written.
    #[error(transparent)]
    Mcap(#[from] crate::plan_mcap::McapError),
    /// A plan or result could not be written as JSON.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
}

/// A command's result.
pub type Result<T> = std::result::Result<T, AppError>;
