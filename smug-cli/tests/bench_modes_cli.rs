//! `smug bench modes`: sequential (full and lazy matrix) against joint planning, its
//! report and raw JSON, and bad mode names.

mod common;

use common::{assert_bad_input, scratch_dir, smug, stderr};

/// The number `key` of a JSON row, asserted finite and positive.
fn positive(row: &serde_json::Value, key: &str) -> f64 {
    let value = row[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing: {row}"));
    assert!(value.is_finite() && value > 0.0, "{key} = {value}: {row}");
    value
}

#[test]
fn modes_bench_on_lunar_writes_every_mode_and_the_differences() {
    let dir = scratch_dir("cli-test-bench-modes", "lunar");
    let out = dir.join("r.md");
    let run = smug(&[
        "bench",
        "modes",
        "--missions",
        "lunar",
        "--runs",
        "1",
        "--modes",
        "full,lazy,joint",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let report = std::fs::read_to_string(&out).unwrap();
    for row in [
        "| lunar 13×10 | sequential, full matrix | 1 | 0 |",
        "| lunar 13×10 | sequential, lazy matrix | 1 | 0 |",
        "| lunar 13×10 | joint, auto | 1 | 0 |",
        "| lunar 13×10 | joint − full | 1 |",
        "| lunar 13×10 | joint − lazy | 1 |",
        "| lunar 13×10 | lazy − full | 1 |",
        "Command: `smug bench modes --missions lunar",
    ] {
        assert!(report.contains(row), "`{row}` missing from:\n{report}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("r.json")).unwrap()).unwrap();
    let runs = json["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 3, "{json}");
    for run in runs {
        assert!(run["error"].is_null(), "{run}");
        positive(run, "cost");
        positive(run, "paths_planned");
        positive(run, "planning_s");
    }
    let modes = json["modes"].as_array().unwrap();
    let names: Vec<&str> = modes.iter().map(|m| m["mode"].as_str().unwrap()).collect();
    assert_eq!(names, ["full", "lazy", "joint"]);
    for row in modes {
        assert_eq!(row["failures"], 0, "{row}");
        for key in [
            "mean_cost",
            "worst_cost",
            "mean_paths_planned",
            "mean_planning_s",
        ] {
            positive(row, key);
        }
    }
    let differences = json["differences"].as_array().unwrap();
    assert_eq!(differences.len(), 3, "{json}");
    for d in differences {
        assert!(d["mean"].as_f64().unwrap().is_finite(), "{d}");
        assert_eq!(d["per_seed"].as_array().unwrap().len(), 1, "{d}");
    }
}

#[test]
fn modes_bench_with_an_unknown_mode_is_exit_2_naming_it() {
    let run = smug(&["bench", "modes", "--modes", "full,bogus", "--runs", "1"]);
    assert_bad_input(
        &run,
        &["bogus", "--modes", "full, lazy, lazy-unsettled, joint"],
    );
}

#[test]
fn modes_bench_on_the_data_map_without_data_is_exit_2_naming_the_flag() {
    let run = smug(&[
        "bench",
        "modes",
        "--missions",
        "data",
        "--modes",
        "lazy",
        "--runs",
        "1",
    ]);
    assert_bad_input(&run, &["--data"]);
}

#[test]
fn modes_bench_with_an_unknown_mission_is_exit_2_naming_it() {
    let run = smug(&["bench", "modes", "--missions", "mars", "--runs", "1"]);
    assert_bad_input(&run, &["mars", "--missions", "lunar-200x10"]);
}

#[test]
fn modes_bench_with_threads_runs_each_count_and_finds_the_same_plans() {
    let dir = std::env::temp_dir().join("smug-bench-modes-threads");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("r.md");
    let run = smug(&[
        "bench",
        "modes",
        "--missions",
        "imported-map",
        "--runs",
        "1",
        "--modes",
        "lazy,joint",
        "--threads",
        "1,2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let report = std::fs::read_to_string(&out).unwrap();
    for row in [
        "## Threads",
        "| imported map 32×32 | sequential, lazy matrix | 2 | 1 |",
        "| imported map 32×32 | joint, auto | 2 | 1 |",
    ] {
        assert!(report.contains(row), "`{row}` missing from:\n{report}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("r.json")).unwrap()).unwrap();
    assert_eq!(json["runs"].as_array().unwrap().len(), 4, "{json}");
    let rows = json["threads"].as_array().unwrap();
    assert_eq!(rows.len(), 4, "{json}");
    for row in rows {
        assert_eq!(row["same_plan"], 1, "{row}");
        positive(row, "mean_total_s");
        // Linux keeps each thread's schedstat: the run's CPU time is measured.
        positive(row, "mean_cpu_s");
    }
}

#[test]
fn modes_bench_with_zero_threads_is_exit_2_naming_the_flag() {
    let run = smug(&["bench", "modes", "--threads", "0", "--runs", "1"]);
    assert_bad_input(&run, &["--threads"]);
}
