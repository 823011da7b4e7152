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

mod checks;
mod expansion;
mod focus;
mod many;
mod params;
#[cfg(test)]
mod test_support;
mod warm;

use self::checks::{timed_state_check, Checks, CountedMotions};
use self::expansion::Expansion;
use self::focus::{Focus, MIN_FOCUS_PERIOD};
pub use self::params::{LazyPrmStarParams, SearchMode};
use crate::roadmap::{AStar, Evaluator, GraphPath, Repair, Roadmap, Validity};
use crate::shortcut::{shortcut, smooth};
use rayon::prelude::*;
use smug_core::pose::angle_distance;
use smug_core::rng::{stage_rng, StageRng};
use smug_core::{
    Bounds2, Budget, BuildContext, Error, FreeRegions, InformedSet, MotionValidator, NoPathReason,
    Objective, Path, PlannerOutcome, PlannerStats, PointToPointPlanner, Pose2, Proof, Result,
    Sampler, StateSpace, StateValidityChecker, Termination, TimeBreakdown,
};
use std::collections::{BTreeMap, BTreeSet};
use std::sync::atomic::Ordering::Relaxed;
use std::sync::Arc;
use std::time::Instant;

/// LazySP rounds an `auto` attempt tries before switching to Lazy Weighted A*.
const AUTO_LAZY_SP_ROUNDS: u32 = 4;

/// Samples between improvement attempts once a query has its first path:
/// `attempt_every`, or `attempt_share` × the samples it drew to find that path if more.
fn improvement_interval(params: &LazyPrmStarParams, samples_to_first_path: u64) -> u32 {
    let scaled = (params.attempt_share * samples_to_first_path as f64).ceil();
    (scaled.min(f64::from(u32::MAX)) as u32).max(params.attempt_every)
}

/// Counters kept across queries.
#[derive(Clone, Debug, Default)]
struct Counts {
    queries: u64,
    samples: u64,
    vertex_checks: u64,
    edge_checks: u64,
    searches: u64,
    /// Attempts answered by repairing the previous search.
    repairs: u64,
    /// Queries answered "no path" at once: an endpoint was cut off.
    cut_off_queries: u64,
    /// Queries answered "no path exists" at once: the endpoints lie in different
    /// components of the free cells (a disc on a grid).
    proved_no_path: u64,
    breakdown: TimeBreakdown,
}

/// LazyPRM* on a shared roadmap.
pub struct LazyPrmStar {
    params: LazyPrmStarParams,
    roadmap: Roadmap,
    astar: AStar,
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
}

/// `k = ⌈e(1 + 1/d) ln n⌉` with `d = 3`, at least 1.
fn connection_k(n: usize) -> usize {
    let k = (std::f64::consts::E * (1.0 + 1.0 / 3.0) * (n.max(1) as f64).ln()).ceil();
    (k as usize).max(1)
}

/// Bytes a roadmap vertex takes with its share of edges (measured order of magnitude:
/// the pose, ~30 neighbours with costs and check states, the search's arrays).
const BYTES_PER_VERTEX: u128 = 512;

/// Refuses sample counts whose roadmap would not fit the memory limit.
fn check_roadmap_size(params: &LazyPrmStarParams) -> Result<()> {
    for (key, count) in [
        ("initial_samples", params.initial_samples),
        ("max_samples", params.max_samples),
    ] {
        let what = format!("a roadmap of {key} = {count} vertices");
        smug_core::limits::check_allocation(&what, count.into(), BYTES_PER_VERTEX)
            .map_err(|message| Error::invalid_param("planner", message))?;
    }
    Ok(())
}

