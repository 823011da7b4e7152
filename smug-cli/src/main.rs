//! `smug`: safe multi-goal planning from the command line.
//!
//! Exit codes: 0 solved / ok, 1 no solution, 2 bad input or error (one line on stderr).
//!
//! A thin layer over `smug-app` (which links every built-in plugin) and `smug-bench`:
//! argument parsing, printing and exit codes.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod bench;
mod check;
mod gtsp;
mod mtsp;
mod p2p;
mod plan;
mod plugins;
mod progress;
mod replan;
mod sweep;
mod team;
mod tsp;
mod worlds;
mod worlds_generate;

/// What a command reports besides errors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Solved / ok (exit 0).
    Ok,
    /// Ran fine but found no solution (exit 1).
    NoSolution,
}

/// Says on stderr why a plan has no solution; the outcome to exit with.
pub fn no_solution(why: smug_app::NoSolution) -> Outcome {
    match why {
        smug_app::NoSolution::DeadlinePassed(why) => eprintln!("smug: no plan: {why}"),
        why => eprintln!("smug: no solution: {why}"),
    }
    Outcome::NoSolution
}

/// Safe multi-goal planning for mobile robots.
#[derive(Parser, Debug)]
#[command(name = "smug", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// List every registered plugin by stage, with its parameters and defaults.
    Plugins(plugins::PluginsArgs),
    /// Load and validate a config, assemble its pipeline and print it resolved.
    Check(check::CheckArgs),
    /// Plan a safe multi-goal mission from a config.
    Plan(plan::PlanArgs),
    /// Replan the rest of a mission from a mission state (pose, visited targets, failed
    /// PoIs, new obstacles).
    Replan(replan::ReplanArgs),
    /// Plan point-to-point queries on one shared roadmap.
    P2p(p2p::P2pArgs),
    /// Solve a TSPLIB instance (a file, or a name in the suite of --data / $SMUG_DATA).
    Tsp(tsp::TspArgs),
    /// Solve a GTSP-LIB instance (generalized TSP: one node per cluster).
    Gtsp(gtsp::GtspArgs),
    /// Solve a single-depot multiple TSP on a TSPLIB file (depot = node 1), min-max or
    /// min-sum.
    Mtsp(mtsp::MtspArgs),
    /// Run benchmarks.
    Bench(bench::BenchArgs),
    /// Sweep configs × seeds × a grid of overrides in local processes, one JSON row per
    /// run (resumable).
    Sweep(sweep::SweepArgs),
    /// One run of a sweep, its row on stdout (what `smug sweep` runs in each process).
    #[command(hide = true)]
    SweepRun(sweep::SweepRunArgs),
    /// Look at, convert, generate and export worlds.
    Worlds(worlds::WorldsArgs),
}

fn run(cli: Cli) -> anyhow::Result<Outcome> {
    match cli.command {
        Command::Plugins(args) => plugins::run(args),
        Command::Check(args) => check::run_check(args),
        Command::Plan(args) => plan::run(args),
        Command::Replan(args) => replan::run(args),
        Command::P2p(args) => p2p::run(args),
        Command::Tsp(args) => tsp::run(args),
        Command::Gtsp(args) => gtsp::run(args),
        Command::Mtsp(args) => mtsp::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Sweep(args) => sweep::run(args),
        Command::SweepRun(args) => sweep::run_one_row(args),
        Command::Worlds(args) => worlds::run(args),
    }
}

/// Restores the default SIGPIPE action, so `smug … | head` ends quietly instead of
/// panicking on a closed pipe.
fn die_quietly_on_closed_pipes() {
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition to the default before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn main() -> ExitCode {
    die_quietly_on_closed_pipes();
    let cli = Cli::parse();
    match run(cli) {
        Ok(Outcome::Ok) => ExitCode::SUCCESS,
        Ok(Outcome::NoSolution) => ExitCode::from(1),
        Err(err) => {
            let message = smug_app::one_line(err.as_ref());
            eprintln!("smug: error: {message}");
            ExitCode::from(2)
        }
    }
}
