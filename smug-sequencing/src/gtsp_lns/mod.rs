//! `gtsp-lns`: a large-neighbourhood search for the generalized TSP in the spirit of
//! GLNS (Smith & Imeson 2017).
//!
//! 1. First tour: every cluster inserted at its cheapest place (random order), then
//!    polished: 2-opt on the nodes (symmetric costs) and the cluster sweep — one
//!    layered DP that re-picks every cluster's node for the current order (the `dp`
//!    selector's [`SelectionProblem::solve_layers`](smug_core::SelectionProblem)) —
//!    then the TSP [`LocalSearch`](crate::LocalSearch) reorders the chosen nodes.
//! 2. Each iteration removes 1..`max(10, max_removal_fraction · m)` clusters (random, a segment,
//!    related to a seed node, or the costliest), reinserts them at their cheapest
//!    places with noisy costs, polishes, and on promising tours moves every cluster to
//!    its best place and node ("move-opt"). Simulated annealing decides acceptance.
//!    Each iteration builds `neighbours_per_iteration` such neighbours (side by side
//!    on large instances, each from its own generator) and judges the cheapest.
//! 3. After each epoch the search restarts from the best tour, reordered by the TSP
//!    local search.
//!
//! The start cluster is cluster 0 and stays first; an open tour's end cluster stays
//! last. With `time_limit_s = 0` a seed and `max_iterations` give bit-identical tours.

mod bounds;
mod improve;
mod insertion;
mod params;
mod search;
mod tour;

pub use params::GtspLnsParams;

use crate::costs::{tour_of, validate, validate_clusters, Dist};
use crate::local_search::search_termination;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use search::Search;
use smug_core::rng::{stage_rng, StageRng};
use smug_core::{Clusters, CostMatrix, Deadline, Sequencer, Termination, Tour, TourKind};
use tour::Problem;

/// Large-neighbourhood GTSP search. `Send + Sync`: each solve starts from a copy of
/// the seeded generator, so solves do not influence each other.
#[derive(Clone, Debug)]
pub struct GtspLns {
    params: GtspLnsParams,
    rng: StageRng,
    /// The run's deadline: the search stops at it with its best tour.
    deadline: Deadline,
}

impl GtspLns {
    /// A solver drawing its randomness from `rng` (e.g. `ctx.rng("sequencer")`).
    pub fn new(params: GtspLnsParams, rng: StageRng) -> smug_core::Result<Self> {
        params
            .validate()
            .map_err(|m| smug_core::Error::invalid_param("sequencer", format!("gtsp-lns: {m}")))?;
        Ok(Self {
            params,
            rng,
            deadline: Deadline::new(),
        })
    }

    /// Stops at `deadline` (a run's; by default one that is never armed).
    pub fn with_deadline(mut self, deadline: Deadline) -> Self {
        self.deadline = deadline;
        self
    }

    /// A solver seeded like a pipeline with seed `seed` would seed it.
    pub fn with_seed(params: GtspLnsParams, seed: u64) -> smug_core::Result<Self> {
        Self::new(params, stage_rng(seed, "sequencer"))
    }

    /// Solves and returns the iterations done too.
    pub fn solve_with_iterations(
        &self,
        costs: &CostMatrix,
        clusters: &Clusters,
        kind: TourKind,
    ) -> smug_core::Result<(Tour, u64)> {
        self.solve_from(costs, clusters, kind, None)
    }

    /// Solves from `initial` when it is a valid tour of the clusters (with the warm
    /// iteration budget), else from a first tour of its own; returns the iterations
    /// done too.
    fn solve_from(
        &self,
        costs: &CostMatrix,
        clusters: &Clusters,
        kind: TourKind,
        initial: Option<&Tour>,
    ) -> smug_core::Result<(Tour, u64)> {
        validate_clusters(costs, clusters, kind)?;
        let problem = Problem::new(Dist::new(costs), clusters, kind);
        let mut rng = self.rng.clone();
        let warm = initial
            .filter(|tour| clusters.is_valid_tour(tour, kind))
            .map(|tour| tour.order.clone());
        let (first, rule) = match warm {
            Some(mut order) => {
                problem.polish(&mut order);
                (order, self.warm_termination())
            }
            None => (
                first_tour(&problem, &self.params, &mut rng),
                self.params.termination(),
            ),
        };
        let mut clock = rule.start_within(&self.deadline);
        let mut search = Search::new(&problem, &self.params, rng, first);
        let iterations = search.run(&mut clock);
        let order = problem.turned_to_start(search.best.0);
        Ok((tour_of(costs, order, kind), iterations))
    }

    /// The stopping rule of a warm-started solve.
    fn warm_termination(&self) -> Termination {
        let iterations = match self.params.warm_iterations {
            0 => self.params.max_iterations,
            n => n,
        };
        search_termination(self.params.time_limit_s, iterations)
    }
}

/// Every cluster inserted at its cheapest place in random order, polished and
/// reordered by the TSP local search.
fn first_tour(problem: &Problem, params: &GtspLnsParams, rng: &mut StageRng) -> Vec<usize> {
    let clusters = problem.clusters;
    let mut order = vec![clusters.members(0)[0]];
    let mut rest: Vec<usize> = (1..clusters.len())
        .filter(|&c| Some(c) != problem.end)
        .collect();
    rest.shuffle(rng);
    if let Some(end) = problem.end {
        order.push(clusters.members(end)[0]);
    }
    problem.insert_all(&mut order, &rest, 0.0, rng);
    problem.polish(&mut order);
    let reorder_rng = StageRng::from_rng(rng);
    problem.reorder(&mut order, params.reorder_iterations, 3, &reorder_rng);
    order
}

impl Sequencer for GtspLns {
    fn solve(&self, costs: &CostMatrix, kind: TourKind) -> smug_core::Result<Tour> {
        validate(costs.len(), kind)?;
        self.solve_clusters(costs, &Clusters::singletons(costs.len()), kind)
    }

    fn solve_clusters(
        &self,
        costs: &CostMatrix,
        clusters: &Clusters,
        kind: TourKind,
    ) -> smug_core::Result<Tour> {
        Ok(self.solve_with_iterations(costs, clusters, kind)?.0)
    }

    fn solve_clusters_from(
        &self,
        costs: &CostMatrix,
        clusters: &Clusters,
        kind: TourKind,
        initial: &Tour,
    ) -> smug_core::Result<Tour> {
        Ok(self.solve_from(costs, clusters, kind, Some(initial))?.0)
    }
}

smug_core::register_plugin!(
    smug_core::registry::SequencerStage,
    name = "gtsp-lns",
    summary =
        "GLNS-style large-neighbourhood search for the generalized TSP (any size; also plain TSP)",
    params = GtspLnsParams,
    build = |params, ctx| Ok(Box::new(
        GtspLns::new(params, ctx.rng("sequencer"))?.with_deadline(ctx.deadline())
    )),
);
