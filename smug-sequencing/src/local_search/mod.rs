//! `local-search`: iterated local search with LK-style and Or-opt moves.
//!
//! 1. A construction ([`Construction`]) gives a first cycle.
//! 2. Local search to a local optimum: on symmetric matrices LK-style chains of 2-opt
//!    flips plus Or-opt; on asymmetric ones reversal-free Or-3opt plus Or-opt (see the
//!    `search` module). Candidate legs come from K-nearest lists and nodes are revisited
//!    only when their surroundings change (don't-look bits).
//! 3. Until the budget is spent: a random double bridge on short blocks, local search
//!    around the changed legs; keep the result if it is no worse than the current tour
//!    or close to the best one (within a fifth of an average leg), else roll it back.
//!    The best tour found is returned, never one worse than the construction.
//!
//! An open path 0 → … → end is solved as a cycle whose leg end → 0 no move may remove.
//! The time budget counts from the start of the solve, but the first descent always
//! completes. With `time_limit_s = 0` and `max_iterations` set, a seed gives
//! bit-identical tours.

mod construct;
mod kick;
mod neighbours;
mod prepared;
mod search;
mod tour;

pub use construct::Construction;

use crate::costs::{tour_of, trivial_tour, validate, Dist};
use crate::error::ParamError;
use crate::held_karp::{HeldKarp, HeldKarpParams};
use kick::Kick;
use neighbours::Neighbours;
use prepared::PreparedCache;
use search::Search;
use serde::{Deserialize, Serialize};
use smug_core::rng::{stage_rng, StageRng};
use smug_core::termination::TerminationClock;
use smug_core::{CostMatrix, Deadline, Sequencer, Termination, Tour, TourKind};

/// Below this many nodes the local search hands over to Held-Karp (exact and instant).
const EXACT_BELOW: usize = 13;
/// A perturbed tour is kept when it is within this fraction of an average leg of the
/// best tour (measured on the TSPLIB suite: 0.2 beats both 0 and 0.5).
const ACCEPT_WORSE_FRACTION: f64 = 0.2;
/// A warm start ([`LocalSearch::solve_from_with_stats`]) spends this fraction (1/n)
/// of the budget: its tour is a local optimum of a matrix that differs in a few legs.
const WARM_SHARE: u64 = 4;
/// Longest block a double bridge moves.
const KICK_MAX_BLOCK: usize = 50;
/// A warm start told which nodes' legs changed ([`Sequencer::solve_from_changed`])
/// kicks this many times per changed node (at most the warm budget), each time around
/// one of them. Against the warm budget's kicks anywhere, measured with lazy costs
/// (alternated runs): lunar 1000 × 10, seeds 1–6, mean cost 5384.3 → 5382.7 and time
/// 1.05 → 0.99 s; lunar 48 × 6 and 200 × 10, 10 seeds, mean cost −0.5% and −0.03%;
/// polygon maps of 40 and 60 targets, 10 seeds, the same (optimal) orders in 0.52 and
/// 0.59 s instead of 0.82 and 1.12 s. Two per node cost 0.3% more on lunar 1000 × 10.
const KICKS_PER_CHANGED_NODE: u64 = 5;

/// Parameters of [`LocalSearch`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LocalSearchParams {
    /// Wall-time budget in seconds; 0 = no time limit (the default: then the result
    /// depends only on the seed).
    pub time_limit_s: f64,
    /// Budget of perturbation rounds (double bridge + local search); 0 = no limit.
    pub max_iterations: u64,
    /// Candidate legs per node: the K cheapest (at least 3).
    pub neighbours: usize,
    /// First tour: `"greedy"` or `"nearest-neighbour"`.
    pub construction: Construction,
}

/// Default budget of perturbation rounds: optimal on eil51 after 100 rounds and on
/// kroA100 after 1000 (`smug tsp --time-limit 0 --iterations N`), in about 0.1 s.
const DEFAULT_ITERATIONS: u64 = 1000;

impl Default for LocalSearchParams {
    /// An iteration budget and no time limit, so that a seed fixes the result.
    fn default() -> Self {
        Self {
            time_limit_s: 0.0,
            max_iterations: DEFAULT_ITERATIONS,
            neighbours: 10,
            construction: Construction::Greedy,
        }
    }
}

