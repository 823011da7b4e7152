//! `lazy-prm-star`: LazyPRM* (Hauser 2015; OMPL's `LazyPRMstar`) with an informed
//! sampler on one roadmap shared by every query of a mission.
//!
//! A query adds its endpoints to the roadmap (they stay), then repeats: A* on the
//! roadmap with the objective's bound as heuristic; check the unknown vertices, then the unknown
//! edges, of the candidate path; remove what is invalid; until a valid path is found or
//! start and goal are disconnected. Between searches the roadmap grows by samples
//! (informed once a path is known), each connected to its k nearest neighbours with
//! `k = ⌈e(1 + 1/3) ln n⌉`. Once a path is known, an attempt repairs the previous
//! search for the vertices added since (incremental A*) instead of searching the whole
//! informed region again. A query stops after `max_stall` solution attempts in a row
//! that improve the best cost by less than `improvement`, when the informed set is
//! empty (the path is optimal), or at its sample or time budget — an unreachable goal
//! ends with "no path", never a hang.

mod attempts;
mod bridge;
mod checks;
mod expansion;
mod focus;
mod growth;
mod many;
mod params;
mod post;
mod query;
#[cfg(test)]
mod test_support;
#[cfg(test)]
mod tests;
mod warm;

use self::bridge::Bridge;
use self::checks::{timed_state_check, Checks, CountedMotions, Counts};
use self::expansion::Expansion;
use self::focus::{Focus, MIN_FOCUS_PERIOD};
pub use self::params::{LazyPrmStarParams, SearchMode};
use crate::grid_disc::FreeRegions;
use crate::roadmap::file::RoadmapSnapshot;
use crate::roadmap::{AStar, Evaluator, GraphPath, Repair, Roadmap, Validity};
use crate::shortcut::{shortcut, smooth};
use rayon::prelude::*;
use smug_core::pose::angle_distance;
use smug_core::rng::{stage_rng, StageRng};
use smug_core::{
    Bounds2, Budget, BuildContext, Deadline, Error, InformedSet, MemoryLimit, MotionValidator,
    NoPathReason, Objective, Path, PlannerOutcome, PlannerStats, PointToPointPlanner, Pose2, Proof,
    Result, RunContext, Sampler, StateSpace, StateValidityChecker, Termination,
};
use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;
use std::time::Instant;

/// LazyPRM* on a shared roadmap.
pub struct LazyPrmStar {
    params: LazyPrmStarParams,
    roadmap: Roadmap,
    astar: AStar,
    /// Buffers of the one-to-many searches run side by side (one per thread in use).
    row_searches: Vec<AStar>,
    sampler: Box<dyn Sampler>,
    states: Arc<dyn StateValidityChecker>,
    motions: Arc<dyn MotionValidator>,
    space: Arc<dyn StateSpace>,
    objective: Arc<dyn Objective>,
    bounds: Bounds2,
    w_t: f64,
    grown: bool,
    /// Whether the roadmap was grown for one-to-many searches.
    grown_for_many: bool,
    /// Vertices with ids from this one on were added after the latest search.
    fresh_from: u32,
    expansion: Expansion,
    /// Bridge samples of queries without a path (see `bridge_sigma`).
    bridge: Bridge,
    /// Endpoints of failed queries found in pockets (see `retry_cut_off`).
    cut_off: BTreeSet<u32>,
    counts: Counts,
    /// Answers given (saved with the roadmap) and loaded (see `load_roadmap`).
    warm: warm::Warm,
    /// The free cells' components when the checker is a disc on a grid (built at the
    /// first query that needs them; `Some(None)`: the checker is not one).
    regions: Option<Option<FreeRegions>>,
    /// Which budget ended the latest query without a path.
    last_budget: Budget,
    /// The run's deadline: queries stop at it, keeping their best path.
    deadline: Deadline,
    /// The run's progress: rows answered together count their legs as each ends.
    progress: smug_core::RunProgress,
}

/// Bytes a roadmap vertex takes with its share of edges (measured order of magnitude:
/// the pose, ~30 neighbours with costs and check states, the search's arrays).
const BYTES_PER_VERTEX: u128 = 512;

/// Refuses sample counts whose roadmap would not fit the memory limit.
fn check_roadmap_size(params: &LazyPrmStarParams, memory: MemoryLimit) -> Result<()> {
    for (key, count) in [
        ("initial_samples", params.initial_samples),
        ("max_samples", params.max_samples),
        ("max_corner_vertices", params.max_corner_vertices),
    ] {
        let what = format!("a roadmap of {key} = {count} vertices");
        memory
            .check(&what, count.into(), BYTES_PER_VERTEX)
            .map_err(|message| Error::invalid_param("planner", message.to_string()))?;
    }
    Ok(())
}

