//! End-to-end tests of `smug replan`: the written plan, exit codes and messages.

mod common;

use common::*;
use std::path::PathBuf;

/// A scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    scratch_dir("replan-cli-tests", name)
}

/// Writes a state file and returns its path as text.
fn state_file(dir: &std::path::Path, text: &str) -> String {
    let path = dir.join("state.toml");
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

fn replan(state: &str, out: &std::path::Path) -> std::process::Output {
    let out = out.to_string_lossy().into_owned();
    smug(&[
        "replan",
        "configs/flat-demo.toml",
        "--state",
        state,
        "--out",
        &out,
    ])
}

fn plan_json(dir: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("plan.json")).unwrap()).unwrap()
}

#[test]
fn replan_writes_a_marked_plan_from_the_state() {
    let dir = scratch("marked");
    let state = state_file(
        &dir,
        "pose = [6.5, 3.0, -1.5708]\nvisited = [\"gauge-b\"]\nfailed_pois = [[\"gauge-a\", 0]]\n\
         [[obstacles]]\ncenter = [2.5, 3.5]\nradius = 0.6\nheight = 1.0\n",
    );
    let out = replan(&state, &dir);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    for file in ["plan.json", "plan.csv", "plan.svg"] {
        assert!(dir.join(file).is_file(), "{file}");
    }
    let plan = plan_json(&dir);
    let sequence: Vec<&str> = plan["sequence"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(sequence.len(), 2);
    assert!(!sequence.contains(&"gauge-b"));
    let gauge_a = plan["pois"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["target"] == "gauge-a");
    assert_eq!(gauge_a.unwrap()["index"], 1, "the failed PoI 0 is excluded");
    let replan = &plan["replan"];
    assert_eq!(replan["state"]["visited"][0], "gauge-b");
    assert_eq!(replan["state"]["obstacles"][0]["radius"], 0.6);
    assert!(replan["state_file"]
        .as_str()
        .unwrap()
        .ends_with("state.toml"));
    assert_eq!(plan["waypoints"][0][0], 6.5);
}

#[test]
fn an_empty_state_writes_the_plan_of_smug_plan() {
    let dir = scratch("empty");
    let planned = dir.join("plan");
    let out = smug(&[
        "plan",
        "configs/flat-demo.toml",
        "--out",
        planned.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let state = state_file(&dir, "pose = [1.0, 1.0, 0.0]\n");
    let replanned = dir.join("replan");
    let out = replan(&state, &replanned);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let (a, b) = (plan_json(&planned), plan_json(&replanned));
    for key in [
        "sequence",
        "pois",
        "segments",
        "waypoints",
        "cost",
        "metrics",
    ] {
        assert_eq!(a[key], b[key], "{key}");
    }
    assert_eq!(
        std::fs::read(planned.join("plan.csv")).unwrap(),
        std::fs::read(replanned.join("plan.csv")).unwrap()
    );
}

#[test]
fn bad_states_exit_2_naming_the_key() {
    let dir = scratch("bad");
    let cases: [(&str, &[&str]); 9] = [
        ("pose = [50.0, 1.0, 0.0]", &["`pose`", "off the map"]),
        (
            "pose = [1.0, 1.0, 0.0]\n[[obstacles]]\ncenter = [1.2, 1.0]\nradius = 0.5\nheight = 1.0",
            &["`pose`", "inside obstacles[0]"],
        ),
        ("pose = [1.0, 1.0, 0.0]\nvisited = [\"nope\"]", &["`visited[0]`", "unknown target id `nope`"]),
        ("pose = [1.0, 1.0, 0.0]\nfailed_pois = [[\"gauge-a\", 5]]", &["`failed_pois[0]`", "out of range"]),
        (
            "pose = [1.0, 1.0, 0.0]\nvisited = [\"gauge-a\"]\nfailed_pois = [[\"gauge-a\", 1]]",
            &["`failed_pois[0]`", "both visited and failed"],
        ),
        ("pose = [1.0, 1.0, 0.0]\nvisitd = []", &["visitd", "line 2"]),
        ("pose = [1.0, 1.0]", &["pose", "length 3"]),
        (
            "pose = [1.0, 1.0, 0.0]\n[[obstacles]]\ncenter = [5.0, 5.0]\nradius = -1.0\nheight = 1.0",
            &["`obstacles[0]`", "radius"],
        ),
        (
            "[[robots]]\nname = \"a\"\npose = [1.0, 1.0, 0.0]",
            &["`robots`", "this is a team state"],
        ),
    ];
    for (text, needles) in cases {
        let state = state_file(&dir, text);
        let out = replan(&state, &dir.join("out"));
        let mut needles = needles.to_vec();
        needles.push("state.toml");
        assert_bad_input(&out, &needles);
    }
    // On the map, but the robot's box overlaps the demo's first box (x from 4 m).
    let state = state_file(&dir, "pose = [3.8, 1.0, 0.0]");
    let out = replan(&state, &dir.join("out"));
    assert_bad_input(&out, &["state.toml", "`pose`", "not valid for the robot"]);
    let out = replan("no/such/state.toml", &dir.join("out"));
    assert_bad_input(&out, &["no/such/state.toml", "cannot read"]);
}

#[test]
fn a_state_that_leaves_no_target_exits_1_and_says_so() {
    let dir = scratch("none-left");
    let out_dir = dir.join("out");
    let earlier = state_file(&dir, "pose = [1.0, 1.0, 0.0]\nvisited = [\"gauge-a\"]");
    assert_eq!(replan(&earlier, &out_dir).status.code(), Some(0));
    for text in [
        "pose = [1.0, 1.0, 0.0]\nvisited = [\"gauge-a\", \"gauge-b\", \"valve-c\"]",
        "pose = [1.0, 1.0, 0.0]\nvisited = [\"gauge-a\", \"gauge-b\"]\nfailed_pois = [[\"valve-c\", 0]]",
    ] {
        let state = state_file(&dir, text);
        let out = replan(&state, &out_dir);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(err.contains("no reachable target"), "{err}");
        // plan.json says so; the earlier plan's table and drawing are gone, the
        // recording of the earlier plans stays.
        let plan = plan_json(&out_dir);
        assert_eq!(plan["status"], "no_plan", "{plan}");
        assert_eq!(plan["cause"], "no_target_left", "{plan}");
        assert!(plan["reason"].as_str().unwrap().contains("no reachable target"));
        assert!(!out_dir.join("plan.csv").exists() && !out_dir.join("plan.svg").exists());
        assert!(out_dir.join("plan.mcap").is_file());
    }
}
