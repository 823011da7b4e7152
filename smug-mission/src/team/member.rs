//! What a team is made of: its robots (each with its own pipeline) and its mission.

use smug_core::mission::Mission;
use smug_core::objective::Objective;
use smug_core::pipeline::Pipeline;
use smug_core::pose::Pose2;
use std::sync::Arc;

/// One robot of a team: its name, its assembled pipeline (on the shared world, without
/// a mission of its own), where it starts and ends.
pub struct TeamMember {
    /// Its name in the team config.
    pub name: String,
    /// Its pipeline (checkers, objective, planner).
    pub pipeline: Pipeline,
    /// Start pose.
    pub start: Pose2,
    /// End pose (`None`: back at the start).
    pub end: Option<Pose2>,
    /// The `time` objective at its speed, for its plan's `time` when the team's unit is
    /// not time (`None`: its cost is its time).
    pub time: Option<Arc<dyn Objective>>,
}

/// What a team does: the shared mission's targets and who may serve them.
pub struct TeamMission {
    /// The targets (with every PoI, as the world gave them).
    pub mission: Mission,
    /// Per target, the robots (indices) allowed to serve it; `None`: every robot.
    pub allowed: Vec<Option<Vec<usize>>>,
    /// The unit of the robots' costs, for the plan (`time` or `objective`).
    pub unit: String,
    /// Keep the roadmap's headings in the waypoints (`[plan] keep_headings`).
    pub keep_headings: bool,
    /// The run's deadline in seconds (`None`: no limit); every robot's planner and the
    /// team sequencer stop at it.
    pub deadline_s: Option<f64>,
    /// Seconds of the deadline spent before planning (assembling the team).
    pub spent_s: f64,
}
