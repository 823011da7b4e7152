//! `smug bench robots`: every robot profile on each world, N seeds: cost, wall time
//! (assembly and planning) and its ratio to ANYmal's on the same world and seed, paths
//! planned, PoIs dropped (invalid, dead ends) and, for missions without a plan, why.

use crate::output::ReportArgs;

use serde::Serialize;
use smug_core::{LoadedConfig, Pipeline};
use smug_mission::plan_mission;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The robots measured by default: `name=profile[+KEY=VALUE…]`, profiles from
/// `configs/robots/`.
const ROBOTS: &str = "anymal=anymal,wheeled=wheeled,rover=rover,rover-prm=rover+planner.type=\"lazy-prm-star\"+selector.type=\"idp\"+plan.sequencing_costs=\"full\",dubins=rover+space.type=\"dubins\"+space.params.turning_radius=1.5";

/// Arguments of `smug bench robots`.
#[derive(clap::Args, Debug)]
pub struct BenchRobotsArgs {
    /// World configs (each with every robot).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "configs/lunar.toml,configs/indoor.toml,configs/imported-map.toml,configs/cluttered.toml"
    )]
    worlds: Vec<PathBuf>,
    /// Robots: `name=profile[+KEY=VALUE…]` (profile: a file of `configs/robots/`
    /// without `.toml`; the first robot is the reference of the time ratios).
    #[arg(long, value_delimiter = ',', default_value = ROBOTS)]
    robots: Vec<String>,
    /// Seeds per world and robot (1..=N).
    #[arg(long, default_value_t = 10)]
    runs: u64,
    /// A new world per seed (default: the world of seed 1 for every run; the planner's
    /// seed still changes). Worlds without a `seed` parameter are the same anyway.
    #[arg(long)]
    vary_world: bool,
    /// `--set`, `--out`, `--json`.
    #[command(flatten)]
    report: ReportArgs,
}

/// One run's measurements.
#[derive(Debug, Serialize)]
struct Run {
    world: String,
    robot: String,
    seed: u64,
    /// Plan cost, `None` without a plan.
    cost: Option<f64>,
    wall_s: f64,
    paths_planned: u64,
    invalid_pois: usize,
    dead_end_pois: usize,
    /// Why there is no plan (the error's first line).
    failure: Option<String>,
}

/// A robot: its name, profile and extra overrides.
struct Robot {
    name: String,
    profile: String,
    set: Vec<String>,
}

fn parse_robot(spec: &str) -> crate::Result<Robot> {
    let (name, rest) = spec.split_once('=').ok_or_else(|| {
        crate::BenchError::Invalid(format!(
            "--robots: `{spec}` is not `name=profile[+KEY=VALUE…]`"
        ))
    })?;
    let mut parts = rest.split('+');
    let profile = parts.next().unwrap_or_default().to_string();
    Ok(Robot {
        name: name.to_string(),
        profile,
        set: parts.map(String::from).collect(),
    })
}

/// Runs `smug bench robots`.
pub fn run(args: BenchRobotsArgs) -> crate::Result<()> {
    let robots: Vec<Robot> = args
        .robots
        .iter()
        .map(|s| parse_robot(s))
        .collect::<crate::Result<_>>()?;
    let mut runs = Vec::new();
    for world in &args.worlds {
        // By default the world of seed 1 for every run (the planner's seed changes); with
        // `--vary-world` the world of each seed (a robot that cannot start there is a
        // row of its own).
        let seeded = crate::objectives::world_is_seeded(world);
        for robot in &robots {
            for seed in 1..=args.runs {
                let mut set = args.report.set.clone();
                if seeded {
                    let world_seed = if args.vary_world { seed } else { 1 };
                    set.insert(0, format!("world.params.seed={world_seed}"));
                }
                let run = plan_once(world, robot, seed, &set)?;
                eprintln!(
                    "{} {} seed {seed}: {} in {:.2} s",
                    run.world,
                    run.robot,
                    run.cost
                        .map_or("no plan".into(), |c| format!("cost {c:.2}")),
                    run.wall_s
                );
                runs.push(run);
            }
        }
    }
    let report = report(&args, &robots, &runs);
    args.report.write(&report, &runs)?;
    Ok(())
}

/// The config text of `world` with `robot`'s profile included after it (the later
/// include wins, as in `configs/lunar-rover.toml`).
fn config_text(world: &Path, profile: &Path) -> String {
    format!(
        "include = [{:?}, {:?}]\n",
        world.display().to_string(),
        profile.display().to_string()
    )
}

