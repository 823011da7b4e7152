//! `smug bench gtsp`: gaps of `gtsp-lns` to the best-known values of the GTSP-LIB
//! suite (from `--data DIR` or `$SMUG_DATA/gtsp`).

pub mod suite;

use crate::gtsp::suite::{
    load_gtsp_suite, run_gtsp_instance, GtspBenchInstance, GtspBenchResult, GTSP_SUITE_DESCRIPTION,
};
use crate::tsp::suite::DATA_ENV;
use smug_sequencing::gtsp_lns::GtspLnsParams;
use smug_sequencing::{read_gtsplib, GtspLns};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Arguments of `smug bench gtsp`.
#[derive(clap::Args, Debug)]
pub struct BenchGtspArgs {
    /// The suite: a folder with `values.csv` (default: `$SMUG_DATA/gtsp`).
    #[arg(long, value_name = "DIR")]
    pub data: Option<PathBuf>,
    /// Time budgets in seconds, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1,10")]
    pub budgets: Vec<f64>,
    /// Only instances with at most this many nodes.
    #[arg(long, default_value_t = 1000)]
    pub max_nodes: usize,
    /// Only these instances (comma-separated names); default: all up to --max-nodes.
    #[arg(long, value_delimiter = ',')]
    pub instances: Vec<String>,
    /// Seed of the search.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Also write the Markdown report to this file.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write every run (with its tour) as JSON here (default: beside `--out`, as `.json`).
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// Runs `smug bench gtsp`.
pub fn run(args: BenchGtspArgs) -> crate::Result<()> {
    crate::error::ensure!(
        !args.budgets.is_empty(),
        "--budgets needs at least one value"
    );
    if let Some(bad) = args.budgets.iter().find(|b| !(b.is_finite() && **b > 0.0)) {
        crate::error::bail!("--budgets: {bad} is not a positive number of seconds");
    }
    let dir = suite_dir(args.data.as_deref())?;
    let suite = select(load_gtsp_suite(&dir)?, &args)?;
    let mut results = Vec::new();
    for (k, instance) in suite.iter().enumerate() {
        let gtsp = read_gtsplib(&instance.path)?;
        for &budget in &args.budgets {
            let params = GtspLnsParams {
                time_limit_s: budget,
                max_iterations: 0,
                ..GtspLnsParams::default()
            };
            let solver = GtspLns::with_seed(params, args.seed)?;
            let result = run_gtsp_instance(instance, &gtsp, &solver, budget)
                .map_err(|e| crate::error::invalid!("{}: {e}", instance.name))?;
            eprintln!(
                "[{}/{}] {} @ {budget} s: {} ({:.2}%) in {:.2} s",
                k + 1,
                suite.len(),
                result.instance,
                result.cost,
                result.gap_percent,
                result.time_s
            );
            results.push(result);
        }
    }
    let report = markdown_report(&dir, &args, &results);
    crate::output::write_report(&report, &results, args.out.as_deref(), args.json.as_deref())?;
    Ok(())
}

/// The suite folder from `--data DIR` or `$SMUG_DATA/gtsp`.
fn suite_dir(data: Option<&Path>) -> crate::Result<PathBuf> {
    let from_env = std::env::var_os(DATA_ENV)
        .filter(|v| !v.is_empty())
        .map(|v| Path::new(&v).join("gtsp"));
    data.map(Path::to_path_buf).or(from_env).ok_or_else(|| {
        crate::error::invalid!(
            "no GTSP-LIB suite given: pass --data DIR or set {DATA_ENV} (the suite is then \
             ${DATA_ENV}/gtsp); {GTSP_SUITE_DESCRIPTION}"
        )
    })
}

/// The instances named in `--instances` (all up to `--max-nodes` when none); unknown
/// names are an error.
fn select(
    suite: Vec<GtspBenchInstance>,
    args: &BenchGtspArgs,
) -> crate::Result<Vec<GtspBenchInstance>> {
    if let Some(unknown) = args
        .instances
        .iter()
        .find(|n| !suite.iter().any(|i| &i.name == *n))
    {
        let known: Vec<&str> = suite.iter().map(|i| i.name.as_str()).collect();
        crate::error::bail!("unknown instance `{unknown}`; known: {}", known.join(", "));
    }
    Ok(suite
        .into_iter()
        .filter(|i| {
            if args.instances.is_empty() {
                i.n <= args.max_nodes
            } else {
                args.instances.contains(&i.name)
            }
        })
        .collect())
}

/// The per-instance table and the mean and largest gaps per budget.
fn markdown_report(dir: &Path, args: &BenchGtspArgs, results: &[GtspBenchResult]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "# GTSP-LIB benchmark: `gtsp-lns` (seed {}), suite {}\n",
        args.seed,
        dir.display()
    );
    let mut header = "| instance | n | m | best known |".to_string();
    let mut rule = "|---|---:|---:|---:|".to_string();
    for budget in &args.budgets {
        let _ = write!(
            header,
            " cost @{budget}s | gap @{budget}s | time @{budget}s |"
        );
        rule.push_str("---:|---:|---:|");
    }
    let _ = writeln!(out, "{header}\n{rule}");
    let mut names: Vec<&str> = Vec::new();
    for r in results {
        if !names.contains(&r.instance.as_str()) {
            names.push(&r.instance);
        }
    }
    for name in names {
        let runs: Vec<&GtspBenchResult> = results.iter().filter(|r| r.instance == name).collect();
        let first = runs[0];
        let mut row = format!("| {name} | {} | {} | {} |", first.n, first.m, first.value);
        for &budget in &args.budgets {
            match runs.iter().find(|r| r.budget_s == budget) {
                Some(r) => {
                    let _ = write!(
                        row,
                        " {} | {:.2}% | {:.2} s |",
                        r.cost, r.gap_percent, r.time_s
                    );
                }
                None => row.push_str(" – | – | – |"),
            }
        }
        let _ = writeln!(out, "{row}");
    }
    let _ = writeln!(out, "\n| budget | instances | mean gap | max gap | optimal or best known reached |\n|---:|---:|---:|---:|---:|");
    for &budget in &args.budgets {
        let gaps: Vec<f64> = results
            .iter()
            .filter(|r| r.budget_s == budget)
            .map(|r| r.gap_percent)
            .collect();
        let mean = gaps.iter().sum::<f64>() / gaps.len().max(1) as f64;
        let max = gaps.iter().copied().fold(0.0, f64::max);
        let hits = gaps.iter().filter(|g| **g <= 0.0).count();
        let _ = writeln!(
            out,
            "| {budget} s | {} | {mean:.2}% | {max:.2}% | {hits} |",
            gaps.len()
        );
    }
    out
}