impl LazyPrmStar {
    /// A planner over the given stages in `bounds`.
    pub fn new(
        params: LazyPrmStarParams,
        sampler: Box<dyn Sampler>,
        states: Arc<dyn StateValidityChecker>,
        motions: Arc<dyn MotionValidator>,
        (space, objective): (Arc<dyn StateSpace>, Arc<dyn Objective>),
        bounds: Bounds2,
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
        check_roadmap_size(&params)?;
        let (w_t, _) = space.lower_bound_weights();
        Ok(Self {
            params,
            roadmap: Roadmap::new(bounds)
                .with_directed_edges(!space.is_symmetric())
                .with_range(params.range.unwrap_or(f64::INFINITY)),
            astar: AStar::default(),
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
            cut_off: BTreeSet::new(),
            counts: Counts::default(),
            warm: warm::Warm::default(),
            regions: None,
            last_budget: Budget::Samples,
        })
    }

    /// Draws the endpoint expansions (see [`LazyPrmStarParams::expand_share`]) from
    /// `rng` (by default a fixed stream of seed 0).
    pub fn with_expansion_rng(mut self, rng: StageRng) -> Self {
        self.expansion = Expansion::new(rng, self.params.expand_reach, self.params.expand_share);
        self
    }

    /// The roadmap (for inspection and tests).
    pub fn roadmap(&self) -> &Roadmap {
        &self.roadmap
    }

    /// Draws `n` samples into the roadmap now.
    pub fn grow(&mut self, n: u64) {
        for _ in 0..n {
            if let Some(sample) = self.draw_sample(None) {
                self.insert_sample(sample);
            }
        }
    }

    fn draw_sample(&mut self, informed: Option<&InformedSet>) -> Option<Pose2> {
        let started = Instant::now();
        let sample = self.sampler.sample(&self.bounds, informed);
        self.counts.samples += 1;
        self.counts.breakdown.sampling_s += started.elapsed().as_secs_f64();
        sample
    }

    /// Draws an expansion sample and adds it (checked first unless vertices are lazy) to
    /// the roadmap and to its end's tree; true if added.
    fn insert_expansion_sample(&mut self) -> bool {
        let started = Instant::now();
        let drawn = self.expansion.sample(self.space.as_ref(), &self.bounds);
        self.counts.samples += 1;
        self.counts.breakdown.sampling_s += started.elapsed().as_secs_f64();
        let Some((end, sample, (from, to))) = drawn else {
            return false;
        };
        let added = self.insert_sample(sample);
        if added {
            let started = Instant::now();
            let joined = self.motions.is_valid_motion(&from, &to);
            self.counts.edge_checks += 1;
            self.counts.breakdown.edge_checking_s += started.elapsed().as_secs_f64();
            if joined {
                self.expansion.grow(end, sample);
            }
        }
        added
    }

    fn check_state(&mut self, state: &Pose2) -> bool {
        timed_state_check(self.states.as_ref(), &mut self.counts, state)
    }

    /// Adds a sample as a vertex (checked first unless vertices are lazy); true if added.
    fn insert_sample(&mut self, sample: Pose2) -> bool {
        let validity = if self.params.lazy_vertices {
            Validity::Unknown
        } else if self.check_state(&sample) {
            Validity::Valid
        } else {
            return false;
        };
        self.add_vertex(sample, validity);
        true
    }

    fn add_vertex(&mut self, pose: Pose2, validity: Validity) -> u32 {
        let started = Instant::now();
        let k = connection_k(self.roadmap.live_vertex_count() + 1);
        let v = self.roadmap.add_vertex(
            pose,
            validity,
            k,
            (self.space.as_ref(), self.w_t),
            self.objective.as_ref(),
        );
        self.counts.breakdown.sampling_s += started.elapsed().as_secs_f64();
        v
    }

    /// The vertex of a query endpoint (added if new), checked; `None` when invalid.
    fn terminal(&mut self, pose: &Pose2) -> Option<u32> {
        if let Some(v) = self.roadmap.find(pose) {
            let mut checks = Checks {
                states: self.states.as_ref(),
                motions: self.motions.as_ref(),
                counts: &mut self.counts,
            };
            return checks.vertex(&mut self.roadmap, v).then_some(v);
        }
        if !self.check_state(pose) {
            return None;
        }
        Some(self.add_vertex(*pose, Validity::Valid))
    }

