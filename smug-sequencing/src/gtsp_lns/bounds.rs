//! Admissible bounds on the legs into and out of each cluster of a GTSP: per node and
//! cluster (the cheapest leg between the node and any member), and per pair of clusters
//! (the cheapest leg between any members; small enough to stay in cache). The search
//! skips legs and moves these bounds rule out, and finds what a full scan would find.

use crate::costs::Dist;
use rayon::prelude::*;
use smug_core::Clusters;

/// The bounds of one matrix and clustering.
pub(crate) struct ClusterBounds {
    n: usize,
    m: usize,
    /// `entering[c · n + a]`: the cheapest leg from node `a` to a member of cluster `c`.
    entering: Vec<f64>,
    /// `leaving[c · n + b]`: the cheapest leg from a member of cluster `c` to node `b`.
    leaving: Vec<f64>,
    /// `between[c · m + e]`: the cheapest leg from a member of `c` to a member of `e`.
    between: Vec<f64>,
    /// `between` transposed: `between_into[e · m + c]` is `between[c · m + e]`.
    between_into: Vec<f64>,
    /// `nearest[c · m..(c + 1) · m]`: the clusters by their cheapest leg from `c`.
    nearest: Vec<u32>,
}

impl ClusterBounds {
    /// The bounds, or `None` when the clusters are nearly all single nodes (then a bound
    /// is the cost itself, and the tables would be as large as the matrix).
    pub(crate) fn new(dist: &Dist, clusters: &Clusters) -> Option<Self> {
        let (n, m) = (dist.len(), clusters.len());
        if m == 0 || 2 * m > n {
            return None;
        }
        // One cluster's rows per task (on the caller's rayon pool).
        let mut entering = vec![f64::INFINITY; m * n];
        let mut leaving = vec![f64::INFINITY; m * n];
        entering
            .par_chunks_mut(n)
            .zip(leaving.par_chunks_mut(n))
            .enumerate()
            .for_each(|(c, (into_c, out_of_c))| {
                let members = clusters.members(c);
                for (a, (lo_in, lo_out)) in into_c.iter_mut().zip(out_of_c.iter_mut()).enumerate() {
                    *lo_in = members
                        .iter()
                        .fold(f64::INFINITY, |lo, &v| lo.min(dist.d(a, v)));
                    *lo_out = members
                        .iter()
                        .fold(f64::INFINITY, |lo, &v| lo.min(dist.d_into(v, a)));
                }
            });
        let mut between = vec![f64::INFINITY; m * m];
        let mut between_into = vec![f64::INFINITY; m * m];
        for e in 0..m {
            for c in 0..m {
                let lo = clusters
                    .members(c)
                    .iter()
                    .fold(f64::INFINITY, |lo, &a| lo.min(entering[e * n + a]));
                between[c * m + e] = lo;
                between_into[e * m + c] = lo;
            }
        }
        let mut nearest = Vec::with_capacity(m * m);
        for c in 0..m {
            let row = &between[c * m..(c + 1) * m];
            let mut by_cost: Vec<u32> = (0..m as u32).collect();
            by_cost.sort_by(|&e, &f| row[e as usize].total_cmp(&row[f as usize]));
            nearest.extend(by_cost);
        }
        Some(Self {
            n,
            m,
            entering,
            leaving,
            between,
            between_into,
            nearest,
        })
    }

    /// A lower bound on `d(a, v) + d(v, b) - removed` over the members `v` of cluster
    /// `c` (`removed` is `d(a, b)`): floating-point addition is monotone, so it holds
    /// after rounding too.
    #[inline]
    pub(crate) fn detour(&self, a: usize, c: usize, b: usize, removed: f64) -> f64 {
        self.entering[c * self.n + a] + self.leaving[c * self.n + b] - removed
    }

    /// Lower bounds on [`detour`](Self::detour) from the clusters `ca` of `a` and `cb` of
    /// `b` alone, `between[ca → c] + between[c → cb] - removed`, of cluster `c` on each of
    /// the first `count` legs of a tour whose positions hold the clusters `cluster` and
    /// whose legs (the last wrapping to the first position) cost `cost`; written to `out`.
    pub(crate) fn cluster_detours(
        &self,
        c: usize,
        cluster: &[u32],
        cost: &[f64],
        count: usize,
        out: &mut Vec<f64>,
    ) {
        let into_c = &self.between_into[c * self.m..(c + 1) * self.m];
        let out_of_c = &self.between[c * self.m..(c + 1) * self.m];
        let bound =
            |ca: u32, cb: u32, removed: f64| into_c[ca as usize] + out_of_c[cb as usize] - removed;
        out.clear();
        out.extend(
            cluster
                .windows(2)
                .zip(cost)
                .take(count)
                .map(|(pair, &removed)| bound(pair[0], pair[1], removed)),
        );
        if count >= cluster.len() && cost.len() >= cluster.len() {
            // The leg from the last position back to the first.
            if let (Some(&last), Some(&first)) = (cluster.last(), cluster.first()) {
                out.push(bound(last, first, cost[cluster.len() - 1]));
            }
        }
    }

    /// Every cluster, by the cheapest leg from a member of `c` to one of its own.
    #[inline]
    pub(crate) fn nearest_out_of(&self, c: usize) -> &[u32] {
        &self.nearest[c * self.m..(c + 1) * self.m]
    }

    /// The cheapest leg from a member of `c` to one of each cluster.
    #[inline]
    pub(crate) fn cheapest_out_of(&self, c: usize) -> &[f64] {
        &self.between[c * self.m..(c + 1) * self.m]
    }
}
