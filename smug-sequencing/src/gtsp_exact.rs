//! `gtsp-exact`: dynamic programming over clusters for the generalized TSP.
//!
//! For each node `s` of the start cluster 0, `best[S][v]` is the cheapest path that
//! leaves `s`, visits one node of each cluster of `S` (a bitset over clusters `1..m`,
//! the end cluster of an open tour excluded) and ends at node `v` of a cluster in `S`.
//! The order is recovered by recomputing each step's minimum. Time `O(|C₀| 2^m n²)`,
//! memory `2^(m−1) n` costs. On singleton clusters it is Held-Karp.

use crate::costs::{tour_of, validate, validate_clusters, Dist};
use crate::error::SequencingError;
use serde::{Deserialize, Serialize};
use smug_core::{Clusters, CostMatrix, Sequencer, Tour, TourKind};

/// Parameters of [`GtspExact`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GtspExactParams {
    /// Largest instance accepted, in clusters (the start cluster included).
    pub max_clusters: usize,
    /// Largest DP table allowed, in MiB.
    pub max_memory_mib: u64,
}

impl Default for GtspExactParams {
    fn default() -> Self {
        Self {
            max_clusters: 20,
            max_memory_mib: 1024,
        }
    }
}

/// Hard cap on `max_clusters`: beyond it the table cannot be indexed.
const CLUSTER_CAP: usize = 32;

/// Exact GTSP solver for few clusters; closed tours and open ones, any matrix.
#[derive(Clone, Debug)]
pub struct GtspExact {
    params: GtspExactParams,
}

impl GtspExact {
    /// A solver with these limits; `max_clusters` must be in `1..=32`.
    pub fn new(params: GtspExactParams) -> smug_core::Result<Self> {
        if params.max_clusters == 0 || params.max_clusters > CLUSTER_CAP {
            return Err(smug_core::Error::invalid_param(
                "sequencer",
                format!(
                    "gtsp-exact: max_clusters = {} is outside 1..={CLUSTER_CAP}",
                    params.max_clusters
                ),
            ));
        }
        Ok(Self { params })
    }

    /// Bytes of the DP table for `m` clusters over `n` nodes.
    pub fn table_bytes(m: usize, n: usize) -> u128 {
        let sets = 1u128 << m.saturating_sub(1).min(127) as u32;
        sets * n as u128 * std::mem::size_of::<f64>() as u128
    }

    /// Whether `m` clusters over `n` nodes are within this solver's limits.
    pub fn fits(&self, m: usize, n: usize) -> bool {
        self.check_size(m, n).is_ok()
    }

    fn check_size(&self, m: usize, n: usize) -> Result<(), SequencingError> {
        if m > self.params.max_clusters {
            return Err(SequencingError::TooManyNodes {
                solver: "gtsp-exact",
                n: m,
                limit: self.params.max_clusters,
                hint: " (max_clusters; counted in clusters); use gtsp-lns",
            });
        }
        let needed = Self::table_bytes(m, n);
        let limit = u128::from(self.params.max_memory_mib) << 20;
        if needed > limit {
            return Err(SequencingError::TooMuchMemory {
                n,
                needed_mib: u64::try_from(needed.div_ceil(1 << 20)).unwrap_or(u64::MAX),
                limit_mib: self.params.max_memory_mib,
            });
        }
        Ok(())
    }
}

impl Sequencer for GtspExact {
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
        validate_clusters(costs, clusters, kind)?;
        self.check_size(clusters.len(), costs.len())?;
        let dist = Dist::new(costs);
        let mut best: Option<(f64, Vec<usize>)> = None;
        for &start in clusters.members(0) {
            let table = Table::fill(&dist, clusters, kind, start);
            let (cost, order) = table.best_tour();
            if best.as_ref().is_none_or(|(b, _)| cost < *b) {
                best = Some((cost, order));
            }
        }
        // Cluster 0 is never empty, so `best` is set.
        let order = best.map(|(_, order)| order).unwrap_or_default();
        Ok(tour_of(costs, order, kind))
    }
}

/// The DP table for one start node. Cluster `c ≥ 1` is bit `c − 1` of a subset.
struct Table<'a> {
    dist: &'a Dist,
    clusters: &'a Clusters,
    start: usize,
    /// End cluster of an open tour: excluded from the subsets, appended last.
    end: Option<usize>,
    /// `best[S * n + v]`: cheapest path start → … → v through one node of each cluster
    /// of `S` (v in a cluster of `S`).
    best: Vec<f64>,
}

/// Iterates over the set bits of a mask, lowest first.
fn bits(mut mask: usize) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let bit = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            bit
        })
    })
}

impl<'a> Table<'a> {
    fn fill(dist: &'a Dist, clusters: &'a Clusters, kind: TourKind, start: usize) -> Self {
        let (m, n) = (clusters.len(), dist.len());
        let end = match kind {
            TourKind::OpenTo(c) if m > 1 => Some(c),
            _ => None,
        };
        let mut table = Self {
            dist,
            clusters,
            start,
            end,
            best: vec![f64::INFINITY; (1usize << (m - 1)) * n],
        };
        for c in 1..m {
            if Some(c) != end {
                for &v in clusters.members(c) {
                    table.best[(1 << (c - 1)) * n + v] = dist.d(start, v);
                }
            }
        }
        table.relax_all();
        table
    }

    /// The bits of every cluster the subsets range over.
    fn full(&self) -> usize {
        let all = (1usize << (self.clusters.len() - 1)) - 1;
        self.end.map_or(all, |c| all & !(1 << (c - 1)))
    }

