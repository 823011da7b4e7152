//! `smug p2p`: point-to-point queries, in order, on one shared roadmap.

use crate::Outcome;
use serde::Serialize;
use smug_core::{
    EndpointFault, LoadedConfig, Mission, Pipeline, PlannerOutcome, Pose2, StateValidityChecker,
};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The pipeline `smug p2p` and `smug bench p2p` use when no config is given: a disc
/// robot on an occupancy grid (`configs/p2p-grid.toml`).
pub(crate) const DEFAULT_CONFIG: &str = include_str!("../../configs/p2p-grid.toml");

/// Arguments of `smug p2p`.
#[derive(clap::Args, Debug)]
pub struct P2pArgs {
    /// The map (ROS map_server-style YAML); absent: the config's world.
    #[arg(long)]
    map: Option<PathBuf>,
    /// Queries, one `sx,sy,syaw,gx,gy,gyaw` per row (a header row is allowed).
    #[arg(long)]
    queries: PathBuf,
    /// Pipeline config for the planner and validity checker (default:
    /// `configs/p2p-grid.toml`, a disc robot on an occupancy grid).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Override a config key.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Use this validity checker (e.g. `clearance-2d`).
    #[arg(long)]
    validity: Option<String>,
    /// Disc radius for `--validity clearance-2d`, metres.
    #[arg(long)]
    radius: Option<f64>,
    /// Obstacle height of imported maps, metres.
    #[arg(long, default_value_t = 2.0)]
    obstacle_height: f64,
    /// Where to write results.json.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// One query's result.
#[derive(Debug, Serialize)]
struct QueryResult {
    status: &'static str,
    /// For `no_path`: `proved` (no path exists) or `budget_spent` (one may exist).
    #[serde(skip_serializing_if = "Option::is_none")]
    no_path: Option<&'static str>,
    /// The cause, machine-readable: for `no_path` `disconnected` (the goal lies
    /// outside the start's free region), `samples`, `time`, `deadline`,
    /// `earlier_query`, `unspecified`; for an invalid endpoint `off_map`,
    /// `in_inflated_obstacle` or `invalid` (the checker says no more).
    #[serde(skip_serializing_if = "Option::is_none")]
    why: Option<&'static str>,
    /// The same in words; absent when solved.
    #[serde(skip_serializing_if = "Option::is_none")]
    reason: Option<String>,
    cost: Option<f64>,
    time_s: f64,
    vertices: u64,
    waypoints: Vec<[f64; 3]>,
}

/// Why an endpoint is invalid: machine-readable cause and the sentence on stderr.
fn endpoint_fault(
    states: Option<&dyn StateValidityChecker>,
    which: &str,
    pose: &Pose2,
) -> (&'static str, String) {
    let disc = states.and_then(|s| s.disc_on_grid());
    let at = format!("the {which} ({}, {})", pose.x, pose.y);
    match disc.as_ref().map(|d| (d.radius, d.fault(pose))) {
        Some((_, Some(EndpointFault::OffMap))) => ("off_map", format!("{at} is {}", EndpointFault::OffMap)),
        Some((radius, Some(fault @ EndpointFault::InInflatedObstacle { .. }))) => (
            "in_inflated_obstacle",
            format!("{at} is {fault}, closer than the robot's radius {radius} m"),
        ),
        Some((radius, None)) => (
            "in_inflated_obstacle",
            format!("{at} is on the boundary of an obstacle inflated by the robot's radius {radius} m"),
        ),
        None => (
            "invalid",
            format!("{at} is invalid for the validity checker (inside an inflated obstacle, or off the map)"),
        ),
    }
}

/// All results.
#[derive(Debug, Serialize)]
struct Results {
    /// The planner that answered (`visibility` when the default config applies).
    planner_type: String,
    queries: Vec<QueryResult>,
    total_time_s: f64,
    planner: smug_core::PlannerStats,
}

fn overrides(args: &P2pArgs) -> Vec<String> {
    let mut set = args.set.clone();
    if let Some(kind) = &args.validity {
        set.push(format!("validity.type={kind}"));
    }
    if let Some(r) = args.radius {
        set.push(format!("validity.params.radius={r}"));
    }
    set
}

fn assemble_with(args: &P2pArgs, first_start: Pose2, set: &[String]) -> anyhow::Result<Pipeline> {
    let loaded = match &args.config {
        Some(path) => LoadedConfig::from_file(path, set)?,
        None => {
            LoadedConfig::from_text(DEFAULT_CONFIG, "<default p2p config>", Path::new("."), set)?
        }
    };
    let Some(map) = &args.map else {
        return Ok(Pipeline::assemble(&loaded)?);
    };
    let layers = smug_worlds::map_file::load_map(map, args.obstacle_height)?;
    let mission = Mission {
        start: first_start,
        end: None,
        targets: Vec::new(),
    };
    let world = layers.into_world(smug_worlds::map_file::file_stem(map), mission, map)?;
    Ok(Pipeline::assemble_with_world(&loaded, world)?)
}

/// The pipeline and its planner's name. Without `--config` and without a
/// `planner.…` override, the exact `visibility` planner answers when it applies (a
/// disc on a grid under path length: the default config's robot), else LazyPRM* with a
/// note on stderr saying why.
fn assemble(args: &P2pArgs, first_start: Pose2) -> anyhow::Result<(Pipeline, String)> {
    let set = overrides(args);
    let planner_set = set.iter().any(|s| s.starts_with("planner."));
    if args.config.is_none() && !planner_set {
        let mut exact = set.clone();
        exact.push("planner.type=visibility".into());
        exact.push("planner.params={}".into());
        match assemble_with(args, first_start, &exact) {
            Ok(pipeline) => return Ok((pipeline, "visibility".into())),
            Err(err) if err.to_string().contains("`visibility` cannot plan here") => {
                eprintln!("smug p2p: {err}; planning with lazy-prm-star");
            }
            Err(err) => return Err(err),
        }
    }
    let pipeline = assemble_with(args, first_start, &set)?;
    let name = pipeline
        .resolved
        .iter()
        .find(|r| r.key == "planner")
        .map_or_else(|| "none".to_string(), |r| r.plugin.clone());
    Ok((pipeline, name))
}

/// Runs `smug p2p`.
pub fn run(args: P2pArgs) -> anyhow::Result<Outcome> {
    let queries = smug_core::queries::read_queries(&args.queries)?;
    let first_start = queries.first().map_or(Pose2::new(0.0, 0.0, 0.0), |q| q.0);
    let (mut pipeline, planner_type) = assemble(&args, first_start)?;
    let planner = pipeline
        .planner
        .as_mut()
        .ok_or_else(|| anyhow::anyhow!("the config has no [planner] section"))?;
    let states = pipeline.state_validity.clone();
    let started = Instant::now();
    let mut results = Vec::with_capacity(queries.len());
    let mut bad_input: Option<String> = None;
    for (k, (start, goal)) in queries.iter().enumerate() {
        let t = Instant::now();
        let outcome = planner.plan(start, goal)?;
        let time_s = t.elapsed().as_secs_f64();
        let (no_path, why, reason) = match &outcome {
            PlannerOutcome::NoPath(reason) => (
                Some(reason.kind()),
                Some(reason.why()),
                Some(reason.to_string()),
            ),
            PlannerOutcome::InvalidStart | PlannerOutcome::InvalidGoal => {
                let (which, pose) = match outcome {
                    PlannerOutcome::InvalidStart => ("start", start),
                    _ => ("goal", goal),
                };
                let (why, reason) = endpoint_fault(states.as_deref(), which, pose);
                bad_input.get_or_insert_with(|| format!("query {}: {reason}", k + 1));
                (None, Some(why), Some(reason))
            }
            _ => (None, None, None),
        };
        if let Some(reason) = &reason {
            eprintln!("query {}: {}: {reason}", k + 1, outcome.status());
        }
        let path = match &outcome {
            PlannerOutcome::Exact(p) | PlannerOutcome::Approximate { path: p, .. } => Some(p),
            _ => None,
        };
        results.push(QueryResult {
            status: outcome.status(),
            no_path,
            why,
            reason,
            cost: outcome.exact_path().map(|p| p.cost),
            time_s,
            vertices: planner.stats().vertices,
            waypoints: path.map_or(Vec::new(), |p| {
                p.states.iter().map(|s| [s.x, s.y, s.yaw]).collect()
            }),
        });
    }
    let results = Results {
        planner_type: planner_type.clone(),
        queries: results,
        total_time_s: started.elapsed().as_secs_f64(),
        planner: planner.stats(),
    };
    let exact = results
        .queries
        .iter()
        .filter(|q| q.status == "exact")
        .count();
    let mean_cost = match exact {
        0 => "—".to_string(),
        n => format!(
            "{:.3}",
            results.queries.iter().filter_map(|q| q.cost).sum::<f64>() / n as f64
        ),
    };
    let count = |kind: &str| {
        results
            .queries
            .iter()
            .filter(|q| q.no_path == Some(kind))
            .count()
    };
    println!(
        "{} queries ({planner_type}): {exact} exact, {} without a path ({} proved none exists, {} budget spent), {} invalid endpoints; mean cost {mean_cost}; {:.3} s; roadmap {} vertices",
        results.queries.len(),
        count("proved") + count("budget_spent"),
        count("proved"),
        count("budget_spent"),
        results.queries.iter().filter(|q| q.status.starts_with("invalid")).count(),
        results.total_time_s,
        results.planner.vertices
    );
    if let Some(out) = &args.out {
        smug_core::output::write_atomic(out, serde_json::to_string_pretty(&results)?.as_bytes())
            .map_err(|e| anyhow::anyhow!("{}: {e}", out.display()))?;
    }
    if let Some(first) = bad_input {
        anyhow::bail!("bad query: {first}");
    }
    Ok(if exact == results.queries.len() {
        Outcome::Ok
    } else {
        Outcome::NoSolution
    })
}
