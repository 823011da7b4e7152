//! `smug tsp`: solve one TSPLIB instance, given as a file or by its name in the suite.
//!
//! Tours are printed as 0-based node indices: TSPLIB node `k` is index `k − 1`. A tour
//! starts at node 0 (TSPLIB node 1); a closed tour's return to 0 is implied. Costs are
//! TSPLIB's (integer distances, e.g. EUC_2D rounded to the nearest integer).
//!
//! The suite (for names here and for `smug bench tsp`) is the folder given by `--data
//! DIR`, else `$SMUG_DATA/tsplib`; the project ships none.

use crate::Outcome;
use serde::Serialize;
use smug_bench::solvers::{sequencer, SolverOptions, TSP_SOLVERS};
use smug_bench::tsp::suite::{gap_percent, load_suite, require_suite_dir, BenchInstance};
use smug_core::TourKind;
use smug_sequencing::read_tsplib;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `smug tsp`.
#[derive(clap::Args, Debug)]
pub struct TspArgs {
    /// A TSPLIB file (.tsp or .atsp), or the name of an instance of the suite (then
    /// its optimum and the gap are reported too).
    pub file: PathBuf,
    /// The suite folder for instance names: `tsp/` and `atsp/` with their
    /// `optima.csv` (default: `$SMUG_DATA/tsplib`).
    #[arg(long, value_name = "DIR")]
    pub data: Option<PathBuf>,
    /// Solver: auto (Held-Karp up to 16 nodes, local search above), held-karp,
    /// local-search or brute-force.
    #[arg(long, default_value = "auto", value_parser = clap::builder::PossibleValuesParser::new(TSP_SOLVERS))]
    pub solver: String,
    /// Local search time budget in seconds (0 = none; then give --iterations).
    #[arg(long, default_value_t = 1.0)]
    pub time_limit: f64,
    /// Local search budget of perturbation rounds; with `--time-limit 0` the tour
    /// depends only on the seed.
    #[arg(long)]
    pub iterations: Option<u64>,
    /// Seed of the local search.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Solve an open path from node 0 to this node (0-based) instead of a closed tour.
    #[arg(long)]
    pub end: Option<usize>,
}

/// What `smug tsp` prints.
#[derive(Serialize)]
struct TspReport {
    name: String,
    n: usize,
    solver: String,
    kind: String,
    cost: serde_json::Value,
    /// The suite's optimal tour length (instances named from the suite only).
    #[serde(skip_serializing_if = "Option::is_none")]
    optimum: Option<serde_json::Value>,
    /// `100 · (cost − optimum) / optimum`, for closed tours of suite instances.
    #[serde(skip_serializing_if = "Option::is_none")]
    gap_percent: Option<f64>,
    tour: Vec<usize>,
    time_s: f64,
}

/// Runs `smug tsp`.
pub fn run(args: TspArgs) -> anyhow::Result<Outcome> {
    let (path, optimum) = match suite_name(&args.file) {
        Some(name) => {
            let instance = find_in_suite(args.data.as_deref(), name)?;
            (instance.path, Some(instance.optimum))
        }
        None => (args.file.clone(), None),
    };
    let instance = read_tsplib(&path)?;
    let solver = sequencer(
        &args.solver,
        &SolverOptions {
            time_limit_s: args.time_limit,
            max_iterations: args.iterations,
            seed: args.seed,
        },
    )?;
    let kind = args.end.map_or(TourKind::Closed, TourKind::OpenTo);
    let started = Instant::now();
    let tour = solver.solve(&instance.costs, kind)?;
    let time_s = started.elapsed().as_secs_f64();
    let report = TspReport {
        name: instance.name,
        n: instance.costs.len(),
        solver: args.solver,
        kind: match kind {
            TourKind::Closed => "closed".into(),
            TourKind::OpenTo(end) => format!("open to {end}"),
        },
        cost: json_number(tour.cost),
        optimum: optimum.map(json_number),
        gap_percent: optimum
            .filter(|_| kind == TourKind::Closed)
            .map(|optimum| gap_percent(tour.cost, optimum)),
        tour: tour.order,
        time_s,
    };
    println!("{}", serde_json::to_string(&report)?);
    Ok(if tour.cost.is_finite() {
        Outcome::Ok
    } else {
        Outcome::NoSolution
    })
}

/// The instance name `file` stands for: a bare word (no `/`, no `.`) that is not an
/// existing file.
fn suite_name(file: &Path) -> Option<&str> {
    let text = file.to_str()?;
    let bare = !text.is_empty() && !text.contains(['/', '\\', '.']);
    (bare && !file.exists()).then_some(text)
}

/// The instance called `name` in the suite.
fn find_in_suite(data: Option<&Path>, name: &str) -> anyhow::Result<BenchInstance> {
    let dir = require_suite_dir(data)?;
    let suite = load_suite(&dir)?;
    let known: Vec<&str> = suite.iter().map(|i| i.name.as_str()).collect();
    let Some(found) = suite.iter().find(|i| i.name == name) else {
        anyhow::bail!(
            "no file `{name}` and no instance `{name}` in the suite {}; known: {}",
            dir.display(),
            known.join(", ")
        );
    };
    Ok(found.clone())
}

/// An integral cost as a JSON integer (TSPLIB costs), anything else as a float.
fn json_number(value: f64) -> serde_json::Value {
    if value.fract() == 0.0 && value.abs() < 9.0e15 {
        serde_json::Value::from(value as i64)
    } else {
        serde_json::Value::from(value)
    }
}
