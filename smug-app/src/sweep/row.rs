//! What one run of a sweep reports: one row, the same from the CLI and from Python
//! (the timing fields, [`TIMING_FIELDS`], aside).

use super::spec::RunSpec;
use crate::outcome::NoSolution;
use crate::version::VERSION;
use serde::{Deserialize, Serialize};
use smug_core::plan::PlanMetrics;
use smug_core::Plan;
use std::collections::BTreeMap;

/// The fields of a row that measure time: they differ between two runs of one spec,
/// every other field is equal.
pub const TIMING_FIELDS: [&str; 2] = ["stage_times_s", "total_time_s"];

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunStatus {
    /// A plan was found.
    Ok,
    /// Some targets cannot be reached (no safe path), or none is left.
    Unreachable,
    /// The run's deadline (`plan.deadline`) passed before a complete plan was found.
    Deadline,
    /// The run failed: a config, input or planning error (the row's `error` says which).
    Error,
}

impl RunStatus {
    /// The status as its row writes it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Ok => "ok",
            Self::Unreachable => "unreachable",
            Self::Deadline => "deadline",
            Self::Error => "error",
        }
    }
}

/// One run of a sweep: what it ran and what it found. Every field is always present
/// (`null` where a run has no value), so rows make columns.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepRow {
    /// The run's id ([`run_id`](super::spec::run_id)).
    pub run_id: String,
    /// The config file, as given.
    pub config: String,
    /// The grid's overrides, `key=value` each.
    pub overrides: Vec<String>,
    /// The seed.
    pub seed: u64,
    /// How the run ended.
    pub status: RunStatus,
    /// Why there is no plan (`unreachable`, `deadline`, `error`), on one line.
    pub error: Option<String>,
    /// The plan's cost under the planning objective.
    pub cost: Option<f64>,
    /// The plan's length in the plane, metres.
    pub length_m: Option<f64>,
    /// Targets the plan visits.
    pub targets: Option<u64>,
    /// Targets left out as unreachable (`plan.skip_unreachable`).
    pub skipped_targets: Vec<String>,
    /// Whether the run's deadline cut a search short (the plan is the best found by then).
    pub deadline_reached: Option<bool>,
    /// Point-to-point paths planned.
    pub paths_planned: Option<u64>,
    /// State validity queries.
    pub validity_queries: Option<u64>,
    /// The plan's metrics (length, climb, cost under every objective, traversability).
    pub metrics: Option<PlanMetrics>,
    /// Wall time per pipeline stage, seconds (timing).
    pub stage_times_s: BTreeMap<String, f64>,
    /// Wall time of the whole run: config, world, plan; seconds (timing).
    pub total_time_s: f64,
    /// The SMUG version that ran it.
    pub smug_version: String,
}

impl SweepRow {
    /// The row of a run that ended with `status` and no plan, for `why`.
    pub fn failed(spec: &RunSpec, status: RunStatus, why: String, total_time_s: f64) -> Self {
        Self {
            run_id: spec.run_id.clone(),
            config: spec.config.display().to_string(),
            overrides: spec.overrides.clone(),
            seed: spec.seed,
            status,
            error: Some(why),
            cost: None,
            length_m: None,
            targets: None,
            skipped_targets: Vec::new(),
            deadline_reached: None,
            paths_planned: None,
            validity_queries: None,
            metrics: None,
            stage_times_s: BTreeMap::new(),
            total_time_s,
            smug_version: VERSION.to_string(),
        }
    }

    /// The row of a run without a solution.
    pub fn no_solution(spec: &RunSpec, why: &NoSolution, total_time_s: f64) -> Self {
        let status = match why {
            NoSolution::Unreachable(_) | NoSolution::NoTargetLeft(_) => RunStatus::Unreachable,
            NoSolution::DeadlinePassed(_) => RunStatus::Deadline,
        };
        Self::failed(spec, status, why.to_string(), total_time_s)
    }

    /// The row of a run that found `plan`.
    pub fn planned(spec: &RunSpec, plan: &Plan, total_time_s: f64) -> Self {
        Self {
            status: RunStatus::Ok,
            error: None,
            cost: Some(plan.cost),
            length_m: Some(plan.metrics.length_m),
            targets: Some(plan.sequence.len() as u64),
            skipped_targets: plan.skipped.clone(),
            deadline_reached: Some(plan.deadline_reached),
            paths_planned: Some(plan.stats.paths_planned),
            validity_queries: Some(plan.stats.validity_queries),
            metrics: Some(plan.metrics.clone()),
            stage_times_s: plan.stats.stage_times_s.clone(),
            ..Self::failed(spec, RunStatus::Ok, String::new(), total_time_s)
        }
    }

    /// The row as one line of JSON (no newline).
    pub fn to_json_line(&self) -> String {
        serde_json::to_string(self).expect("a row is plain data")
    }
}
