//! `smug bench paper --quick`: the smoke version of the paper's tables runs through the
//! CLI, writes a sane report and raw JSON.

mod common;

use common::{smug, stderr};

fn mean(runs: &[serde_json::Value], key: &str, field: &str) -> f64 {
    let values: Vec<f64> = runs
        .iter()
        .filter(|r| r["experiment"] == key && r["error"].is_null())
        .map(|r| r[field].as_f64().unwrap())
        .collect();
    assert!(!values.is_empty(), "no successful run of {key}");
    values.iter().sum::<f64>() / values.len() as f64
}

#[test]
fn quick_paper_bench_writes_a_sane_report() {
    let dir = std::env::temp_dir().join(format!("smug-bench-paper-{}", std::process::id()));
    let report = dir.join("report.md");
    let out = smug(&[
        "bench",
        "paper",
        "--quick",
        "--out",
        report.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "stderr: {}", stderr(&out));

    let text = std::fs::read_to_string(&report).unwrap();
    for table in ["Table I", "Table II", "Table III", "Table IV", "Checks"] {
        assert!(text.contains(table), "{table} missing from:\n{text}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    let runs = json["bench"]["raw"].as_array().unwrap();
    assert!(runs.iter().all(|r| r["error"].is_null()), "a run failed");

    let (dp, idp) = ("lunar/dp", "lunar/idp");
    assert!(
        mean(runs, idp, "planning_s") <= mean(runs, dp, "planning_s"),
        "IDP slower than DP"
    );
    let (dp_cost, idp_cost) = (mean(runs, dp, "cost"), mean(runs, idp, "cost"));
    assert!(
        dp_cost > 0.0 && idp_cost <= 1.02 * dp_cost,
        "IDP {idp_cost} vs DP {dp_cost}"
    );
    assert!(
        mean(runs, "scalability/12/dp", "paths_planned")
            > mean(runs, "scalability/12/idp", "paths_planned"),
        "DP plans every PoI pair, IDP fewer"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn p2p_bench_without_data_exits_2_naming_the_suite() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_smug"))
        .args(["bench", "p2p", "--scenarios", "1"])
        .current_dir(common::workspace())
        .env_remove("SMUG_DATA")
        .output()
        .unwrap();
    common::assert_bad_input(
        &out,
        &[
            "--data DIR",
            "SMUG_DATA",
            "MovingAI 2D pathfinding benchmark",
            "Sturtevant",
            "mapf/random-32-32-10.map + mapf/random-32-32-10-random-1.scen",
            "https://movingai.com/benchmarks/",
            "--generated",
        ],
    );
    // `$SMUG_DATA/movingai` is where the maps are looked for.
    let data = std::env::temp_dir().join(format!("smug-no-data-{}", std::process::id()));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_smug"))
        .args(["bench", "p2p", "--maps", "random-32-32-10"])
        .current_dir(common::workspace())
        .env("SMUG_DATA", &data)
        .output()
        .unwrap();
    let expected = data.join("movingai/mapf/random-32-32-10.map");
    common::assert_bad_input(&out, &[expected.to_str().unwrap(), "cannot read"]);
}

#[test]
fn p2p_bench_runs_on_generated_maps_without_data() {
    let dir = std::env::temp_dir().join(format!("smug-bench-p2p-gen-{}", std::process::id()));
    let report = dir.join("p2p.md");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_smug"))
        .args(["bench", "p2p", "--generated", "--scenarios", "10", "--out"])
        .arg(&report)
        .args(["--maps", "random-32x32-d10-s1,maze-33x33-s1"])
        .current_dir(common::workspace())
        .env_remove("SMUG_DATA")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "stderr: {}", stderr(&out));
    let text = std::fs::read_to_string(&report).unwrap();
    for row in [
        "| random-32x32-d10-s1 | lazy-prm-star | 10/10 | 0 |",
        "| random-32x32-d10-s1 | visibility | 10/10 | 0 | 1.0000 | 1.0000 |",
        "| maze-33x33-s1 | lazy-prm-star | 10/10 | 0 |",
        "| maze-33x33-s1 | visibility | 10/10 | 0 | 1.0000 | 1.0000 |",
    ] {
        assert!(text.contains(row), "`{row}` missing from:\n{text}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn lattice_bench_compares_both_planners_on_a_generated_map() {
    let dir = std::env::temp_dir().join(format!("smug-bench-lattice-{}", std::process::id()));
    let report = dir.join("lattice.md");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_smug"))
        .args(["bench", "lattice", "--families", "terrain", "--cells", "64"])
        .args(["--models", "reeds-shepp", "--queries", "3", "--budget", "1"])
        .arg("--out")
        .arg(&report)
        .current_dir(common::workspace())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "stderr: {}", stderr(&out));
    let text = std::fs::read_to_string(&report).unwrap();
    assert!(
        text.contains("| terrain-64x64-d20-s1 | reeds-shepp | default | 3 | 0 | 0 |"),
        "{text}"
    );
    let raw: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(dir.join("lattice.json")).unwrap()).unwrap();
    assert_eq!(raw.len(), 3);
    for query in &raw {
        let (ours, theirs) = (query["lattice"][0].as_f64(), query["prm"][0].as_f64());
        assert!(ours.is_some() && theirs.is_some(), "{query}");
    }
    std::fs::remove_dir_all(&dir).ok();
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_smug"))
        .args(["bench", "lattice", "--families", "mazes"])
        .current_dir(common::workspace())
        .output()
        .unwrap();
    common::assert_bad_input(&bad, &["--families", "mazes"]);
}