impl LocalSearchParams {
    /// The stopping rule: the time budget, the iteration budget, or both.
    pub fn termination(&self) -> Termination {
        search_termination(self.time_limit_s, self.max_iterations)
    }

    /// Checks the values; the message names the offending parameter.
    pub fn validate(&self) -> Result<(), ParamError> {
        check_search_budget(self.time_limit_s, self.max_iterations)?;
        if self.neighbours < 3 {
            return Err(ParamError::Neighbours(self.neighbours));
        }
        Ok(())
    }
}

/// A search's stopping rule from its `time_limit_s` (0: none) and `max_iterations`
/// (0: none) parameters.
pub(crate) fn search_termination(time_limit_s: f64, max_iterations: u64) -> Termination {
    let time = (time_limit_s > 0.0).then_some(time_limit_s);
    let iterations = (max_iterations > 0).then_some(max_iterations);
    Termination::from_budgets(time, iterations)
}

/// Checks a search's budget parameters: a finite time ≥ 0, and not both unbounded.
pub(crate) fn check_search_budget(
    time_limit_s: f64,
    max_iterations: u64,
) -> Result<(), ParamError> {
    if !(time_limit_s >= 0.0 && time_limit_s.is_finite()) {
        return Err(ParamError::TimeLimit(time_limit_s));
    }
    if time_limit_s == 0.0 && max_iterations == 0 {
        return Err(ParamError::NeverStops);
    }
    Ok(())
}

/// What a local search run did, besides its tour.
#[derive(Clone, Debug, PartialEq)]
pub struct SearchStats {
    /// True cost of the constructed tour (of the initial tour, for a warm start).
    pub construction_cost: f64,
    /// True cost of the first local optimum.
    pub first_optimum_cost: f64,
    /// Perturbation rounds done.
    pub iterations: u64,
}

/// Iterated local search for any size, matrix and tour kind. `Send + Sync`: each solve
/// starts from a copy of the seeded generator, so solves do not influence each other.
#[derive(Clone, Debug)]
pub struct LocalSearch {
    params: LocalSearchParams,
    rng: StageRng,
    /// The run's deadline: the search stops at it with its best tour.
    deadline: Deadline,
    /// The working copy and candidate lists of the last search, for the next one.
    prepared: PreparedCache,
}

impl LocalSearch {
    /// A solver drawing its randomness from `rng` (e.g. `ctx.rng("sequencer")`).
    pub fn new(params: LocalSearchParams, rng: StageRng) -> smug_core::Result<Self> {
        params.validate().map_err(|m| {
            smug_core::Error::invalid_param("sequencer", format!("local-search: {m}"))
        })?;
        Ok(Self {
            params,
            rng,
            deadline: Deadline::new(),
            prepared: PreparedCache::default(),
        })
    }

    /// Stops at `deadline` (a run's; by default one that is never armed).
    pub fn with_deadline(mut self, deadline: Deadline) -> Self {
        self.deadline = deadline;
        self
    }

    /// A solver seeded like a pipeline with seed `seed` would seed it.
    pub fn with_seed(params: LocalSearchParams, seed: u64) -> smug_core::Result<Self> {
        Self::new(params, stage_rng(seed, "sequencer"))
    }

    /// The parameters.
    pub fn params(&self) -> &LocalSearchParams {
        &self.params
    }

    /// Solves and reports what the search did.
    pub fn solve_with_stats(
        &self,
        costs: &CostMatrix,
        kind: TourKind,
    ) -> smug_core::Result<(Tour, SearchStats)> {
        validate(costs.len(), kind)?;
        if costs.len() < EXACT_BELOW {
            let tour = match trivial_tour(costs, kind) {
                Some(tour) => tour,
                None => HeldKarp::new(HeldKarpParams::default())?.solve(costs, kind)?,
            };
            let stats = SearchStats {
                construction_cost: tour.cost,
                first_optimum_cost: tour.cost,
                iterations: 0,
            };
            return Ok((tour, stats));
        }
        Ok(self.search_from(costs, kind, Start::Cold))
    }

