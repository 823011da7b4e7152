//! The measurements of `smug bench team`, shared by the harness and its report.

use serde::Serialize;
use smug_core::TeamObjective;

/// One robot's part of one plan.
#[derive(Debug, Serialize)]
pub(super) struct RobotRun {
    pub(super) name: String,
    pub(super) targets: usize,
    pub(super) cost: f64,
    pub(super) time_s: f64,
    pub(super) length_m: f64,
}

/// One team plan's measurements.
#[derive(Debug, Serialize)]
pub(super) struct Run {
    pub(super) config: String,
    pub(super) seed: u64,
    /// `shared` or `alone`.
    pub(super) how: &'static str,
    pub(super) objective: TeamObjective,
    pub(super) total: f64,
    pub(super) makespan: f64,
    pub(super) robots: Vec<RobotRun>,
    pub(super) paths_planned: u64,
    pub(super) rounds: u64,
    /// Wall time of the run that made it (both objectives for `shared`), seconds.
    pub(super) wall_s: f64,
}