impl LazyPrmStar {
    /// Vertices expanded by every search so far (queries' and rows').
    fn expansions(&self) -> u64 {
        let rows: u64 = self.row_searches.iter().map(|a| a.expansions).sum();
        self.astar.expansions + rows
    }

    /// A planner over the given stages in `bounds`, outside any run (no deadline, the
    /// default memory limit).
    pub fn new(
        params: LazyPrmStarParams,
        sampler: Box<dyn Sampler>,
        states: Arc<dyn StateValidityChecker>,
        motions: Arc<dyn MotionValidator>,
        stages: (Arc<dyn StateSpace>, Arc<dyn Objective>),
        bounds: Bounds2,
    ) -> Result<Self> {
        let run = RunContext::default();
        Self::new_in(params, sampler, states, motions, stages, bounds, &run)
    }

    /// A planner over the given stages in `bounds` within `run`: its roadmap must fit
    /// the run's memory limit, its queries stop at the run's deadline.
    pub fn new_in(
        params: LazyPrmStarParams,
        sampler: Box<dyn Sampler>,
        states: Arc<dyn StateValidityChecker>,
        motions: Arc<dyn MotionValidator>,
        (space, objective): (Arc<dyn StateSpace>, Arc<dyn Objective>),
        bounds: Bounds2,
        run: &RunContext,
    ) -> Result<Self> {
        if !(params.improvement.is_finite() && (0.0..1.0).contains(&params.improvement)) {
            return Err(Error::invalid_param(
                "planner",
                format!("improvement must be in [0, 1), got {}", params.improvement),
            ));
        }
        for (name, value) in [
            ("attempt_share", params.attempt_share),
            ("focus", params.focus),
            ("one_to_many_density", params.one_to_many_density),
            ("bridge_sigma", params.bridge_sigma),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(Error::invalid_param(
                    "planner",
                    format!("{name} must be finite and ≥ 0, got {value}"),
                ));
            }
        }
        if params.range.is_some_and(|r| r.is_nan() || r <= 0.0) {
            return Err(Error::invalid_param("planner", "range must be > 0"));
        }
        if params.time_limit.is_some_and(|t| t.is_nan() || t <= 0.0) {
            return Err(Error::invalid_param("planner", "time_limit must be > 0"));
        }
        if !(0.0..=1.0).contains(&params.expand_share) {
            return Err(Error::invalid_param(
                "planner",
                format!(
                    "expand_share must be in [0, 1], got {}",
                    params.expand_share
                ),
            ));
        }
        if !(params.expand_reach.is_finite() && params.expand_reach > 0.0) {
            return Err(Error::invalid_param(
                "planner",
                format!(
                    "expand_reach must be finite and > 0, got {}",
                    params.expand_reach
                ),
            ));
        }
        check_roadmap_size(&params, run.memory)?;
        let (w_t, _) = space.lower_bound_weights();
        Ok(Self {
            params,
            roadmap: Roadmap::new(bounds)
                .with_directed_edges(!space.is_symmetric())
                .with_range(params.range.unwrap_or(f64::INFINITY)),
            astar: AStar::default(),
            row_searches: Vec::new(),
            sampler,
            states,
            motions,
            space,
            objective,
            bounds,
            w_t,
            grown: false,
            grown_for_many: false,
            fresh_from: 0,
            expansion: Expansion::new(
                stage_rng(0, EXPANSION_STREAM),
                params.expand_reach,
                params.expand_share,
            ),
            bridge: Bridge::new(stage_rng(0, BRIDGE_STREAM), params.bridge_sigma),
            cut_off: BTreeSet::new(),
            counts: Counts::default(),
            warm: warm::Warm::default(),
            regions: None,
            last_budget: Budget::Samples,
            deadline: run.deadline.clone(),
            progress: run.progress.clone(),
        })
    }

    /// Draws the endpoint expansions (see [`LazyPrmStarParams::expand_share`]) from
    /// `rng` (by default a fixed stream of seed 0).
    pub fn with_expansion_rng(mut self, rng: StageRng) -> Self {
        self.expansion = Expansion::new(rng, self.params.expand_reach, self.params.expand_share);
        self
    }

    /// Draws the bridge samples (see [`LazyPrmStarParams::bridge_sigma`]) from `rng`
    /// (by default a fixed stream of seed 0).
    pub fn with_bridge_rng(mut self, rng: StageRng) -> Self {
        self.bridge = Bridge::new(rng, self.params.bridge_sigma);
        self
    }

    /// The roadmap (for inspection and tests).
    pub fn roadmap(&self) -> &Roadmap {
        &self.roadmap
    }
}

