//! Point-to-point queries, in order, on one shared roadmap (`smug p2p`, `smug.p2p`):
//! one typed result that both front ends serialise.

use crate::{AppError, Result};
use serde::Serialize;
use smug_core::{
    EndpointFault, LoadedConfig, Pipeline, PlannerOutcome, PlannerStats, Pose2,
    StateValidityChecker, World,
};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The pipeline used when no config is given: a disc robot on an occupancy grid
/// (`configs/p2p-grid.toml`).
pub const DEFAULT_CONFIG: &str = include_str!("../../configs/p2p-grid.toml");

/// Where the queries are planned.
#[derive(Clone, Debug)]
pub enum P2pWorld {
    /// The config's `[world]`.
    Config,
    /// This world (its mission is replaced by one that starts at the first query).
    Given(Box<World>),
    /// A map file (ROS map_server-style YAML) with this obstacle height, metres.
    Map {
        /// The YAML file.
        path: PathBuf,
        /// Height given to occupied cells, metres.
        obstacle_height: f64,
    },
}

/// What to plan the queries with.
#[derive(Clone, Debug)]
pub struct P2pRequest {
    /// The pipeline config; `None`: [`DEFAULT_CONFIG`].
    pub config: Option<PathBuf>,
    /// `KEY=VALUE` overrides.
    pub set: Vec<String>,
    /// Where to plan.
    pub world: P2pWorld,
    /// Without a config and without a `planner.…` override, try the exact `visibility`
    /// planner first (it applies to a disc on a grid under path length), else fall back
    /// to the config's planner (`smug p2p` does; `smug.p2p` plans with the config's).
    pub prefer_exact: bool,
}

/// One query's result.
#[derive(Clone, Debug, Serialize)]
pub struct QueryRow {
    /// `exact`, `approximate`, `no_path`, `invalid_start` or `invalid_goal`.
    pub status: &'static str,
    /// For `no_path`: `proved` (no path exists) or `budget_spent` (one may exist).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub no_path: Option<&'static str>,
    /// The cause, machine-readable: for `no_path` `disconnected` (the goal lies
    /// outside the start's free region), `samples`, `time`, `deadline`,
    /// `earlier_query`, `unspecified`; for an invalid endpoint `off_map`,
    /// `in_inflated_obstacle` or `invalid` (the checker says no more).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub why: Option<&'static str>,
    /// The same in words; absent when solved.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// The exact path's cost.
    pub cost: Option<f64>,
    /// Planning time, seconds.
    pub time_s: f64,
    /// Roadmap vertices after the query.
    pub vertices: u64,
    /// The path's states `[x, y, yaw]` (exact or approximate), else empty.
    pub waypoints: Vec<[f64; 3]>,
}

/// Every query's result (the JSON `smug p2p --out` writes).
#[derive(Clone, Debug, Serialize)]
pub struct P2pResults {
    /// The planner that answered (`visibility` when the default config applies).
    pub planner_type: String,
    /// One row per query, in order.
    pub queries: Vec<QueryRow>,
    /// Time for every query, seconds.
    pub total_time_s: f64,
    /// The planner's counters after the last query.
    pub planner: PlannerStats,
}

impl P2pResults {
    /// Queries answered with an exact path.
    pub fn exact(&self) -> usize {
        self.queries.iter().filter(|q| q.status == "exact").count()
    }

    /// The first query with an invalid endpoint, as `query K: why` (1-based).
    pub fn first_bad_query(&self) -> Option<String> {
        self.queries.iter().enumerate().find_map(|(k, q)| {
            q.status
                .starts_with("invalid")
                .then(|| format!("query {}: {}", k + 1, q.reason.as_deref().unwrap_or("")))
        })
    }
}

/// A pipeline ready to answer queries, and its planner's name.
pub struct P2pPlanner {
    pipeline: Pipeline,
    planner_type: String,
}

