//! `auto`: Held-Karp up to a size threshold, local search above it.

use crate::held_karp::{HeldKarp, HeldKarpParams};
use crate::local_search::{Construction, LocalSearch, LocalSearchParams};
use serde::{Deserialize, Serialize};
use smug_core::rng::StageRng;
use smug_core::{CostMatrix, Sequencer, Tour, TourKind};

/// Parameters of [`Auto`]: the threshold, then the local search's own parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AutoParams {
    /// Largest instance (in nodes, the start included) solved exactly by Held-Karp;
    /// at most 20.
    pub threshold: usize,
    /// Local search: wall-time budget in seconds (0 = none).
    pub time_limit_s: f64,
    /// Local search: budget of perturbation rounds; unset = no limit.
    pub max_iterations: u64,
    /// Local search: candidate legs per node.
    pub neighbours: usize,
    /// Local search: first tour, `"greedy"` or `"nearest-neighbour"`.
    pub construction: Construction,
}

impl Default for AutoParams {
    fn default() -> Self {
        let ls = LocalSearchParams::default();
        Self {
            threshold: 16,
            time_limit_s: ls.time_limit_s,
            max_iterations: ls.max_iterations,
            neighbours: ls.neighbours,
            construction: ls.construction,
        }
    }
}

impl AutoParams {
    /// The local search part.
    pub fn local_search(&self) -> LocalSearchParams {
        LocalSearchParams {
            time_limit_s: self.time_limit_s,
            max_iterations: self.max_iterations,
            neighbours: self.neighbours,
            construction: self.construction,
        }
    }
}

/// Exact for small instances, iterated local search for the rest.
#[derive(Clone, Debug)]
pub struct Auto {
    threshold: usize,
    exact: HeldKarp,
    heuristic: LocalSearch,
}

impl Auto {
    /// The combined solver; the local search draws from `rng`.
    pub fn new(params: AutoParams, rng: StageRng) -> smug_core::Result<Self> {
        let exact_params = HeldKarpParams::default();
        if params.threshold > exact_params.max_nodes {
            return Err(smug_core::Error::invalid_param(
                "sequencer",
                format!(
                    "auto: threshold = {} is above Held-Karp's limit of {} nodes",
                    params.threshold, exact_params.max_nodes
                ),
            ));
        }
        Ok(Self {
            threshold: params.threshold,
            exact: HeldKarp::new(exact_params)?,
            heuristic: LocalSearch::new(params.local_search(), rng)?,
        })
    }
}

impl Sequencer for Auto {
    fn solve(&self, costs: &CostMatrix, kind: TourKind) -> smug_core::Result<Tour> {
        if costs.len() <= self.threshold {
            self.exact.solve(costs, kind)
        } else {
            self.heuristic.solve(costs, kind)
        }
    }
}

smug_core::register_plugin!(
    smug_core::registry::SequencerStage,
    name = "auto",
    summary = "held-karp up to `threshold` nodes (default 16: 15 targets, a start and an end), local-search above",
    params = AutoParams,
    build = |params, ctx| Ok(Box::new(Auto::new(params, ctx.rng("sequencer"))?)),
);
