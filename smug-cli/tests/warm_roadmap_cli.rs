//! End-to-end tests of `smug plan --save-roadmap` and `smug replan --roadmap`: an
//! empty state on the saved roadmap reproduces the plan bit-identically; a roadmap of
//! another world or robot, or a truncated one, is refused naming the file and why.

mod common;

use common::*;
use std::path::{Path, PathBuf};

/// A scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    scratch_dir("warm-roadmap-tests", name)
}

fn text(p: &Path) -> String {
    p.to_string_lossy().into_owned()
}

/// Plans `config` into `dir/plan`, saving its roadmap to `dir/<stem>.roadmap`.
fn plan_saving(config: &str, dir: &Path) -> PathBuf {
    let file = dir.join("saved.roadmap");
    let out = smug(&[
        "plan",
        config,
        "--out",
        &text(&dir.join("plan")),
        "--save-roadmap",
        &text(&file),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    file
}

fn replan_on(
    config: &str,
    dir: &Path,
    state: &str,
    roadmap: &Path,
    extra: &[&str],
) -> std::process::Output {
    let state_file = dir.join("state.toml");
    std::fs::write(&state_file, state).unwrap();
    let mut args = vec![
        "replan".to_string(),
        config.to_string(),
        "--state".into(),
        text(&state_file),
        "--out".into(),
        text(&dir.join("replan")),
        "--roadmap".into(),
        text(roadmap),
    ];
    args.extend(extra.iter().map(|s| s.to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    smug(&args)
}

fn plan_json(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("plan.json")).unwrap()).unwrap()
}

/// The state at the mission's start with nothing else: `pose` from the plan.
fn empty_state(plan: &serde_json::Value) -> String {
    let w = &plan["segments"][0]["path"]["states"][0];
    format!("pose = [{}, {}, {}]\n", w["x"], w["y"], w["yaw"])
}

#[test]
fn an_empty_state_on_the_saved_roadmap_reproduces_the_plan_bit_identically() {
    for config in ["configs/lunar.toml", "configs/flat-demo.toml"] {
        let dir = scratch(config.trim_start_matches("configs/"));
        let roadmap = plan_saving(config, &dir);
        let original = plan_json(&dir.join("plan"));
        let out = replan_on(config, &dir, &empty_state(&original), &roadmap, &[]);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        let again = plan_json(&dir.join("replan"));
        for key in [
            "sequence",
            "pois",
            "segments",
            "waypoints",
            "cost",
            "metrics",
        ] {
            assert_eq!(original[key], again[key], "{config}: {key}");
        }
        let counters = &again["stats"]["counters"];
        assert!(
            counters["warm_answers_served"].as_u64().unwrap() > 0,
            "{config}"
        );
        assert_eq!(counters["samples"], 0, "{config}: nothing planned again");
    }
}

#[test]
fn a_roadmap_of_another_world_or_robot_or_truncated_is_refused_naming_why() {
    let dir = scratch("refused");
    let roadmap = plan_saving("configs/flat-demo.toml", &dir);
    let original = plan_json(&dir.join("plan"));
    let state = empty_state(&original);
    let name = roadmap.file_name().unwrap().to_str().unwrap();
    let lunar = "pose = [2.0, 2.0, 0.7853981633974483]\n";
    let out = replan_on("configs/lunar.toml", &dir, lunar, &roadmap, &[]);
    assert_bad_input(&out, &[name, "another world"]);
    let out = replan_on(
        "configs/flat-demo.toml",
        &dir,
        &state,
        &roadmap,
        &["--set", "robot.width=0.5"],
    );
    assert_bad_input(&out, &[name, "another robot"]);
    let bytes = std::fs::read(&roadmap).unwrap();
    for keep in [0, 40, bytes.len() / 2, bytes.len() - 1] {
        let cut = dir.join("cut.roadmap");
        std::fs::write(&cut, &bytes[..keep]).unwrap();
        let out = replan_on("configs/flat-demo.toml", &dir, &state, &cut, &[]);
        let why = if keep > 300 {
            "truncated"
        } else {
            "not a SMUG roadmap"
        };
        assert_bad_input(&out, &["cut.roadmap", why]);
    }
    let mut damaged = bytes.clone();
    let last = damaged.len() - 2;
    damaged[last] ^= 1;
    let bad = dir.join("damaged.roadmap");
    std::fs::write(&bad, &damaged).unwrap();
    let out = replan_on("configs/flat-demo.toml", &dir, &state, &bad, &[]);
    assert_bad_input(&out, &["damaged.roadmap", "checksum"]);
    let other = String::from_utf8(bytes)
        .unwrap()
        .replacen("\"version\":1", "\"version\":7", 1);
    let versioned = dir.join("v7.roadmap");
    std::fs::write(&versioned, other).unwrap();
    let out = replan_on("configs/flat-demo.toml", &dir, &state, &versioned, &[]);
    assert_bad_input(&out, &["v7.roadmap", "version 7"]);
}