    fn relax_all(&mut self) {
        let (full, n) = (self.full(), self.dist.len());
        for set in 1..=full {
            if set & !full != 0 || set.count_ones() < 2 {
                continue;
            }
            for bit in bits(set) {
                for &v in self.clusters.members(bit + 1) {
                    self.best[set * n + v] = self.cheapest_step(set, bit, v).1;
                }
            }
        }
    }

    /// The predecessor of `v` (in cluster `bit + 1`) on the best path through `set`,
    /// and that path's cost.
    fn cheapest_step(&self, set: usize, bit: usize, v: usize) -> (usize, f64) {
        let n = self.dist.len();
        let rest = set & !(1 << bit);
        let mut best = (usize::MAX, f64::INFINITY);
        for other in bits(rest) {
            for &u in self.clusters.members(other + 1) {
                let cost = self.best[rest * n + u] + self.dist.d(u, v);
                if cost < best.1 || best.0 == usize::MAX {
                    best = (u, cost);
                }
            }
        }
        best
    }

    /// The cheapest way to finish from `v`: back to the start, or into the end cluster
    /// (its node and the cost).
    fn finish(&self, v: usize) -> (Option<usize>, f64) {
        match self.end {
            None => (None, self.dist.d(v, self.start)),
            Some(c) => self
                .clusters
                .members(c)
                .iter()
                .map(|&w| (Some(w), self.dist.d(v, w)))
                .fold((None, f64::INFINITY), |a, b| {
                    if b.1 < a.1 || a.0.is_none() {
                        b
                    } else {
                        a
                    }
                }),
        }
    }

    /// The best tour's cost on the working matrix and its nodes in order.
    fn best_tour(&self) -> (f64, Vec<usize>) {
        let (full, n) = (self.full(), self.dist.len());
        if full == 0 {
            let (last, cost) = self.finish(self.start);
            return (cost, std::iter::once(self.start).chain(last).collect());
        }
        let mut pick = (usize::MAX, None, f64::INFINITY);
        for bit in bits(full) {
            for &v in self.clusters.members(bit + 1) {
                let (w, tail) = self.finish(v);
                let cost = self.best[full * n + v] + tail;
                if cost < pick.2 || pick.0 == usize::MAX {
                    pick = (v, w, cost);
                }
            }
        }
        let (mut v, last, cost) = pick;
        let mut reversed: Vec<usize> = last.into_iter().collect();
        let mut set = full;
        while set.count_ones() > 1 {
            reversed.push(v);
            let bit = self.clusters.of(v) - 1;
            let (u, _) = self.cheapest_step(set, bit, v);
            set &= !(1 << bit);
            v = u;
        }
        reversed.push(v);
        reversed.push(self.start);
        reversed.reverse();
        (cost, reversed)
    }
}

smug_core::register_plugin!(
    smug_core::registry::SequencerStage,
    name = "gtsp-exact",
    summary = "exact DP over clusters for the generalized TSP (m ≤ ~16 clusters; also plain TSP)",
    params = GtspExactParams,
    build = |params, _ctx| Ok(Box::new(GtspExact::new(params)?)),
);

#[cfg(test)]
mod tests {
    use super::*;

    fn solver() -> GtspExact {
        GtspExact::new(GtspExactParams::default()).unwrap()
    }

    #[test]
    fn picks_the_cheap_node_of_each_cluster() {
        // Nodes on a line at x = 0, 10, 1, 11, 2; clusters {0}, {1, 2}, {3, 4}.
        let x = [0.0, 10.0, 1.0, 11.0, 2.0_f64];
        let costs = CostMatrix::from_fn(5, |i, j| (x[i] - x[j]).abs()).unwrap();
        let clusters = Clusters::new(5, vec![vec![0], vec![1, 2], vec![3, 4]]).unwrap();
        let tour = solver()
            .solve_clusters(&costs, &clusters, TourKind::Closed)
            .unwrap();
        assert!(
            tour.order == [0, 2, 4] || tour.order == [0, 4, 2],
            "{tour:?}"
        );
        assert_eq!(tour.cost, 4.0);
        let open = solver()
            .solve_clusters(&costs, &clusters, TourKind::OpenTo(1))
            .unwrap();
        assert_eq!((open.order, open.cost), (vec![0, 4, 2], 3.0));
    }

    #[test]
    fn single_clusters_and_errors() {
        let costs = CostMatrix::from_fn(3, |i, j| (i + j) as f64).unwrap();
        let one = Clusters::new(3, vec![vec![0, 1, 2]]).unwrap();
        let tour = solver()
            .solve_clusters(&costs, &one, TourKind::Closed)
            .unwrap();
        assert_eq!((tour.order.len(), tour.cost), (1, 0.0));
        let two = Clusters::new(3, vec![vec![2, 1], vec![0]]).unwrap();
        let open = solver()
            .solve_clusters(&costs, &two, TourKind::OpenTo(1))
            .unwrap();
        assert_eq!((open.order, open.cost), (vec![1, 0], 1.0));
        let err = solver()
            .solve_clusters(&costs, &two, TourKind::OpenTo(2))
            .unwrap_err()
            .to_string();
        assert!(err.contains("end cluster 2"), "{err}");
        let wrong = Clusters::singletons(4);
        assert!(solver()
            .solve_clusters(&costs, &wrong, TourKind::Closed)
            .is_err());
        let many = CostMatrix::from_fn(22, |i, j| (i + j) as f64).unwrap();
        let err = solver()
            .solve(&many, TourKind::Closed)
            .unwrap_err()
            .to_string();
        assert!(err.contains("22") && err.contains("max_clusters"), "{err}");
    }
}
