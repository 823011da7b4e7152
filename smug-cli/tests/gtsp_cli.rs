//! `smug gtsp` and `smug bench gtsp` on GTSP-LIB files the test writes (no third-party
//! data): a 4 × 4 lattice whose columns are the clusters.

mod common;

use common::{assert_bad_input, smug, stderr, stdout};
use std::fmt::Write as _;
use std::path::PathBuf;

fn temp_dir(label: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("smug-gtsp-cli-{label}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A 4 × 4 lattice of spacing 10, its columns the 4 sets: the best tour visits one row,
/// 0 → 10 → 20 → 30 → 0, cost 60.
fn columns_text(sets: &str) -> String {
    let mut text = "NAME: 4columns16\nTYPE: GTSP\nDIMENSION: 16\nGTSP_SETS: 4\n\
                    EDGE_WEIGHT_TYPE: EUC_2D\nNODE_COORD_SECTION\n"
        .to_string();
    for k in 0..16 {
        let _ = writeln!(text, "{} {} {}", k + 1, 10 * (k % 4), 10 * (k / 4));
    }
    text + "GTSP_SET_SECTION\n" + sets + "EOF\n"
}

const COLUMNS: &str = "1 1 5 9 13 -1\n2 2 6 10 14 -1\n3 3 7 11 15 -1\n4 4 8 12 16 -1\n";

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text.trim()).unwrap_or_else(|e| panic!("{e}: {text}"))
}

#[test]
fn solves_a_gtsp_file_reproducibly_with_both_solvers() {
    let dir = temp_dir("solve");
    let file = dir.join("4columns16.gtsp");
    std::fs::write(&file, columns_text(COLUMNS)).unwrap();
    let file = file.to_str().unwrap();
    let args = [
        "gtsp",
        file,
        "--time",
        "0",
        "--iterations",
        "50",
        "--seed",
        "3",
    ];
    let first = smug(&args);
    assert!(first.status.success(), "{}", stderr(&first));
    let report = json(&stdout(&first));
    assert_eq!(report["cost"], 60.0);
    assert_eq!(report["clusters"], 4);
    assert_eq!(report["tour"].as_array().unwrap().len(), 4);
    let again = json(&stdout(&smug(&args)));
    assert_eq!(report["tour"], again["tour"]);
    let exact = smug(&["gtsp", file, "--solver", "gtsp-exact", "--end", "3"]);
    let exact = json(&stdout(&exact));
    assert_eq!(exact["cost"], 30.0);
    assert_eq!(exact["kind"], "open to cluster 3");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_files_and_options_are_exit_2_with_the_line() {
    let dir = temp_dir("bad");
    let file = dir.join("bad.gtsp");
    std::fs::write(
        &file,
        columns_text("1 1 5 -1\n2 2 6 -1\n3 3 7 -1\n4 4 99 -1\n"),
    )
    .unwrap();
    let out = smug(&["gtsp", file.to_str().unwrap()]);
    assert_bad_input(&out, &["bad.gtsp:27:", "node 99 is not in 1..=16"]);
    let good = dir.join("good.gtsp");
    std::fs::write(&good, columns_text(COLUMNS)).unwrap();
    let out = smug(&["gtsp", good.to_str().unwrap(), "--end", "7"]);
    assert_bad_input(&out, &["end cluster 7"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bench_gtsp_reports_gaps_to_the_values_of_the_data_folder() {
    let dir = temp_dir("bench");
    std::fs::write(dir.join("4columns16.gtsp"), columns_text(COLUMNS)).unwrap();
    std::fs::write(
        dir.join("values.csv"),
        "instance,file,n,m,value\n4columns16,4columns16.gtsp,16,4,60\n",
    )
    .unwrap();
    let out = smug(&[
        "bench",
        "gtsp",
        "--data",
        dir.to_str().unwrap(),
        "--budgets",
        "0.05",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report = stdout(&out);
    assert!(
        report.contains("| 4columns16 | 16 | 4 | 60 | 60 | 0.00% |"),
        "{report}"
    );
    assert!(
        report.contains("| 0.05 s | 1 | 0.00% | 0.00% | 1 |"),
        "{report}"
    );
    let missing = smug(&["bench", "gtsp", "--data", "/nonexistent-smug-suite"]);
    assert_bad_input(&missing, &["values.csv"]);
    std::fs::remove_dir_all(&dir).unwrap();
}