    /// Checks the unknown vertices, then the unknown edges, of `path`, and removes
    /// every invalid one found (all of them, so that one search discards as many bad
    /// edges as possible). True when the whole path is valid.
    fn validate(&mut self, path: &GraphPath) -> bool {
        let mut checks = Checks {
            states: self.states.as_ref(),
            motions: self.motions.as_ref(),
            counts: &mut self.counts,
        };
        let mut valid = true;
        for &v in &path.vertices {
            valid &= checks.vertex(&mut self.roadmap, v);
        }
        if valid {
            for &e in &path.edges {
                valid &= checks.edge(&mut self.roadmap, e);
            }
        }
        valid
    }

    /// One A* search on the optimistic roadmap (no checks), within `bound`.
    fn optimistic_search(&mut self, s: u32, g: u32, bound: f64) -> Option<GraphPath> {
        let started = Instant::now();
        let found = self
            .astar
            .search(&self.roadmap, s, g, self.objective.as_ref(), bound);
        self.counts.searches += 1;
        self.counts.breakdown.astar_s += started.elapsed().as_secs_f64();
        found
    }

    /// One Lazy Weighted A* search within `bound`; its checking time is booked as
    /// checking, not search.
    fn lazy_weighted_search(&mut self, s: u32, g: u32, bound: f64) -> Option<GraphPath> {
        let started = Instant::now();
        let checking_before =
            self.counts.breakdown.edge_checking_s + self.counts.breakdown.vertex_checking_s;
        let mut checks = Checks {
            states: self.states.as_ref(),
            motions: self.motions.as_ref(),
            counts: &mut self.counts,
        };
        let found = self.astar.search_lazy(
            &mut self.roadmap,
            s,
            g,
            self.objective.as_ref(),
            &mut checks,
            bound,
        );
        self.counts.searches += 1;
        let checking = self.counts.breakdown.edge_checking_s
            + self.counts.breakdown.vertex_checking_s
            - checking_before;
        self.counts.breakdown.astar_s += (started.elapsed().as_secs_f64() - checking).max(0.0);
        found
    }

    /// The latest search of this query repaired for the vertices added since (see
    /// [`AStar::repair`]), timed as A*; [`Repair::NoBase`] when that cannot be done.
    fn repair(&mut self, s: u32, g: u32) -> Repair {
        if !self.params.incremental_attempts {
            return Repair::NoBase;
        }
        let started = Instant::now();
        let fresh_from = self.fresh_from;
        let repaired = self
            .astar
            .repair(&self.roadmap, s, g, fresh_from, self.objective.as_ref());
        if repaired != Repair::NoBase {
            self.fresh_from = self.roadmap.vertex_count() as u32;
            self.counts.repairs += 1;
        }
        self.counts.breakdown.astar_s += started.elapsed().as_secs_f64();
        repaired
    }

    /// Searches and validates until a valid path is found or `s` and `g` are disconnected.
    /// `best_cost` is the cost of a valid path known to be in the roadmap (valid edges
    /// are never removed), so no search needs to open a vertex estimated above it;
    /// `rounds_done` LazySP rounds of this attempt were already spent (by a repair).
    fn attempt(&mut self, s: u32, g: u32, best_cost: f64, rounds_done: u32) -> Option<GraphPath> {
        // Slack for sums of the same edges in another order.
        let bound = best_cost * (1.0 + 1e-9);
        self.fresh_from = self.roadmap.vertex_count() as u32;
        let lazy_sp_rounds = match self.params.search {
            SearchMode::LazySp => u32::MAX,
            SearchMode::LazyWeighted => 0,
            SearchMode::Auto => AUTO_LAZY_SP_ROUNDS,
        };
        let mut rounds = rounds_done;
        let found = loop {
            if rounds >= lazy_sp_rounds {
                break self.lazy_weighted_search(s, g, bound);
            }
            rounds += 1;
            match self.optimistic_search(s, g, bound) {
                None => break None,
                Some(path) if self.validate(&path) => break Some(path),
                Some(_) => {}
            }
        };
        if found.is_none() {
            self.roadmap.refresh_components();
        }
        found
    }

