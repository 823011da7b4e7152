//! `auto`: Held-Karp up to a size threshold, local search above it; for clustered
//! (GTSP) problems, `gtsp-exact` while its DP is small and `gtsp-lns` above it.

use crate::gtsp_exact::{GtspExact, GtspExactParams};
use crate::gtsp_lns::{GtspLns, GtspLnsParams};
use crate::held_karp::{HeldKarp, HeldKarpParams};
use crate::local_search::{Construction, LocalSearch, LocalSearchParams};
use serde::{Deserialize, Serialize};
use smug_core::rng::StageRng;
use smug_core::{Clusters, CostMatrix, Sequencer, Tour, TourKind};

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
    /// Largest clustered (GTSP) problem solved exactly by `gtsp-exact`, in DP steps
    /// `2^(clusters−1) · nodes²`; larger ones go to `gtsp-lns` with its defaults (and
    /// `time_limit_s`).
    pub exact_cluster_work: f64,
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
            exact_cluster_work: DEFAULT_EXACT_CLUSTER_WORK,
        }
    }
}

/// Default [`AutoParams::exact_cluster_work`]: measured, the exact DP on the indoor
/// joint problem (13 clusters, 25 nodes: 2.6e6 steps) takes milliseconds per solve and
/// gives the same costs as `gtsp-lns`, on lunar 13×10 (14 clusters, 131 nodes: 1.4e8
/// steps) about 5× the planning time of `gtsp-lns` at the same cost.
pub const DEFAULT_EXACT_CLUSTER_WORK: f64 = 2e7;

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
    exact_cluster_work: f64,
    clusters_exact: GtspExact,
    clusters_heuristic: GtspLns,
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
        if params.exact_cluster_work.is_nan() || params.exact_cluster_work < 0.0 {
            return Err(smug_core::Error::invalid_param(
                "sequencer",
                format!(
                    "auto: exact_cluster_work = {} must be a number ≥ 0",
                    params.exact_cluster_work
                ),
            ));
        }
        Ok(Self {
            threshold: params.threshold,
            exact: HeldKarp::new(exact_params)?,
            heuristic: LocalSearch::new(params.local_search(), rng.clone())?,
            exact_cluster_work: params.exact_cluster_work,
            clusters_exact: GtspExact::new(GtspExactParams::default())?,
            clusters_heuristic: GtspLns::new(
                GtspLnsParams {
                    time_limit_s: params.time_limit_s,
                    ..GtspLnsParams::default()
                },
                rng,
            )?,
        })
    }

    /// The heuristics stop at `deadline` (a run's; by default one that is never armed).
    pub fn with_deadline(mut self, deadline: smug_core::Deadline) -> Self {
        self.heuristic = self.heuristic.with_deadline(deadline.clone());
        self.clusters_heuristic = self.clusters_heuristic.with_deadline(deadline);
        self
    }

    /// Whether the clustered problem goes to `gtsp-exact`: it fits that solver's limits
    /// and needs at most `exact_cluster_work` DP steps.
    fn clusters_exactly(&self, costs: &CostMatrix, clusters: &Clusters) -> bool {
        let (m, n) = (clusters.len(), costs.len());
        let work = 2f64.powi(m.saturating_sub(1) as i32) * (n as f64).powi(2);
        self.clusters_exact.fits(m, n) && work <= self.exact_cluster_work
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

    fn solve_from(
        &self,
        costs: &CostMatrix,
        kind: TourKind,
        initial: &Tour,
    ) -> smug_core::Result<Tour> {
        if costs.len() <= self.threshold {
            self.exact.solve(costs, kind)
        } else {
            self.heuristic.solve_from(costs, kind, initial)
        }
    }

    fn solve_from_changed(
        &self,
        costs: &CostMatrix,
        kind: TourKind,
        initial: &Tour,
        changed: &[usize],
    ) -> smug_core::Result<Tour> {
        if costs.len() <= self.threshold {
            self.exact.solve(costs, kind)
        } else {
            self.heuristic
                .solve_from_changed(costs, kind, initial, changed)
        }
    }

    fn solve_clusters(
        &self,
        costs: &CostMatrix,
        clusters: &Clusters,
        kind: TourKind,
    ) -> smug_core::Result<Tour> {
        if self.clusters_exactly(costs, clusters) {
            self.clusters_exact.solve_clusters(costs, clusters, kind)
        } else {
            self.clusters_heuristic
                .solve_clusters(costs, clusters, kind)
        }
    }

    fn solve_clusters_from(
        &self,
        costs: &CostMatrix,
        clusters: &Clusters,
        kind: TourKind,
        initial: &Tour,
    ) -> smug_core::Result<Tour> {
        if self.clusters_exactly(costs, clusters) {
            // The exact solver needs no start tour.
            self.clusters_exact.solve_clusters(costs, clusters, kind)
        } else {
            self.clusters_heuristic
                .solve_clusters_from(costs, clusters, kind, initial)
        }
    }
}

smug_core::register_plugin!(
    smug_core::registry::SequencerStage,
    name = "auto",
    summary = "held-karp up to `threshold` nodes (default 16: 15 targets, a start and an end), local-search above; clustered (joint mode): gtsp-exact while small, gtsp-lns above",
    params = AutoParams,
    build = |params, ctx| Ok(Box::new(
        Auto::new(params, ctx.rng("sequencer"))?.with_deadline(ctx.deadline())
    )),
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_negative_or_nan_exact_cluster_work_is_refused_naming_it() {
        for bad in [-1.0, f64::NAN] {
            let params = AutoParams {
                exact_cluster_work: bad,
                ..AutoParams::default()
            };
            let err = Auto::new(params, smug_core::rng::stage_rng(1, "sequencer")).unwrap_err();
            assert!(err.to_string().contains("exact_cluster_work"), "{err}");
        }
    }
}
