//! `smug tsp` and `smug bench tsp` on a suite folder the test writes (no third-party
//! data): the folder comes from `--data DIR`, else `$SMUG_DATA/tsplib`, and without
//! either the commands say what the suite is and where to get it.

mod common;

use common::{assert_bad_input, stderr, stdout, workspace};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `smug` with `SMUG_DATA` set to `data` (or removed).
fn smug_with(data: Option<&Path>, args: &[&str]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_smug"));
    command.args(args).current_dir(workspace());
    match data {
        Some(dir) => command.env("SMUG_DATA", dir),
        None => command.env_remove("SMUG_DATA"),
    };
    command.output().expect("the smug binary runs")
}

fn temp_dir(label: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("smug-tsp-cli-{label}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A 4 × 4 lattice of spacing 10 (EUC_2D): 16 unit steps, optimum 160.
fn grid_text(name: &str) -> String {
    let mut text = format!(
        "NAME: {name}\nTYPE: TSP\nDIMENSION: 16\nEDGE_WEIGHT_TYPE: EUC_2D\nNODE_COORD_SECTION\n"
    );
    for k in 0..16 {
        let _ = writeln!(text, "{} {} {}", k + 1, 10 * (k % 4), 10 * (k / 4));
    }
    text + "EOF\n"
}

/// 20 nodes, leg i → i + 1 (mod 20) costs 2, every other leg 100: optimum 40.
fn ring_text() -> String {
    let n = 20;
    let mut text = format!(
        "NAME: ring20\nTYPE: ATSP\nDIMENSION: {n}\nEDGE_WEIGHT_TYPE: EXPLICIT\n\
         EDGE_WEIGHT_FORMAT: FULL_MATRIX\nEDGE_WEIGHT_SECTION\n"
    );
    for i in 0..n {
        let row: Vec<&str> = (0..n)
            .map(|j| {
                if j == i {
                    "0"
                } else if j == (i + 1) % n {
                    "2"
                } else {
                    "100"
                }
            })
            .collect();
        let _ = writeln!(text, "{}", row.join(" "));
    }
    text + "EOF\n"
}

/// Writes the suite into `dir`: grid4x4 (optimum 160), grid4x4-low (the same lattice
/// listed at 128, so every tour is 25% above it) and the asymmetric ring20 (40).
fn write_suite(dir: &Path) {
    let (tsp, atsp) = (dir.join("tsp"), dir.join("atsp"));
    std::fs::create_dir_all(&tsp).unwrap();
    std::fs::create_dir_all(&atsp).unwrap();
    std::fs::write(tsp.join("grid4x4.tsp"), grid_text("grid4x4")).unwrap();
    std::fs::write(tsp.join("grid4x4-low.tsp"), grid_text("grid4x4-low")).unwrap();
    std::fs::write(
        tsp.join("optima.csv"),
        "name,optimal_tour_length\ngrid4x4,160\ngrid4x4-low,128\n",
    )
    .unwrap();
    std::fs::write(atsp.join("ring20.atsp"), ring_text()).unwrap();
    std::fs::write(
        atsp.join("optima.csv"),
        "name,optimal_tour_length\nring20,40\n",
    )
    .unwrap();
}

/// The parts of the message every suite-less run must show.
const SUITE_NEEDLES: [&str; 8] = [
    "TSPLIB95",
    "Reinelt",
    "Heidelberg",
    "--data DIR",
    "SMUG_DATA",
    "tsp/NAME.tsp",
    "atsp/NAME.atsp",
    "optima.csv",
];

#[test]
fn without_data_or_smug_data_both_commands_exit_2_naming_the_suite() {
    assert_bad_input(&smug_with(None, &["bench", "tsp"]), &SUITE_NEEDLES);
    assert_bad_input(&smug_with(None, &["tsp", "grid4x4"]), &SUITE_NEEDLES);
    let empty = smug_with(Some(Path::new("")), &["bench", "tsp"]);
    assert_bad_input(&empty, &["no TSPLIB suite given"]);
}

/// Runs `smug bench tsp` with `args` and returns the raw JSON runs.
fn bench(data: Option<&Path>, out: &Path, args: &[&str]) -> Vec<serde_json::Value> {
    let mut all = vec![
        "bench",
        "tsp",
        "--budgets",
        "0.2",
        "--out",
        out.to_str().unwrap(),
    ];
    all.extend_from_slice(args);
    let run = smug_with(data, &all);
    assert_eq!(run.status.code(), Some(0), "stderr: {}", stderr(&run));
    let json = std::fs::read_to_string(out.with_extension("json")).unwrap();
    serde_json::from_str::<serde_json::Value>(&json)
        .unwrap()
        .as_array()
        .unwrap()
        .clone()
}

#[test]
fn bench_tsp_with_data_reports_the_gaps() {
    let dir = temp_dir("bench");
    write_suite(&dir.join("suite"));
    let out = dir.join("report.md");
    let suite = dir.join("suite");
    let runs = bench(None, &out, &["--data", suite.to_str().unwrap()]);
    let gaps: Vec<(&str, f64, f64)> = runs
        .iter()
        .map(|r| {
            let name = r["instance"].as_str().unwrap();
            (
                name,
                r["cost"].as_f64().unwrap(),
                r["gap_percent"].as_f64().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        gaps,
        [
            ("grid4x4", 160.0, 0.0),
            ("grid4x4-low", 160.0, 25.0),
            ("ring20", 40.0, 0.0)
        ]
    );
    let report = std::fs::read_to_string(&out).unwrap();
    assert!(
        report.contains("| grid4x4-low | 16 | 128 | 160 | 25.00% |"),
        "{report}"
    );
    assert!(
        report.contains("| ring20 (ATSP) | 20 | 40 | 40 | 0.00% |"),
        "{report}"
    );
    assert!(
        report.contains("| auto | 0.2 s | 12.50% | 25.00% | 0.00% | 0.00% |"),
        "{report}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn smug_data_is_the_fallback_and_data_wins_over_it() {
    let root = temp_dir("env");
    write_suite(&root.join("tsplib"));
    let out = root.join("report.md");
    let runs = bench(Some(&root), &out, &["--instances", "ring20"]);
    assert_eq!(runs.len(), 1);
    assert_eq!(runs[0]["gap_percent"].as_f64(), Some(0.0));
    let report = std::fs::read_to_string(&out).unwrap();
    let suite = root.join("tsplib");
    assert!(report.contains(&suite.display().to_string()), "{report}");

    let ghost = root.join("nothing-here");
    let runs = bench(
        Some(&ghost),
        &out,
        &["--data", suite.to_str().unwrap(), "--instances", "grid4x4"],
    );
    assert_eq!(runs[0]["cost"].as_f64(), Some(160.0));
    let missing = smug_with(Some(&ghost), &["bench", "tsp"]);
    assert_bad_input(&missing, &["nothing-here/tsplib", "optima.csv"]);
    std::fs::remove_dir_all(&root).ok();
}

#[test]
fn tsp_solves_a_suite_instance_by_name_and_reports_its_gap() {
    let root = temp_dir("name");
    write_suite(&root.join("tsplib"));
    let run = smug_with(Some(&root), &["tsp", "grid4x4-low", "--time-limit", "0.2"]);
    assert_eq!(run.status.code(), Some(0), "stderr: {}", stderr(&run));
    let report: serde_json::Value = serde_json::from_str(&stdout(&run)).unwrap();
    assert_eq!(report["cost"], 160);
    assert_eq!(report["optimum"], 128);
    assert_eq!(report["gap_percent"].as_f64(), Some(25.0));

    let suite = root.join("tsplib");
    let by_option = smug_with(None, &["tsp", "ring20", "--data", suite.to_str().unwrap()]);
    let report: serde_json::Value = serde_json::from_str(&stdout(&by_option)).unwrap();
    assert_eq!(
        (report["cost"].as_f64(), report["gap_percent"].as_f64()),
        (Some(40.0), Some(0.0))
    );

    let unknown = smug_with(Some(&root), &["tsp", "grid9x9"]);
    assert_bad_input(
        &unknown,
        &["no instance `grid9x9`", "grid4x4, grid4x4-low, ring20"],
    );
    std::fs::remove_dir_all(&root).ok();
}

#[test]
fn tsp_with_a_file_needs_no_suite() {
    let file = "smug-sequencing/tests/data/grid4x4.tsp";
    let run = smug_with(None, &["tsp", file]);
    assert_eq!(run.status.code(), Some(0), "stderr: {}", stderr(&run));
    let report: serde_json::Value = serde_json::from_str(&stdout(&run)).unwrap();
    assert_eq!(
        (report["name"].as_str(), report["cost"].as_f64()),
        (Some("grid4x4"), Some(160.0))
    );
    assert!(report.get("optimum").is_none() && report.get("gap_percent").is_none());
    let open = smug_with(None, &["tsp", file, "--end", "4"]);
    let report: serde_json::Value = serde_json::from_str(&stdout(&open)).unwrap();
    assert_eq!(
        report["cost"], 150,
        "15 unit steps from node 0 to its neighbour 4"
    );
    assert_bad_input(
        &smug_with(None, &["tsp", "no/such.tsp"]),
        &["no/such.tsp", "cannot read"],
    );
}
