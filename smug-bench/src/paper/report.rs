//! The Markdown report of `smug bench paper`: Tables I–IV with the paper's numbers
//! beside ours, and the targets checked.

use super::runs::{PaperBench, Run, SCALABILITY, SELECTORS, VALIDITY};
use serde::Serialize;
use smug_core::TimeBreakdown;
use std::fmt::Write;

/// The paper's Table I: (world, selector) → (time s, cost).
const PAPER_TABLE_I: [(&str, &str, f64, f64); 6] = [
    ("lunar", "dp", 71.87, 97.22),
    ("lunar", "idp", 8.05, 97.58),
    ("lunar", "irba", 8.25, 100.08),
    ("indoor", "dp", 7.59, 82.05),
    ("indoor", "idp", 7.20, 82.85),
    ("indoor", "irba", 7.18, 83.66),
];
/// The paper's Table II times (s), in `VALIDITY` order.
const PAPER_TABLE_II: [f64; 3] = [8.05, 9.39, 11.56];
/// The paper's Table III (s): A*, sampling, edge, vertex, misc; hierarchical then full.
const PAPER_TABLE_III: [[f64; 5]; 2] = [
    [5.05, 0.43, 2.32, 0.01, 0.24],
    [4.79, 0.84, 5.68, 0.05, 0.23],
];
/// The paper's Table IV times (s): rows `SCALABILITY`, columns `SELECTORS`.
const PAPER_TABLE_IV: [[f64; 3]; 4] = [
    [5.42, 1.05, 0.74],
    [20.12, 5.12, 5.82],
    [80.49, 22.31, 19.67],
    [508.71, 176.17, 180.42],
];

/// Reads one part of the planner's time breakdown.
type BreakdownPart = fn(&TimeBreakdown) -> f64;

/// Mean and sample standard deviation.
#[derive(Clone, Copy, Debug, Default)]
struct Stat {
    mean: f64,
    std: f64,
    n: usize,
}

impl Stat {
    fn of(values: impl Iterator<Item = f64>) -> Self {
        let v: Vec<f64> = values.collect();
        let n = v.len();
        if n == 0 {
            return Self::default();
        }
        let mean = v.iter().sum::<f64>() / n as f64;
        let var = if n > 1 {
            v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64
        } else {
            0.0
        };
        Self {
            mean,
            std: var.sqrt(),
            n,
        }
    }

    fn show(&self, digits: usize) -> String {
        if self.n == 0 {
            return "—".to_string();
        }
        format!("{:.digits$} ± {:.digits$}", self.mean, self.std)
    }
}

fn stat(bench: &PaperBench, key: &str, field: impl Fn(&Run) -> f64) -> Stat {
    Stat::of(bench.runs_of(key).map(field))
}

fn has(bench: &PaperBench, key: &str) -> bool {
    bench.experiments.iter().any(|e| e.key == key)
}

/// One target or sanity check, measured.
#[derive(Clone, Debug, Serialize)]
pub struct Check {
    /// What is checked.
    pub name: String,
    /// The measured value, in words.
    pub measured: String,
    /// Whether it holds.
    pub passed: bool,
}

fn check(name: &str, measured: String, passed: bool) -> Check {
    Check {
        name: name.to_string(),
        measured,
        passed,
    }
}

