//! The output of a planning run: order, chosen PoIs, segments, waypoints, statistics.

use crate::path::Path;
use crate::pose::{Pose2, Waypoint};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

pub use crate::timing::TimeBreakdown;

/// Counters and timings of a planning run.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PlanStats {
    /// Point-to-point paths planned (cache misses of the path oracle).
    pub paths_planned: u64,
    /// State validity queries.
    pub validity_queries: u64,
    /// Wall time per pipeline stage (world, sequencing, selection, …), seconds.
    pub stage_times_s: BTreeMap<String, f64>,
    /// The point-to-point planner's time breakdown.
    pub breakdown: TimeBreakdown,
    /// Any other counters a stage reports.
    pub counters: BTreeMap<String, u64>,
    /// Pose pairs the planner found no path between, by why (`proved:disconnected`,
    /// `proved:exhausted`, `budget_spent:samples`, `budget_spent:time`, …): the
    /// legs the plan could not use, and whether a bigger budget could change that.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub legs_without_path: BTreeMap<String, u64>,
}

/// The PoI chosen for one target.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChosenPoi {
    /// Target id.
    pub target: String,
    /// Index of the PoI in the target's list.
    pub index: usize,
    /// The PoI itself.
    pub pose: Pose2,
}

/// A PoI left out of a plan: the robot cannot get there from the start, or cannot get
/// from there to the end (proved by the planner, e.g. a forward-only car facing a stone
/// up close).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DeadEndPoi {
    /// Target id.
    pub target: String,
    /// Index of the PoI in the target's list.
    pub index: usize,
    /// The PoI itself.
    pub pose: Pose2,
    /// Why: which way is closed and the planner's proof.
    pub why: String,
}

/// One collision-free leg of the plan.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    /// Where it starts: `"start"` or a target id.
    pub from: String,
    /// Where it ends: a target id, `"start"` or `"end"`.
    pub to: String,
    /// The path.
    pub path: Path,
}

/// A safe multi-goal plan.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    /// Target ids in visiting order.
    pub sequence: Vec<String>,
    /// The chosen PoI per target, in visiting order.
    pub pois: Vec<ChosenPoi>,
    /// The legs start → first PoI → … → end.
    pub segments: Vec<Segment>,
    /// `[x, y, z, yaw]` from start to end, for a local planner.
    pub waypoints: Vec<Waypoint>,
    /// For models that drive backwards (Reeds–Shepp): whether the robot reverses into
    /// each waypoint (absent when it never does).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reversing: Vec<bool>,
    /// Total cost under the planning objective.
    pub cost: f64,
    /// Length, cost under every objective, and traversability along the plan.
    #[serde(default)]
    pub metrics: PlanMetrics,
    /// Targets left out (unreachable, with `skip_unreachable = true`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub skipped: Vec<String>,
    /// PoIs left out because the robot cannot reach them from the start or reach the
    /// end from them (proved), for models whose motions are directed.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dead_ends: Vec<DeadEndPoi>,
    /// True when the run's deadline cut an anytime search short (a planner query, the
    /// sequencer's local search): the plan is complete and valid, the best found by then.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub deadline_reached: bool,
    /// Counters and timings.
    pub stats: PlanStats,
    /// The files the `[traversability]` section named (an ONNX model, a layer file), by
    /// name as written, with the FNV-1a digest of their contents.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub traversability_files: BTreeMap<String, String>,
    /// Set on a replan: the mission state it started from and what it left out.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replan: Option<ReplanInfo>,
}

/// Traversability below this counts as risky ground in [`PlanMetrics::risky_length_m`].
pub const RISKY_TRAVERSABILITY: f64 = 0.5;

/// A plan's length, costs under each objective and the ground it crosses.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PlanMetrics {
    /// The objective the plan was made with.
    pub objective: String,
    /// Length in the plane along the space's motions, metres.
    pub length_m: f64,
    /// Height climbed (Σ max(0, Δz) along the path, sampled every half cell), metres.
    pub climb_m: f64,
    /// Cost under each registered objective: the planning one with its configured
    /// parameters, the others with their defaults (those the world cannot support,
    /// e.g. without a traversability layer, are left out).
    pub costs: BTreeMap<String, f64>,
    /// Lowest traversability along the path (`None` without a traversability layer).
    pub traversability_min: Option<f64>,
    /// Length-weighted mean traversability along the path.
    pub traversability_mean: Option<f64>,
    /// Length spent where traversability is below [`RISKY_TRAVERSABILITY`], metres.
    pub risky_length_m: Option<f64>,
}

/// What marks a plan as a replan: the state it started from and what it left out.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReplanInfo {
    /// The state file, when the state came from one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub state_file: Option<String>,
    /// The mission state the replan started from.
    pub state: crate::mission::MissionState,
    /// Targets not visited by this plan (besides the visited ones), with the reason.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub skipped: Vec<SkippedTarget>,
}

/// A target the replan leaves out.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SkippedTarget {
    /// Target id.
    pub target: String,
    /// Why, e.g. "every PoI failed".
    pub reason: String,
}

/// One robot's part of a team plan: its name, its plan (targets, PoIs, waypoints,
/// cost, gears) and its travel time.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RobotPlan {
    /// The robot's name in the team config.
    pub name: String,
    /// Travel time of its route under the `time` objective at its own speed, seconds.
    pub time: f64,
    /// Its plan (the cost in the team's unit).
    #[serde(flatten)]
    pub plan: Plan,
}

/// A team plan: one plan per robot, the team's sum and makespan.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TeamPlan {
    /// What the team minimised.
    pub objective: crate::stages::TeamObjective,
    /// The unit of the costs (`time`, or the objective every robot planned with).
    pub unit: String,
    /// The objective's value: `total` for the sum, `makespan` for the makespan.
    pub cost: f64,
    /// Sum of the robots' costs.
    pub total: f64,
    /// Largest robot cost.
    pub makespan: f64,
    /// One entry per robot, in the config's order (a robot with nothing to do has an
    /// empty sequence).
    pub robots: Vec<RobotPlan>,
    /// Counters and timings of the whole team run (paths planned by every robot,
    /// rounds of the lazy team sequencing, stage times).
    pub stats: PlanStats,
    /// Set when the plan is a team replan: the state it started from, the robots
    /// lost and the targets left out.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replan: Option<TeamReplanInfo>,
}

/// What a team replan started from and left out.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TeamReplanInfo {
    /// The state file, when the state came from one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub state_file: Option<String>,
    /// The team state the replan started from.
    pub state: crate::mission::TeamState,
    /// Robots lost: no plan of theirs, their targets shared among the others.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lost: Vec<String>,
    /// Targets not visited by this plan (besides the visited ones), with the reason.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub skipped: Vec<SkippedTarget>,
}
