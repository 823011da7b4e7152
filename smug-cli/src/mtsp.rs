//! `smug mtsp`: a single-depot multiple TSP on a TSPLIB file (depot = node 1; every other
//! node a customer), for the sum of the salesmen's tour lengths or the longest one.
//!
//! Routes are printed as TSPLIB node numbers (1-based), the depot left out.

use crate::Outcome;
use serde::Serialize;
use smug_core::{RouteSize, TeamObjective, TeamSequencer, TeamSolution};
use smug_sequencing::read_tsplib;
use smug_sequencing::team::{
    mtsp_costs, mtsp_problem, MtspDistance, TeamAuto, TeamAutoParams, TeamLns, TeamLnsParams,
};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `smug mtsp`.
#[derive(clap::Args, Debug)]
pub struct MtspArgs {
    /// A TSPLIB file; node 1 is the depot.
    pub file: PathBuf,
    /// Number of salesmen (robots), all starting and ending at the depot.
    #[arg(long)]
    pub salesmen: usize,
    /// `minmax` (the longest tour, ties on the sum) or `minsum` (the sum of the tours).
    #[arg(long, value_parser = ["minmax", "minsum"])]
    pub objective: String,
    /// Time budget in seconds (0 = none; then give --iterations).
    #[arg(long, default_value_t = 1.0)]
    pub time: f64,
    /// Budget of search iterations; with `--time 0` the result depends only on the seed.
    #[arg(long)]
    pub iterations: Option<u64>,
    /// Seed of the search.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// `euclid`: unrounded Euclidean distances (the mTSP literature's); `tsplib`: the
    /// file's integer TSPLIB distances.
    #[arg(long, default_value = "euclid", value_parser = ["euclid", "tsplib"])]
    pub distance: String,
    /// Fewest customers per salesman.
    #[arg(long)]
    pub min_size: Option<usize>,
    /// Most customers per salesman.
    #[arg(long)]
    pub max_size: Option<usize>,
    /// Print one JSON object (with the routes) instead of text.
    #[arg(long)]
    pub json: bool,
    /// Override a `team-lns` parameter (`KEY=VALUE`, e.g. `sum_elite=8`; `--time` and
    /// `--iterations` set the budget).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
}

/// What `smug mtsp --json` prints.
#[derive(Serialize)]
struct MtspReport {
    name: String,
    customers: usize,
    salesmen: usize,
    objective: String,
    distance: String,
    total: f64,
    makespan: f64,
    route_sizes: Vec<usize>,
    route_costs: Vec<f64>,
    /// TSPLIB node numbers, depot (1) left out.
    routes: Vec<Vec<usize>>,
    time_s: f64,
}

/// Runs `smug mtsp`.
pub fn run(args: MtspArgs) -> anyhow::Result<Outcome> {
    anyhow::ensure!(
        args.time.is_finite() && args.time >= 0.0,
        "--time {}: must be a number of seconds ≥ 0",
        args.time
    );
    anyhow::ensure!(
        args.salesmen > 0,
        "--salesmen 0: needs at least one salesman"
    );
    let instance = read_tsplib(&args.file)?;
    let customers = instance.costs.len().saturating_sub(1);
    anyhow::ensure!(
        customers > 0,
        "{}: needs a depot and at least one customer",
        args.file.display()
    );
    let distance = match args.distance.as_str() {
        "tsplib" => MtspDistance::Tsplib,
        _ => MtspDistance::Euclid,
    };
    let objective = match args.objective.as_str() {
        "minsum" => TeamObjective::Sum,
        _ => TeamObjective::Makespan,
    };
    let route_size = route_size(&args, customers);
    let costs = mtsp_costs(&instance, distance)?;
    let problem = mtsp_problem(costs, args.salesmen, objective, route_size)?;
    let lns = TeamLnsParams {
        time_limit_s: args.time,
        max_iterations: args.iterations.unwrap_or(0),
        ..smug_bench::mtsp::lns_params(&args.set)?
    };
    let solver = TeamAuto::new(
        TeamAutoParams::default(),
        TeamLns::with_seed(lns, args.seed)?,
    )?;
    let started = Instant::now();
    let solution = solver.solve(&problem)?;
    let time_s = started.elapsed().as_secs_f64();
    let report = report(&args, instance.name, customers, &solution, time_s);
    if args.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        print_text(&report);
    }
    Ok(if solution.total.is_finite() {
        Outcome::Ok
    } else {
        Outcome::NoSolution
    })
}

fn route_size(args: &MtspArgs, customers: usize) -> Option<RouteSize> {
    (args.min_size.is_some() || args.max_size.is_some()).then(|| RouteSize {
        min: args.min_size.unwrap_or(0),
        max: args.max_size.unwrap_or(customers),
    })
}

fn report(
    args: &MtspArgs,
    name: String,
    customers: usize,
    solution: &TeamSolution,
    time_s: f64,
) -> MtspReport {
    MtspReport {
        name,
        customers,
        salesmen: args.salesmen,
        objective: args.objective.clone(),
        distance: args.distance.clone(),
        total: solution.total,
        makespan: solution.makespan,
        route_sizes: solution.routes.iter().map(Vec::len).collect(),
        route_costs: solution.costs.clone(),
        routes: solution
            .routes
            .iter()
            .map(|route| route.iter().map(|v| v.node + 1).collect())
            .collect(),
        time_s,
    }
}

fn print_text(report: &MtspReport) {
    println!(
        "{} ({} customers, {} salesmen, {}, {} distances): makespan {:.4}, total {:.4} in {:.2} s",
        report.name,
        report.customers,
        report.salesmen,
        report.objective,
        report.distance,
        report.makespan,
        report.total,
        report.time_s
    );
    for (r, (size, cost)) in report
        .route_sizes
        .iter()
        .zip(&report.route_costs)
        .enumerate()
    {
        println!("  salesman {}: {size} customers, cost {cost:.4}", r + 1);
    }
}
