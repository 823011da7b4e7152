//! End-to-end tests of plan.mcap: `smug plan` writes it beside plan.json, its path
//! equals plan.json's waypoints, and `smug replan` appends the replan after the plan.

mod common;

use common::*;
use smug_app::plan_mcap::{read_plan_mcap, McapPlan, PLAN_TOPIC, TF_TOPIC};
use std::path::Path;

/// plan.json of `dir`.
fn plan_json(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("plan.json")).unwrap()).unwrap()
}

/// Asserts that path number `index` of `mcap` holds plan.json's waypoints of `dir`:
/// positions and z exactly, yaw through its quaternion to 1e-12.
fn assert_path_is_plan_json(mcap: &McapPlan, index: usize, dir: &Path) {
    let plan = plan_json(dir);
    let waypoints = plan["waypoints"].as_array().unwrap();
    let path = &mcap.paths[index];
    assert_eq!(path.header.frame_id, "map");
    assert_eq!(path.poses.len(), waypoints.len());
    for (pose, w) in path.poses.iter().zip(waypoints) {
        let p = &pose.pose.position;
        let field = |k: usize| w[k].as_f64().unwrap();
        assert_eq!([p.x, p.y, p.z], [field(0), field(1), field(2)]);
        let yaw = pose.pose.orientation.yaw();
        let diff = (yaw - field(3) + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        assert!(diff.abs() < 1e-12, "yaw {yaw} vs {}", field(3));
    }
}

#[test]
fn lunar_plan_mcap_holds_plan_json_s_waypoints_and_the_run() {
    let dir = scratch_dir("mcap-cli-tests", "lunar");
    let out_dir = dir.to_string_lossy().into_owned();
    let out = smug(&[
        "plan",
        "configs/lunar.toml",
        "--seed",
        "3",
        "--out",
        &out_dir,
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let mcap = read_plan_mcap(&dir.join("plan.mcap")).unwrap();
    assert_eq!(mcap.profile, "ros2");
    assert_eq!(mcap.paths.len(), 1);
    assert_path_is_plan_json(&mcap, 0, &dir);
    let waypoints = plan_json(&dir)["waypoints"].as_array().unwrap().len();
    assert_eq!(mcap.counts[TF_TOPIC], waypoints);
    for (topic, schema) in [
        (PLAN_TOPIC, "nav_msgs/msg/Path"),
        ("/smug/pois", "geometry_msgs/msg/PoseArray"),
        ("/smug/markers", "visualization_msgs/msg/MarkerArray"),
        ("/smug/occupancy", "nav_msgs/msg/OccupancyGrid"),
        ("/smug/traversability", "nav_msgs/msg/OccupancyGrid"),
        (TF_TOPIC, "tf2_msgs/msg/TFMessage"),
    ] {
        let channel = (topic.to_owned(), schema.to_owned(), "ros2msg".to_owned());
        assert!(mcap.channels.contains(&channel), "{channel:?}");
    }
    let meta = &mcap.metadata[0];
    assert_eq!(meta["kind"], "plan");
    assert_eq!(meta["seed"], "3");
    assert_eq!(meta["version"], env!("CARGO_PKG_VERSION"));
    assert!(
        meta["config"].contains("type = \"lunar\""),
        "{}",
        meta["config"]
    );

    // The same run writes the same bytes.
    let again = scratch_dir("mcap-cli-tests", "lunar-again");
    let again_dir = again.to_string_lossy().into_owned();
    let out = smug(&[
        "plan",
        "configs/lunar.toml",
        "--seed",
        "3",
        "--out",
        &again_dir,
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(
        std::fs::read(dir.join("plan.mcap")).unwrap(),
        std::fs::read(again.join("plan.mcap")).unwrap()
    );
}

#[test]
fn a_replan_appends_its_path_after_the_plan_s() {
    let dir = scratch_dir("mcap-cli-tests", "replan");
    let out_dir = dir.to_string_lossy().into_owned();
    let out = smug(&["plan", "configs/flat-demo.toml", "--out", &out_dir]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let first = read_plan_mcap(&dir.join("plan.mcap")).unwrap();
    let state = dir.join("state.toml");
    std::fs::write(
        &state,
        "pose = [6.5, 3.0, -1.5708]\nvisited = [\"gauge-b\"]\n",
    )
    .unwrap();
    let state = state.to_string_lossy().into_owned();
    let out = smug(&[
        "replan",
        "configs/flat-demo.toml",
        "--state",
        &state,
        "--out",
        &out_dir,
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let both = read_plan_mcap(&dir.join("plan.mcap")).unwrap();
    assert_eq!(both.paths.len(), 2);
    assert_eq!(both.paths[0], first.paths[0]);
    assert_path_is_plan_json(&both, 1, &dir);
    let stamp = |m: &McapPlan, k: usize| m.paths[k].header.stamp.sec;
    assert!(stamp(&both, 1) > stamp(&both, 0));
    let kinds: Vec<&str> = both.metadata.iter().map(|m| m["kind"].as_str()).collect();
    assert_eq!(kinds, ["plan", "replan"]);
}

#[test]
fn output_mcap_false_writes_no_mcap() {
    let dir = scratch_dir("mcap-cli-tests", "off");
    let out_dir = dir.to_string_lossy().into_owned();
    let out = smug(&[
        "plan",
        "configs/flat-demo.toml",
        "--set",
        "output.mcap=false",
        "--out",
        &out_dir,
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(dir.join("plan.json").is_file());
    assert!(!dir.join("plan.mcap").exists());
}