impl P2pPlanner {
    /// Assembles the pipeline of `request` (a world of maps only when the request
    /// gives one: queries need no mission); with the fallback of [`P2pRequest::prefer_exact`] taken, also why
    /// `visibility` did not apply.
    pub fn assemble(request: &P2pRequest) -> Result<(Self, Option<String>)> {
        let planner_set = request.set.iter().any(|s| s.starts_with("planner."));
        let mut note = None;
        if request.prefer_exact && request.config.is_none() && !planner_set {
            let mut exact = request.set.clone();
            exact.push("planner.type=visibility".into());
            exact.push("planner.params={}".into());
            match assemble_with(request, &exact) {
                Ok(pipeline) => {
                    let planner_type = "visibility".to_string();
                    return Ok((
                        Self {
                            pipeline,
                            planner_type,
                        },
                        None,
                    ));
                }
                Err(err) if err.to_string().contains("`visibility` cannot plan here") => {
                    note = Some(err.to_string());
                }
                Err(err) => return Err(err),
            }
        }
        let pipeline = assemble_with(request, &request.set)?;
        let planner_type = pipeline
            .resolved
            .iter()
            .find(|r| r.key == "planner")
            .map_or_else(|| "none".to_string(), |r| r.plugin.clone());
        Ok((
            Self {
                pipeline,
                planner_type,
            },
            note,
        ))
    }

    /// The planner's plugin name.
    pub fn planner_type(&self) -> &str {
        &self.planner_type
    }

    /// Plans the queries in order on one roadmap; `each` sees every row as it is made
    /// (with its 0-based index).
    pub fn run(
        &mut self,
        queries: &[(Pose2, Pose2)],
        mut each: impl FnMut(usize, &QueryRow),
    ) -> Result<P2pResults> {
        let states = self.pipeline.state_validity.clone();
        let planner = self.pipeline.planner.as_mut().ok_or(AppError::NoPlanner)?;
        let started = Instant::now();
        let mut rows = Vec::with_capacity(queries.len());
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
                PlannerOutcome::InvalidStart => {
                    let (why, reason) = endpoint_fault(states.as_deref(), "start", start);
                    (None, Some(why), Some(reason))
                }
                PlannerOutcome::InvalidGoal => {
                    let (why, reason) = endpoint_fault(states.as_deref(), "goal", goal);
                    (None, Some(why), Some(reason))
                }
                _ => (None, None, None),
            };
            let path = match &outcome {
                PlannerOutcome::Exact(p) | PlannerOutcome::Approximate { path: p, .. } => Some(p),
                _ => None,
            };
            let row = QueryRow {
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
            };
            each(k, &row);
            rows.push(row);
        }
        Ok(P2pResults {
            planner_type: self.planner_type.clone(),
            queries: rows,
            total_time_s: started.elapsed().as_secs_f64(),
            planner: planner.stats(),
        })
    }
}

/// Plans `queries` as `request` says (see [`P2pPlanner`]).
pub fn p2p(request: &P2pRequest, queries: &[(Pose2, Pose2)]) -> Result<P2pResults> {
    let (mut planner, _) = P2pPlanner::assemble(request)?;
    planner.run(queries, |_, _| {})
}

fn assemble_with(request: &P2pRequest, set: &[String]) -> Result<Pipeline> {
    let loaded = match &request.config {
        Some(path) => LoadedConfig::from_file(path, set)?,
        None => {
            LoadedConfig::from_text(DEFAULT_CONFIG, "<default p2p config>", Path::new("."), set)?
        }
    };
    let world = match &request.world {
        P2pWorld::Config => None,
        P2pWorld::Given(world) => Some((**world).clone()),
        P2pWorld::Map {
            path,
            obstacle_height,
        } => {
            let layers = smug_worlds::map_file::load_map(path, *obstacle_height)?;
            Some(layers.into_world(smug_worlds::map_file::file_stem(path)))
        }
    };
    Ok(Pipeline::assemble_with(
        &loaded,
        world.map(|w| (w, None)),
        None,
    )?)
}

/// Why an endpoint is invalid: machine-readable cause and the sentence to show.
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
