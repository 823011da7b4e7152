//! SMUG's mission orchestration, above the core: a mission planned through an assembled
//! pipeline ([`plan_mission`]) in the sequential or joint mode (sequencing, PoI
//! selection, refinement, dead ends, plan assembly), replanning from a mission state
//! ([`replan_mission`], the long-lived [`MissionSession`]), post-processing and
//! evaluation. The path oracle ([`PathOracle`]) lives here: every
//! query of a mission goes through it and shares the planner's roadmap. The core keeps
//! the model, the stage traits, config, the registry and pipeline assembly; the deadline and memory limit come with the
//! pipeline's run context.

#![warn(missing_docs)]

mod assembly;
mod dead_ends;
pub mod evaluation;
mod fingerprint;
mod joint;
mod layout;
mod lazy;
mod matrix;
pub mod oracle;
pub mod post_process;
mod probe;
mod replan;
mod run;
mod sequential;
mod session;
mod team;
#[cfg(test)]
mod test_support;
mod unreachable;

pub use fingerprint::{fingerprint, traversability_files};
pub use oracle::{KnownAnswers, OracleStats, PathOracle, PlannedPath};
pub use probe::{CutOff, Side};
pub use replan::{
    assemble_replan, assemble_replan_fingerprinted, changed_discs, replan_mission,
    replan_mission_reporting, NoTargetLeft, ReplanInfo, SkippedTarget,
};
pub use run::{plan_mission, plan_mission_reporting, MissionFailed};
pub use session::{MissionSession, WorldUpdate};
pub use smug_core::mission::{Mission, PlanOptions};
pub use team::{plan_team, TeamMember, TeamMission};
pub use unreachable::Unreachable;
