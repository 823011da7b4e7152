//! What the replan tests share: the properties every replan must have, and random
//! mission states of the flat demo.

use proptest::prelude::*;
use smug_core::mission::{DiscObstacle, MissionState};
use smug_core::{Pipeline, Plan};

/// Checks the replan's properties against the state and the updated world.
pub fn check_replan(plan: &Plan, pipeline: &Pipeline, state: &MissionState) {
    let mission = &pipeline.given_mission.as_ref().unwrap();
    for chosen in &plan.pois {
        assert!(
            !state.visited.contains(&chosen.target),
            "visited {chosen:?}"
        );
        assert!(
            !state.failed(&chosen.target, chosen.index),
            "failed {chosen:?}"
        );
        let target = mission
            .targets
            .iter()
            .find(|t| t.id == chosen.target)
            .unwrap();
        assert_eq!(target.pois[chosen.index], chosen.pose);
    }
    let first = plan.segments.first().unwrap().path.states[0];
    assert_eq!(first, state.pose(), "starts at the state's pose");
    let last = *plan.segments.last().unwrap().path.states.last().unwrap();
    let end = mission.end_pose();
    assert_eq!((last.x, last.y), (end.x, end.y), "ends at the end pose");
    let w = plan.waypoints.first().unwrap();
    assert_eq!((w.x, w.y), (state.pose[0], state.pose[1]));
    let motions = pipeline.motion_validator.clone().unwrap();
    for segment in &plan.segments {
        for pair in segment.path.states.windows(2) {
            assert!(motions.check_motion(&pair[0], &pair[1]).is_valid());
        }
    }
    for pair in plan.waypoints.windows(2) {
        assert!(motions
            .check_motion(&pair[0].pose(), &pair[1].pose())
            .is_valid());
    }
    let mut states: Vec<_> = plan.waypoints.iter().map(|w| w.pose()).collect();
    states.extend(
        plan.segments
            .iter()
            .flat_map(|s| s.path.states.iter().copied()),
    );
    for p in &states {
        for o in &state.obstacles {
            assert!(!o.contains(p.x, p.y), "{p:?} inside the new obstacle {o:?}");
        }
    }
    let mut covered: Vec<&String> = plan.sequence.iter().chain(&plan.skipped).collect();
    covered.extend(&state.visited);
    covered.sort();
    assert_eq!(
        covered.len(),
        mission.targets.len(),
        "every target accounted for once"
    );
}

/// Free poses of the flat demo (outside both boxes, clear of the walls).
pub const POSES: [[f64; 3]; 6] = [
    [1.0, 1.0, 0.0],
    [3.0, 2.0, 1.0],
    [6.5, 3.0, -1.5],
    [6.5, 6.5, 2.0],
    [10.5, 2.0, 3.0],
    [2.0, 7.0, -0.5],
];

pub fn state_strategy() -> impl Strategy<Value = MissionState> {
    (
        0..POSES.len(),
        prop::collection::vec(any::<bool>(), 3),
        prop::collection::vec(any::<bool>(), 5),
        prop::option::of((0.5..11.5f64, 0.5..7.5f64, 0.3..0.8f64)),
    )
        .prop_map(|(pose, visited, failed, obstacle)| {
            let ids = ["gauge-a", "gauge-b", "valve-c"];
            let pois = [
                ("gauge-a", 0),
                ("gauge-a", 1),
                ("gauge-b", 0),
                ("gauge-b", 1),
                ("valve-c", 0),
            ];
            let visited: Vec<String> = ids
                .iter()
                .zip(&visited)
                .filter(|(_, v)| **v)
                .map(|(id, _)| id.to_string())
                .collect();
            let failed_pois = pois
                .iter()
                .zip(&failed)
                .filter(|((id, _), f)| **f && !visited.iter().any(|v| v == id))
                .map(|((id, k), _)| (id.to_string(), *k))
                .collect();
            let pose = POSES[pose];
            // Keep the obstacle off the robot and the end pose (1, 1).
            let obstacles = obstacle
                .map(|(x, y, radius)| DiscObstacle {
                    center: [x, y],
                    radius,
                    height: 1.0,
                })
                .filter(|o| {
                    let clear = |p: [f64; 2]| {
                        (p[0] - o.center[0]).hypot(p[1] - o.center[1]) > o.radius + 1.0
                    };
                    clear([pose[0], pose[1]]) && clear([1.0, 1.0])
                })
                .into_iter()
                .collect();
            MissionState {
                pose,
                visited,
                failed_pois,
                obstacles,
            }
        })
}
