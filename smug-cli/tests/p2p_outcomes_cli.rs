//! `smug p2p` says how a query without a path ended, through the planner's typed
//! outcome: no path exists (proved) or the budget ran out, for the exact planner and
//! for LazyPRM*; an endpoint inside an inflated obstacle or off the map is bad input
//! (exit 2) named as such. The map is written by the test.

mod common;

use common::{scratch_dir, smug, stderr, stdout};
use std::path::{Path, PathBuf};

/// A 14 × 8 map (rows top-down, `#` blocked): a wall with a one-cell door, and a
/// closed box whose inside no robot reaches.
const MAP: [&str; 8] = [
    "..............",
    "....#...#####.",
    "....#...#...#.",
    "........#...#.",
    "....#...#...#.",
    "....#...#####.",
    "....#.........",
    "....#.........",
];

/// Writes the map (YAML + ASCII PGM) into `dir`.
fn write_map(dir: &Path) -> PathBuf {
    let mut pgm = format!("P2\n{} {}\n255\n", MAP[0].len(), MAP.len());
    for row in MAP {
        let values: Vec<&str> = row
            .chars()
            .map(|c| if c == '#' { "0" } else { "254" })
            .collect();
        pgm.push_str(&values.join(" "));
        pgm.push('\n');
    }
    std::fs::write(dir.join("box.pgm"), pgm).unwrap();
    let yaml = dir.join("box.yaml");
    std::fs::write(
        &yaml,
        "image: box.pgm\nresolution: 1.0\norigin: [0.0, 0.0, 0.0]\noccupied_thresh: 0.65\nfree_thresh: 0.196\nnegate: 0\n",
    )
    .unwrap();
    yaml
}

/// Runs `smug p2p` on the map with `queries` (CSV rows) and extra arguments; the
/// output and the results JSON.
fn p2p(dir: &Path, queries: &str, extra: &[&str]) -> (std::process::Output, serde_json::Value) {
    let map = write_map(dir);
    let csv = dir.join("q.csv");
    std::fs::write(&csv, format!("sx,sy,syaw,gx,gy,gyaw\n{queries}")).unwrap();
    let results = dir.join("results.json");
    std::fs::remove_file(&results).ok();
    let mut args = vec![
        "p2p",
        "--map",
        map.to_str().unwrap(),
        "--queries",
        csv.to_str().unwrap(),
        "--radius",
        "0.25",
        "--out",
        results.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let out = smug(&args);
    let json = std::fs::read_to_string(&results)
        .map(|text| serde_json::from_str(&text).unwrap())
        .unwrap_or(serde_json::Value::Null);
    (out, json)
}

/// Into the closed box, then across the door: one proved "no path", one path.
const INTO_THE_BOX_AND_ACROSS: &str = "1.5,1.5,0,10.5,4.5,0\n1.5,1.5,0,6.5,6.5,0\n";

fn assert_proved_none_then_solved(out: &std::process::Output, json: &serde_json::Value) {
    assert_eq!(out.status.code(), Some(1), "stderr: {}", stderr(out));
    assert!(
        stderr(out).contains(
            "query 1: no_path: no path exists: the goal lies outside the start's free region"
        ),
        "{}",
        stderr(out)
    );
    assert!(
        stdout(out).contains("1 without a path (1 proved none exists, 0 budget spent)"),
        "{}",
        stdout(out)
    );
    let q = &json["queries"];
    assert_eq!(q[0]["status"], "no_path");
    assert_eq!(q[0]["no_path"], "proved");
    assert_eq!(q[0]["why"], "disconnected");
    assert_eq!(q[1]["status"], "exact", "a solvable query is solved");
    assert!(q[1].get("no_path").is_none());
}

#[test]
fn the_exact_planner_proves_an_unreachable_goal() {
    let dir = scratch_dir("p2p-outcomes", "exact");
    let (out, json) = p2p(&dir, INTO_THE_BOX_AND_ACROSS, &[]);
    assert_eq!(json["planner_type"], "visibility");
    assert_proved_none_then_solved(&out, &json);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn lazy_prm_star_proves_an_unreachable_goal_without_spending_its_budget() {
    let dir = scratch_dir("p2p-outcomes", "lazy");
    let (out, json) = p2p(
        &dir,
        INTO_THE_BOX_AND_ACROSS,
        &["--set", "planner.params.max_samples=20000"],
    );
    assert_eq!(json["planner_type"], "lazy-prm-star");
    assert_proved_none_then_solved(&out, &json);
    assert_eq!(json["planner"]["counters"]["proved_no_path"], 1);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn lazy_prm_star_says_when_its_budget_ran_out() {
    let dir = scratch_dir("p2p-outcomes", "budget");
    // Across the wall with a budget of 1 sample and no corner vertices (they alone
    // would join start and goal; 3 samples can, over the wall's end): a path exists,
    // none is found.
    let (out, json) = p2p(
        &dir,
        "1.5,1.5,0,6.5,6.5,0\n",
        &[
            "--set",
            "planner.params.max_samples=1",
            "--set",
            "planner.params.initial_samples=0",
            "--set",
            "planner.params.corner_vertices=false",
        ],
    );
    assert_eq!(out.status.code(), Some(1), "stderr: {}", stderr(&out));
    let q = &json["queries"][0];
    assert_eq!(q["status"], "no_path");
    assert_eq!(q["no_path"], "budget_spent");
    assert_eq!(q["why"], "samples");
    assert!(
        stderr(&out).contains(
            "no path found before the sample budget ran out (max_samples); one may exist"
        ),
        "{}",
        stderr(&out)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_endpoint_in_an_inflated_obstacle_is_bad_input_named_as_such() {
    let dir = scratch_dir("p2p-outcomes", "inflated");
    // The start 0.1 from the wall at x = 4 (radius 0.25); the goal inside the wall.
    for (extra, planner) in [
        (&[][..], "visibility"),
        (
            &["--set", "planner.params.max_samples=2000"][..],
            "lazy-prm-star",
        ),
    ] {
        let (out, json) = p2p(&dir, "3.9,1.5,0,6.5,6.5,0\n1.5,1.5,0,4.5,0.5,0\n", extra);
        assert_eq!(out.status.code(), Some(2), "stderr: {}", stderr(&out));
        let err = stderr(&out);
        assert!(
            err.contains("query 1: invalid_start: the start (3.9, 1.5) is inside an inflated obstacle (0.100 m from the nearest blocked cell), closer than the robot's radius 0.25 m"),
            "{planner}: {err}"
        );
        assert!(
            err.contains("query 2: invalid_goal: the goal (4.5, 0.5) is inside an inflated obstacle (0.000 m"),
            "{planner}: {err}"
        );
        assert!(err.contains("smug: error: bad query: query 1: the start (3.9, 1.5) is inside an inflated obstacle"), "{planner}: {err}");
        assert_eq!(json["planner_type"], planner);
        assert_eq!(json["queries"][0]["why"], "in_inflated_obstacle");
        assert_eq!(json["queries"][1]["why"], "in_inflated_obstacle");
    }
    std::fs::remove_dir_all(&dir).ok();
}