/// The checks the numbers allow: sanity (IDP ≤ DP time, IDP within 2% of DP) always,
/// the targets on a full run.
pub fn checks(bench: &PaperBench) -> Vec<Check> {
    let mut list = Vec::new();
    let time = |key: &str| stat(bench, key, |r| r.planning_s).mean;
    let cost = |key: &str| stat(bench, key, |r| r.cost).mean;
    for world in ["lunar", "indoor"] {
        let (dp, idp, irba) = (
            format!("{world}/dp"),
            format!("{world}/idp"),
            format!("{world}/irba"),
        );
        if !has(bench, &dp) || !has(bench, &idp) {
            continue;
        }
        list.push(check(
            &format!("{world}: IDP time ≤ DP time"),
            format!("{:.3} s vs {:.3} s", time(&idp), time(&dp)),
            time(&idp) <= time(&dp),
        ));
        list.push(check(
            &format!("{world}: IDP cost within 2% of DP"),
            format!("{:+.2}%", 100.0 * (cost(&idp) / cost(&dp) - 1.0)),
            cost(&idp) <= 1.02 * cost(&dp),
        ));
        if world == "lunar" && has(bench, &irba) {
            list.push(check(
                "lunar: IRBA cost ≥ IDP cost on average",
                format!("{:.2} vs {:.2}", cost(&irba), cost(&idp)),
                cost(&irba) >= cost(&idp),
            ));
        }
    }
    if bench.quick {
        return list;
    }
    let mut at_most = |name: &str, key: &str, limit: f64| {
        if has(bench, key) {
            let t = time(key);
            list.push(check(name, format!("{t:.3} s"), t <= limit));
        }
    };
    at_most("lunar 13 × 10 IDP ≤ 0.5 s", "lunar/idp", 0.5);
    at_most("lunar 13 × 10 DP ≤ 5 s", "lunar/dp", 5.0);
    at_most("48 × 6 IDP ≤ 5 s", "scalability/48/idp", 5.0);
    at_most("48 × 6 DP ≤ 30 s", "scalability/48/dp", 30.0);
    if has(bench, "validity/0.3-0.3") && has(bench, "validity/full") {
        let (h, f) = ("validity/0.3-0.3", "validity/full");
        let faster = 1.0 - time(h) / time(f);
        let dearer = cost(h) / cost(f) - 1.0;
        let end_to_end_faster =
            1.0 - stat(bench, h, |r| r.total_s).mean / stat(bench, f, |r| r.total_s).mean;
        // Amdahl: checks free of cost would save at most their share of the planner's time.
        let checking_share = stat(bench, f, |r| {
            let b = &r.breakdown;
            (b.edge_checking_s + b.vertex_checking_s) / b.total_s().max(1e-12)
        })
        .mean;
        let per_path = |key: &str| time(key) / stat(bench, key, |r| r.paths_planned as f64).mean;
        let faster_per_path = 1.0 - per_path(h) / per_path(f);
        list.push(check(
            "hierarchical 0.3/0.3 ≥ 30% faster than full collision at ≤ 1% more cost",
            format!(
                "{:.0}% faster, {:+.2}% cost (per path planned: {:.0}% faster; end to end: \
                 {:.0}% faster; checking is {:.0}% of full collision's planner time, the \
                 most cheaper checks can save)",
                100.0 * faster,
                100.0 * dearer,
                100.0 * faster_per_path,
                100.0 * end_to_end_faster,
                100.0 * checking_share,
            ),
            faster >= 0.30 && dearer <= 0.01,
        ));
    }
    list
}

/// The whole Markdown report.
pub fn markdown(bench: &PaperBench, checks: &[Check]) -> String {
    let mut md = String::new();
    header(&mut md, bench);
    table_i(&mut md, bench);
    table_ii(&mut md, bench);
    table_iii(&mut md, bench);
    table_iv(&mut md, bench);
    checks_section(&mut md, checks);
    failures(&mut md, bench);
    md
}

fn header(md: &mut String, bench: &PaperBench) {
    let _ = writeln!(
        md,
        "# SMUG against the paper (Chen et al. 2023)\n\n\
         {} run(s) per experiment (config seeds 1..={}), {}{}. Times are means ± standard \
         deviations in seconds; **time** is planning (sequencing + selection + \
         post-processing: what the paper times), **end to end** adds building the world, \
         traversability and distance field. The paper's numbers: i7-9750H laptop, 10 runs.\n",
        bench.runs,
        bench.runs,
        if bench.vary_world {
            "a new world per seed"
        } else {
            "one world (world seed 1) for every run, as the paper's 10 runs on one world"
        },
        if bench.quick {
            "; `--quick` smoke version"
        } else {
            ""
        },
    );
}

fn table_i(md: &mut String, bench: &PaperBench) {
    if !has(bench, "lunar/idp") {
        return;
    }
    let _ = writeln!(
        md,
        "## Table I: selectors (lunar 13 × 10, indoor 12 × 2)\n\n\
         | world | selector | time (s) | paper | speed-up | end to end (s) | cost | paper | paths planned |\n\
         |---|---|---:|---:|---:|---:|---:|---:|---:|"
    );
    for (world, selector, paper_time, paper_cost) in PAPER_TABLE_I {
        let key = format!("{world}/{selector}");
        if !has(bench, &key) {
            continue;
        }
        let time = stat(bench, &key, |r| r.planning_s);
        let _ = writeln!(
            md,
            "| {world} | {} | {} | {paper_time:.2} | {:.0}× | {} | {} | {paper_cost:.2} | {:.0} |",
            selector.to_uppercase(),
            time.show(3),
            paper_time / time.mean,
            stat(bench, &key, |r| r.total_s).show(3),
            stat(bench, &key, |r| r.cost).show(2),
            stat(bench, &key, |r| r.paths_planned as f64).mean,
        );
    }
    md.push('\n');
}

