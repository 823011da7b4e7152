//! `smug bench modes`: the sequential mode with the full and with the lazy cost matrix
//! against the joint mode (a GTSP over every PoI, the `auto` sequencer), on several missions and
//! N seeds (issue 17's comparison): cost, paths planned, planning time, failures, and
//! joint minus sequential per seed.

mod cpu;
pub mod polygons;
mod report;
pub mod runs;
mod threads;

use crate::error::ResultExt as _;
use crate::output::ReportArgs;
use report::{report, Summary};
pub use runs::{Mission, Mode, Polygons, Run, MISSIONS, MODES, POLYGON_SET};
use serde::Serialize;
use smug_core::{LoadedConfig, Pipeline, Plan, Scenario};
use smug_mission::plan_mission;
use std::path::PathBuf;

/// Arguments of `smug bench modes`.
#[derive(clap::Args, Debug)]
pub struct BenchModesArgs {
    /// Missions by name: lunar (13×10), indoor (12×2), lunar-48x6, lunar-200x10 (200
    /// targets × 10 PoIs on 100×100 m: slow in the joint mode, opt-in), the other
    /// shipped configs (flat-demo, flat-dubins, imported-map, indoor-disc,
    /// lunar-wheeled, lunar-rover); poly-20, poly-40, poly-60 (generated polygon maps of
    /// 2000 × 2000 cells, a disc robot of one cell across, one PoI per target); data,
    /// data-open (the `--data` map).
    #[arg(long, value_delimiter = ',', default_value = "lunar,indoor,lunar-48x6")]
    missions: Vec<String>,
    /// Seeds per mission and mode (1..=N); the seed sets the world and the planner.
    #[arg(long, default_value_t = 10)]
    runs: u64,
    /// Modes by name: full (sequential, full matrix), lazy (sequential, lazy matrix),
    /// lazy-unsettled (lazy without planning early legs again for the order),
    /// joint (GTSP over every PoI, the `auto` sequencer: exact while small, LNS above).
    #[arg(long, value_delimiter = ',', default_value = "full,lazy,joint")]
    modes: Vec<String>,
    /// A polygon map in the CRL `MAP_POINTS_CITY_POINTS` text format for the `data`
    /// and `data-open` missions (rasterised to 2000 × 2000 square cells over its border).
    #[arg(long)]
    data: Option<PathBuf>,
    /// Thread counts (e.g. `1,2`): every run again on a pool of each, the report's
    /// Threads section compares their times and plans (the tables above use the
    /// first count's runs); unset: rayon's default pool, once.
    #[arg(long, value_delimiter = ',')]
    threads: Vec<usize>,
    /// `--set`, `--out`, `--json`.
    #[command(flatten)]
    report: ReportArgs,
}

/// The JSON written beside the report.
#[derive(Debug, Serialize)]
struct Raw<'a> {
    seeds: u64,
    runs: &'a [Run],
    threads: &'a [threads::ThreadRow],
    #[serde(flatten)]
    summary: &'a Summary,
}

/// Runs `smug bench modes`.
pub fn run(args: BenchModesArgs) -> crate::Result<()> {
    let missions = lookup("--missions", "mission", &args.missions, &MISSIONS, |m| {
        m.name
    })?;
    let modes = lookup("--modes", "mode", &args.modes, &MODES, |m| m.name)?;
    let needs_data = missions
        .iter()
        .any(|m| matches!(m.polygons, Some(Polygons::Data { .. })));
    if needs_data && args.data.is_none() {
        crate::error::bail!("--missions data, data-open: need --data FILE (a CRL text map)");
    }
    if args.runs == 0 {
        crate::error::bail!("--runs: must be at least 1");
    }
    if args.threads.contains(&0) {
        crate::error::bail!("--threads: every count must be at least 1");
    }
    let pools = thread_pools(&args.threads)?;
    let mut runs = Vec::new();
    for mission in &missions {
        for mode in &modes {
            for seed in 1..=args.runs {
                for (threads, pool) in &pools {
                    eprintln!("{} / {} / seed {seed}", mission.name, mode.name);
                    let plan =
                        || plan_once(mission, mode, seed, &args.report.set, args.data.as_deref());
                    let before = cpu::CpuTimes::now();
                    let mut run = match pool {
                        Some(pool) => pool.install(plan)?,
                        None => plan()?,
                    };
                    run.threads = *threads;
                    if let (Some(before), Some(after)) = (before, cpu::CpuTimes::now()) {
                        let spent = after.since(before);
                        (run.cpu_s, run.waited_s) = (Some(spent.run_s), Some(spent.waited_s));
                    }
                    runs.push(run);
                }
            }
        }
    }
    // The tables use the first count's runs (every run when no count is given).
    let first: Vec<Run> = runs
        .iter()
        .filter(|r| r.threads == pools[0].0)
        .cloned()
        .collect();
    let summary = Summary::of(&missions, &modes, &first);
    let thread_rows = if args.threads.is_empty() {
        Vec::new()
    } else {
        threads::rows(&missions, &modes, &args.threads, &runs)
    };
    let raw = Raw {
        seeds: args.runs,
        runs: &runs,
        summary: &summary,
        threads: &thread_rows,
    };
    args.report.write(
        &format!(
            "{}{}\nCommand: `{}`\n",
            report(
                &missions,
                &modes,
                args.runs,
                &args.report.set,
                &summary,
                &first
            ),
            threads_section(&thread_rows, &missions, &modes),
            command_line()
        ),
        &raw,
    )?;
    Ok(())
}

