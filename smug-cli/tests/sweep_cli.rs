//! End-to-end tests of `smug sweep`: configs × seeds × a grid in local processes, one
//! row per run, resumable; bad input is exit 2 naming it; a failed run is a row.

mod common;

use common::*;
use smug_app::sweep::{RunStatus, SweepRow};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Two small configs in `dir`: lunar with 3 stones × 3 PoIs, and the flat demo.
fn two_configs(dir: &Path) -> [PathBuf; 2] {
    let configs = workspace().join("configs");
    let lunar = dir.join("lunar-small.toml");
    std::fs::write(
        &lunar,
        format!(
            "include = {:?}\n[world]\ntype = \"lunar\"\nparams = {{ targets = 3, pois_per_target = 3 }}\n",
            configs.join("lunar.toml").display().to_string()
        ),
    )
    .unwrap();
    let flat = dir.join("flat.toml");
    std::fs::write(
        &flat,
        format!(
            "include = {:?}\n",
            configs.join("flat-demo.toml").display().to_string()
        ),
    )
    .unwrap();
    [lunar, flat]
}

fn rows(path: &Path) -> Vec<SweepRow> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|line| serde_json::from_str(line).unwrap())
        .collect()
}

fn sweep(configs: &[PathBuf], seeds: &str, out: &Path) -> std::process::Output {
    let mut args = vec!["sweep".to_string()];
    args.extend(configs.iter().map(|c| c.display().to_string()));
    args.extend(
        [
            "--seeds",
            seeds,
            "--grid",
            "planner.params.max_stall=2,3",
            "--jobs",
            "2",
            "--out",
        ]
        .map(String::from),
    );
    args.push(out.display().to_string());
    smug(&args.iter().map(String::as_str).collect::<Vec<_>>())
}

#[test]
fn a_sweep_runs_every_combination_once_and_resumes_where_it_stopped() {
    let dir = scratch_dir("sweep-cli-tests", "resume");
    let configs = two_configs(&dir);
    let out = dir.join("runs.jsonl");

    // Two seeds first (a sweep stopped half-way), then three: only the new runs run.
    let first = sweep(&configs, "1..2", &out);
    assert!(first.status.success(), "{}", stderr(&first));
    assert_eq!(rows(&out).len(), 8);
    let second = sweep(&configs, "1..3", &out);
    assert!(second.status.success(), "{}", stderr(&second));
    assert!(
        stderr(&second).contains("12 runs: 8 already in"),
        "{}",
        stderr(&second)
    );
    let all = rows(&out);
    assert_eq!(all.len(), 12);
    let combinations: BTreeSet<(String, u64, Vec<String>)> = all
        .iter()
        .map(|r| (r.config.clone(), r.seed, r.overrides.clone()))
        .collect();
    assert_eq!(combinations.len(), 12, "a combination ran twice");
    let ids: BTreeSet<&str> = all.iter().map(|r| r.run_id.as_str()).collect();
    assert_eq!(ids.len(), 12, "two runs share an id");
    for row in &all {
        assert_eq!(row.status, RunStatus::Ok, "{row:?}");
        assert!(row.cost.unwrap() > 0.0 && row.length_m.unwrap() > 0.0);
        assert!(row.paths_planned.unwrap() > 0 && row.metrics.is_some());
        assert!(row.stage_times_s.contains_key("total"), "{row:?}");
    }

    // Done: a rerun skips every row and adds nothing.
    let before = std::fs::read(&out).unwrap();
    let again = sweep(&configs, "1..3", &out);
    assert!(again.status.success(), "{}", stderr(&again));
    assert!(
        stderr(&again).contains("12 already in") && stderr(&again).contains("0 to run"),
        "{}",
        stderr(&again)
    );
    assert_eq!(std::fs::read(&out).unwrap(), before);

    // A row is the plan `smug plan` makes for its config, seed and overrides.
    let row = all
        .iter()
        .find(|r| r.config.ends_with("lunar-small.toml") && r.seed == 3)
        .unwrap();
    let mut args = vec!["plan".to_string(), row.config.clone()];
    args.extend(["--seed".into(), "3".into(), "--json".into(), "--out".into()]);
    args.push(dir.join("plan").display().to_string());
    args.extend(
        row.overrides
            .iter()
            .flat_map(|o| ["--set".to_string(), o.clone()]),
    );
    let plan = smug(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(plan.status.success(), "{}", stderr(&plan));
    let plan: serde_json::Value = serde_json::from_str(&stdout(&plan)).unwrap();
    assert_eq!(plan["cost"].as_f64(), row.cost);
    assert_eq!(plan["stats"]["paths_planned"].as_u64(), row.paths_planned);
}

#[test]
fn a_failed_run_is_a_row_with_its_error_not_a_failed_sweep() {
    let dir = scratch_dir("sweep-cli-tests", "failed-run");
    let configs = two_configs(&dir);
    let out = dir.join("runs.jsonl");
    // A threshold above its pair: the config and its parameters read, the run fails
    // when the checker is built.
    let result = smug(&[
        "sweep",
        &configs[0].display().to_string(),
        "--grid",
        "validity.params.t_low=0.9",
        "--out",
        &out.display().to_string(),
    ]);
    assert!(result.status.success(), "{}", stderr(&result));
    let rows = rows(&out);
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0].status, RunStatus::Error);
    let error = rows[0].error.as_deref().unwrap();
    assert!(error.contains("t_low"), "{error}");
    assert!(rows[0].cost.is_none());
}

#[test]
fn bad_input_is_exit_2_naming_it() {
    let dir = scratch_dir("sweep-cli-tests", "bad-input");
    let [config, _] = two_configs(&dir);
    let config = config.display().to_string();
    let out = dir.join("runs.jsonl").display().to_string();
    let missing = dir.join("missing.toml").display().to_string();
    for (args, needles) in [
        (
            vec![missing.as_str()],
            vec![missing.as_str(), "cannot read"],
        ),
        (
            vec![&config, "--grid", "planner.params.max_stall"],
            vec!["planner.params.max_stall", "expected KEY=V1,V2"],
        ),
        (
            vec![&config, "--seeds", "3..1"],
            vec!["seeds `3..1`", "ends (1) before it starts (3)"],
        ),
        (
            vec![&config, "--seeds", "1..x"],
            vec!["seeds `1..x`", "`x` is not a seed"],
        ),
        (
            vec![&config, "--grid", "robot.lenght=1,2"],
            vec!["lunar-small.toml", "robot.lenght", "unknown field"],
        ),
        (
            vec![&config, "--grid", "planner.params.not_a_param=1,2"],
            vec![
                "lunar-small.toml",
                "planner.params.not_a_param",
                "unknown field",
            ],
        ),
        (
            vec![&config, "--grid", "planner.type=no-such-planner"],
            vec!["lunar-small.toml", "planner.type", "no-such-planner"],
        ),
        (
            vec![&config, "--grid", "seed=1,2"],
            vec!["seed=1,2", "seeds, not the grid"],
        ),
        (
            vec![&config, "--out", &config],
            vec!["lunar-small.toml", "--out"],
        ),
    ] {
        let mut all = vec!["sweep"];
        all.extend(args.iter().copied());
        if !args.contains(&"--out") {
            all.extend(["--out", &out]);
        }
        assert_bad_input(&smug(&all), &needles);
    }
    assert!(!Path::new(&out).exists(), "a refused sweep wrote rows");
    let zero_jobs = smug(&["sweep", &config, "--jobs", "0", "--out", &out]);
    assert_eq!(zero_jobs.status.code(), Some(2), "{}", stderr(&zero_jobs));
}
