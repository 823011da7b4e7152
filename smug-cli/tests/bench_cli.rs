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