    /// Grows the roadmap and searches until the stall rule, the budget or optimality stops.
    fn solve(&mut self, start: &Pose2, goal: &Pose2, s: u32, g: u32) -> Option<GraphPath> {
        let budget =
            Termination::from_budgets(self.params.time_limit, Some(self.params.max_samples));
        let mut clock = budget.start();
        let mut best = if self.roadmap.maybe_connected(s, g) {
            self.attempt(s, g, f64::INFINITY, 0)
        } else {
            None
        };
        let (mut stall, mut since_attempt) = (0u32, 0u32);
        // Before the first solution, wait longer after each failed attempt (the roadmap
        // must grow by a share of its size), so cluttered maps do not search per sample.
        let mut wait = 1u32;
        // Once a path is known, samples between attempts (see `attempt_share`).
        let mut interval = self.params.attempt_every;
        let mut focus = Focus::new(
            self.params.focus,
            self.objective.cost_bound(start, goal),
            self.whole_bounds_cost(start, goal),
            self.focus_period(),
        );
        let max_stall = self.params.max_stall;
        let stalled = |best: &Option<GraphPath>, stall: u32| best.is_some() && stall >= max_stall;
        self.expansion.begin(start, goal);
        while !clock.is_done() && !stalled(&best, stall) {
            // `best` changes only at the end of an iteration.
            let best_cost = best.as_ref().map_or(f64::INFINITY, |b| b.cost);
            let focusing = !focus.covers(best_cost);
            let expanding = best.is_none()
                && clock.iterations() >= self.params.expand_after
                && self.expansion.is_due();
            let (inserted, widened) = if expanding {
                clock.tick();
                (self.insert_expansion_sample(), false)
            } else {
                let focused = if focusing {
                    focus.next_set(start, goal)
                } else {
                    None
                };
                let from_focus = focused.is_some();
                let informed = focused.or_else(|| {
                    best.as_ref().map(|b| InformedSet {
                        start: *start,
                        goal: *goal,
                        best_cost: b.cost,
                    })
                });
                clock.tick();
                let Some(sample) = self.draw_sample(informed.as_ref()) else {
                    if from_focus {
                        focus.widen(self.focus_period());
                        continue; // the focus fell outside the bounds: widen it
                    }
                    break; // the informed set is empty: nothing can improve the path
                };
                let widened = focusing && focus.tick();
                if widened {
                    focus.widen(self.focus_period());
                }
                (self.insert_sample(sample), widened)
            };
            if !inserted && !widened {
                continue;
            }
            since_attempt += 1;
            let due = match &best {
                None => since_attempt >= wait && self.roadmap.maybe_connected(s, g),
                // While focusing, once per focus period: the roadmap grows by a share
                // of its size between searches, as before the first path.
                Some(_) if focusing => widened,
                Some(_) => since_attempt >= interval,
            };
            if !due {
                continue;
            }
            since_attempt = 0;
            let repaired = match best {
                Some(_) => self.repair(s, g),
                None => Repair::NoBase,
            };
            let found = match repaired {
                Repair::NoCheaper => {
                    // As a searched attempt: a stall only once the focus covers the
                    // informed set.
                    if focus.covers(best_cost) {
                        stall += 1;
                    }
                    continue;
                }
                // The repair was this attempt's first search round.
                Repair::Cheaper(path) if self.validate(&path) => Some(path),
                Repair::Cheaper(_) => self.attempt(s, g, best_cost, 1),
                Repair::NoBase => self.attempt(s, g, best_cost, 0),
            };
            if found.is_none() && best.is_none() {
                wait = ((self.roadmap.live_vertex_count() / 20) as u32).max(1);
            }
            if found.is_none() && best.is_some() && focus.covers(best_cost) {
                // No cheaper path: a stalled attempt, as a repair that finds none.
                stall += 1;
            }
            if let Some(path) = found {
                if best.is_none() {
                    interval = improvement_interval(&self.params, clock.iterations());
                }
                // A round counts as stalled only once the focus covers the informed
                // set: until then the samples have not yet reached all of it.
                if path.cost > best_cost * (1.0 - self.params.improvement)
                    && focus.covers(best_cost)
                {
                    stall += 1;
                } else {
                    stall = 0;
                }
                if path.cost < best_cost {
                    best = Some(path);
                }
            }
        }
        if best.is_none() && since_attempt > 0 && self.roadmap.maybe_connected(s, g) {
            // The samples since the last attempt may have connected the endpoints.
            best = self.attempt(s, g, f64::INFINITY, 0);
        }
        if best.is_none() {
            self.cut_off_pocket(s, g);
            self.last_budget = if smug_core::deadline::passed() {
                Budget::Deadline
            } else if self
                .params
                .time_limit
                .is_some_and(|t| clock.elapsed().as_secs_f64() >= t)
            {
                Budget::Time
            } else {
                Budget::Samples
            };
        }
        best
    }

