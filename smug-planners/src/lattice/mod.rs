//! `lattice`: a state-lattice planner for curvature-limited motion models (Dubins,
//! Reeds–Shepp), after Hybrid A* (Dolgov et al. 2008) and SBPL's / Nav2's lattice
//! planners.
//!
//! The search runs over lattice poses (points `resolution` apart, `headings` evenly
//! spaced headings) joined by motion primitives: per heading, straight and full-lock
//! motions of two lengths, forward (and reverse where the model has a reverse gear),
//! each the model's own shortest curve between two lattice poses. The start joins the
//! lattice poses around it by the model's curves; every goal is reached by an
//! analytic shot, the model's curve from a lattice pose within `shot_radius` of it,
//! checked only when it would be the cheapest way on (lazily). Costs are the
//! pipeline's objective, validity its state checker and motion validator (any robot:
//! boxes on terrain as well as discs on grids). The heuristic is the larger of the
//! objective's bound (the model's obstacle-free curve) and a 2D obstacle-aware
//! distance (module `heuristic`); both are admissible, so the search is optimal for its
//! lattice, and a search that runs out of lattice poses proves that no path exists at
//! this resolution ([`smug_core::Proof::Exhausted`]).
//!
//! One search from a start answers every goal of a cost-matrix row or a DP layer
//! (one-to-many), and what a search learns (which lattice poses are valid, what every
//! primitive it tried costs and whether it is valid) is kept for the mission's later
//! queries: after the first few, searches are pure graph searches.

mod bounds;
mod buffers;
mod caches;
mod edges;
mod focus;
mod heuristic;
mod layer;
mod params;
mod pool;
mod primitives;
mod prove;
mod queue;
mod samples;
mod search;
mod shots;
mod sources;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_samples;

pub use params::LatticeParams;
pub use primitives::{Lattice, Primitive, Primitives, StateId};
pub use shots::sideways_bound;

use params::{check_params, default_resolution, invalid};
use sources::MAX_SOURCES;

use smug_core::{
    BuildContext, LayerOutcome, MotionValidator, NoPathReason, Objective, PlannerOutcome,
    PlannerStats, PointToPointPlanner, Pose2, Result, StateSpace, StateValidityChecker,
    TimeBreakdown,
};
use std::collections::BTreeMap;
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};

/// Counters of the planner's work.
#[derive(Clone, Debug, Default)]
pub(crate) struct Counts {
    queries: u64,
    searches: u64,
    expansions: u64,
    state_checks: u64,
    edge_checks: u64,
    shot_checks: u64,
    /// Shots solved for their cost (each once per goal's table).
    shot_costs: u64,
    breakdown: TimeBreakdown,
}

impl Counts {
    /// Adds `other`'s counts to these.
    fn add(&mut self, other: &Counts) {
        self.queries += other.queries;
        self.searches += other.searches;
        self.expansions += other.expansions;
        self.state_checks += other.state_checks;
        self.edge_checks += other.edge_checks;
        self.shot_checks += other.shot_checks;
        self.shot_costs += other.shot_costs;
        self.breakdown.add(&other.breakdown);
    }
}

/// What every search reads: the lattice, the pipeline's stages, and the caches (which
/// searches on several threads fill together).
pub(crate) struct Shared {
    params: LatticeParams,
    lattice: Lattice,
    primitives: Primitives,
    /// Distinct displacements of the primitives with their straight length, metres.
    displacements: Vec<(i32, i32, f64)>,
    space: Arc<dyn StateSpace>,
    objective: Arc<dyn Objective>,
    states: Arc<dyn StateValidityChecker>,
    motions: Arc<dyn MotionValidator>,
    radius: f64,
    shot_radius: f64,
    caches: caches::Caches,
    /// Every primitive's cost (`k · stride + p`) when the objective's costs do not
    /// depend on where a motion is; `None`: each is costed where it is used.
    primitive_costs: Option<Vec<f32>>,
    /// The states the motion validator checks along every primitive, from the
    /// origin; `None` when it does not check motions by a fixed set of states (or the
    /// model's curves depend on where they are).
    primitive_states: Option<samples::PrimitiveStates>,
    /// The run's deadline: searches stop at it.
    deadline: smug_core::Deadline,
    /// The run's progress: rows searched side by side count their legs as they end.
    progress: smug_core::RunProgress,
}

/// The lattice planner.
pub struct LatticePlanner {
    shared: Shared,
    /// Buffers of idle searchers, one per thread that searched at once.
    searchers: Mutex<Vec<buffers::Searcher>>,
    counts: Counts,
    last_costs: Vec<Option<f64>>,
}

