//! `plan.mcap`: a plan as ROS 2 messages (CDR, profile `ros2`, `ros2msg` schemas) for
//! Foxglove, RViz2 and `ros2 bag play`, with the run's config, seed and version as MCAP
//! metadata. A replan appends its messages after the earlier plan's.
//!
//! Topics (frame `map`): [`PLAN_TOPIC`] (`nav_msgs/Path`), [`POIS_TOPIC`]
//! (`geometry_msgs/PoseArray`), [`MARKERS_TOPIC`] (`visualization_msgs/MarkerArray`),
//! [`OCCUPANCY_TOPIC`] and [`TRAVERSABILITY_TOPIC`] (`nav_msgs/OccupancyGrid`),
//! [`TF_TOPIC`] (`tf2_msgs/TFMessage`). The plan's messages are stamped from 1 s on (a
//! replan's 1 s after the earlier plan's last), so a run writes the same bytes each time.
//! A team plan puts each robot's path and PoIs on topics of its own (see [`RobotTopics`])
//! and its transforms as frame `<robot>/base_link`.

mod file;
mod scene;
mod team;

pub use file::{
    read_plan_mcap, write_plan_mcap, write_team_plan_mcap, McapError, McapPlan, RunInfo, WriteMode,
};
pub use scene::{
    scene_messages, traversability_cell, PlanScene, RobotTopics, Stamped, FRAME, MARKERS_TOPIC,
    OCCUPANCY_TOPIC, PLAN_TOPIC, POIS_TOPIC, TF_TOPIC, TRAVERSABILITY_TOPIC,
};
pub use team::{team_scene_messages, TeamScene};
