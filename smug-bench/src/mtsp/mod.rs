//! `smug bench mtsp`: `team-lns` on single-depot mTSP suites (a folder laid out as
//! [`suite`] describes, passed with `--data`), per row × budget × seed, against the
//! best-known values (LKH-3's in most rows). One thread: the runs are sequential.

pub mod report;
pub mod suite;

use crate::output::ReportArgs;
use serde::Serialize;
use smug_sequencing::read_tsplib;
use smug_sequencing::team::{mtsp_costs, mtsp_problem, TeamLns, TeamLnsParams};
use std::path::{Path, PathBuf};
use std::time::Instant;
use suite::{gap_percent, instance_path, load_rows, MtspRow};

/// Arguments of `smug bench mtsp`.
#[derive(clap::Args, Debug)]
pub struct BenchMtspArgs {
    /// The suite folder (`instances/`, `best_known.csv`).
    #[arg(long, value_name = "DIR")]
    pub data: PathBuf,
    /// Sets to run (column `set`; `mTSPLib-MinMax16` = the rows of mtsplib_minmax.csv).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "mTSPLib-MinMax,mTSPLib-MinSum"
    )]
    pub sets: Vec<String>,
    /// Only these instances (comma-separated names); default: all of the sets.
    #[arg(long, value_delimiter = ',')]
    pub instances: Vec<String>,
    /// Only rows of this objective (`minmax` or `minsum`); default: both.
    #[arg(long, value_parser = ["minmax", "minsum"])]
    pub objective: Option<String>,
    /// Only rows with at most this many customers.
    #[arg(long)]
    pub max_customers: Option<usize>,
    /// Fewest customers per salesman on rows without size bounds (0: idle salesmen
    /// allowed). LKH-3's tours, the best-known values of most rows, use every salesman
    /// (its MTSP_MIN_SIZE defaults to 1), and He & Hao's sets require it.
    #[arg(long, default_value_t = 0)]
    pub min_size: usize,
    /// Time budgets in seconds, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1,10")]
    pub budgets: Vec<f64>,
    /// Seeds, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1,2,3")]
    pub seeds: Vec<u64>,
    /// `--set KEY=VALUE` overrides a `team-lns` parameter; `--out`, `--json` as usual.
    #[command(flatten)]
    pub report: ReportArgs,
}

/// One run: a row, a budget, a seed.
#[derive(Clone, Debug, Serialize)]
pub struct MtspRun {
    /// The row.
    #[serde(flatten)]
    pub row: MtspRow,
    /// Customers (depot excluded).
    pub n: usize,
    /// Time budget in seconds.
    pub budget_s: f64,
    /// Seed.
    pub seed: u64,
    /// The objective's value found (makespan or total).
    pub value: f64,
    /// Largest route.
    pub makespan: f64,
    /// Sum of the routes.
    pub total: f64,
    /// `100 · (value − best_known) / best_known`.
    pub gap_percent: f64,
    /// Wall time in seconds.
    pub time_s: f64,
    /// Ruin-and-recreate iterations done.
    pub iterations: u64,
    /// Customers per route.
    pub route_sizes: Vec<usize>,
}

/// A row left out, and why.
#[derive(Clone, Debug, Serialize)]
pub struct Skipped {
    /// The row.
    pub row: MtspRow,
    /// Why.
    pub reason: String,
}

/// Everything `--json` holds.
#[derive(Serialize)]
struct Raw<'a> {
    runs: &'a [MtspRun],
    skipped: &'a [Skipped],
}

/// Runs `smug bench mtsp`.
pub fn run_bench(args: BenchMtspArgs) -> crate::Result<()> {
    check_args(&args)?;
    let params = lns_params(&args.report.set)?;
    let rows = select(load_rows(&args.data)?, &args)?;
    let mut runs = Vec::new();
    let mut skipped = Vec::new();
    let total = rows.len() * args.budgets.len() * args.seeds.len();
    for mut row in rows {
        if row.route_size.is_none() && args.min_size > 0 {
            row.route_size = Some(smug_core::RouteSize {
                min: args.min_size,
                max: usize::MAX,
            });
        }
        let Some(path) = instance_path(&args.data, &row.instance) else {
            let reason = "no instance file in instances/".to_string();
            skipped.push(Skipped { row, reason });
            continue;
        };
        let prepared = prepare(&path, &row);
        let (problem, n) = match prepared {
            Ok(p) => p,
            Err(e) => {
                skipped.push(Skipped {
                    row,
                    reason: e.to_string(),
                });
                continue;
            }
        };
        if args.max_customers.is_some_and(|most| n > most) {
            let reason = format!("{n} customers > --max-customers");
            skipped.push(Skipped { row, reason });
            continue;
        }
        for &budget in &args.budgets {
            for &seed in &args.seeds {
                let run = solve(&problem, &row, n, budget, seed, &params)?;
                progress(runs.len() + 1, total, &run);
                runs.push(run);
            }
        }
    }
    let text = report::markdown(&args, &runs, &skipped);
    args.report.write(
        &text,
        &Raw {
            runs: &runs,
            skipped: &skipped,
        },
    )
}

