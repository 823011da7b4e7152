//! `smug gtsp`: solve one GTSP-LIB instance (one node per cluster).
//!
//! Tours are printed as 0-based node indices (GTSP-LIB node `k` is index `k − 1`), one
//! per cluster, starting in cluster 0 (the file's set 1); a closed tour's return is
//! implied. Costs are TSPLIB's (integer distances).

use crate::Outcome;
use serde::Serialize;
use smug_bench::solvers::GTSP_SOLVERS;
use smug_core::TourKind;
use smug_sequencing::gtsp_lns::GtspLnsParams;
use smug_sequencing::{read_gtsplib, GtspExact, GtspExactParams, GtspLns};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `smug gtsp`.
#[derive(clap::Args, Debug)]
pub struct GtspArgs {
    /// A GTSP-LIB file (TSPLIB with GTSP_SETS and a GTSP_SET_SECTION).
    pub file: PathBuf,
    /// Solver: gtsp-lns (large-neighbourhood search) or gtsp-exact (DP over clusters,
    /// up to 20 clusters).
    #[arg(long, default_value = "gtsp-lns", value_parser = clap::builder::PossibleValuesParser::new(GTSP_SOLVERS))]
    pub solver: String,
    /// Time budget in seconds (0 = none; then give --iterations).
    #[arg(long, default_value_t = 1.0)]
    pub time: f64,
    /// Budget of search iterations; with `--time 0` the tour depends only on the seed.
    #[arg(long)]
    pub iterations: Option<u64>,
    /// Seed of the search.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// End the tour in this cluster (0-based; the file's set k is cluster k − 1)
    /// instead of returning to the start cluster.
    #[arg(long)]
    pub end: Option<usize>,
}

/// What `smug gtsp` prints.
#[derive(Serialize)]
struct GtspReport {
    name: String,
    n: usize,
    clusters: usize,
    solver: String,
    kind: String,
    cost: f64,
    /// Search iterations done (gtsp-lns).
    #[serde(skip_serializing_if = "Option::is_none")]
    iterations: Option<u64>,
    tour: Vec<usize>,
    time_s: f64,
}

/// Runs `smug gtsp`.
pub fn run(args: GtspArgs) -> anyhow::Result<Outcome> {
    anyhow::ensure!(
        args.time.is_finite() && args.time >= 0.0,
        "--time {}: must be a number of seconds ≥ 0",
        args.time
    );
    let instance = read_gtsplib(&args.file)?;
    let kind = args.end.map_or(TourKind::Closed, TourKind::OpenTo);
    let started = Instant::now();
    let (tour, iterations) = if args.solver == "gtsp-exact" {
        let solver = GtspExact::new(GtspExactParams::default())?;
        let tour = smug_core::Sequencer::solve_clusters(
            &solver,
            &instance.costs,
            &instance.clusters,
            kind,
        )?;
        (tour, None)
    } else {
        let params = GtspLnsParams {
            time_limit_s: args.time,
            max_iterations: args.iterations.unwrap_or(0),
            ..GtspLnsParams::default()
        };
        let solver = GtspLns::with_seed(params, args.seed)?;
        let (tour, iterations) =
            solver.solve_with_iterations(&instance.costs, &instance.clusters, kind)?;
        (tour, Some(iterations))
    };
    let time_s = started.elapsed().as_secs_f64();
    let report = GtspReport {
        name: instance.name,
        n: instance.costs.len(),
        clusters: instance.clusters.len(),
        solver: args.solver,
        kind: match kind {
            TourKind::Closed => "closed".into(),
            TourKind::OpenTo(end) => format!("open to cluster {end}"),
        },
        cost: tour.cost,
        iterations,
        tour: tour.order,
        time_s,
    };
    println!("{}", serde_json::to_string(&report)?);
    Ok(if report.cost.is_finite() {
        Outcome::Ok
    } else {
        Outcome::NoSolution
    })
}
