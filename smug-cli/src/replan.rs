//! `smug replan`: the rest of a mission from a mission state, to plan.json, plan.csv
//! and plan.svg like `smug plan`, the plan marked as a replan.

use crate::plan::print_summary;
use crate::progress::Progress;
use crate::Outcome;
use smug_app::outputs::{refuse_overwriting_inputs, write_no_plan, write_outputs};
use smug_app::plan_mcap::WriteMode;
use smug_app::replan::{replan_from, stages, ReplanRequest};
use smug_app::{NoPlan, NoSolution, Planned};
use smug_core::mission::MissionState;
use std::path::PathBuf;

/// Arguments of `smug replan`.
#[derive(clap::Args, Debug)]
pub struct ReplanArgs {
    /// The pipeline config (TOML) the mission was planned with.
    config: PathBuf,
    /// The mission state (TOML): `pose`, `visited`, `failed_pois`, `[[obstacles]]`; for a
    /// team config, `[[robots]]` with each robot's `name` and `pose` (or `lost = true`).
    #[arg(long, value_name = "STATE.toml")]
    state: PathBuf,
    /// Override a config key (see `smug check --help`).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Override the config's seed.
    #[arg(long)]
    seed: Option<u64>,
    /// Output directory for plan.json, plan.csv, plan.svg and plan.mcap (default: the config's
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
    let loaded = smug_app::load_config(&args.config, &args.set, args.seed)?;
    let out = args
        .out
        .clone()
        .or_else(|| loaded.config.output.dir.clone())
        .unwrap_or_else(|| PathBuf::from("out"));
    refuse_overwriting_inputs(&out, &loaded, std::slice::from_ref(&args.state))?;
    if smug_app::team::is_team(&loaded) {
        let roadmap = args.roadmap.as_ref();
        return crate::team::replan(&loaded, &args.state, &out, args.json, roadmap);
    }
    let state = MissionState::from_file(&args.state)?;
    let progress = Progress::start(stages::ASSEMBLING);
    let request = ReplanRequest {
        state: &args.state,
        roadmap: args.roadmap.as_deref(),
    };
    let planned = replan_from(&loaded, &state, &request, &mut |stage| {
        progress.stage(stage)
    });
    progress.finish();
    let Planned { plan, pipeline, .. } = match planned? {
        smug_app::Outcome::Solved(planned) => planned,
        // A passed deadline is an error here (exit 2), as it always was for replans.
        smug_app::Outcome::NoSolution {
            why:
                NoPlan {
                    why: NoSolution::DeadlinePassed(why),
                    ..
                },
        } => anyhow::bail!("{why}"),
        smug_app::Outcome::NoSolution { why } => {
            write_no_plan(&why.report, &loaded.config.output, &out, WriteMode::Append)?;
            eprintln!("smug: no solution: {}", why.why);
            return Ok(Outcome::NoSolution);
        }
    };
    write_outputs(&plan, &pipeline, &out, WriteMode::Append)?;
    if args.json {
        println!("{}", smug_app::outputs::plan_json(&plan)?);
    } else {
        print_summary(&plan, &pipeline, &out);
    }
    Ok(Outcome::Ok)
}
