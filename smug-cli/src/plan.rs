//! `smug plan`: the whole mission, from a config to plan.json, plan.csv and plan.svg.

use crate::Outcome;
use smug_core::mission::Unreachable;
use smug_core::{plan_mission, LoadedConfig, Pipeline, Plan, World};
use smug_worlds::render::{render_svg, RenderOptions};
use std::path::{Path, PathBuf};

/// Arguments of `smug plan`.
#[derive(clap::Args, Debug)]
pub struct PlanArgs {
    /// The pipeline config (TOML).
    config: PathBuf,
    /// Override a config key (see `smug check --help`).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Override the config's seed.
    #[arg(long)]
    seed: Option<u64>,
    /// Seconds after which searches stop with their best result and no new path is
    /// planned (sets `plan.deadline`): a complete plan found by then is written and
    /// marked `deadline_reached`, else smug exits 1 saying so.
    #[arg(long, value_name = "SECONDS")]
    deadline: Option<String>,
    /// Output directory for plan.json, plan.csv and plan.svg (default: the config's
    /// `output.dir`, else `out`).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print plan.json to stdout instead of a summary.
    #[arg(long)]
    json: bool,
    /// After the mission, save the planner's roadmap (vertices, edges, check status,
    /// costs, answered queries) to FILE, for `smug replan --roadmap FILE`.
    #[arg(long, value_name = "FILE")]
    save_roadmap: Option<PathBuf>,
}

/// Runs `smug plan`.
pub fn run(args: PlanArgs) -> anyhow::Result<Outcome> {
    let mut set = args.set.clone();
    if let Some(seed) = args.seed {
        set.push(format!("seed={seed}"));
    }
    if let Some(seconds) = &args.deadline {
        set.push(format!("plan.deadline={seconds}"));
    }
    let loaded = LoadedConfig::from_file(&args.config, &set)?;
    let out = args
        .out
        .clone()
        .or_else(|| loaded.config.output.dir.clone())
        .unwrap_or_else(|| PathBuf::from("out"));
    refuse_overwriting_inputs(&out, &loaded, &[])?;
    let progress = Progress::start("building the world and the checkers");
    let mut pipeline = Pipeline::assemble(&loaded)?;
    progress.stage("planning: sequencing the targets, selecting the poses of interest");
    let options = pipeline.config.plan;
    let planned = plan_mission(&mut pipeline, options);
    progress.finish();
    let plan = match planned {
        Ok(plan) => plan,
        Err(smug_core::Error::Stage { source, .. }) if source.is::<Unreachable>() => {
            eprintln!("smug: no solution: {source}");
            return Ok(Outcome::NoSolution);
        }
        Err(err @ smug_core::Error::DeadlinePassed { .. }) => {
            eprintln!("smug: no plan: {err}");
            return Ok(Outcome::NoSolution);
        }
        Err(err) => return Err(err.into()),
    };
    if plan.deadline_reached {
        eprintln!(
            "smug: the deadline cut a search short: the plan is complete and valid, the best \
             found by then (marked `deadline_reached` in plan.json)"
        );
    }
    let world = pipeline.world.clone().expect("plan_mission needs a world");
    write_outputs(&plan, &world, &pipeline, &out)?;
    if let Some(file) = &args.save_roadmap {
        save_roadmap(&pipeline, &loaded, &world, file)?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&plan)?);
    } else {
        print_summary(&plan, &pipeline, &out);
    }
    Ok(Outcome::Ok)
}

/// Writes the planner's roadmap after a mission to `file`, fingerprinted for
/// `loaded` on `world` (the world as built from the config).
fn save_roadmap(
    pipeline: &Pipeline,
    loaded: &LoadedConfig,
    world: &World,
    file: &Path,
) -> anyhow::Result<()> {
    let snapshot = pipeline
        .planner
        .as_ref()
        .and_then(|p| p.save_roadmap())
        .ok_or_else(|| {
            anyhow::anyhow!(
                "{}: cannot save a roadmap: the configured planner keeps none",
                file.display()
            )
        })?;
    smug_core::write_roadmap(file, &snapshot, &smug_core::Fingerprint::of(loaded, world))?;
    Ok(())
}

/// A spinner on stderr naming the running stage, shown only in a terminal.
pub(crate) struct Progress(Option<indicatif::ProgressBar>);

impl Progress {
    pub(crate) fn start(stage: &str) -> Self {
        use std::io::IsTerminal;
        if !std::io::stderr().is_terminal() {
            return Self(None);
        }
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(100));
        bar.set_message(stage.to_string());
        Self(Some(bar))
    }

    pub(crate) fn stage(&self, stage: &str) {
        if let Some(bar) = &self.0 {
            bar.set_message(stage.to_string());
        }
    }

    pub(crate) fn finish(&self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}

