//! `smug check`: load, validate and assemble a config, print it resolved.

use crate::Outcome;
use smug_core::{LoadedConfig, Pipeline};
use std::path::PathBuf;

/// Arguments of `smug check`.
#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// The pipeline config (TOML).
    config: PathBuf,
    /// Override a config key, e.g. `--set planner.params.max_stall=5` or
    /// `--set 'selector.type="dp"'` (a bare word is taken as a string).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
}

/// Runs `smug check`: load, validate, assemble, print the resolved pipeline.
pub fn run_check(args: CheckArgs) -> anyhow::Result<Outcome> {
    let loaded = LoadedConfig::from_file(&args.config, &args.set)?;
    if smug_app::team::is_team(&loaded) {
        return crate::team::check(&args.config, &loaded);
    }
    let pipeline = Pipeline::assemble(&loaded)?;
    println!("# {}: configuration is valid", args.config.display());
    if let (Some(world), Some(m)) = (&pipeline.world, &pipeline.given_mission) {
        let g = world.elevation.geometry;
        println!(
            "# world `{}`: {}×{} cells at {} m, {} targets, {} poses of interest",
            world.name,
            g.size[0],
            g.size[1],
            g.resolution,
            m.targets.len(),
            m.poi_count()
        );
    }
    if !pipeline.dropped_pois.is_empty() {
        println!(
            "# {} PoIs are not valid for the robot and were left out: {}",
            pipeline.dropped_pois.len(),
            pipeline
                .dropped_pois
                .iter()
                .map(|d| format!("{}[{}]", d.target, d.index))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let missing: Vec<&str> = [
        ("world", pipeline.world.is_some()),
        ("validity", pipeline.state_validity.is_some()),
        ("motion", pipeline.motion_validator.is_some()),
        ("planner", pipeline.planner.is_some()),
        ("sequencer", pipeline.sequencer.is_some()),
        ("selector", pipeline.selector.is_some()),
    ]
    .into_iter()
    .filter_map(|(name, present)| (!present).then_some(name))
    .collect();
    if !missing.is_empty() {
        println!(
            "# not configured (needed by `smug plan`): {}",
            missing.join(", ")
        );
    }
    println!();
    print!("{}", pipeline.resolved_toml());
    Ok(Outcome::Ok)
}