/// Lattice poses beyond which rows are searched one at a time (each thread's buffers
/// take about 24 bytes per pose).
const MAX_PARALLEL_STATES: usize = 8_000_000;

/// Lattice poses at most (memory: about 50 bytes per pose and primitive).
const MAX_STATES: usize = 60_000_000;

impl LatticePlanner {
    /// Searches stop at `deadline` (a run's; by default one that is never armed).
    pub fn with_deadline(mut self, deadline: smug_core::Deadline) -> Self {
        self.shared.deadline = deadline;
        self
    }

    /// Counts the legs of rows searched side by side in `progress` as each row ends
    /// (a run's; by default one nobody reads).
    pub fn with_progress(mut self, progress: smug_core::RunProgress) -> Self {
        self.shared.progress = progress;
        self
    }

    /// The planner on `bounds` for the model `space` (which must be curvature-limited),
    /// costs by `objective`, validity by `states` and `motions`.
    pub fn new(
        params: LatticeParams,
        bounds: smug_core::Bounds2,
        space: Arc<dyn StateSpace>,
        objective: Arc<dyn Objective>,
        states: Arc<dyn StateValidityChecker>,
        motions: Arc<dyn MotionValidator>,
    ) -> Result<Self> {
        let Some(radius) = space.turning_radius() else {
            return Err(invalid(
                "space.type",
                "`lattice` plans for curvature-limited models (dubins, reeds-shepp); use `lazy-prm-star` or `visibility` for holonomic ones",
            ));
        };
        let side = (bounds.max[0] - bounds.min[0]).min(bounds.max[1] - bounds.min[1]);
        if !(radius.is_finite() && radius > 0.0) || 2.0 * radius > side {
            return Err(invalid(
                "space.params.turning_radius",
                format!("a turning radius of {radius} m does not fit a map {side:.3} m across (a U-turn needs twice the radius)"),
            ));
        }
        check_params(&params)?;
        let cell = params
            .resolution
            .unwrap_or_else(|| default_resolution(radius));
        let shot_radius = params.shot_radius.unwrap_or(3.0 * radius).max(2.0 * cell);
        let lattice = Lattice::new(bounds, cell, params.headings);
        if lattice.nx < 2 || lattice.ny < 2 {
            return Err(invalid(
                "planner.params.resolution",
                format!("{cell} m leaves fewer than 2 × 2 lattice points on the map"),
            ));
        }
        if lattice.len() > MAX_STATES {
            return Err(invalid(
                "planner.params.resolution",
                format!(
                    "{cell} m gives {} lattice poses on this map, more than {MAX_STATES}: choose a coarser resolution or fewer headings",
                    lattice.len()
                ),
            ));
        }
        let layout = primitives::Layout {
            space: space.as_ref(),
            radius,
            reverse: space.has_reverse_gear(),
        };
        let primitives = layout.primitives(&lattice);
        if primitives.by_heading.iter().any(Vec::is_empty) {
            return Err(invalid(
                "planner.params.resolution",
                format!("{cell} m is too coarse for a turning radius of {radius} m: some heading has no motion primitive"),
            ));
        }
        let displacements = distinct_displacements(&primitives, cell);
        let primitive_costs = objective
            .is_translation_invariant()
            .then(|| edges::primitive_costs(&lattice, &primitives, objective.as_ref()));
        let primitive_states = space
            .is_translation_invariant()
            .then(|| samples::PrimitiveStates::new(&lattice, &primitives, motions.as_ref()))
            .flatten();
        Ok(Self {
            shared: Shared {
                caches: caches::Caches::new(&lattice, primitives.stride, shot_radius),
                params,
                lattice,
                primitives,
                displacements,
                primitive_costs,
                primitive_states,
                space,
                objective,
                states,
                motions,
                radius,
                shot_radius,
                deadline: smug_core::Deadline::new(),
                progress: smug_core::RunProgress::default(),
            },
            searchers: Mutex::new(Vec::new()),
            counts: Counts::default(),
            last_costs: Vec::new(),
        })
    }

    /// The lattice searched.
    pub fn lattice(&self) -> &Lattice {
        &self.shared.lattice
    }

    /// The motion primitives per heading.
    pub fn primitives(&self) -> &Primitives {
        &self.shared.primitives
    }

    /// The search's costs of the last query's paths before shortcutting, one per goal
    /// (`None`: no path); with the default penalties, the objective's cost of the
    /// lattice path.
    pub fn last_costs(&self) -> &[Option<f64>] {
        &self.last_costs
    }
}