fn table_ii(md: &mut String, bench: &PaperBench) {
    if !has(bench, VALIDITY[0].0) {
        return;
    }
    let _ = writeln!(
        md,
        "## Table II: hierarchical validity (lunar 13 × 10, IDP)\n\n\
         | validity | time (s) | paper | end to end (s) | cost | validity queries | distance-field queries |\n\
         |---|---:|---:|---:|---:|---:|---:|"
    );
    for ((key, label, _, _), paper) in VALIDITY.iter().zip(PAPER_TABLE_II) {
        let counter =
            |name: &'static str| move |r: &Run| r.counters.get(name).copied().unwrap_or(0) as f64;
        let _ = writeln!(
            md,
            "| {label} | {} | {paper:.2} | {} | {} | {:.0} | {:.0} |",
            stat(bench, key, |r| r.planning_s).show(3),
            stat(bench, key, |r| r.total_s).show(3),
            stat(bench, key, |r| r.cost).show(2),
            stat(bench, key, |r| r.validity_queries as f64).mean,
            stat(bench, key, counter("validity_esdf_queries")).mean,
        );
    }
    md.push('\n');
}

fn table_iii(md: &mut String, bench: &PaperBench) {
    let (h, f) = (VALIDITY[0].0, VALIDITY[2].0);
    if !has(bench, h) || !has(bench, f) {
        return;
    }
    let parts: [(&str, BreakdownPart); 5] = [
        ("A*", |b| b.astar_s),
        ("sampling", |b| b.sampling_s),
        ("edge checking", |b| b.edge_checking_s),
        ("vertex checking", |b| b.vertex_checking_s),
        ("miscellaneous", |b| b.misc_s),
    ];
    let _ = writeln!(
        md,
        "## Table III: where the planner's time goes (lunar 13 × 10, IDP)\n\n\
         | part | hierarchical 0.3/0.3 (s) | share | paper | full collision (s) | share | paper |\n\
         |---|---:|---:|---:|---:|---:|---:|"
    );
    let total = |key: &str| stat(bench, key, |r| r.breakdown.total_s()).mean;
    for (i, (name, part)) in parts.iter().enumerate() {
        let (hs, fs) = (
            stat(bench, h, |r| part(&r.breakdown)).mean,
            stat(bench, f, |r| part(&r.breakdown)).mean,
        );
        let _ = writeln!(
            md,
            "| {name} | {hs:.4} | {:.0}% | {:.2} | {fs:.4} | {:.0}% | {:.2} |",
            100.0 * hs / total(h),
            PAPER_TABLE_III[0][i],
            100.0 * fs / total(f),
            PAPER_TABLE_III[1][i],
        );
    }
    let _ = writeln!(
        md,
        "| **planner total** | {:.4} | | 8.05 | {:.4} | | 11.59 |\n",
        total(h),
        total(f)
    );
}

fn table_iv(md: &mut String, bench: &PaperBench) {
    if !has(bench, "scalability/6/idp") {
        return;
    }
    let _ = writeln!(
        md,
        "## Table IV: scalability (lunar, N ToIs × 6 PoIs)\n\n\
         | ToIs | DP time (s) | paper | IDP time (s) | paper | IRBA time (s) | paper | DP cost | IDP cost | IRBA cost | paths DP / IDP / IRBA |\n\
         |---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for (row, targets) in SCALABILITY.iter().enumerate() {
        let keys = SELECTORS.map(|s| format!("scalability/{targets}/{s}"));
        if !has(bench, &keys[0]) {
            continue;
        }
        let mut line = format!("| {targets} |");
        for (col, key) in keys.iter().enumerate() {
            let _ = write!(
                line,
                " {} | {:.2} |",
                stat(bench, key, |r| r.planning_s).show(3),
                PAPER_TABLE_IV[row][col]
            );
        }
        for key in &keys {
            let _ = write!(line, " {} |", stat(bench, key, |r| r.cost).show(2));
        }
        let paths =
            keys.map(|k| format!("{:.0}", stat(bench, &k, |r| r.paths_planned as f64).mean));
        let _ = writeln!(md, "{line} {} |", paths.join(" / "));
    }
    md.push('\n');
}

fn checks_section(md: &mut String, checks: &[Check]) {
    if checks.is_empty() {
        return;
    }
    let _ = writeln!(md, "## Checks\n\n| check | measured | |\n|---|---|---|");
    for c in checks {
        let mark = if c.passed { "✓" } else { "✗" };
        let _ = writeln!(md, "| {} | {} | {mark} |", c.name, c.measured);
    }
    md.push('\n');
}

fn failures(md: &mut String, bench: &PaperBench) {
    let failed: Vec<&Run> = bench.raw.iter().filter(|r| r.error.is_some()).collect();
    if failed.is_empty() {
        return;
    }
    let _ = writeln!(md, "## Failed runs (left out of the means)\n");
    for r in failed {
        let _ = writeln!(
            md,
            "- {} seed {}: {}",
            r.experiment,
            r.seed,
            r.error.as_deref().unwrap_or("")
        );
    }
    md.push('\n');
}
