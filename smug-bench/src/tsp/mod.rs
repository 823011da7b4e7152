//! `smug bench tsp`: gaps to the proven optima of the TSPLIB suite (from `--data DIR`
//! or `$SMUG_DATA/tsplib`, see [`suite`]), with OR-Tools beside them on request.

pub mod suite;

use crate::solvers::{sequencer, SolverOptions, TSP_SOLVERS};
use crate::tsp::suite::{load_suite, run_instance, BenchInstance, BenchResult};
use smug_sequencing::read_tsplib;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Arguments of `smug bench tsp`.
#[derive(clap::Args, Debug)]
pub struct BenchTspArgs {
    /// The suite: a folder with `tsp/` and `atsp/` and their `optima.csv`
    /// (default: `$SMUG_DATA/tsplib`).
    #[arg(long, value_name = "DIR")]
    pub data: Option<PathBuf>,
    /// Time budgets in seconds, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1,10")]
    pub budgets: Vec<f64>,
    /// Only these instances (comma-separated names); default: all.
    #[arg(long, value_delimiter = ',')]
    pub instances: Vec<String>,
    /// Solver.
    #[arg(long, default_value = "auto", value_parser = clap::builder::PossibleValuesParser::new(TSP_SOLVERS))]
    pub solver: String,
    /// Seed of the local search.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Also run OR-Tools' routing solver (guided local search, same budgets) through
    /// `python3` (needs `pip install ortools`); its times include Python's start-up.
    #[arg(long)]
    pub ortools: bool,
    /// Also write the Markdown report to this file.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write every run (with its tour) as JSON here (default: beside `--out`, as `.json`).
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// Name of the OR-Tools runs in the report.
const ORTOOLS: &str = "or-tools";

/// Runs `smug bench tsp`.
pub fn run_bench(args: BenchTspArgs) -> crate::Result<()> {
    crate::error::ensure!(
        !args.budgets.is_empty(),
        "--budgets needs at least one value"
    );
    if let Some(bad) = args.budgets.iter().find(|b| !(b.is_finite() && **b > 0.0)) {
        crate::error::bail!("--budgets: {bad} is not a positive number of seconds");
    }
    if args.ortools {
        ortools::check_available()?;
    }
    let dir = suite::require_suite_dir(args.data.as_deref())?;
    let suite = select(load_suite(&dir)?, &args.instances)?;
    let mut results = Vec::new();
    for (k, instance) in suite.iter().enumerate() {
        let costs = read_tsplib(&instance.path)?.costs;
        for &budget in &args.budgets {
            let options = SolverOptions {
                time_limit_s: budget,
                max_iterations: None,
                seed: args.seed,
            };
            let solver = sequencer(&args.solver, &options)?;
            let result = run_instance(instance, &costs, solver.as_ref(), &args.solver, budget)
                .map_err(|e| crate::error::invalid!("{}: {e}", instance.name))?;
            progress(k, suite.len(), &result);
            results.push(result);
            if args.ortools {
                let result = ortools::solve(instance, &costs, budget)?;
                progress(k, suite.len(), &result);
                results.push(result);
            }
        }
    }
    let report = markdown_report(&dir, &args, &results);
    crate::output::write_report(&report, &results, args.out.as_deref(), args.json.as_deref())?;
    Ok(())
}

fn progress(k: usize, total: usize, r: &BenchResult) {
    eprintln!(
        "[{}/{total}] {} {} @ {} s: {} ({:.2}%) in {:.2} s",
        k + 1,
        r.instance,
        r.solver,
        r.budget_s,
        r.cost,
        r.gap_percent,
        r.time_s
    );
}

/// The instances named in `names` (all when empty); unknown names are an error.
fn select(suite: Vec<BenchInstance>, names: &[String]) -> crate::Result<Vec<BenchInstance>> {
    if names.is_empty() {
        return Ok(suite);
    }
    if let Some(unknown) = names.iter().find(|n| !suite.iter().any(|i| &i.name == *n)) {
        let known: Vec<&str> = suite.iter().map(|i| i.name.as_str()).collect();
        crate::error::bail!("unknown instance `{unknown}`; known: {}", known.join(", "));
    }
    Ok(suite
        .into_iter()
        .filter(|i| names.contains(&i.name))
        .collect())
}

fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

fn max(values: &[f64]) -> Option<f64> {
    values.iter().copied().reduce(f64::max)
}

fn percent(value: Option<f64>) -> String {
    value.map_or("–".to_string(), |g| format!("{g:.2}%"))
}

/// The per-instance table and the mean gaps, symmetric and asymmetric apart.
fn markdown_report(dir: &Path, args: &BenchTspArgs, results: &[BenchResult]) -> String {
    let mut solvers = vec![args.solver.as_str()];
    if args.ortools {
        solvers.push(ORTOOLS);
    }
    let mut out = String::new();
    let _ = writeln!(
        out,
        "# TSPLIB benchmark: `{}` (seed {}), suite {}\n",
        args.solver,
        args.seed,
        dir.display()
    );
    let _ = writeln!(out, "{}", table_header(&args.budgets, &solvers));
    let mut names: Vec<&str> = Vec::new();
    for r in results {
        if !names.contains(&r.instance.as_str()) {
            names.push(&r.instance);
        }
    }
    for name in names {
        let _ = writeln!(out, "{}", table_row(name, &args.budgets, &solvers, results));
    }
    let _ = writeln!(
        out,
        "\n| solver | budget | mean gap, symmetric | max gap, symmetric | mean gap, ATSP | max gap, ATSP |\n|---|---:|---:|---:|---:|---:|"
    );
    for solver in &solvers {
        for &budget in &args.budgets {
            let gaps = |asymmetric: bool| -> Vec<f64> {
                results
                    .iter()
                    .filter(|r| {
                        r.solver == *solver && r.budget_s == budget && r.asymmetric == asymmetric
                    })
                    .map(|r| r.gap_percent)
                    .collect()
            };
            let (sym, asym) = (gaps(false), gaps(true));
            let _ = writeln!(
                out,
                "| {solver} | {budget} s | {} | {} | {} | {} |",
                percent(mean(&sym)),
                percent(max(&sym)),
                percent(mean(&asym)),
                percent(max(&asym))
            );
        }
    }
    out
}

fn table_header(budgets: &[f64], solvers: &[&str]) -> String {
    let mut header = "| instance | n | optimum |".to_string();
    let mut rule = "|---|---:|---:|".to_string();
    for budget in budgets {
        let _ = write!(
            header,
            " cost @{budget}s | gap @{budget}s | time @{budget}s |"
        );
        rule.push_str("---:|---:|---:|");
        for solver in &solvers[1..] {
            let _ = write!(header, " {solver} gap @{budget}s |");
            rule.push_str("---:|");
        }
    }
    format!("{header}\n{rule}")
}

fn table_row(name: &str, budgets: &[f64], solvers: &[&str], results: &[BenchResult]) -> String {
    let find = |solver: &str, budget: f64| {
        results
            .iter()
            .find(|r| r.instance == name && r.solver == solver && r.budget_s == budget)
    };
    let Some(first) = results.iter().find(|r| r.instance == name) else {
        return String::new();
    };
    let kind = if first.asymmetric { " (ATSP)" } else { "" };
    let mut row = format!("| {name}{kind} | {} | {} |", first.n, first.optimum);
    for &budget in budgets {
        match find(solvers[0], budget) {
            Some(r) => {
                let _ = write!(
                    row,
                    " {} | {:.2}% | {:.2} s |",
                    r.cost, r.gap_percent, r.time_s
                );
            }
            None => row.push_str(" – | – | – |"),
        }
        for solver in &solvers[1..] {
            let gap = find(solver, budget).map(|r| r.gap_percent);
            let _ = write!(row, " {} |", percent(gap));
        }
    }
    row
}

/// OR-Tools through `python3`, for comparison only.
mod ortools {
    use super::ORTOOLS;
    use crate::error::ResultExt as _;
    use crate::tsp::suite::{BenchInstance, BenchResult};
    use smug_core::CostMatrix;
    use std::process::Command;
    use std::time::Instant;

