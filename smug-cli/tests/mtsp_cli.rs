//! `smug mtsp` and `smug bench mtsp` on a TSPLIB file the test writes (no third-party
//! data): two rays of six customers each, on either side of the depot, whose optima are
//! known by construction (min-max with two salesmen: one ray each, makespan 12, total 24).

mod common;

use common::{assert_bad_input, scratch_dir, smug, stderr, stdout};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn temp_dir(label: &str) -> PathBuf {
    scratch_dir("mtsp-cli", label)
}

/// Depot (node 1) at the origin, customers at x = ±1..±6 on the x axis.
fn two_rays(dir: &Path) -> PathBuf {
    let mut text =
        "NAME: tworays\nTYPE: TSP\nDIMENSION: 13\nEDGE_WEIGHT_TYPE: EUC_2D\nNODE_COORD_SECTION\n1 0 0\n"
            .to_string();
    for k in 1..=6 {
        let _ = writeln!(text, "{} {k} 0", k + 1);
        let _ = writeln!(text, "{} -{k} 0", k + 7);
    }
    let path = dir.join("tworays.tsp");
    std::fs::write(&path, text + "EOF\n").unwrap();
    path
}

/// `smug mtsp FILE --salesmen SALESMEN --objective OBJECTIVE REST…`.
fn mtsp(file: &str, salesmen: &str, objective: &str, rest: &[&str]) -> std::process::Output {
    let mut args = vec![
        "mtsp",
        file,
        "--salesmen",
        salesmen,
        "--objective",
        objective,
    ];
    args.extend_from_slice(rest);
    smug(&args)
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text.trim()).unwrap_or_else(|e| panic!("{e}: {text}"))
}

#[test]
fn minmax_splits_the_rays_and_a_seed_fixes_the_routes() {
    let dir = temp_dir("solve");
    let file = two_rays(&dir);
    let file = file.to_str().unwrap();
    let args = [
        "mtsp",
        file,
        "--salesmen",
        "2",
        "--objective",
        "minmax",
        "--time",
        "0",
        "--iterations",
        "300",
        "--seed",
        "4",
        "--json",
    ];
    let out = smug(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    let report = json(&stdout(&out));
    assert!(
        (report["makespan"].as_f64().unwrap() - 12.0).abs() < 1e-9,
        "{report}"
    );
    assert!(
        (report["total"].as_f64().unwrap() - 24.0).abs() < 1e-9,
        "{report}"
    );
    assert_eq!(report["route_sizes"], serde_json::json!([6, 6]));
    let mut nodes: Vec<u64> = report["routes"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r.as_array().unwrap().iter().map(|v| v.as_u64().unwrap()))
        .collect();
    nodes.sort();
    assert_eq!(nodes, (2..=13).collect::<Vec<u64>>());
    assert_eq!(report["routes"], json(&stdout(&smug(&args)))["routes"]);
    // Text output: the costs and one line per salesman.
    let text = mtsp(file, "3", "minsum", &["--time", "0.2"]);
    assert!(text.status.success(), "{}", stderr(&text));
    let text = stdout(&text);
    assert!(text.contains("total 24.0000"), "{text}");
    assert_eq!(
        text.lines().filter(|l| l.contains("salesman")).count(),
        3,
        "{text}"
    );
}

#[test]
fn bad_mtsp_input_is_named() {
    let dir = temp_dir("bad");
    let file = two_rays(&dir);
    let file = file.to_str().unwrap();
    let missing = dir.join("missing.tsp");
    let out = smug(&[
        "mtsp",
        missing.to_str().unwrap(),
        "--salesmen",
        "2",
        "--objective",
        "minmax",
    ]);
    assert_bad_input(&out, &["missing.tsp"]);
    let out = smug(&["mtsp", file, "--salesmen", "0", "--objective", "minmax"]);
    assert_bad_input(&out, &["--salesmen"]);
    let out = smug(&[
        "mtsp",
        file,
        "--salesmen",
        "2",
        "--objective",
        "minmax",
        "--min-size",
        "7",
    ]);
    assert_bad_input(&out, &["route sizes 7..=12"]);
    let out = smug(&["mtsp", file, "--salesmen", "2", "--objective", "fastest"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("fastest"), "{}", stderr(&out));
    for (set, culprit) in [
        ("sum_elit=8", "sum_elit"),
        ("sum_elite=eight", "sum_elite=eight"),
        ("sum_elite", "sum_elite"),
        ("blink_rate=2.0", "blink_rate"),
    ] {
        assert_bad_input(&mtsp(file, "2", "minsum", &["--set", set]), &[culprit]);
    }
}

#[test]
fn set_overrides_team_lns_parameters() {
    let dir = temp_dir("set");
    let file = two_rays(&dir);
    let file = file.to_str().unwrap();
    let run = |extra: &[&str]| {
        let mut rest = vec!["--time", "0", "--iterations", "400", "--json"];
        rest.extend_from_slice(extra);
        let out = mtsp(file, "3", "minsum", &rest);
        assert!(out.status.success(), "{}", stderr(&out));
        json(&stdout(&out))
    };
    let plain = run(&[]);
    // The default pool spelled out changes nothing (the overrides that do reach the
    // search are checked above: an out-of-range value is refused).
    let same = run(&["--set", "sum_elite=4", "--set", "sum_offspring=8"]);
    assert_eq!(plain["routes"], same["routes"]);
    assert!(
        (same["total"].as_f64().unwrap() - 24.0).abs() < 1e-9,
        "{same}"
    );
}

#[test]
fn bench_mtsp_reports_gaps_and_the_rows_it_leaves_out() {
    let dir = temp_dir("bench");
    std::fs::create_dir_all(dir.join("instances")).unwrap();
    two_rays(&dir.join("instances"));
    std::fs::write(
        dir.join("best_known.csv"),
        "instance,m,objective,best_known,source,distance,set,n,min_size,max_size,note\n\
         tworays,2,minmax,12,\"by construction, one ray each\",euclid,Tiny,12,,,\n\
         tworays,2,minsum,24,\"by construction\",euclid,Tiny,12,5,7,\n\
         nowhere,2,minmax,1,x,euclid,Tiny,3,,,no file\n\
         tworays,3,minmax,12,x,euclid,Other,12,,,\n",
    )
    .unwrap();
    let out_md = dir.join("report.md");
    let out = smug(&[
        "bench",
        "mtsp",
        "--data",
        dir.to_str().unwrap(),
        "--sets",
        "Tiny",
        "--budgets",
        "0.1",
        "--seeds",
        "1,2",
        "--out",
        out_md.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report = std::fs::read_to_string(&out_md).unwrap();
    assert!(report.contains("## Tiny"), "{report}");
    assert!(!report.contains("## Other"), "{report}");
    assert!(
        report.contains("| tworays | 2 | minsum | 12 | 5..7 | 24 |"),
        "{report}"
    );
    assert!(
        report.contains("| 0.1 s | 2 | +0.000% | +0.000% | +0.000% | 2 | 2 |"),
        "{report}"
    );
    assert!(
        report.contains("| Tiny | nowhere | 2 | minmax | no instance file"),
        "{report}"
    );
    let raw = json(&std::fs::read_to_string(dir.join("report.json")).unwrap());
    assert_eq!(raw["runs"].as_array().unwrap().len(), 4);
    let out = smug(&[
        "bench",
        "mtsp",
        "--data",
        dir.to_str().unwrap(),
        "--sets",
        "Nope",
    ]);
    assert_bad_input(&out, &["unknown set `Nope`", "Other, Tiny"]);
}
