//! `smug bench replan`: replanning after three mission events (a failed pose at the next
//! target, a new obstacle across the next leg, the robot halfway through) on lunar
//! 13×10 and 48×6, N seeds: the replan's time on the updated world (world, checkers and
//! planner built from scratch) against the full plan's, and its cost against the rest
//! of the original plan; and the same replan on the warm roadmap the plan left
//! (`--save-roadmap`/`--roadmap`, here in memory): its time and its cost against the
//! replan from scratch; and in memory, in a [`MissionSession`], against the replan from
//! scratch and against the replan from scratch with lazy sequencing costs.

use crate::output::write_report;

use serde::Serialize;
use smug_core::mission::{DiscObstacle, MissionState};
use smug_core::{LoadedConfig, Pipeline, Plan};
use smug_mission::plan_mission;
use smug_mission::{assemble_replan, changed_discs, replan_mission, MissionSession};
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `smug bench replan`.
#[derive(clap::Args, Debug)]
pub struct BenchReplanArgs {
    /// The lunar config (13×10 as given, and 48×6 through `--set`).
    #[arg(long, default_value = "configs/lunar.toml")]
    config: PathBuf,
    /// Seeds (1..=N); the seed sets the world and the planner.
    #[arg(long, default_value_t = 10)]
    runs: u64,
    /// Write the Markdown report here (else stdout only).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write the raw numbers as JSON here (default: beside `--out`, as `.json`).
    #[arg(long)]
    json: Option<PathBuf>,
}

/// The mission sizes: (label, overrides).
const SIZES: [(&str, &[&str]); 2] = [
    ("lunar 13×10", &[]),
    (
        "lunar 48×6",
        &["world.params.targets=48", "world.params.pois_per_target=6"],
    ),
];

/// The events, by name.
const EVENTS: [&str; 3] = ["failed pose", "new obstacle", "halfway"];

/// One replan's measurements.
#[derive(Debug, Serialize)]
struct Run {
    size: String,
    event: String,
    seed: u64,
    plan_s: f64,
    replan_s: f64,
    replan_cost: f64,
    /// The original plan's cost from the event's pose on (the same targets).
    rest_cost: f64,
    targets_left: usize,
    /// The same replan on the plan's warm roadmap: time and cost.
    warm_s: f64,
    warm_cost: f64,
    /// The same replan in a [`MissionSession`] that planned the mission and kept its
    /// pipeline in memory: time, cost, and paths it planned (the others were served
    /// from the session's kept paths).
    session_s: f64,
    session_cost: f64,
    session_paths_planned: u64,
    /// The replan from scratch with `plan.sequencing_costs = "lazy"` (what a session
    /// does with the pairs it keeps no path for): time and cost.
    scratch_lazy_s: f64,
    scratch_lazy_cost: f64,
    error: Option<String>,
}

/// The from-scratch replan of `state` on `loaded`: its time and its plan.
fn replan_from_scratch(
    loaded: &LoadedConfig,
    state: &MissionState,
    event: &str,
) -> (f64, smug_core::Result<Plan>) {
    let started = Instant::now();
    let replanned = assemble_replan(loaded, state, event).and_then(|mut p| {
        let options = p.config.plan;
        replan_mission(&mut p, options, state)
    });
    (started.elapsed().as_secs_f64(), replanned)
}

/// The state after `event` on the original `plan` (whose mission starts at `start`).
fn event_state(event: &str, plan: &Plan, start: [f64; 3]) -> MissionState {
    let here = |k: usize| {
        let p = plan.pois[k].pose;
        [p.x, p.y, p.yaw]
    };
    match event {
        "failed pose" => MissionState {
            pose: here(0),
            failed_pois: vec![(plan.pois[0].target.clone(), plan.pois[0].index)],
            ..MissionState::default()
        },
        "new obstacle" => {
            let leg = &plan.segments[0].path.states;
            let mid = leg[leg.len() / 2];
            MissionState {
                pose: start,
                obstacles: vec![DiscObstacle {
                    center: [mid.x, mid.y],
                    radius: 0.6,
                    height: 1.0,
                }],
                ..MissionState::default()
            }
        }
        _ => {
            let half = plan.sequence.len() / 2;
            MissionState {
                pose: here(half - 1),
                visited: plan.sequence[..half].to_vec(),
                ..MissionState::default()
            }
        }
    }
}

