//! `smug bench`: benchmarks, each a subcommand with Markdown/JSON reports.

use crate::Outcome;
use clap::Subcommand;

/// Arguments of `smug bench`.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    #[command(subcommand)]
    which: BenchCommand,
}

#[derive(Subcommand, Debug)]
enum BenchCommand {
    /// The paper's experiments (Tables I–IV) with the paper's numbers beside ours.
    Paper(crate::bench_paper::BenchPaperArgs),
    /// TSP solvers on the TSPLIB suite (--data DIR or $SMUG_DATA/tsplib): gap to the
    /// optimum and time.
    Tsp(crate::bench_tsp::BenchTspArgs),
    /// GTSP solver on the GTSP-LIB suite (--data DIR or $SMUG_DATA/gtsp): gap to the
    /// best-known values and time.
    Gtsp(crate::bench_gtsp::BenchGtspArgs),
    /// LazyPRM* on MovingAI maps: scenarios solved, length against the optimum, time.
    P2p(crate::bench_p2p::BenchP2pArgs),
    /// State validity checkers: checks per second and distance-field queries.
    Validity(crate::bench_validity::BenchValidityArgs),
    /// The missions under each objective: length, risk, energy, time, planning time.
    Objectives(crate::bench_objectives::BenchObjectivesArgs),
    /// Replanning after a failed pose, a new obstacle and halfway through: replan time
    /// and cost on lunar 13×10 and 48×6.
    Replan(crate::bench_replan::BenchReplanArgs),
    /// Sequential (full and lazy cost matrix) against joint planning (GTSP over every
    /// PoI): cost, paths planned, planning time and joint minus sequential per seed.
    Modes(crate::bench_modes::BenchModesArgs),
}

/// Runs `smug bench`.
pub fn run(args: BenchArgs) -> anyhow::Result<Outcome> {
    match args.which {
        BenchCommand::Paper(args) => crate::bench_paper::run(args),
        BenchCommand::Tsp(args) => crate::bench_tsp::run_bench(args),
        BenchCommand::Gtsp(args) => crate::bench_gtsp::run(args),
        BenchCommand::Validity(args) => crate::bench_validity::run(args),
        BenchCommand::P2p(args) => crate::bench_p2p::run(args),
        BenchCommand::Objectives(args) => crate::bench_objectives::run(args),
        BenchCommand::Replan(args) => crate::bench_replan::run(args),
        BenchCommand::Modes(args) => crate::bench_modes::run(args),
    }
}
