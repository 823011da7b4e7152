//! `smug bench objectives`: the lunar and indoor missions planned under each objective,
//! N seeds each; every plan measured under every objective (length, risk, energy,
//! time) so the trade-offs show side by side.

use crate::output::ReportArgs;

use serde::Serialize;
use smug_core::registry::{ObjectiveStage, Stage};
use smug_core::{LoadedConfig, Pipeline};
use smug_mission::plan_mission;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `smug bench objectives`.
#[derive(clap::Args, Debug)]
pub struct BenchObjectivesArgs {
    /// Mission configs to plan (each under every objective).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "configs/lunar.toml,configs/indoor.toml"
    )]
    configs: Vec<PathBuf>,
    /// Seeds per config and objective (1..=N).
    #[arg(long, default_value_t = 10)]
    runs: u64,
    /// Objectives to plan with (default: every registered one).
    #[arg(long, value_delimiter = ',')]
    objectives: Vec<String>,
    /// A new world per seed (default: the world of seed 1 for every run; the planner's
    /// seed still changes). Worlds without a `seed` parameter are the same anyway.
    #[arg(long)]
    vary_world: bool,
    /// `--set`, `--out`, `--json`.
    #[command(flatten)]
    report: ReportArgs,
}

/// One plan's measurements.
#[derive(Debug, Serialize)]
struct Run {
    config: String,
    objective: String,
    seed: u64,
    length_m: f64,
    climb_m: f64,
    traversability_mean: Option<f64>,
    traversability_min: Option<f64>,
    risky_length_m: Option<f64>,
    energy_j: Option<f64>,
    time_s: Option<f64>,
    planning_s: f64,
}

/// Runs `smug bench objectives`.
pub fn run(args: BenchObjectivesArgs) -> crate::Result<()> {
    let objectives = if args.objectives.is_empty() {
        ObjectiveStage::registry()?
            .names()
            .into_iter()
            .map(String::from)
            .collect()
    } else {
        args.objectives.clone()
    };
    let mut runs = Vec::new();
    for config in &args.configs {
        let fixed_world = !args.vary_world && world_is_seeded(config);
        for objective in &objectives {
            for seed in 1..=args.runs {
                let mut set = args.report.set.clone();
                if fixed_world {
                    set.push("world.params.seed=1".to_string());
                }
                runs.push(plan_once(config, objective, seed, &set)?);
            }
        }
    }
    let report = report(&args, &objectives, &runs);
    args.report.write(&report, &runs)?;
    Ok(())
}

/// Whether the config's world takes a `seed` parameter (procedural worlds): the config
/// assembles with it set.
pub(crate) fn world_is_seeded(config: &std::path::Path) -> bool {
    LoadedConfig::from_file(config, &["world.params.seed=1".to_string()])
        .is_ok_and(|loaded| Pipeline::assemble(&loaded).is_ok())
}

fn plan_once(
    config: &std::path::Path,
    objective: &str,
    seed: u64,
    set: &[String],
) -> crate::Result<Run> {
    let mut overrides = vec![
        format!("objective.type=\"{objective}\""),
        format!("seed={seed}"),
    ];
    overrides.extend(set.iter().cloned());
    let loaded = LoadedConfig::from_file(config, &overrides)?;
    let mut pipeline = Pipeline::assemble(&loaded)?;
    let started = Instant::now();
    let plan = plan_mission(&mut pipeline, loaded.config.plan)?;
    let planning_s = started.elapsed().as_secs_f64();
    let m = &plan.metrics;
    Ok(Run {
        config: config.display().to_string(),
        objective: objective.to_string(),
        seed,
        length_m: m.length_m,
        climb_m: m.climb_m,
        traversability_mean: m.traversability_mean,
        traversability_min: m.traversability_min,
        risky_length_m: m.risky_length_m,
        energy_j: m.costs.get("energy").copied(),
        time_s: m.costs.get("time").copied(),
        planning_s,
    })
}

fn mean(values: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    let values: Vec<f64> = values.collect::<Option<_>>()?;
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

fn cell(value: Option<f64>, digits: usize) -> String {
    value.map_or("–".into(), |v| format!("{v:.digits$}"))
}

fn report(args: &BenchObjectivesArgs, objectives: &[String], runs: &[Run]) -> String {
    let mut out = String::from("# Objectives: one mission, every cost\n\n");
    let _ = writeln!(
        out,
        "Each mission planned under each objective ({} seeds, means); every plan measured \
         under every objective. Risk: traversability τ along the path (mean, minimum, metres \
         below τ = 0.5). Planning: sequencing, selection and post-processing, seconds.\n",
        args.runs
    );
    for config in &args.configs {
        let config = config.display().to_string();
        let _ = writeln!(out, "## {config}\n");
        out.push_str("| objective | length m | climb m | mean τ | min τ | m below τ 0.5 | energy kJ | time s | planning s |\n");
        out.push_str("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
        for objective in objectives {
            let rows: Vec<&Run> = runs
                .iter()
                .filter(|r| r.config == config && &r.objective == objective)
                .collect();
            let avg = |f: &dyn Fn(&Run) -> Option<f64>| mean(rows.iter().map(|r| f(r)));
            let _ = writeln!(
                out,
                "| {objective} | {} | {} | {} | {} | {} | {} | {} | {} |",
                cell(avg(&|r| Some(r.length_m)), 2),
                cell(avg(&|r| Some(r.climb_m)), 2),
                cell(avg(&|r| r.traversability_mean), 3),
                cell(avg(&|r| r.traversability_min), 3),
                cell(avg(&|r| r.risky_length_m), 2),
                cell(avg(&|r| r.energy_j.map(|e| e / 1000.0)), 2),
                cell(avg(&|r| r.time_s), 1),
                cell(avg(&|r| Some(r.planning_s)), 3),
            );
        }
        out.push('\n');
    }
    out
}