    /// The iterated local search from a constructed tour with the whole budget, or
    /// from a warm start's tour with the warm budget (a [`WARM_SHARE`]th of the
    /// budget; told what changed, [`KICKS_PER_CHANGED_NODE`] per changed node at
    /// most, every node but the changed ones taken as locally optimal and every kick
    /// next to one); never a tour costlier than the one it started from.
    fn search_from(
        &self,
        costs: &CostMatrix,
        kind: TourKind,
        start: Start<'_>,
    ) -> (Tour, SearchStats) {
        let rule = match start {
            Start::Cold => self.params.termination(),
            Start::Warm(_) => self.warm_termination(),
            Start::Changed(_, changed) => self.focused_termination(changed.len()),
        };
        let (initial, changed) = (start.tour(), start.changed());
        let mut clock = rule.start_within(&self.deadline);
        let prepared = self.prepared.take(costs, self.params.neighbours);
        let (dist, neighbours) = (&prepared.dist, &prepared.neighbours);
        let end = match kind {
            TourKind::Closed => None,
            TourKind::OpenTo(end) => Some(end),
        };
        let fixed = end.map(|end| (end, 0));
        let first = match initial {
            Some(tour) => tour.order.clone(),
            None => construct::construct(self.params.construction, dist, neighbours, fixed),
        };
        let construction = tour_of(costs, rotate_to_start(&first, end), kind);

        let mut search = Search::new(dist, neighbours, &first, fixed);
        match changed {
            Some(nodes) => nodes.iter().for_each(|&c| search.activate(c)),
            None => search.activate_all(),
        }
        search.optimise();
        search.tour.commit();
        let first_optimum_cost = costs.tour_cost(&search.tour.path_from(0, end), kind);

        let kick = if dist.is_symmetric() {
            Kick::SegmentSwap
        } else {
            Kick::TripleReversal
        };
        let iterations = self.perturb_until_done(&mut search, kick, &mut clock, changed);
        let tour = tour_of(costs, search.tour.path_from(0, end), kind);
        drop(search);
        self.prepared.keep(prepared);
        let stats = SearchStats {
            construction_cost: construction.cost,
            first_optimum_cost,
            iterations,
        };
        // Moves are judged on the finite working copy; never hand back a worse tour.
        if construction.cost < tour.cost {
            (construction, stats)
        } else {
            (tour, stats)
        }
    }

    /// The stopping rule of a warm start: a [`WARM_SHARE`]th of each budget.
    fn warm_termination(&self) -> Termination {
        let p = &self.params;
        search_termination(
            p.time_limit_s / WARM_SHARE as f64,
            p.max_iterations.div_ceil(WARM_SHARE),
        )
    }

    /// The stopping rule of a warm start told that the legs of `changed` nodes
    /// changed: [`KICKS_PER_CHANGED_NODE`] kicks per node, at most the warm budget.
    fn focused_termination(&self, changed: usize) -> Termination {
        let p = &self.params;
        let focused = KICKS_PER_CHANGED_NODE * changed.max(1) as u64;
        let iterations = match p.max_iterations {
            0 => focused,
            n => n.div_ceil(WARM_SHARE).min(focused),
        };
        search_termination(p.time_limit_s / WARM_SHARE as f64, iterations)
    }

    /// Solves starting from `initial` (a tour of the same nodes found on a matrix that
    /// differs in some legs: the previous round of a lazy loop) with the warm budget;
    /// from scratch when `initial` is not a tour of `costs` of this kind or the
    /// instance is solved exactly.
    pub fn solve_from_with_stats(
        &self,
        costs: &CostMatrix,
        kind: TourKind,
        initial: &Tour,
    ) -> smug_core::Result<(Tour, SearchStats)> {
        self.warm(costs, kind, Start::Warm(initial))
    }

    /// A warm start (`start` is not [`Start::Cold`]), or a solve from scratch when
    /// its tour is not one of `costs` of this kind, a changed node is not a node, or
    /// the instance is solved exactly.
    fn warm(
        &self,
        costs: &CostMatrix,
        kind: TourKind,
        start: Start<'_>,
    ) -> smug_core::Result<(Tour, SearchStats)> {
        validate(costs.len(), kind)?;
        let n = costs.len();
        let usable = start.tour().is_some_and(|tour| tour.is_valid_for(n, kind))
            && start
                .changed()
                .is_none_or(|nodes| nodes.iter().all(|&c| c < n));
        if n < EXACT_BELOW || !usable {
            return self.solve_with_stats(costs, kind);
        }
        Ok(self.search_from(costs, kind, start))
    }

