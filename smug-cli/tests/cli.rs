//! End-to-end tests of the `smug` binary: exit codes and error messages.

mod common;

use common::*;

/// Writes `text` as a config next to the shipped ones (so includes resolve) and
/// returns its path relative to the workspace.
fn temp_config(name: &str, text: &str) -> String {
    let dir = workspace().join("target").join("cli-test-configs");
    std::fs::create_dir_all(dir.join("robots")).unwrap();
    std::fs::copy(
        workspace().join("configs/robots/anymal.toml"),
        dir.join("robots/anymal.toml"),
    )
    .unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

fn demo_config() -> String {
    std::fs::read_to_string(workspace().join("configs/flat-demo.toml")).unwrap()
}

#[test]
fn plugins_lists_every_stage_and_the_builtin_plugins() {
    let out = smug(&["plugins"]);
    assert_eq!(out.status.code(), Some(0));
    let text = stdout(&out);
    for needle in [
        "[world]",
        "[planner]",
        "[selector]",
        "[team_sequencer]",
        "team-auto",
        "se2",
        "flat",
        "informed",
        "uniform",
        "discrete",
        "brute-force",
        "path-length",
        "traversability",
        "energy",
        "time",
        "rotation_weight = 0.5",
    ] {
        assert!(text.contains(needle), "`{needle}` missing from:\n{text}");
    }
    let json: serde_json::Value =
        serde_json::from_slice(&smug(&["plugins", "--json"]).stdout).unwrap();
    assert_eq!(json.as_array().unwrap().len(), 11);
}

#[test]
fn every_shipped_mission_config_plans() {
    for entry in std::fs::read_dir(workspace().join("configs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        if !text.contains("[selector]") && !path.ends_with("lunar-full-collision.toml") {
            continue; // a fragment or a pipeline without PoI selection
        }
        let out = workspace()
            .join("target/cli-test-configs/plans")
            .join(path.file_stem().unwrap());
        let run = smug(&[
            "plan",
            path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(
            run.status.code(),
            Some(0),
            "{}: {}",
            path.display(),
            stderr(&run)
        );
        assert!(
            out.join("plan.json").exists(),
            "{}: no plan.json",
            path.display()
        );
    }
}

#[test]
fn every_shipped_pipeline_config_checks() {
    for entry in std::fs::read_dir(workspace().join("configs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        if !text.contains("[world]") {
            continue; // a fragment such as a robot profile
        }
        let out = smug(&["check", path.to_str().unwrap()]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{}: {}",
            path.display(),
            stderr(&out)
        );
    }
}

#[test]
fn check_prints_the_resolved_pipeline_with_defaults() {
    let out = smug(&["check", "configs/flat-demo.toml"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("world `flat-demo`: 120×80 cells"), "{text}");
    assert!(
        text.contains("max_attempts = 10000"),
        "sampler defaults missing: {text}"
    );
    assert!(
        text.contains("length = 1.07"),
        "included robot profile missing: {text}"
    );
}

#[test]
fn misspelt_key_names_the_key_and_its_line() {
    let config = temp_config(
        "misspelt.toml",
        &demo_config().replace("[sampler]", "[samplr]"),
    );
    let line = demo_config()
        .lines()
        .position(|l| l == "[sampler]")
        .unwrap()
        + 1;
    assert_bad_input(
        &smug(&["check", &config]),
        &[
            "`samplr`",
            "unknown field",
            &format!("misspelt.toml:{line}"),
        ],
    );
}

#[test]
fn misspelt_plugin_parameter_names_the_key_and_its_line() {
    let text = demo_config().replace(
        "type = \"informed\"",
        "type = \"informed\"\nparams = { max_atempts = 3 }",
    );
    let config = temp_config("param.toml", &text);
    assert_bad_input(
        &smug(&["check", &config]),
        &[
            "`sampler.params.max_atempts`",
            "param.toml:",
            "max_attempts",
        ],
    );
}

#[test]
fn unknown_plugin_lists_the_known_names() {
    let config = temp_config(
        "unknown.toml",
        &demo_config().replace("type = \"informed\"", "type = \"informd\""),
    );
    assert_bad_input(
        &smug(&["check", &config]),
        &[
            "`sampler.type`",
            "unknown sampler plugin `informd`",
            "known sampler plugins: bridge, informed, uniform",
        ],
    );
}

#[test]
fn wrong_type_names_the_key() {
    let config = temp_config(
        "type.toml",
        &demo_config().replace("seed = 1", "seed = \"one\""),
    );
    assert_bad_input(
        &smug(&["check", &config]),
        &["`seed`", "invalid type", "type.toml:"],
    );
}

#[test]
fn overrides_change_values_and_reject_unknown_keys() {
    let out = smug(&[
        "check",
        "configs/flat-demo.toml",
        "--set",
        "sampler.type=uniform",
        "--set",
        "objective.params.rotation_weight=0",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(stdout(&out).contains("type = \"uniform\""));
    assert!(stdout(&out).contains("rotation_weight = 0"));
    assert_bad_input(
        &smug(&[
            "check",
            "configs/flat-demo.toml",
            "--set",
            "planner.params.max_stal=5",
        ]),
        &[
            "--set planner.params.max_stal=5",
            "`planner.params.max_stal`: unknown field",
        ],
    );
    assert_bad_input(
        &smug(&[
            "check",
            "configs/flat-demo.toml",
            "--set",
            "sampler.params.max_atempts=5",
        ]),
        &[
            "--set sampler.params.max_atempts=5",
            "`sampler.params.max_atempts`: unknown field",
        ],
    );
    assert_bad_input(
        &smug(&["check", "configs/flat-demo.toml", "--set", "robot.lenght=1"]),
        &["`robot.lenght`", "unknown field"],
    );
}

#[test]
fn bad_values_and_missing_files_are_errors_not_panics() {
    assert_bad_input(
        &smug(&["check", "configs/does-not-exist.toml"]),
        &["does-not-exist.toml", "cannot read"],
    );
    let config = temp_config(
        "weights.toml",
        &demo_config().replace("translation_weight = 1.0", "translation_weight = -1.0"),
    );
    assert_bad_input(
        &smug(&["check", &config]),
        &["translation_weight must be finite and > 0"],
    );
    let config = temp_config("syntax.toml", "seed = \n");
    assert_bad_input(
        &smug(&["check", &config]),
        &["syntax.toml:1", "TOML syntax error"],
    );
    let config = temp_config(
        "outside.toml",
        &demo_config().replace("x = 10.5, y = 5.0", "x = 30.0, y = 5.0"),
    );
    assert_bad_input(
        &smug(&["check", &config]),
        &["PoI 0 of target `valve-c`", "outside the map"],
    );
}

#[test]
fn usage_errors_exit_with_2() {
    assert_eq!(smug(&["frobnicate"]).status.code(), Some(2));
    assert_eq!(smug(&["check"]).status.code(), Some(2));
}

#[test]
fn plan_writes_json_csv_and_svg() {
    let out = workspace().join("target").join("cli-test-plan");
    let _ = std::fs::remove_dir_all(&out);
    let run = smug(&[
        "plan",
        "configs/flat-demo.toml",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    assert!(
        stdout(&run).contains("planned 3 targets"),
        "{}",
        stdout(&run)
    );
    for file in ["plan.json", "plan.csv", "plan.svg"] {
        assert!(
            out.join(file)
                .metadata()
                .map(|m| m.len() > 100)
                .unwrap_or(false),
            "{file} missing or empty"
        );
    }
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    assert_eq!(written["status"], "planned");
    assert!(written["sequence"]
        .as_array()
        .is_some_and(|s| !s.is_empty()));
    let json = smug(&[
        "plan",
        "configs/flat-demo.toml",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    let plan: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(plan["status"], "planned");
    for key in ["sequence", "pois", "segments", "waypoints", "cost", "stats"] {
        assert!(plan.get(key).is_some(), "plan.json lacks `{key}`");
    }
    assert_eq!(
        plan["waypoints"][0].as_array().unwrap().len(),
        4,
        "waypoints are [x, y, z, yaw]"
    );
}

#[test]
fn an_unreachable_target_exits_with_1_and_is_named() {
    // valve-c's PoI walled in by a box around it.
    let text = demo_config().replace(
        "{ min = [8.0, 3.0], max = [9.0, 8.0], height = 1.0 },",
        "{ min = [8.0, 3.0], max = [9.0, 8.0], height = 1.0 },\n    { min = [9.0, 3.4], max = [12.0, 3.6], height = 1.0 },\n    { min = [9.0, 6.4], max = [12.0, 6.6], height = 1.0 },\n    { min = [9.0, 3.4], max = [9.2, 6.6], height = 1.0 },\n    { min = [11.8, 3.4], max = [12.0, 6.6], height = 1.0 },",
    ).replace("type = \"lazy-prm-star\"", "type = \"lazy-prm-star\"\nparams = { max_samples = 800 }").replace("params = { shortcut = true }\n", "");
    let config = temp_config("walled.toml", &text);
    let run = smug(&["plan", &config, "--out", "target/cli-test-walled"]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(1), "{err}");
    assert!(err.contains("`valve-c`"), "{err}");
    // plan.json names the target and how the legs to it ended.
    let text = std::fs::read_to_string(workspace().join("target/cli-test-walled/plan.json"));
    let plan: serde_json::Value = serde_json::from_str(&text.unwrap()).unwrap();
    assert_eq!(plan["status"], "no_plan");
    assert_eq!(plan["cause"], "unreachable");
    assert!(plan["reason"].as_str().unwrap().contains("`valve-c`"));
    let target = &plan["unreachable"][0];
    assert_eq!(target["kind"], "target");
    assert_eq!(target["target"], "valve-c");
    assert_eq!(target["no_path"], "budget_spent", "{target}");
    assert!(!target["legs"].as_object().unwrap().is_empty(), "{target}");
    assert!(plan["stats"]["paths_planned"].as_u64().unwrap() > 0);
    // Once a leg came back without a path, the start's legs to each target tell which
    // target it is, before the PoI selection spends a budget on every leg into the
    // walled PoI (9 legs and 4 spent budgets before, 5 and 2 now).
    let spent = &plan["stats"]["legs_without_path"]["budget_spent:samples"];
    assert!(spent.as_u64().unwrap() <= 2, "{}", plan["stats"]);
    let skip = smug(&[
        "plan",
        &config,
        "--out",
        "target/cli-test-walled",
        "--set",
        "plan.skip_unreachable=true",
    ]);
    assert_eq!(skip.status.code(), Some(0), "{}", stderr(&skip));
    assert!(
        stdout(&skip).contains("skipped unreachable targets: valve-c"),
        "{}",
        stdout(&skip)
    );
    assert!(
        stdout(&skip).contains("planned 2 targets"),
        "{}",
        stdout(&skip)
    );
    // With the full matrix the start's row is planned first and already tells: the
    // mission ends after its three legs, not after every row and the selection.
    let full = smug(&[
        "plan",
        &config,
        "--out",
        "target/cli-test-walled",
        "--set",
        "plan.sequencing_costs=\"full\"",
    ]);
    assert_eq!(full.status.code(), Some(1), "{}", stderr(&full));
    assert!(stderr(&full).contains("`valve-c`"), "{}", stderr(&full));
    let text = std::fs::read_to_string(workspace().join("target/cli-test-walled/plan.json"));
    let plan: serde_json::Value = serde_json::from_str(&text.unwrap()).unwrap();
    assert_eq!(plan["unreachable"][0]["target"], "valve-c");
    assert_eq!(plan["stats"]["paths_planned"], 3, "{}", plan["stats"]);
}

#[test]
fn an_output_that_would_overwrite_an_input_is_refused() {
    // A mission config that happens to be named like an output, planned into its own
    // folder: the plan must not replace it.
    let dir = workspace().join("target/cli-test-overwrite");
    std::fs::create_dir_all(&dir).unwrap();
    let anymal = workspace().join("configs/robots/anymal.toml");
    let text = std::fs::read_to_string(workspace().join("configs/flat-demo.toml"))
        .unwrap()
        .replace(
            "include = \"robots/anymal.toml\"",
            &format!("include = {:?}", anymal.to_str().unwrap()),
        );
    let config = dir.join("plan.json");
    std::fs::write(&config, &text).unwrap();
    let run = smug(&[
        "plan",
        config.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    assert!(
        stderr(&run).contains("plan.json") && stderr(&run).contains("is an input"),
        "{}",
        stderr(&run)
    );
    assert_eq!(std::fs::read_to_string(&config).unwrap(), text, "untouched");
}

#[test]
fn a_killed_run_leaves_the_previous_plan_intact() {
    let out = workspace().join("target/cli-test-killed");
    let out_arg = out.to_str().unwrap();
    let first = smug(&["plan", "configs/flat-demo.toml", "--out", out_arg]);
    assert_eq!(first.status.code(), Some(0), "{}", stderr(&first));
    let before = std::fs::read(out.join("plan.json")).unwrap();
    // A mission of many seconds, killed while it plans.
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_smug"))
        .args(["plan", "configs/lunar-rover.toml", "--out", out_arg])
        .current_dir(workspace())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    child.kill().unwrap();
    child.wait().unwrap();
    assert_eq!(std::fs::read(out.join("plan.json")).unwrap(), before);
    let leftovers: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}
