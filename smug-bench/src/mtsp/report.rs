//! The Markdown report of `smug bench mtsp`: per set, a table of rows × budgets (mean
//! and best over the seeds, gaps to the best-known value), a summary per budget and the
//! rows left out with why.

use super::{BenchMtspArgs, MtspRun, Skipped};
use std::fmt::Write as _;

/// A gap this small counts as reaching the best-known value.
pub const AT_BEST_PERCENT: f64 = 0.01;

/// The runs of one row (set, instance, m, objective) at one budget.
struct Cell<'a> {
    runs: Vec<&'a MtspRun>,
}

impl Cell<'_> {
    fn mean(&self, f: impl Fn(&MtspRun) -> f64) -> f64 {
        self.runs.iter().map(|r| f(r)).sum::<f64>() / self.runs.len() as f64
    }

    fn best(&self, f: impl Fn(&MtspRun) -> f64) -> f64 {
        self.runs.iter().map(|r| f(r)).fold(f64::INFINITY, f64::min)
    }
}

fn same_row(a: &MtspRun, b: &MtspRun) -> bool {
    a.row.set == b.row.set
        && a.row.instance == b.row.instance
        && a.row.m == b.row.m
        && a.row.objective == b.row.objective
}

/// The rows in order of first appearance, each as its first run.
fn rows(runs: &[MtspRun]) -> Vec<&MtspRun> {
    let mut rows: Vec<&MtspRun> = Vec::new();
    for run in runs {
        if !rows.iter().any(|r| same_row(r, run)) {
            rows.push(run);
        }
    }
    rows
}

fn cell<'a>(runs: &'a [MtspRun], row: &MtspRun, budget: f64) -> Cell<'a> {
    Cell {
        runs: runs
            .iter()
            .filter(|r| same_row(r, row) && r.budget_s == budget)
            .collect(),
    }
}

/// The whole report.
pub fn markdown(args: &BenchMtspArgs, runs: &[MtspRun], skipped: &[Skipped]) -> String {
    let mut out = String::new();
    let seeds: Vec<String> = args.seeds.iter().map(u64::to_string).collect();
    let _ = writeln!(
        out,
        "# mTSP benchmark: `team-lns`, one thread, seeds {}, suite {}\n",
        seeds.join(", "),
        args.data.display()
    );
    let _ = writeln!(
        out,
        "Gap = 100·(ours − best-known)/best-known; \"at BK\" = within {AT_BEST_PERCENT}%. \
         The best-known value is LKH-3's verified tour value in most rows (column `src`: \
         `LKH` = re-measured from a stored LKH-3 tour, `claim` = a value LKH-3's scripts \
         state, no tour); `LKH runAll` is the value in Helsgaun's runAll script where the \
         row has one.\n"
    );
    if args.min_size > 0 {
        let _ = writeln!(
            out,
            "Rows without size bounds ran with at least {} customer(s) per salesman \
             (`--min-size`; column `sizes`).\n",
            args.min_size
        );
    }
    if !args.report.set.is_empty() {
        let _ = writeln!(out, "team-lns overrides: `{}`\n", args.report.set.join(" "));
    }
    let mut sets: Vec<&str> = Vec::new();
    for run in runs {
        if !sets.contains(&run.row.set.as_str()) {
            sets.push(&run.row.set);
        }
    }
    for set in sets {
        let set_runs: Vec<MtspRun> = runs.iter().filter(|r| r.row.set == set).cloned().collect();
        write_set(&mut out, set, &args.budgets, &set_runs);
    }
    write_skipped(&mut out, skipped);
    out
}

fn write_set(out: &mut String, set: &str, budgets: &[f64], runs: &[MtspRun]) {
    let _ = writeln!(out, "## {set}\n");
    let mut header =
        "| instance | m | obj | n | sizes | best-known | src | LKH runAll |".to_string();
    let mut rule = "|---|---|---|---|---|---|---|---|".to_string();
    for b in budgets {
        let _ = write!(
            header,
            " mean @{b}s | best @{b}s | gap mean | gap best | time |"
        );
        rule.push_str("---|---|---|---|---|");
    }
    let _ = writeln!(out, "{header}\n{rule}");
    for row in rows(runs) {
        let sizes = row.row.route_size.map_or("–".to_string(), |s| {
            let max = s.max.min(row.n);
            format!("{}..{max}", s.min)
        });
        let src = if row.row.status.starts_with("optimal") {
            "opt"
        } else if row.row.verified == "yes" || !row.row.status.is_empty() {
            "LKH"
        } else {
            "claim"
        };
        let lkh = row
            .row
            .lkh_claimed
            .map_or("–".to_string(), |v| format!("{v}"));
        let _ = write!(
            out,
            "| {} | {} | {} | {} | {sizes} | {} | {src} | {lkh} |",
            row.row.instance, row.row.m, row.row.objective, row.n, row.row.best_known
        );
        for &b in budgets {
            let c = cell(runs, row, b);
            if c.runs.is_empty() {
                out.push_str(" – | – | – | – | – |");
                continue;
            }
            let _ = write!(
                out,
                " {:.4} | {:.4} | {:+.3}% | {:+.3}% | {:.2} s |",
                c.mean(|r| r.value),
                c.best(|r| r.value),
                c.mean(|r| r.gap_percent),
                c.best(|r| r.gap_percent),
                c.mean(|r| r.time_s)
            );
        }
        out.push('\n');
    }
    write_summary(out, budgets, runs);
}

fn write_summary(out: &mut String, budgets: &[f64], runs: &[MtspRun]) {
    let _ = writeln!(
        out,
        "\n| budget | cells | mean gap (seed mean) | worst gap (seed mean) | worst single run | cells at BK (best seed) | cells at BK (every seed) |\n|---|---|---|---|---|---|---|"
    );
    for &b in budgets {
        let cells: Vec<Cell> = rows(runs)
            .into_iter()
            .map(|row| cell(runs, row, b))
            .filter(|c| !c.runs.is_empty())
            .collect();
        if cells.is_empty() {
            continue;
        }
        let means: Vec<f64> = cells.iter().map(|c| c.mean(|r| r.gap_percent)).collect();
        let worst_run = cells
            .iter()
            .flat_map(|c| c.runs.iter().map(|r| r.gap_percent))
            .fold(f64::NEG_INFINITY, f64::max);
        let at_best = cells
            .iter()
            .filter(|c| c.best(|r| r.gap_percent) <= AT_BEST_PERCENT)
            .count();
        let always = cells
            .iter()
            .filter(|c| c.runs.iter().all(|r| r.gap_percent <= AT_BEST_PERCENT))
            .count();
        let _ = writeln!(
            out,
            "| {b} s | {} | {:+.3}% | {:+.3}% | {:+.3}% | {at_best} | {always} |",
            cells.len(),
            means.iter().sum::<f64>() / means.len() as f64,
            means.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            worst_run
        );
    }
    out.push('\n');
}

fn write_skipped(out: &mut String, skipped: &[Skipped]) {
    if skipped.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "## Rows left out\n\n| set | instance | m | objective | why |\n|---|---|---|---|---|"
    );
    for s in skipped {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} |",
            s.row.set, s.row.instance, s.row.m, s.row.objective, s.reason
        );
    }
    out.push('\n');
}
