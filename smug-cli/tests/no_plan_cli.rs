//! `smug plan` without a plan (exit 1) still writes a plan.json that says so, machine-
//! readably: `status: no_plan`, stderr's reason, what could not be reached and why, the
//! run's statistics; a plan's plan.json says `status: planned`.

mod common;

use common::{scratch_dir, smug, stderr, workspace};
use std::path::Path;

/// plan.json in `dir`, parsed.
fn plan_json(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("plan.json")).expect("plan.json is written");
    serde_json::from_str(&text).unwrap()
}

#[test]
fn a_car_that_cannot_close_its_tour_gets_a_no_plan_plan_json() {
    let out = scratch_dir("no-plan-cli", "dubins-lunar");
    // A plan from before in the directory: its drawings must not outlive it.
    std::fs::write(out.join("plan.csv"), "x,y,z,yaw\n").unwrap();
    let run = smug(&[
        "plan",
        "configs/lunar.toml",
        "--set",
        "space.type=\"dubins\"",
        "--set",
        "space.params.turning_radius=1.5",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(1), "{err}");
    assert!(err.contains("end pose"), "{err}");
    let plan = plan_json(&out);
    assert_eq!(plan["status"], "no_plan");
    assert_eq!(plan["cause"], "cut_off");
    let reason = plan["reason"].as_str().unwrap();
    assert!(
        !reason.is_empty() && err.contains(reason),
        "{reason} / {err}"
    );
    let end = &plan["unreachable"][0];
    assert_eq!(end["kind"], "end");
    assert_eq!(end["no_path"], "proved");
    assert_eq!(end["why"], "exhausted");
    assert_eq!(end["pose"].as_array().unwrap().len(), 3);
    assert!(plan["stats"]["validity_queries"].as_u64().unwrap() > 0);
    assert!(plan["stats"]["stage_times_s"]["total"].as_f64().unwrap() > 0.0);
    for file in ["plan.csv", "plan.svg", "plan.mcap"] {
        assert!(!out.join(file).exists(), "{file} written without a plan");
    }
}

#[test]
fn an_unreachable_target_is_named_with_how_its_legs_ended() {
    // valve-c's PoI walled in by a box around it, LazyPRM* on a small sample budget.
    let text = std::fs::read_to_string(workspace().join("configs/flat-demo.toml"))
        .unwrap()
        .replace(
            "{ min = [8.0, 3.0], max = [9.0, 8.0], height = 1.0 },",
            "{ min = [8.0, 3.0], max = [9.0, 8.0], height = 1.0 },\n    { min = [9.0, 3.4], max = [12.0, 3.6], height = 1.0 },\n    { min = [9.0, 6.4], max = [12.0, 6.6], height = 1.0 },\n    { min = [9.0, 3.4], max = [9.2, 6.6], height = 1.0 },\n    { min = [11.8, 3.4], max = [12.0, 6.6], height = 1.0 },",
        )
        .replace(
            "type = \"lazy-prm-star\"",
            "type = \"lazy-prm-star\"\nparams = { max_samples = 800 }",
        )
        .replace("params = { shortcut = true }\n", "");
    // Beside a copy of the robot it includes.
    let dir = scratch_dir("no-plan-cli", "walled-config");
    std::fs::create_dir_all(dir.join("robots")).unwrap();
    let robot = workspace().join("configs/robots/anymal.toml");
    std::fs::copy(robot, dir.join("robots/anymal.toml")).unwrap();
    let config = dir.join("walled.toml");
    std::fs::write(&config, text).unwrap();
    let out = scratch_dir("no-plan-cli", "walled");
    let run = smug(&[
        "plan",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(1), "{err}");
    let plan = plan_json(&out);
    assert_eq!(plan["status"], "no_plan");
    assert_eq!(plan["cause"], "unreachable");
    assert!(plan["reason"].as_str().unwrap().contains("`valve-c`"));
    let target = &plan["unreachable"][0];
    assert_eq!(target["kind"], "target");
    assert_eq!(target["target"], "valve-c");
    assert_eq!(target["no_path"], "budget_spent", "{target}");
    assert!(!target["legs"].as_object().unwrap().is_empty(), "{target}");
    assert!(plan["stats"]["paths_planned"].as_u64().unwrap() > 0);
}

#[test]
fn a_plan_says_it_is_planned_in_plan_json_and_on_stdout() {
    let out = scratch_dir("no-plan-cli", "planned");
    let run = smug(&[
        "plan",
        "configs/flat-demo.toml",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let plan = plan_json(&out);
    assert_eq!(plan["status"], "planned");
    assert!(plan["sequence"].as_array().is_some_and(|s| !s.is_empty()));
    let json = smug(&[
        "plan",
        "configs/flat-demo.toml",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    let printed: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(printed["status"], "planned");
}
