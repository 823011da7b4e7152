//! `smug plugins`: every registered plugin by stage.

use crate::Outcome;
use smug_core::registry::catalogue;

/// Arguments of `smug plugins`.
#[derive(clap::Args, Debug)]
pub struct PluginsArgs {
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Runs `smug plugins`.
pub fn run(args: PluginsArgs) -> anyhow::Result<Outcome> {
    let stages = catalogue()?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&stages)?);
        return Ok(Outcome::Ok);
    }
    for stage in &stages {
        println!("[{}] {}", stage.stage, stage.summary);
        if stage.plugins.is_empty() {
            println!("  (no plugins registered yet)");
        }
        for plugin in &stage.plugins {
            println!("  {:<20} {}", plugin.name, plugin.summary);
            for (key, value) in &plugin.params {
                println!("      {key} = {value}");
            }
        }
        println!();
    }
    Ok(Outcome::Ok)
}
