//! `smug replan`: the rest of a mission from a mission state, to plan.json, plan.csv
//! and plan.svg like `smug plan`, the plan marked as a replan.

use crate::plan::{print_summary, refuse_overwriting_inputs, write_outputs, Progress};
use crate::Outcome;
use smug_core::mission::{
    assemble_replan_fingerprinted, changed_discs, replan_mission, MissionState, NoTargetLeft,
    Unreachable,
};
use smug_core::LoadedConfig;
use std::path::PathBuf;

/// Arguments of `smug replan`.
#[derive(clap::Args, Debug)]
pub struct ReplanArgs {
    /// The pipeline config (TOML) the mission was planned with.
    config: PathBuf,
    /// The mission state (TOML): `pose`, `visited`, `failed_pois`, `[[obstacles]]`.
    #[arg(long, value_name = "STATE.toml")]
    state: PathBuf,
    /// Override a config key (see `smug check --help`).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Override the config's seed.
    #[arg(long)]
    seed: Option<u64>,
    /// Output directory for plan.json, plan.csv and plan.svg (default: the config's
    /// `output.dir`, else `out`).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print plan.json to stdout instead of a summary.
    #[arg(long)]
    json: bool,
    /// Start from the roadmap `smug plan --save-roadmap FILE` saved (refused, exit 2,
    /// when built for another world, robot or config, of another version, or damaged).
    #[arg(long, value_name = "FILE")]
    roadmap: Option<PathBuf>,
}

/// Runs `smug replan`.
pub fn run(args: ReplanArgs) -> anyhow::Result<Outcome> {
    let mut set = args.set.clone();
    if let Some(seed) = args.seed {
        set.push(format!("seed={seed}"));
    }
    let loaded = LoadedConfig::from_file(&args.config, &set)?;
    let state = MissionState::from_file(&args.state)?;
    let out = args
        .out
        .clone()
        .or_else(|| loaded.config.output.dir.clone())
        .unwrap_or_else(|| PathBuf::from("out"));
    refuse_overwriting_inputs(&out, &loaded, std::slice::from_ref(&args.state))?;
    let progress = Progress::start("building the updated world and the checkers");
    let state_name = args.state.display().to_string();
    let (mut pipeline, fingerprint) = assemble_replan_fingerprinted(&loaded, &state, &state_name)?;
    if let Some(file) = &args.roadmap {
        progress.stage("loading the roadmap");
        let snapshot = smug_core::read_roadmap(file, &fingerprint)?;
        let changed = changed_discs(&state, &loaded.config.robot);
        let planner = pipeline
            .planner
            .as_mut()
            .ok_or_else(|| anyhow::anyhow!("{}: the config has no planner", file.display()))?;
        planner
            .load_roadmap(snapshot, &changed)
            .map_err(|e| anyhow::anyhow!("{}: {e}", file.display()))?;
    }
    progress.stage("replanning the remaining targets");
    let options = pipeline.config.plan;
    let planned = replan_mission(&mut pipeline, options, &state);
    progress.finish();
    let mut plan = match planned {
        Ok(plan) => plan,
        Err(smug_core::Error::Stage { source, .. })
            if source.is::<Unreachable>() || source.is::<NoTargetLeft>() =>
        {
            eprintln!("smug: no solution: {source}");
            return Ok(Outcome::NoSolution);
        }
        Err(err) => return Err(err.into()),
    };
    if let Some(info) = plan.replan.as_mut() {
        info.state_file = Some(state_name);
    }
    let world = pipeline
        .world
        .clone()
        .expect("replan_mission needs a world");
    write_outputs(&plan, &world, &pipeline, &out)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&plan)?);
    } else {
        print_summary(&plan, &pipeline, &out);
    }
    Ok(Outcome::Ok)
}
