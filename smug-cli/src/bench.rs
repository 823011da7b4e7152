//! `smug bench`: benchmarks, each a subcommand with Markdown/JSON reports; the
//! harnesses live in `smug-bench`, this file only dispatches to them.

use crate::Outcome;
use clap::Subcommand;
use smug_bench::{
    gtsp, lattice, modes, mtsp, objectives, p2p, paper, replan, robots, team, tsp, validity,
};

/// Arguments of `smug bench`.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    #[command(subcommand)]
    which: BenchCommand,
}

#[derive(Subcommand, Debug)]
enum BenchCommand {
    /// The paper's experiments (Tables I–IV) with the paper's numbers beside ours.
    Paper(paper::BenchPaperArgs),
    /// TSP solvers on the TSPLIB suite (--data DIR or $SMUG_DATA/tsplib): gap to the
    /// optimum and time.
    Tsp(tsp::BenchTspArgs),
    /// GTSP solver on the GTSP-LIB suite (--data DIR or $SMUG_DATA/gtsp): gap to the
    /// best-known values and time.
    Gtsp(gtsp::BenchGtspArgs),
    /// team-lns on single-depot mTSP suites (--data DIR: instances/, best_known.csv):
    /// gaps to the best-known (mostly LKH-3) values per budget and seed.
    Mtsp(mtsp::BenchMtspArgs),
    /// LazyPRM* on MovingAI maps: scenarios solved, length against the optimum, time.
    P2p(p2p::BenchP2pArgs),
    /// State validity checkers: checks per second and distance-field queries.
    Validity(validity::BenchValidityArgs),
    /// The missions under each objective: length, risk, energy, time, planning time.
    Objectives(objectives::BenchObjectivesArgs),
    /// Replanning after a failed pose, a new obstacle and halfway through: replan time
    /// and cost on lunar 13×10 and 48×6.
    Replan(replan::BenchReplanArgs),
    /// Sequential (full and lazy cost matrix) against joint planning (GTSP over every
    /// PoI): cost, paths planned, planning time and joint minus sequential per seed.
    Modes(modes::BenchModesArgs),
    /// Every robot profile (and the car models with the lattice planner) on each world:
    /// cost, wall time and its ratio to ANYmal's, paths planned, PoIs dropped and why.
    Robots(robots::BenchRobotsArgs),
    /// The lattice planner against LazyPRM* with ten times its budget, query by query,
    /// on generated maps for every car model: costlier how often, by how much, time.
    Lattice(lattice::BenchLatticeArgs),
    /// Team missions (lunar-team, indoor-team) for the sum and the makespan: per-robot
    /// loads, costs and times, and the two objectives checked against each other.
    Team(team::BenchTeamArgs),
}

/// Runs `smug bench`.
pub fn run(args: BenchArgs) -> anyhow::Result<Outcome> {
    match args.which {
        BenchCommand::Paper(args) => paper::run(args),
        BenchCommand::Tsp(args) => tsp::run_bench(args),
        BenchCommand::Gtsp(args) => gtsp::run(args),
        BenchCommand::Mtsp(args) => mtsp::run_bench(args),
        BenchCommand::Validity(args) => validity::run(args),
        BenchCommand::P2p(args) => p2p::run(args),
        BenchCommand::Objectives(args) => objectives::run(args),
        BenchCommand::Replan(args) => replan::run(args),
        BenchCommand::Modes(args) => modes::run(args),
        BenchCommand::Robots(args) => robots::run(args),
        BenchCommand::Lattice(args) => lattice::run(&args),
        BenchCommand::Team(args) => team::run(args),
    }?;
    Ok(Outcome::Ok)
}
