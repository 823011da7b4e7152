//! `smug bench paper`: the paper's experiments (Tables I–IV) on the procedural worlds,
//! N seeds each, with the paper's numbers beside ours (report in `report`).

mod report;
pub mod runs;

use crate::output::write_report;
pub use runs::{Experiment, PaperBench, Run, SCALABILITY, SELECTORS, VALIDITY};

use smug_core::{LoadedConfig, Pipeline, Plan};
use smug_mission::plan_mission;
use std::path::{Path, PathBuf};

/// Arguments of `smug bench paper`.
#[derive(clap::Args, Debug)]
pub struct BenchPaperArgs {
    /// Runs (seeds 1..=N) per experiment.
    #[arg(long, default_value_t = 10)]
    runs: u64,
    /// A smoke version in about a minute: 2 runs, scalability up to 12 ToIs only.
    #[arg(long)]
    quick: bool,
    /// Only these tables (comma-separated: 1, 2, 3, 4; 3 comes with 2).
    #[arg(long, value_delimiter = ',')]
    tables: Vec<u8>,
    /// A new world per seed (default: the world of seed 1 for every run, as the
    /// paper's 10 runs on one world; the planner's seed still changes).
    #[arg(long)]
    vary_world: bool,
    /// The folder with lunar.toml, indoor.toml and lunar-full-collision.toml.
    #[arg(long, default_value = "configs")]
    configs: PathBuf,
    /// Write the Markdown report here (else stdout only).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write every raw run as JSON here (default: beside `--out`, as `.json`).
    #[arg(long)]
    json: Option<PathBuf>,
}

fn experiment(key: String, config: &str, set: &[&str]) -> Experiment {
    Experiment {
        key,
        config: config.to_string(),
        set: set
            .iter()
            .filter(|s| !s.is_empty())
            .map(|s| s.to_string())
            .collect(),
    }
}

/// The experiments of the chosen tables, in report order.
fn experiments(tables: &[u8], quick: bool) -> Vec<Experiment> {
    let wants = |t: u8| tables.is_empty() || tables.contains(&t);
    let mut list = Vec::new();
    if wants(1) {
        for (world, config) in [("lunar", "lunar.toml"), ("indoor", "indoor.toml")] {
            for selector in SELECTORS {
                let set = format!("selector.type={selector}");
                list.push(experiment(format!("{world}/{selector}"), config, &[&set]));
            }
        }
    }
    if wants(2) || wants(3) {
        for (key, _, config, set) in VALIDITY {
            list.push(experiment(key.to_string(), config, &[set]));
        }
    }
    if wants(4) {
        let sizes = if quick {
            &SCALABILITY[..2]
        } else {
            &SCALABILITY[..]
        };
        for &targets in sizes {
            for selector in SELECTORS {
                let set = [
                    format!("selector.type={selector}"),
                    format!("world.params.targets={targets}"),
                    "world.params.pois_per_target=6".to_string(),
                ];
                let set: Vec<&str> = set.iter().map(String::as_str).collect();
                list.push(experiment(
                    format!("scalability/{targets}/{selector}"),
                    "lunar.toml",
                    &set,
                ));
            }
        }
    }
    list
}

/// Plans one experiment with one seed; a planning failure is recorded, not raised.
fn run_once(exp: &Experiment, seed: u64, configs: &Path, vary_world: bool) -> crate::Result<Run> {
    let mut set = exp.set.clone();
    set.push(format!("seed={seed}"));
    if !vary_world {
        set.push("world.params.seed=1".to_string());
    }
    let loaded = LoadedConfig::from_file(&configs.join(&exp.config), &set)?;
    let mut pipeline = Pipeline::assemble(&loaded)?;
    let options = pipeline.config.plan;
    Ok(match plan_mission(&mut pipeline, options) {
        Ok(plan) => run_from_plan(exp, seed, &plan),
        Err(err) => Run {
            error: Some(err.to_string()),
            ..run_from_plan(exp, seed, &Plan::default())
        },
    })
}

fn run_from_plan(exp: &Experiment, seed: u64, plan: &Plan) -> Run {
    let s = &plan.stats;
    let time = |key: &str| s.stage_times_s.get(key).copied().unwrap_or(0.0);
    Run {
        experiment: exp.key.clone(),
        seed,
        error: None,
        cost: plan.cost,
        planning_s: time("sequencing") + time("selection") + time("post-processing"),
        total_s: time("total"),
        paths_planned: s.paths_planned,
        validity_queries: s.validity_queries,
        breakdown: s.breakdown,
        stage_times_s: s.stage_times_s.clone(),
        counters: s.counters.clone(),
    }
}

/// A progress bar over all runs on stderr (hidden when stderr is not a terminal).
fn progress_bar(total: u64) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(total);
    let style = indicatif::ProgressStyle::with_template(
        "{elapsed_precise} [{bar:30}] {pos}/{len} runs, eta {eta}: {msg}",
    )
    .map(|s| s.progress_chars("=> "));
    if let Ok(style) = style {
        bar.set_style(style);
    }
    bar
}

/// Runs every experiment `runs` times (seeds 1..=runs).
pub fn run_experiments(
    list: Vec<Experiment>,
    runs: u64,
    configs: &Path,
    vary_world: bool,
    quick: bool,
) -> crate::Result<PaperBench> {
    let bar = progress_bar(list.len() as u64 * runs);
    let mut raw = Vec::new();
    // Seed by seed through every experiment (not experiment by experiment), so that a
    // drift in the machine's load or clock hits all experiments alike.
    for seed in 1..=runs {
        for exp in &list {
            bar.set_message(format!("{} seed {seed}", exp.key));
            raw.push(run_once(exp, seed, configs, vary_world)?);
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    Ok(PaperBench {
        runs,
        vary_world,
        quick,
        experiments: list,
        raw,
    })
}

/// Runs `smug bench paper`.
pub fn run(args: BenchPaperArgs) -> crate::Result<()> {
    let runs = if args.quick { 2 } else { args.runs.max(1) };
    let list = experiments(&args.tables, args.quick);
    let bench = run_experiments(list, runs, &args.configs, args.vary_world, args.quick)?;
    let checks = report::checks(&bench);
    let report = report::markdown(&bench, &checks);
    let raw = serde_json::json!({ "bench": bench, "checks": checks });
    write_report(&report, &raw, args.out.as_deref(), args.json.as_deref())?;
    Ok(())
}