pub(crate) fn write_outputs(
    plan: &Plan,
    world: &World,
    pipeline: &Pipeline,
    dir: &Path,
) -> anyhow::Result<()> {
    let output = &pipeline.config.output;
    std::fs::create_dir_all(dir)
        .map_err(|e| anyhow::anyhow!("{}: cannot create: {e}", dir.display()))?;
    // Each file whole or not at all: a killed run leaves the previous plan intact.
    let write = |name: &str, text: String| {
        let path = dir.join(name);
        smug_core::output::write_atomic(&path, text.as_bytes())
            .map_err(|e| anyhow::anyhow!("{}: cannot write: {e}", path.display()))
    };
    if output.json {
        write("plan.json", serde_json::to_string_pretty(plan)?)?;
    }
    if output.csv {
        write("plan.csv", plan_csv(plan))?;
    }
    if output.svg {
        write("plan.svg", render_svg(world, &render_options(plan, world)))?;
    }
    Ok(())
}

/// The files `smug plan` writes into `dir`.
const OUTPUT_FILES: [&str; 3] = ["plan.json", "plan.csv", "plan.svg"];

/// Refuses an output directory where a plan file would overwrite one of the run's
/// inputs (its config files, maps, missions, layers, and `extra`, e.g. a mission state).
pub(crate) fn refuse_overwriting_inputs(
    dir: &Path,
    loaded: &LoadedConfig,
    extra: &[PathBuf],
) -> anyhow::Result<()> {
    let outputs: Vec<PathBuf> = OUTPUT_FILES.iter().map(|name| dir.join(name)).collect();
    let mut inputs = loaded.input_files();
    inputs.extend(extra.iter().cloned());
    match smug_core::output::output_over_input(&outputs, &inputs) {
        Some(path) => anyhow::bail!(
            "{}: is an input of this run; choose another --out (or [output] dir)",
            path.display()
        ),
        None => Ok(()),
    }
}

/// `plan.csv`: `x,y,z,yaw` per waypoint, and a `reversing` column (0/1) when the
/// plan ever drives backwards (as `plan.json`'s `reversing`).
fn plan_csv(plan: &Plan) -> String {
    let gears = plan.reversing.len() == plan.waypoints.len() && !plan.reversing.is_empty();
    let mut csv = String::from(if gears {
        "x,y,z,yaw,reversing\n"
    } else {
        "x,y,z,yaw\n"
    });
    for (i, w) in plan.waypoints.iter().enumerate() {
        csv += &format!("{},{},{},{}", w.x, w.y, w.z, w.yaw);
        if gears {
            csv += if plan.reversing[i] { ",1" } else { ",0" };
        }
        csv.push('\n');
    }
    csv
}

fn render_options(plan: &Plan, world: &World) -> RenderOptions {
    let highlighted = plan
        .pois
        .iter()
        .filter_map(|c| {
            world
                .mission
                .targets
                .iter()
                .position(|t| t.id == c.target)
                .map(|t| (t, c.index))
        })
        .collect();
    RenderOptions {
        title: Some(format!(
            "{}: cost {:.2}, {} targets",
            world.name,
            plan.cost,
            plan.sequence.len()
        )),
        paths: vec![plan.waypoints.iter().map(|w| [w.x, w.y]).collect()],
        highlighted_pois: highlighted,
        ..RenderOptions::default()
    }
}

pub(crate) fn print_summary(plan: &Plan, pipeline: &Pipeline, out: &Path) {
    let s = &plan.stats;
    let b = &s.breakdown;
    println!(
        "planned {} targets, cost {:.3}, {} waypoints; {} paths planned, {} validity queries",
        plan.sequence.len(),
        plan.cost,
        plan.waypoints.len(),
        s.paths_planned,
        s.validity_queries
    );
    let stage = |name: &str| s.stage_times_s.get(name).copied().unwrap_or(0.0);
    // The joint mode has one stage where the sequential mode has two.
    let mut stages = match s.stage_times_s.get("joint") {
        Some(joint) => format!("joint {joint:.3}"),
        None => format!(
            "sequencing {:.3}, selection {:.3}",
            stage("sequencing"),
            stage("selection")
        ),
    };
    if let Some(refine) = s.stage_times_s.get("refine") {
        stages.push_str(&format!(", refine {refine:.3}"));
    }
    println!(
        "time {:.3} s ({stages}); planner: A* {:.3}, sampling {:.3}, edge checking {:.3}, vertex checking {:.3}, misc {:.3}",
        stage("total"),
        b.astar_s,
        b.sampling_s,
        b.edge_checking_s,
        b.vertex_checking_s,
        b.misc_s
    );
    if !plan.skipped.is_empty() {
        println!("skipped unreachable targets: {}", plan.skipped.join(", "));
    }
    if !pipeline.dropped_pois.is_empty() {
        println!(
            "{} PoIs were not valid for the robot and were left out",
            pipeline.dropped_pois.len()
        );
    }
    println!("order: {}", plan.sequence.join(" → "));
    println!("wrote {}/plan.json, plan.csv, plan.svg", out.display());
}