    /// The iterated local search loop; leaves the best tour found in `search` and
    /// returns the rounds done.
    ///
    /// Acceptance: a perturbed-and-reoptimised tour replaces the current one when it is
    /// no worse, or when it is within a small threshold of the best tour (a fraction of
    /// an average leg), which lets the search drift across plateaus and shallow basins.
    fn perturb_until_done(
        &self,
        search: &mut Search<'_>,
        kick: Kick,
        clock: &mut TerminationClock<'_>,
        around: Option<&[usize]>,
    ) -> u64 {
        let mut rng = self.rng.clone();
        let eps = search.dist.eps();
        let mut current = search.cost();
        let mut best = current;
        let mut best_order = search.tour.order().to_vec();
        let threshold = ACCEPT_WORSE_FRACTION * best.abs() / search.tour.len() as f64;
        while !clock.is_done() {
            clock.tick();
            let Some(kick_cost) = search.kick(kick, &mut rng, KICK_MAX_BLOCK, around) else {
                break;
            };
            let candidate = current + kick_cost - search.optimise();
            if candidate <= current || candidate < best + threshold {
                search.tour.commit();
                current = candidate;
                if candidate < best - eps {
                    best = candidate;
                    best_order.clear();
                    best_order.extend_from_slice(search.tour.order());
                }
            } else {
                search.tour.rollback(0);
            }
        }
        if current > best + eps {
            search.reset(&best_order);
        }
        clock.iterations()
    }
}

/// `order` (a cycle) read from node 0, ending at `end` if given.
fn rotate_to_start(order: &[usize], end: Option<usize>) -> Vec<usize> {
    tour::ArrayTour::new(order).path_from(0, end)
}

impl Sequencer for LocalSearch {
    fn solve(&self, costs: &CostMatrix, kind: TourKind) -> smug_core::Result<Tour> {
        Ok(self.solve_with_stats(costs, kind)?.0)
    }

    fn solve_from(
        &self,
        costs: &CostMatrix,
        kind: TourKind,
        initial: &Tour,
    ) -> smug_core::Result<Tour> {
        Ok(self.solve_from_with_stats(costs, kind, initial)?.0)
    }

    fn solve_from_changed(
        &self,
        costs: &CostMatrix,
        kind: TourKind,
        initial: &Tour,
        changed: &[usize],
    ) -> smug_core::Result<Tour> {
        Ok(self.warm(costs, kind, Start::Changed(initial, changed))?.0)
    }
}

/// Where a search starts: a constructed tour, a warm start's tour, or a warm start's
/// tour with the nodes whose legs changed since it was found.
#[derive(Clone, Copy)]
enum Start<'a> {
    Cold,
    Warm(&'a Tour),
    Changed(&'a Tour, &'a [usize]),
}

impl<'a> Start<'a> {
    /// The warm start's tour.
    fn tour(self) -> Option<&'a Tour> {
        match self {
            Start::Cold => None,
            Start::Warm(tour) | Start::Changed(tour, _) => Some(tour),
        }
    }

    /// The nodes whose legs changed, when told.
    fn changed(self) -> Option<&'a [usize]> {
        match self {
            Start::Changed(_, changed) => Some(changed),
            _ => None,
        }
    }
}

/// The tour a construction heuristic gives (what the local search starts from), with
/// `neighbours` candidate legs per node for the greedy construction.
pub fn construct_tour(
    costs: &CostMatrix,
    kind: TourKind,
    method: Construction,
    neighbours: usize,
) -> smug_core::Result<Tour> {
    validate(costs.len(), kind)?;
    if let Some(tour) = trivial_tour(costs, kind) {
        return Ok(tour);
    }
    let dist = Dist::new(costs);
    let lists = Neighbours::new(&dist, neighbours.max(1));
    let end = match kind {
        TourKind::Closed => None,
        TourKind::OpenTo(end) => Some(end),
    };
    let cycle = construct::construct(method, &dist, &lists, end.map(|e| (e, 0)));
    Ok(tour_of(costs, rotate_to_start(&cycle, end), kind))
}

smug_core::register_plugin!(
    smug_core::registry::SequencerStage,
    name = "local-search",
    summary = "iterated LK-style/Or-opt local search (any size; asymmetric and open paths ok)",
    params = LocalSearchParams,
    build = |params, ctx| Ok(Box::new(
        LocalSearch::new(params, ctx.rng("sequencer"))?.with_deadline(ctx.deadline())
    )),
);
