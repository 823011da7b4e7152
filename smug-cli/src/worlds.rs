//! `smug worlds`: look at, convert and export worlds (filled in with the worlds issue).

use crate::Outcome;
use clap::Subcommand;

/// Arguments of `smug worlds`.
#[derive(clap::Args, Debug)]
pub struct WorldsArgs {
    #[command(subcommand)]
    command: WorldsCommand,
}

#[derive(Subcommand, Debug)]
enum WorldsCommand {}

/// Runs `smug worlds`.
pub fn run(args: WorldsArgs) -> anyhow::Result<Outcome> {
    match args.command {}
}