/// The distinct `(di, dj)` of all primitives with their straight length in metres.
fn distinct_displacements(primitives: &Primitives, cell: f64) -> Vec<(i32, i32, f64)> {
    let mut all: Vec<(i32, i32)> = primitives
        .by_heading
        .iter()
        .flatten()
        .map(|p| (p.di, p.dj))
        .collect();
    all.sort_unstable();
    all.dedup();
    all.into_iter()
        .map(|(di, dj)| (di, dj, cell * (di as f64).hypot(dj as f64)))
        .collect()
}

impl PointToPointPlanner for LatticePlanner {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        let mut outcomes = self.plan_many(start, std::slice::from_ref(goal))?;
        Ok(outcomes.pop().expect("one outcome per goal"))
    }

    fn plan_many(&mut self, start: &Pose2, goals: &[Pose2]) -> Result<Vec<PlannerOutcome>> {
        self.counts.queries += goals.len() as u64;
        Ok(self.search(start, goals, self.shared.params.max_expansions))
    }

    /// The rows' searches run side by side on rayon's threads, sharing the caches;
    /// each search's answer is the same as alone (see module `caches`).
    fn plan_rows(&mut self, rows: &[(Pose2, Vec<Pose2>)]) -> Result<Vec<Vec<PlannerOutcome>>> {
        self.plan_rows_weighted(rows, self.shared.params.heuristic_weight)
    }

    /// [`Self::plan_rows`] with the heuristic weighted by `order_heuristic_weight`.
    fn plan_order_rows(
        &mut self,
        rows: &[(Pose2, Vec<Pose2>)],
    ) -> Result<Vec<Vec<PlannerOutcome>>> {
        self.plan_rows_weighted(rows, self.shared.params.order_heuristic_weight)
    }

    fn answers_many(&self) -> bool {
        true
    }

    /// From the goals' obstacle-aware distances (module `bounds`).
    fn cost_bounds(&mut self, starts: &[Pose2], goals: &[Pose2]) -> Result<Option<Vec<Vec<f64>>>> {
        let (bounds, counts) = Self::with_searcher(&self.shared, &self.searchers, |worker| {
            worker.cost_bounds(starts, goals)
        });
        self.counts.add(&counts);
        Ok(Some(bounds))
    }

    fn answers_layers(&self) -> bool {
        true
    }

    /// One search from every source at once (module `layer`; more than
    /// `MAX_SOURCES` sources: one search each); beside it, where rows
    /// run side by side, the next layer's search from `goals` (at offset 0: their
    /// values are not known yet) runs until this one ends, only to fill the caches the
    /// next layer's own search will read (state, primitive and shot validity, the
    /// goals' heuristics, the starts' curves). The caches hold pure functions of the
    /// world, so the answers are the same as without it (`tests/threads.rs`); the next
    /// search runs warm (on lunar a layer searched warm takes a third of the time).
    fn plan_layer(
        &mut self,
        sources: &[(Pose2, f64)],
        goals: &[Pose2],
        next: &[Pose2],
    ) -> Result<Vec<LayerOutcome>> {
        if sources.len() > MAX_SOURCES {
            return smug_core::plan_layer_by_sources(self, sources, goals);
        }
        self.counts.queries += goals.len() as u64;
        let (shared, pool) = (&self.shared, &self.searchers);
        let max = shared.params.max_expansions;
        let weight = shared.params.heuristic_weight;
        let layer = || Self::with_searcher(shared, pool, |w| w.search_layer(sources, goals, max));
        let ((answers, counts), ahead) = if next.is_empty() || !self.plans_rows_side_by_side() {
            (layer(), Counts::default())
        } else {
            let stop = AtomicBool::new(false);
            let starts: Vec<(Pose2, f64)> = goals.iter().map(|&g| (g, 0.0)).collect();
            rayon::join(
                || {
                    let answered = layer();
                    stop.store(true, std::sync::atomic::Ordering::Relaxed);
                    answered
                },
                || {
                    let ahead = |w: &mut search::Worker<'_>| w.warm_layer(&starts, next, max);
                    Self::with_searcher_as(shared, pool, weight, Some(&stop), ahead).1
                },
            )
        };
        self.counts.add(&counts);
        self.counts.add(&ahead);
        Ok(answers)
    }

    fn plans_rows_side_by_side(&self) -> bool {
        self.shared.lattice.len() <= MAX_PARALLEL_STATES
    }

    fn proves_dead_ends(&self) -> bool {
        true
    }

    fn prove_unreachable(
        &mut self,
        start: &Pose2,
        goal: &Pose2,
        effort: u64,
    ) -> Result<Option<NoPathReason>> {
        let outcome = self.search(start, std::slice::from_ref(goal), effort.max(1));
        Ok(outcome[0].no_path_reason().filter(NoPathReason::is_proved))
    }

    /// The pairs' proving searches (no path is built) run side by side, as rows do
    /// ([`Self::plan_rows`]).
    fn prove_each_unreachable(
        &mut self,
        pairs: &[(Pose2, Pose2)],
        effort: u64,
    ) -> Result<Vec<Option<NoPathReason>>> {
        let (shared, pool) = (&self.shared, &self.searchers);
        let proved = self.side_by_side(pairs, |(start, goal)| {
            let (mut proofs, counts) = Self::with_searcher(shared, pool, |worker| {
                worker.prove(start, std::slice::from_ref(goal), effort.max(1))
            });
            (proofs.pop().flatten(), counts)
        });
        Ok(proved
            .into_iter()
            .map(|(proof, counts)| {
                self.counts.add(&counts);
                proof
            })
            .collect())
    }

    fn prove_unreachable_from(
        &mut self,
        start: &Pose2,
        goals: &[Pose2],
        effort: u64,
    ) -> Result<Vec<Option<NoPathReason>>> {
        Ok(self.prove(start, goals, effort.max(1)))
    }

    /// One small forward search from each start to `goal`, stopping at the first
    /// that proves nothing (the rest then prove nothing either); as many side by side
    /// as rayon has threads. Each is cheap when
    /// the goal cannot be entered: the 2D heuristic, seeded only where a final shot
    /// into the goal can start, is infinite almost everywhere, and an exhausted search
    /// keeps its proof for the starts whose joins it closed. (A search backwards from
    /// the goal turned half round would be one search, but it is not a proof: the
    /// search joins its start to the lattice only nearby, while shots into a goal come
    /// from up to `shot_radius` away.)
    fn prove_unenterable(
        &mut self,
        goal: &Pose2,
        starts: &[Pose2],
        effort: u64,
    ) -> Result<Vec<Option<NoPathReason>>> {
        let mut proofs = vec![None; starts.len()];
        let pairs: Vec<(Pose2, Pose2)> = starts.iter().map(|start| (*start, *goal)).collect();
        // As many side by side as there are threads: the answers are the sequence's
        // (those after the first that proves nothing are dropped).
        let batch = rayon::current_num_threads().max(1);
        for (b, chunk) in pairs.chunks(batch).enumerate() {
            for (k, proof) in self
                .prove_each_unreachable(chunk, effort)?
                .into_iter()
                .enumerate()
            {
                if proof.is_none() {
                    return Ok(proofs);
                }
                proofs[b * batch + k] = proof;
            }
        }
        Ok(proofs)
    }

    fn stats(&self) -> PlannerStats {
        let c = &self.counts;
        let known = self.shared.caches.states_known();
        PlannerStats {
            queries: c.queries,
            vertices: known,
            edges: c.edge_checks,
            breakdown: c.breakdown,
            counters: BTreeMap::from([
                (
                    "lattice_poses".to_string(),
                    self.shared.lattice.len() as u64,
                ),
                ("searches".to_string(), c.searches),
                ("expansions".to_string(), c.expansions),
                ("state_checks".to_string(), c.state_checks),
                ("edge_checks".to_string(), c.edge_checks),
                ("shot_checks".to_string(), c.shot_checks),
                ("shot_costs".to_string(), c.shot_costs),
                (
                    "primitives".to_string(),
                    self.shared
                        .primitives
                        .by_heading
                        .iter()
                        .map(Vec::len)
                        .sum::<usize>() as u64,
                ),
            ]),
        }
    }
}

/// The lattice planner on the pipeline of `ctx` (its world, space, objective, checkers,
/// deadline and progress).
pub(crate) fn build_planner(params: LatticeParams, ctx: &BuildContext) -> Result<LatticePlanner> {
    let world = ctx.world()?;
    Ok(LatticePlanner::new(
        params,
        world.bounds(),
        ctx.space(),
        ctx.objective(),
        ctx.state_validity()?,
        ctx.motion_validator()?,
    )?
    .with_deadline(ctx.deadline())
    .with_progress(ctx.progress()))
}

smug_core::register_plugin!(
    smug_core::registry::PlannerStage,
    name = "lattice",
    summary = "car-like robots (dubins, reeds-shepp): A* on a lattice of poses and the model's curves, one-to-many, proves dead ends",
    params = LatticeParams,
    build = |params, ctx| Ok(Box::new(build_planner(params, ctx)?)),
);
