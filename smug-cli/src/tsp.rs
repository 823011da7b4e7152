//! `smug tsp` and `smug bench tsp` (filled in with the sequencing issue).

use crate::Outcome;

/// Arguments of `smug tsp`.
#[derive(clap::Args, Debug)]
pub struct TspArgs {
    /// A TSPLIB file (.tsp or .atsp).
    pub file: std::path::PathBuf,
}

/// Arguments of `smug bench tsp`.
#[derive(clap::Args, Debug)]
pub struct BenchTspArgs {}

/// Runs `smug tsp`.
pub fn run(args: TspArgs) -> anyhow::Result<Outcome> {
    anyhow::bail!(
        "{}: `smug tsp` is not available in this version yet",
        args.file.display()
    )
}

/// Runs `smug bench tsp`.
pub fn run_bench(_args: BenchTspArgs) -> anyhow::Result<Outcome> {
    anyhow::bail!("`smug bench tsp` is not available in this version yet")
}
