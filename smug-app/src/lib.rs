//! SMUG's application layer, shared by the `smug` CLI and the Python package: it links
//! every built-in plugin crate once (so their `inventory` registrations are in any
//! binary that uses this crate) and offers what both front ends do:
//!
//! - [`plan()`]: a config to a plan (and [`outputs`]: plan.json, plan.csv, plan.svg,
//!   and [`plan_mcap`]: plan.mcap for the ROS 2 viewers; [`no_plan`]: the plan.json of
//!   a mission that ended without a plan);
//! - [`replan()`]: the rest of a mission from a mission state file;
//! - [`p2p`]: point-to-point queries on one shared roadmap, one typed result;
//! - [`save_roadmap`] / [`load_roadmap`]: the planner's roadmap file;
//! - [`sweep`]: configs × seeds × a grid of overrides, one row per run (`smug sweep`,
//!   `smug.sweep`);
//! - one [`Outcome`] (`Solved` / `NoSolution { why }`) beside a typed [`AppError`],
//!   instead of each front end deciding what counts as "no solution".
//!
//! The front ends keep argument parsing, printing and (for Python) conversion.

#![warn(missing_docs)]

// Name every plugin crate so that its `inventory` registrations are linked in. This is
// the one list of the built-in plugins (beside the fuzz harness's own).
use smug_objectives as _;
use smug_planners as _;
use smug_samplers as _;
use smug_selection as _;
use smug_sequencing as _;
use smug_spaces as _;
use smug_validity as _;
use smug_worlds as _;

pub mod error;
pub mod no_plan;
pub mod outcome;
pub mod outputs;
pub mod p2p;
pub mod plan;
pub mod plan_mcap;
pub mod replan;
pub mod roadmap;
pub mod ros;
pub mod sweep;
pub mod team;
pub mod team_outputs;
pub mod team_replan;
pub mod team_session;
pub mod version;

pub use error::{AppError, Result};
pub use no_plan::{NoPlan, NoPlanReport};
pub use outcome::{one_line, NoSolution, Outcome};
pub use plan::{load_config, plan, Planned, WORLD_STAGES};
pub use replan::{replan, ReplanRequest};
pub use roadmap::{load_roadmap, save_roadmap};
/// The long-lived mission session (plan, then replan in place as the robot goes), for
/// the front ends: through the application layer, like every other command.
pub use smug_mission::{MissionSession, WorldUpdate};
pub use version::VERSION;