    /// Reads `{"costs": [[…]]}` (integers) and a budget in seconds; prints the order.
    const SCRIPT: &str = r#"
import json, sys
from ortools.constraint_solver import pywrapcp, routing_enums_pb2
costs = json.load(open(sys.argv[1]))["costs"]
manager = pywrapcp.RoutingIndexManager(len(costs), 1, 0)
routing = pywrapcp.RoutingModel(manager)
routing.SetArcCostEvaluatorOfAllVehicles(routing.RegisterTransitMatrix(costs))
params = pywrapcp.DefaultRoutingSearchParameters()
params.first_solution_strategy = routing_enums_pb2.FirstSolutionStrategy.PATH_CHEAPEST_ARC
params.local_search_metaheuristic = routing_enums_pb2.LocalSearchMetaheuristic.GUIDED_LOCAL_SEARCH
params.time_limit.FromMilliseconds(int(float(sys.argv[2]) * 1000))
solution = routing.SolveWithParameters(params)
order, index = [], routing.Start(0)
while not routing.IsEnd(index):
    order.append(manager.IndexToNode(index))
    index = solution.Value(routing.NextVar(index))
print(json.dumps(order))
"#;

    /// Fails unless `python3 -c "import ortools"` works.
    pub(super) fn check_available() -> crate::Result<()> {
        let status = Command::new("python3")
            .args(["-c", "import ortools"])
            .status()
            .context("--ortools: cannot run python3")?;
        crate::error::ensure!(
            status.success(),
            "--ortools: python3 cannot import ortools (pip install ortools)"
        );
        Ok(())
    }

    /// Solves `instance` with OR-Tools within `budget` seconds.
    pub(super) fn solve(
        instance: &BenchInstance,
        costs: &CostMatrix,
        budget: f64,
    ) -> crate::Result<BenchResult> {
        let n = costs.len();
        let rows: Vec<Vec<i64>> = (0..n)
            .map(|i| (0..n).map(|j| costs.get(i, j).round() as i64).collect())
            .collect();
        let file = std::env::temp_dir().join(format!("smug-ortools-{}.json", std::process::id()));
        std::fs::write(&file, serde_json::json!({ "costs": rows }).to_string())
            .with_context(|| format!("writing {}", file.display()))?;
        let started = Instant::now();
        let output = Command::new("python3")
            .arg("-c")
            .arg(SCRIPT)
            .arg(&file)
            .arg(budget.to_string())
            .output()
            .context("running python3")?;
        let time_s = started.elapsed().as_secs_f64();
        let _ = std::fs::remove_file(&file);
        crate::error::ensure!(
            output.status.success(),
            "OR-Tools failed on {}: {}",
            instance.name,
            String::from_utf8_lossy(&output.stderr).trim()
        );
        let order: Vec<usize> = serde_json::from_slice(&output.stdout)
            .with_context(|| format!("reading OR-Tools' tour for {}", instance.name))?;
        crate::error::ensure!(
            order.len() == n,
            "OR-Tools returned {} of {n} nodes",
            order.len()
        );
        Ok(BenchResult::new(
            instance, costs, ORTOOLS, budget, order, time_s,
        ))
    }
}
