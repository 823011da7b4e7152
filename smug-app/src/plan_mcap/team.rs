//! A team plan as ROS 2 messages: the shared world's grids and markers once (every
//! robot's chosen PoIs green), then each robot's path and chosen PoIs on topics of its
//! own (`/smug/<robot>/plan`, `/smug/<robot>/pois`) and its pose along its path on `/tf`
//! as frame `<robot>/base_link`, the robots side by side in time.

use super::scene::{
    map_messages, occupancy_message, route_messages, transforms, PlanScene, RobotTopics, Stamped,
};
use smug_core::{Mission, Plan, TeamPlan, World};

/// What one team plan's messages show.
pub struct TeamScene<'a> {
    /// The team plan.
    pub plan: &'a TeamPlan,
    /// The world it was made in.
    pub world: &'a World,
    /// The mission as planned.
    pub mission: &'a Mission,
}

/// Every message of `scene`, stamped from `t0_ns` on, in log-time order (robots in
/// the team's order at equal times).
pub fn team_scene_messages(scene: &TeamScene<'_>, t0_ns: u64) -> Vec<Stamped> {
    let everyone = every_robots_pois(scene.plan);
    let shared = PlanScene {
        plan: &everyone,
        world: scene.world,
        mission: scene.mission,
        invalid_pois: &[],
    };
    let mut messages = vec![occupancy_message(&shared, t0_ns)];
    messages.extend(map_messages(&shared, t0_ns));
    let mut moves = Vec::new();
    for robot in &scene.plan.robots {
        let topics = RobotTopics::of_robot(&robot.name);
        let own = PlanScene {
            plan: &robot.plan,
            ..shared
        };
        messages.extend(route_messages(&own, &topics, t0_ns));
        moves.extend(transforms(&robot.plan, &topics, t0_ns));
    }
    // Stable: at equal times the robots keep the team's order.
    moves.sort_by_key(|m| m.time_ns);
    messages.extend(moves);
    messages
}

/// A plan holding every robot's chosen PoIs (for the markers' colours).
fn every_robots_pois(plan: &TeamPlan) -> Plan {
    Plan {
        pois: plan
            .robots
            .iter()
            .flat_map(|r| r.plan.pois.iter().cloned())
            .collect(),
        ..Plan::default()
    }
}