/// The Threads section (empty without `--threads`).
fn threads_section(rows: &[threads::ThreadRow], missions: &[&Mission], modes: &[&Mode]) -> String {
    if rows.is_empty() {
        return String::new();
    }
    threads::section(rows, |mission, mode| {
        let mission = missions
            .iter()
            .find(|m| m.name == mission)
            .map_or(mission, |m| m.label);
        let mode = modes
            .iter()
            .find(|m| m.name == mode)
            .map_or(mode, |m| m.label);
        (mission.to_string(), mode.to_string())
    })
}

/// One pool per thread count, with the count (`(None, None)`: rayon's default pool).
#[allow(clippy::type_complexity)]
fn thread_pools(
    counts: &[usize],
) -> crate::Result<Vec<(Option<usize>, Option<rayon::ThreadPool>)>> {
    if counts.is_empty() {
        return Ok(vec![(None, None)]);
    }
    counts
        .iter()
        .map(|&threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| crate::error::invalid!("--threads {threads}: {e}"))?;
            Ok((Some(threads), Some(pool)))
        })
        .collect()
}

/// The command that ran, as typed after the program's name (`smug …`).
fn command_line() -> String {
    let args: Vec<String> = std::env::args().skip(1).collect();
    format!("smug {}", args.join(" "))
}

/// The known items named in `names` (in that order, without repeats); an unknown name
/// is an error naming it and the known ones.
fn lookup<'a, T>(
    flag: &str,
    what: &str,
    names: &[String],
    known: &'a [T],
    name: impl Fn(&T) -> &'static str,
) -> crate::Result<Vec<&'a T>> {
    let mut found: Vec<&T> = Vec::new();
    for wanted in names.iter().map(|n| n.trim()) {
        let item = known.iter().find(|k| name(k) == wanted).ok_or_else(|| {
            let all: Vec<&str> = known.iter().map(&name).collect();
            crate::error::invalid!(
                "{flag}: unknown {what} `{wanted}`; known: {}",
                all.join(", ")
            )
        })?;
        if !found.iter().any(|f| name(f) == wanted) {
            found.push(item);
        }
    }
    Ok(found)
}

/// Plans `mission` in `mode` with `seed`. A config or map that does not load is an
/// error (bad input); a pipeline that does not assemble (a start in collision) or a
/// planning failure is a run with `error` set.
fn plan_once(
    mission: &Mission,
    mode: &Mode,
    seed: u64,
    set: &[String],
    data: Option<&std::path::Path>,
) -> crate::Result<Run> {
    let mut overrides: Vec<String> = mission.set.iter().map(|s| s.to_string()).collect();
    if mission.polygons.is_some() {
        overrides.extend(POLYGON_SET.iter().map(|s| s.to_string()));
    }
    overrides.extend(mode.set.iter().map(|s| s.to_string()));
    overrides.push(format!("seed={seed}"));
    overrides.extend(set.iter().cloned());
    let context = || format!("{} / {} / seed {seed}", mission.name, mode.name);
    // A world whose start the robot cannot stand on (some seeds of the wheeled and
    // rover worlds) fails assembly: a failed run, not a bad input.
    let assembled = match mission.polygons {
        None => {
            let loaded = LoadedConfig::from_file(std::path::Path::new(mission.config), &overrides)
                .with_context(context)?;
            Pipeline::assemble(&loaded)
        }
        Some(source) => polygon_pipeline(source, seed, data, &overrides).with_context(context)?,
    };
    let planned = assembled.and_then(|mut pipeline| {
        let options = pipeline.config.plan;
        plan_mission(&mut pipeline, options)
    });
    let mut run = Run {
        mission: mission.name.into(),
        mode: mode.name.into(),
        seed,
        cost: None,
        paths_planned: None,
        planning_s: None,
        order: Vec::new(),
        error: None,
        total_s: None,
        threads: None,
        cpu_s: None,
        waited_s: None,
    };
    match planned {
        Ok(plan) => {
            run.order = plan.sequence.clone();
            run.cost = Some(plan.cost);
            run.paths_planned = Some(plan.stats.paths_planned);
            run.planning_s = Some(planning_s(&plan));
            run.total_s = plan.stats.stage_times_s.get("total").copied();
        }
        Err(err) => run.error = Some(err.to_string()),
    }
    Ok(run)
}

/// The pipeline of a polygon mission (see [`POLYGON_SET`]) on its map; the outer error
/// is a map or config that does not load, the inner one a pipeline that does not
/// assemble.
fn polygon_pipeline(
    source: Polygons,
    seed: u64,
    data: Option<&std::path::Path>,
    overrides: &[String],
) -> crate::Result<smug_core::Result<Pipeline>> {
    let (map, open) = match source {
        Polygons::Generated(targets) => (polygons::generated(targets, seed)?, false),
        Polygons::Data { open } => {
            let Some(path) = data else {
                crate::error::bail!("the data missions need --data FILE (a CRL text map)");
            };
            (polygons::read_crl(path)?, open)
        }
    };
    let config = format!(
        "{}\n[sequencer]\ntype = \"auto\"\n\n[selector]\ntype = \"idp\"\n",
        smug_app::p2p::DEFAULT_CONFIG
    );
    let loaded = LoadedConfig::from_text(
        &config,
        "<bench modes: polygons>",
        std::path::Path::new("."),
        overrides,
    )?;
    let Scenario { world, mission } = polygons::world(&map, open)?;
    Ok(Pipeline::assemble_with(
        &loaded,
        Some((world, Some(mission))),
        None,
    ))
}

/// The plan's planning time: its `total` minus the pipeline's build times (as `smug
/// plan` reports them, `build:<stage>`).
fn planning_s(plan: &Plan) -> f64 {
    let times = &plan.stats.stage_times_s;
    let built: f64 = times
        .iter()
        .filter(|(stage, _)| stage.starts_with("build:"))
        .map(|(_, s)| s)
        .sum();
    times.get("total").copied().unwrap_or(0.0) - built
}