/// The original plan's cost from the event's pose on.
fn rest_cost(event: &str, plan: &Plan) -> f64 {
    let from = match event {
        "failed pose" => 1,
        "new obstacle" => 0,
        _ => plan.sequence.len() / 2,
    };
    plan.segments[from..].iter().map(|s| s.path.cost).sum()
}

fn measure(
    size: &str,
    set: &[&str],
    seed: u64,
    config: &std::path::Path,
) -> crate::Result<Vec<Run>> {
    let mut set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    set.push(format!("seed={seed}"));
    let loaded = LoadedConfig::from_file(config, &set)?;
    set.push("plan.sequencing_costs=\"lazy\"".into());
    let lazy = LoadedConfig::from_file(config, &set)?;
    let started = Instant::now();
    let mut pipeline = Pipeline::assemble(&loaded)?;
    let options = pipeline.config.plan;
    let plan = plan_mission(&mut pipeline, options)?;
    let plan_s = started.elapsed().as_secs_f64();
    let saved = pipeline
        .planner
        .as_ref()
        .and_then(|p| p.save_roadmap())
        .ok_or_else(|| {
            crate::error::invalid!("{}: the planner keeps no roadmap", config.display())
        })?;
    let s = pipeline
        .given_mission
        .as_ref()
        .map(|m| m.start)
        .ok_or_else(|| crate::error::invalid!("{}: the config has no world", config.display()))?;
    let mut runs = Vec::new();
    for event in EVENTS {
        let state = event_state(event, &plan, [s.x, s.y, s.yaw]);
        let (replan_s, replanned) = replan_from_scratch(&loaded, &state, event);
        let (scratch_lazy_s, scratch_lazy) = replan_from_scratch(&lazy, &state, event);
        let changed = changed_discs(&state, &loaded.config.robot);
        let started = Instant::now();
        let warm = assemble_replan(&loaded, &state, event).and_then(|mut p| {
            if let Some(planner) = p.planner.as_mut() {
                planner.load_roadmap(&saved, &changed)?;
            }
            let options = p.config.plan;
            replan_mission(&mut p, options, &state)
        });
        let warm_s = started.elapsed().as_secs_f64();
        let mut session = MissionSession::new(&loaded)?;
        session.plan()?;
        let started = Instant::now();
        let in_memory = session.replan(&state);
        let session_s = started.elapsed().as_secs_f64();
        let (replan_cost, targets_left, warm_cost, error) = match (replanned, warm) {
            (Ok(r), Ok(w)) => (r.cost, r.sequence.len(), w.cost, None),
            (Err(e), _) | (_, Err(e)) => (f64::NAN, 0, f64::NAN, Some(e.to_string())),
        };
        let (session_cost, session_paths_planned, error) = match in_memory {
            Ok(p) => (p.cost, p.stats.paths_planned, error),
            Err(e) => (f64::NAN, 0, error.or(Some(format!("in memory: {e}")))),
        };
        let (scratch_lazy_cost, error) = match scratch_lazy {
            Ok(p) => (p.cost, error),
            Err(e) => (f64::NAN, error.or(Some(format!("lazy from scratch: {e}")))),
        };
        runs.push(Run {
            size: size.into(),
            event: event.into(),
            seed,
            plan_s,
            replan_s,
            replan_cost,
            rest_cost: rest_cost(event, &plan),
            targets_left,
            warm_s,
            warm_cost,
            session_s,
            session_cost,
            session_paths_planned,
            scratch_lazy_s,
            scratch_lazy_cost,
            error,
        });
    }
    Ok(runs)
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let v: Vec<f64> = values.collect();
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

fn report(runs: &[Run], seeds: u64) -> String {
    let mut md = format!(
        "# Replanning (`smug bench replan`, seeds 1..={seeds})\n\n\
         Replan = world, checkers and planner built from scratch on the updated world, \
         then the remaining targets planned (`assemble_replan` + `replan_mission`); plan = \
         the full mission from scratch (`Pipeline::assemble` + `plan_mission`). Cost ratio = \
         replan cost / the original plan's cost from the same pose on (the failed-pose \
         and obstacle events force a change, halfway does not). Means over the seeds \
         whose replan succeeded. Warm = the same replan with the roadmap the plan left \
         loaded first (in memory; what only the new obstacle touches is checked again): \
         its time (world and checkers still built), the speed-up of from scratch over \
         warm, and its cost / the from-scratch replan's. In memory = the same replan in a \
         `MissionSession` that planned the mission and kept its pipeline (world, checkers, \
         planner with its roadmap, planned paths): the new obstacle applied locally, \
         kept paths it does not touch served again, the pairs it keeps no path for (from \
         the robot's new pose, or blocked by the obstacle) planned only where the tour \
         uses them (the cost matrix filled lazily): its time, the speed-up of from \
         scratch over it, its cost / the from-scratch replan's, and the paths it planned \
         (mean).\n\n\
         | mission | event | ok | plan (s) | replan (s) | replan / plan time | replan cost | original rest | cost ratio | warm (s) | scratch / warm time | warm / scratch cost | in memory (s) | scratch / in-memory time | in-memory / scratch cost | in-memory paths planned |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n"
    );
    for (size, _) in SIZES {
        for event in EVENTS {
            let all: Vec<&Run> = runs
                .iter()
                .filter(|r| r.size == size && r.event == event)
                .collect();
            let ok: Vec<&&Run> = all.iter().filter(|r| r.error.is_none()).collect();
            let plan = mean(ok.iter().map(|r| r.plan_s));
            let replan = mean(ok.iter().map(|r| r.replan_s));
            let cost = mean(ok.iter().map(|r| r.replan_cost));
            let rest = mean(ok.iter().map(|r| r.rest_cost));
            let ratio = mean(ok.iter().map(|r| r.replan_cost / r.rest_cost));
            let warm = mean(ok.iter().map(|r| r.warm_s));
            let warm_ratio = mean(ok.iter().map(|r| r.warm_cost / r.replan_cost));
            let memory = mean(ok.iter().map(|r| r.session_s));
            let memory_ratio = mean(ok.iter().map(|r| r.session_cost / r.replan_cost));
            let memory_paths = mean(ok.iter().map(|r| r.session_paths_planned as f64));
            let _ = writeln!(
                md,
                "| {size} | {event} | {}/{} | {plan:.3} | {replan:.3} | {:.2} | {cost:.2} | {rest:.2} | {ratio:.3} | {warm:.3} | {:.2} | {warm_ratio:.4} | {memory:.4} | {:.1} | {memory_ratio:.4} | {memory_paths:.1} |",
                ok.len(),
                all.len(),
                replan / plan,
                replan / warm,
                replan / memory
            );
        }
    }
    md.push_str(&lazy_table(runs));
    for r in runs.iter().filter(|r| r.error.is_some()) {
        let _ = writeln!(
            md,
            "\n- {} / {} / seed {}: {}",
            r.size,
            r.event,
            r.seed,
            r.error.as_deref().unwrap_or_default()
        );
    }
    md
}

/// The in-memory replan against the replan from scratch with lazy sequencing costs
/// (the session fills the pairs it keeps no path for lazily: this compares it with a
/// replan that does the same for every pair).
fn lazy_table(runs: &[Run]) -> String {
    let mut md = String::from(
        "\nAgainst lazy sequencing costs from scratch too: the same replan from scratch \
         with `plan.sequencing_costs = \"lazy\"` (every pair planned only where the tour \
         uses it, as the session does for the pairs it keeps no path for): its time, the \
         speed-up of it over in memory, and the in-memory cost / its cost.\n\n\
         | mission | event | lazy from scratch (s) | lazy scratch / in-memory time | in-memory / lazy scratch cost |\n\
         |---|---|---|---|---|\n",
    );
    for (size, _) in SIZES {
        for event in EVENTS {
            let ok: Vec<&Run> = runs
                .iter()
                .filter(|r| r.size == size && r.event == event && r.error.is_none())
                .collect();
            let lazy = mean(ok.iter().map(|r| r.scratch_lazy_s));
            let memory = mean(ok.iter().map(|r| r.session_s));
            let cost = mean(ok.iter().map(|r| r.session_cost / r.scratch_lazy_cost));
            let _ = writeln!(
                md,
                "| {size} | {event} | {lazy:.3} | {:.1} | {cost:.4} |",
                lazy / memory
            );
        }
    }
    md
}

/// Runs `smug bench replan`.
pub fn run(args: BenchReplanArgs) -> crate::Result<()> {
    let mut runs = Vec::new();
    for (size, set) in SIZES {
        for seed in 1..=args.runs {
            eprintln!("{size}, seed {seed}");
            runs.extend(measure(size, set, seed, &args.config)?);
        }
    }
    write_report(
        &report(&runs, args.runs),
        &runs,
        args.out.as_deref(),
        args.json.as_deref(),
    )?;
    Ok(())
}