impl PointToPointPlanner for LazyPrmStar {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        let started = Instant::now();
        let before = self.counts.breakdown;
        self.counts.queries += 1;
        if let Some(outcome) = self.warm.reuse(start, goal) {
            return Ok(outcome);
        }
        self.ensure_grown();
        let outcome = match (self.terminal(start), self.terminal(goal)) {
            (None, _) => PlannerOutcome::InvalidStart,
            (_, None) => PlannerOutcome::InvalidGoal,
            (Some(s), Some(g)) if s == g => PlannerOutcome::Exact(Path {
                states: vec![*start],
                cost: 0.0,
            }),
            (Some(s), Some(g)) => self.solve_query(start, goal, s, g),
        };
        let accounted = self.counts.breakdown.total_s() - before.total_s();
        self.counts.breakdown.misc_s += (started.elapsed().as_secs_f64() - accounted).max(0.0);
        self.warm.record(start, goal, &outcome);
        Ok(outcome)
    }

    fn plan_many(&mut self, start: &Pose2, goals: &[Pose2]) -> Result<Vec<PlannerOutcome>> {
        if !self.params.one_to_many {
            return goals.iter().map(|goal| self.plan(start, goal)).collect();
        }
        let rows = [(*start, goals.to_vec())];
        Ok(self.plan_rows_on_roadmap(&rows).pop().unwrap_or_default())
    }

    /// With `one_to_many`, every row's search side by side (see
    /// `plan_rows_on_roadmap`); else query by query.
    fn plan_rows(&mut self, rows: &[(Pose2, Vec<Pose2>)]) -> Result<Vec<Vec<PlannerOutcome>>> {
        if !self.params.one_to_many {
            return rows
                .iter()
                .map(|(start, goals)| self.plan_many(start, goals))
                .collect();
        }
        Ok(self.plan_rows_on_roadmap(rows))
    }

    fn answers_many(&self) -> bool {
        self.params.one_to_many
    }

    fn save_roadmap(&self) -> Option<Vec<u8>> {
        self.snapshot().to_bytes()
    }

    fn load_roadmap(&mut self, saved: &[u8], changed: &[smug_core::ChangedDisc]) -> Result<()> {
        let snapshot =
            RoadmapSnapshot::from_bytes(saved).map_err(|e| Error::stage("planner", e))?;
        self.load(snapshot, changed)
    }

    fn update_world(
        &mut self,
        ctx: &BuildContext,
        changed: &[smug_core::ChangedDisc],
    ) -> Result<()> {
        self.carry_on(ctx, changed)
    }

    fn stats(&self) -> PlannerStats {
        let c = &self.counts;
        let mut counters = BTreeMap::from([
            ("samples".to_string(), c.samples),
            ("vertex_checks".to_string(), c.vertex_checks),
            ("edge_checks".to_string(), c.edge_checks),
            ("astar_searches".to_string(), c.searches),
            ("astar_repairs".to_string(), c.repairs),
            ("cut_off_queries".to_string(), c.cut_off_queries),
            ("proved_no_path".to_string(), c.proved_no_path),
            ("astar_expansions".to_string(), self.expansions()),
        ]);
        counters.extend(self.load_counters());
        PlannerStats {
            queries: c.queries,
            vertices: self.roadmap.live_vertex_count() as u64,
            edges: self.roadmap.live_edge_count() as u64,
            breakdown: c.breakdown,
            counters,
        }
    }
}

/// The random stream of the endpoint expansions.
const EXPANSION_STREAM: &str = "planner-expansion";

/// The random stream of the bridge samples.
const BRIDGE_STREAM: &str = "planner-bridge";

/// LazyPRM* for the pipeline of `ctx`.
pub(crate) fn build_planner(params: LazyPrmStarParams, ctx: &BuildContext) -> Result<LazyPrmStar> {
    let bounds = ctx.world()?.bounds();
    Ok(LazyPrmStar::new_in(
        params,
        ctx.new_sampler()?,
        ctx.state_validity()?,
        ctx.motion_validator()?,
        (ctx.space(), ctx.objective()),
        bounds,
        ctx.run(),
    )?
    .with_expansion_rng(ctx.rng(EXPANSION_STREAM))
    .with_bridge_rng(ctx.rng(BRIDGE_STREAM)))
}

smug_core::register_plugin!(
    smug_core::registry::PlannerStage,
    name = "lazy-prm-star",
    summary = "LazyPRM* with informed sampling on one roadmap shared by all queries",
    params = LazyPrmStarParams,
    build = |params, ctx| Ok(Box::new(build_planner(params, ctx)?)),
);