    /// True when no path joins `start` and `goal`, proved cheaply: for a disc on a
    /// grid, they lie in different components of the free cells (see [`FreeRegions`]).
    fn proved_disconnected(&mut self, start: &Pose2, goal: &Pose2) -> bool {
        let states = &self.states;
        let regions = self
            .regions
            .get_or_insert_with(|| states.disc_on_grid().map(|disc| FreeRegions::new(&disc)));
        let proved = regions
            .as_ref()
            .is_some_and(|r| r.disconnected(start, goal));
        if proved {
            self.counts.proved_no_path += 1;
        }
        proved
    }

    /// Grows the initial roadmap before the first query: corner vertices, then
    /// `initial_samples`.
    fn ensure_grown(&mut self) {
        if !self.grown {
            self.grown = true;
            self.add_corner_vertices();
            self.grow(self.params.initial_samples);
        }
    }

    /// For a disc on a grid and straight motions, a valid vertex at each of the grid's
    /// corner and corridor waypoints inside the bounds (see
    /// [`LazyPrmStarParams::corner_vertices`]).
    fn add_corner_vertices(&mut self) {
        if !self.params.corner_vertices || !self.space.is_holonomic() {
            return;
        }
        let Some(disc) = self.states.disc_on_grid() else {
            return;
        };
        let corridors = disc.corridor_waypoints();
        for [x, y] in disc.corner_waypoints().into_iter().chain(corridors) {
            if self.bounds.contains(x, y) {
                self.insert_sample(Pose2::new(x, y, 0.0));
            }
        }
    }