fn check_args(args: &BenchMtspArgs) -> crate::Result<()> {
    crate::error::ensure!(
        !args.budgets.is_empty(),
        "--budgets needs at least one value"
    );
    if let Some(bad) = args.budgets.iter().find(|b| !(b.is_finite() && **b > 0.0)) {
        crate::error::bail!("--budgets: {bad} is not a positive number of seconds");
    }
    crate::error::ensure!(!args.seeds.is_empty(), "--seeds needs at least one value");
    crate::error::ensure!(
        args.data.is_dir(),
        "--data {}: not a folder",
        args.data.display()
    );
    Ok(())
}

/// The `team-lns` parameters with `--set KEY=VALUE` overrides (keys are
/// [`TeamLnsParams`] fields, values TOML), checked.
pub fn lns_params(overrides: &[String]) -> crate::Result<TeamLnsParams> {
    let mut table = toml::Table::try_from(TeamLnsParams::default())
        .map_err(|e| crate::error::invalid!("team-lns parameters: {e}"))?;
    for item in overrides {
        let (key, value) = item
            .split_once('=')
            .ok_or_else(|| crate::error::invalid!("--set {item}: expected KEY=VALUE"))?;
        let parsed: toml::Table = toml::from_str(&format!("v = {value}"))
            .map_err(|e| crate::error::invalid!("--set {item}: {e}"))?;
        table.insert(key.trim().to_string(), parsed["v"].clone());
    }
    let params: TeamLnsParams = table
        .try_into()
        .map_err(|e| crate::error::invalid!("--set: {e}"))?;
    params
        .validate()
        .map_err(|e| crate::error::invalid!("--set: team-lns: {e}"))?;
    Ok(params)
}

/// The rows of the chosen sets (and instances); unknown names are errors.
fn select(rows: Vec<MtspRow>, args: &BenchMtspArgs) -> crate::Result<Vec<MtspRow>> {
    for set in &args.sets {
        if !rows.iter().any(|r| &r.set == set) {
            let mut known: Vec<&str> = rows.iter().map(|r| r.set.as_str()).collect();
            known.sort();
            known.dedup();
            crate::error::bail!("--sets: unknown set `{set}`; known: {}", known.join(", "));
        }
    }
    let chosen: Vec<MtspRow> = rows
        .into_iter()
        .filter(|r| args.sets.contains(&r.set))
        .filter(|r| args.instances.is_empty() || args.instances.contains(&r.instance))
        .filter(|r| args.objective.as_ref().is_none_or(|o| &r.objective == o))
        .collect();
    crate::error::ensure!(
        !chosen.is_empty(),
        "no row of the sets {:?} matches --instances {:?}",
        args.sets,
        args.instances
    );
    Ok(chosen)
}

fn prepare(path: &Path, row: &MtspRow) -> crate::Result<(smug_core::TeamProblem, usize)> {
    let instance = read_tsplib(path)?;
    let n = instance.costs.len().saturating_sub(1);
    let costs = mtsp_costs(&instance, row.mtsp_distance())
        .map_err(|e| crate::error::invalid!("{}: {e}", path.display()))?;
    let size = row.route_size.map(|mut s| {
        s.max = s.max.min(n);
        s
    });
    let problem = mtsp_problem(costs, row.m, row.team_objective(), size)
        .map_err(|e| crate::error::invalid!("{} m={}: {e}", row.instance, row.m))?;
    Ok((problem, n))
}

fn solve(
    problem: &smug_core::TeamProblem,
    row: &MtspRow,
    n: usize,
    budget: f64,
    seed: u64,
    params: &TeamLnsParams,
) -> crate::Result<MtspRun> {
    let params = TeamLnsParams {
        time_limit_s: budget,
        max_iterations: 0,
        ..params.clone()
    };
    let solver = TeamLns::with_seed(params, seed)?;
    let started = Instant::now();
    let (solution, iterations) = solver.solve_with_iterations(problem, None)?;
    let time_s = started.elapsed().as_secs_f64();
    problem
        .validate(&solution)
        .map_err(|e| crate::error::invalid!("{} m={}: {e}", row.instance, row.m))?;
    let value = problem.score(&solution).0;
    Ok(MtspRun {
        row: row.clone(),
        n,
        budget_s: budget,
        seed,
        value,
        makespan: solution.makespan,
        total: solution.total,
        gap_percent: gap_percent(value, row.best_known),
        time_s,
        iterations,
        route_sizes: solution.routes.iter().map(Vec::len).collect(),
    })
}

fn progress(k: usize, total: usize, run: &MtspRun) {
    eprintln!(
        "[{k}/{total}] {} m={} {} @ {} s seed {}: {:.4} ({:+.3}%) in {:.2} s",
        run.row.instance,
        run.row.m,
        run.row.objective,
        run.budget_s,
        run.seed,
        run.value,
        run.gap_percent,
        run.time_s
    );
}