fn plan_once(world: &Path, robot: &Robot, seed: u64, set: &[String]) -> crate::Result<Run> {
    let base = world.parent().unwrap_or(Path::new("."));
    let world_abs = std::fs::canonicalize(world)?;
    let profile =
        std::fs::canonicalize(base.join("robots").join(format!("{}.toml", robot.profile)))?;
    let mut overrides = vec![format!("seed={seed}")];
    overrides.extend(robot.set.iter().cloned());
    overrides.extend(set.iter().cloned());
    let text = config_text(&world_abs, &profile);
    let started = Instant::now();
    let loaded = LoadedConfig::from_text(&text, "bench-robots.toml", base, &overrides)?;
    let mut run = Run {
        world: world.display().to_string(),
        robot: robot.name.clone(),
        seed,
        cost: None,
        wall_s: 0.0,
        paths_planned: 0,
        invalid_pois: 0,
        dead_end_pois: 0,
        failure: None,
    };
    // A world the robot cannot start in (an invalid start pose) is a row, not an abort.
    let planned = Pipeline::assemble(&loaded).and_then(|mut pipeline| {
        run.invalid_pois = pipeline.dropped_pois.len();
        plan_mission(&mut pipeline, loaded.config.plan)
    });
    run.wall_s = started.elapsed().as_secs_f64();
    match planned {
        Ok(plan) => {
            run.cost = Some(plan.cost);
            run.paths_planned = plan.stats.paths_planned;
            run.dead_end_pois = plan.dead_ends.len();
        }
        Err(err) => run.failure = Some(err.to_string().lines().next().unwrap_or("").to_string()),
    }
    Ok(run)
}

fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

fn cell(value: Option<f64>, digits: usize) -> String {
    value.map_or("–".into(), |v| format!("{v:.digits$}"))
}

fn report(args: &BenchRobotsArgs, robots: &[Robot], runs: &[Run]) -> String {
    let mut out = String::from("# Robots: every profile on each world\n\n");
    let _ = writeln!(
        out,
        "{} seeds per world and robot, {}; cost: mean over the seeds that planned. Wall: config, assembly and \
         planning in one process, seconds; × ref: the mean over seeds of the \
         wall time divided by `{}`'s on the same world and seed. Dropped PoIs: invalid \
         for the robot / dead ends (proved). Robots: {}.\n",
        args.runs,
        if args.vary_world {
            "the world of each seed (procedural worlds)"
        } else {
            "the world of seed 1 each time (the planner's seed changes)"
        },
        robots.first().map_or("", |r| r.name.as_str()),
        args.robots.join(", ")
    );
    for world in &args.worlds {
        let world = world.display().to_string();
        let _ = writeln!(out, "## {world}\n");
        out.push_str(
            "| robot | planned | cost | wall s | × ref | paths | dropped PoIs | no plan: why |\n",
        );
        out.push_str("|---|---:|---:|---:|---:|---:|---:|---|\n");
        for robot in robots {
            let rows: Vec<&Run> = runs
                .iter()
                .filter(|r| r.world == world && r.robot == robot.name)
                .collect();
            let costs: Vec<f64> = rows.iter().filter_map(|r| r.cost).collect();
            let walls: Vec<f64> = rows.iter().map(|r| r.wall_s).collect();
            let ratios: Vec<f64> = rows
                .iter()
                .filter_map(|r| {
                    let reference = runs.iter().find(|q| {
                        q.world == world
                            && q.seed == r.seed
                            && robots.first().is_some_and(|f| f.name == q.robot)
                    })?;
                    Some(r.wall_s / reference.wall_s)
                })
                .collect();
            let paths: Vec<f64> = rows.iter().map(|r| r.paths_planned as f64).collect();
            let invalid: Vec<f64> = rows.iter().map(|r| r.invalid_pois as f64).collect();
            let dead: Vec<f64> = rows.iter().map(|r| r.dead_end_pois as f64).collect();
            let mut why: Vec<&str> = rows.iter().filter_map(|r| r.failure.as_deref()).collect();
            why.dedup();
            let _ = writeln!(
                out,
                "| {} | {}/{} | {} | {} | {} | {} | {} / {} | {} |",
                robot.name,
                costs.len(),
                rows.len(),
                cell(mean(&costs), 2),
                cell(mean(&walls), 3),
                cell(mean(&ratios), 1),
                cell(mean(&paths), 0),
                cell(mean(&invalid), 1),
                cell(mean(&dead), 1),
                why.join("; ")
            );
        }
        out.push('\n');
    }
    out
}