    /// A query between the valid endpoint vertices `s ≠ g` of `start` and `goal`:
    /// "no path" at once when one is cut off, else solved and post-processed.
    fn solve_query(&mut self, start: &Pose2, goal: &Pose2, s: u32, g: u32) -> PlannerOutcome {
        if self.proved_disconnected(start, goal) {
            return PlannerOutcome::NoPath(NoPathReason::Proved(Proof::Disconnected));
        }
        if self.cut_off.contains(&s) || self.cut_off.contains(&g) {
            self.counts.cut_off_queries += 1;
            return PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::EarlierQuery));
        }
        match self.solve(start, goal, s, g) {
            Some(path) => PlannerOutcome::Exact(self.post_processed(&path)),
            None => PlannerOutcome::NoPath(NoPathReason::BudgetSpent(self.last_budget)),
        }
    }

    /// After a failed query: cuts off the endpoint whose component is the smaller one
    /// if it holds less than half the roadmap (both on a tie), unless retried.
    fn cut_off_pocket(&mut self, s: u32, g: u32) {
        if self.params.retry_cut_off {
            return;
        }
        self.roadmap.refresh_components();
        let half = self.roadmap.live_vertex_count() / 2;
        let (size_s, size_g) = (
            self.roadmap.component_size(s),
            self.roadmap.component_size(g),
        );
        for (v, size, other) in [(s, size_s, size_g), (g, size_g, size_s)] {
            if size <= other && size < half {
                self.cut_off.insert(v);
            }
        }
    }

    /// A cost whose informed set holds the whole bounds: every corner's sum of
    /// distances to the foci, weighted, plus the rotational lower bound.
    fn whole_bounds_cost(&self, start: &Pose2, goal: &Pose2) -> f64 {
        let (w_t, w_r) = self.objective.bound_weights();
        let [x0, y0] = self.bounds.min;
        let [x1, y1] = self.bounds.max;
        let farthest = [[x0, y0], [x0, y1], [x1, y0], [x1, y1]]
            .iter()
            .map(|&[x, y]| (x - start.x).hypot(y - start.y) + (x - goal.x).hypot(y - goal.y))
            .fold(0.0, f64::max);
        w_t * farthest + w_r * angle_distance(start.yaw, goal.yaw)
    }

    /// Samples the focus gets before it widens: a share of the roadmap (as the wait
    /// between failed attempts), at least [`MIN_FOCUS_PERIOD`].
    fn focus_period(&self) -> u64 {
        ((self.roadmap.live_vertex_count() / 20) as u64).max(MIN_FOCUS_PERIOD)
    }

    /// The path of `graph_path`, shortcut or smoothed as configured; the motion checks
    /// of that post-processing are counted and timed as edge checks.
    fn post_processed(&mut self, graph_path: &GraphPath) -> Path {
        let motions = CountedMotions::new(self.motions.as_ref());
        let path = self.post_process(graph_path, &motions);
        let (checks, nanoseconds) = (
            motions.checks.load(Relaxed),
            motions.nanoseconds.load(Relaxed),
        );
        self.count_post_processing(checks, nanoseconds);
        path
    }

    /// [`post_processed`](Self::post_processed) for many paths, processed in parallel
    /// (each path's processing is deterministic and independent of the others, so
    /// the paths are the same as one by one; the checking time booked is the sum
    /// over the threads).
    fn post_processed_all(&mut self, graph_paths: &[GraphPath]) -> Vec<Path> {
        let motions = CountedMotions::new(self.motions.as_ref());
        let this = &*self;
        let paths = graph_paths
            .par_iter()
            .map(|graph_path| this.post_process(graph_path, &motions))
            .collect();
        let (checks, nanoseconds) = (
            motions.checks.load(Relaxed),
            motions.nanoseconds.load(Relaxed),
        );
        self.count_post_processing(checks, nanoseconds);
        paths
    }

    fn count_post_processing(&mut self, checks: u64, nanoseconds: u64) {
        self.counts.edge_checks += checks;
        self.counts.breakdown.edge_checking_s += nanoseconds as f64 * 1e-9;
    }

    /// The shortcut or smoothed path of `graph_path`, its checks made through `motions`.
    fn post_process(&self, graph_path: &GraphPath, motions: &CountedMotions) -> Path {
        let states: Vec<Pose2> = graph_path
            .vertices
            .iter()
            .map(|&v| *self.roadmap.pose(v))
            .collect();
        let processed = if self.params.smooth {
            smooth(
                &states,
                motions,
                self.space.as_ref(),
                self.objective.as_ref(),
            )
        } else if self.params.shortcut {
            shortcut(&states, motions)
        } else {
            return Path::new(states, self.objective.as_ref());
        };
        let processed = Path::new(processed, self.objective.as_ref());
        // A shortcut never costs more under a metric objective; under others (risk,
        // energy, time) a straighter path may cross costlier ground: keep the cheaper.
        if processed.cost <= graph_path.cost * (1.0 + 1e-9) + 1e-12 {
            processed
        } else {
            Path::new(states, self.objective.as_ref())
        }
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
        Ok(self.plan_many_on_roadmap(start, goals))
    }

    fn answers_many(&self) -> bool {
        self.params.one_to_many
    }

    fn save_roadmap(&self) -> Option<smug_core::RoadmapSnapshot> {
        Some(self.snapshot())
    }

    fn load_roadmap(
        &mut self,
        snapshot: smug_core::RoadmapSnapshot,
        changed: &[smug_core::ChangedDisc],
    ) -> Result<()> {
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
            ("astar_expansions".to_string(), self.astar.expansions),
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

fn build_planner(params: LazyPrmStarParams, ctx: &BuildContext) -> Result<LazyPrmStar> {
    let bounds = ctx.world()?.bounds();
    Ok(LazyPrmStar::new(
        params,
        ctx.new_sampler()?,
        ctx.state_validity()?,
        ctx.motion_validator()?,
        (ctx.space(), ctx.objective()),
        bounds,
    )?
    .with_expansion_rng(ctx.rng(EXPANSION_STREAM)))
}

smug_core::register_plugin!(
    smug_core::registry::PlannerStage,
    name = "lazy-prm-star",
    summary = "LazyPRM* with informed sampling on one roadmap shared by all queries",
    params = LazyPrmStarParams,
    build = |params, ctx| Ok(Box::new(build_planner(params, ctx)?)),
);

#[cfg(test)]
mod tests {
    use super::test_support::{Free, Lcg, Ring};
    use super::*;
    use smug_core::{PathLength, Se2Space};

    fn planner(params: LazyPrmStarParams) -> Result<LazyPrmStar> {
        LazyPrmStar::new(
            params,
            Box::new(Lcg(7)),
            Arc::new(Free),
            Arc::new(Free),
            (
                Arc::new(Se2Space::default()),
                Arc::new(PathLength::default()),
            ),
            Bounds2 {
                min: [0.0, 0.0],
                max: [10.0, 10.0],
            },
        )
    }

    #[test]
    fn negative_or_non_finite_shares_and_focus_are_rejected() {
        for bad in [-0.1, f64::INFINITY, f64::NAN] {
            let share = LazyPrmStarParams {
                attempt_share: bad,
                ..LazyPrmStarParams::default()
            };
            let focus = LazyPrmStarParams {
                focus: bad,
                ..LazyPrmStarParams::default()
            };
            assert!(planner(share).is_err(), "attempt_share {bad}");
            assert!(planner(focus).is_err(), "focus {bad}");
        }
    }

    #[test]
    fn improvement_rounds_scale_with_the_samples_the_first_path_needed() {
        let params = LazyPrmStarParams {
            attempt_share: 0.1,
            ..LazyPrmStarParams::default()
        };
        assert_eq!(
            improvement_interval(&params, 0),
            5,
            "a path on the roadmap as is"
        );
        assert_eq!(
            improvement_interval(&params, 30),
            5,
            "at least attempt_every"
        );
        assert_eq!(improvement_interval(&params, 5_000), 500);
        let reference = LazyPrmStarParams::default();
        assert_eq!(
            improvement_interval(&reference, 5_000),
            5,
            "share 0: the reference"
        );
    }

    #[test]
    fn the_focus_alternates_with_the_bounds_and_widens_geometrically() {
        let (a, b) = (Pose2::new(0.0, 0.0, 0.0), Pose2::new(4.0, 0.0, 0.0));
        let mut focus = Focus::new(0.5, 4.0, 100.0, 3);
        let set = focus.next_set(&a, &b).expect("first sample: the focus");
        assert!((set.best_cost - 6.0).abs() < 1e-12);
        assert!(focus.next_set(&a, &b).is_none(), "then the bounds");
        assert!(
            !focus.tick() && !focus.tick() && focus.tick(),
            "due after 3"
        );
        focus.widen(3);
        let set = focus.next_set(&a, &b).unwrap();
        assert!((set.best_cost - 8.0).abs() < 1e-12, "excess 1.0");
        assert!(!focus.covers(10.0) && focus.covers(8.0));
        let small = Focus::new(0.5, 4.0, 5.0, 3);
        assert!(small.covers(1e9), "the focus holds the whole bounds");
        let mut off = Focus::new(0.0, 4.0, 100.0, 3);
        assert!(
            (0..4).all(|_| off.next_set(&a, &b).is_none()),
            "0: no focus"
        );
    }

    #[test]
    fn a_query_in_free_space_finds_the_straight_line_with_every_option() {
        let params = LazyPrmStarParams {
            attempt_share: 0.1,
            focus: 0.5,
            smooth: true,
            ..LazyPrmStarParams::default()
        };
        let mut p = planner(params).unwrap();
        let (a, b) = (Pose2::new(1.0, 1.0, 0.0), Pose2::new(9.0, 8.0, 0.0));
        let outcome = p.plan(&a, &b).unwrap();
        let path = outcome.exact_path().expect("a path");
        assert!((path.cost - a.xy_distance(&b)).abs() < 1e-9);
        assert!(p.stats().counters["samples"] < p.params.max_samples);
    }

    fn ring_planner(retry_cut_off: bool) -> LazyPrmStar {
        let params = LazyPrmStarParams {
            max_samples: 1_000,
            retry_cut_off,
            ..LazyPrmStarParams::default()
        };
        LazyPrmStar::new(
            params,
            Box::new(Lcg(7)),
            Arc::new(Ring),
            Arc::new(Ring),
            (
                Arc::new(Se2Space::default()),
                Arc::new(PathLength::default()),
            ),
            Bounds2 {
                min: [0.0, 0.0],
                max: [10.0, 10.0],
            },
        )
        .unwrap()
    }

    #[test]
    fn a_spent_time_budget_is_named_as_such() {
        let mut p = ring_planner(true);
        p.params.max_samples = u64::MAX;
        p.params.time_limit = Some(0.05);
        let outcome = p.plan(&Pose2::new(1.0, 1.0, 0.0), &Pose2::new(8.0, 8.0, 0.0));
        assert_eq!(
            outcome.unwrap(),
            PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::Time))
        );
    }

    #[test]
    fn an_endpoint_in_a_pocket_is_cut_off_after_one_failed_budget() {
        let pocket = Pose2::new(8.0, 8.0, 0.0);
        let mut p = ring_planner(false);
        let first = p.plan(&Pose2::new(1.0, 1.0, 0.0), &pocket).unwrap();
        assert_eq!(
            first,
            PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::Samples))
        );
        let spent = p.stats().counters["samples"];
        assert!(spent >= 1_000, "the whole budget: {spent}");
        let second = p.plan(&pocket, &Pose2::new(1.0, 9.0, 0.0)).unwrap();
        assert_eq!(
            second,
            PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::EarlierQuery))
        );
        assert_eq!(
            p.stats().counters["samples"],
            spent,
            "no budget spent again"
        );
        assert_eq!(p.stats().counters["cut_off_queries"], 1);
        let free = p.plan(&Pose2::new(1.0, 9.0, 0.0), &Pose2::new(1.0, 1.0, 0.0));
        assert!(
            free.unwrap().exact_path().is_some(),
            "the other end is not cut off"
        );

        let mut retried = ring_planner(true);
        retried.plan(&Pose2::new(1.0, 1.0, 0.0), &pocket).unwrap();
        retried.plan(&pocket, &Pose2::new(1.0, 9.0, 0.0)).unwrap();
        assert!(
            retried.stats().counters["samples"] >= 2_000,
            "a second budget"
        );
        assert_eq!(retried.stats().counters["cut_off_queries"], 0);
    }
}
