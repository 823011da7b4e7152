//! A GTSP tour as the list of its nodes, and what the search does to it: cost,
//! cluster removal and cheapest insertion.

use crate::costs::Dist;
use rand::Rng;
use smug_core::rng::StageRng;
use smug_core::{Clusters, SelectionProblem, TourKind};

/// A stand-in node index for "anywhere": the end of an open tour's sweep.
const ANYWHERE: usize = usize::MAX;

/// The instance as the search sees it: the working matrix, the clusters and whether
/// the last position is fixed (an open tour's end cluster).
pub(crate) struct Problem<'a> {
    /// Finite working copy of the costs.
    pub(crate) dist: Dist,
    /// The clusters; cluster 0 is the start.
    pub(crate) clusters: &'a Clusters,
    /// The end cluster of an open tour.
    pub(crate) end: Option<usize>,
}

impl<'a> Problem<'a> {
    pub(crate) fn new(dist: Dist, clusters: &'a Clusters, kind: TourKind) -> Self {
        let end = match kind {
            TourKind::OpenTo(c) if clusters.len() > 1 => Some(c),
            _ => None,
        };
        Self {
            dist,
            clusters,
            end,
        }
    }

    /// Number of clusters, i.e. the length of a complete tour.
    pub(crate) fn len(&self) -> usize {
        self.clusters.len()
    }

    /// Cost of a tour (closed: with the return leg).
    pub(crate) fn cost(&self, order: &[usize]) -> f64 {
        let legs: f64 = order.windows(2).map(|w| self.dist.d(w[0], w[1])).sum();
        match (self.end, order.first(), order.last()) {
            (None, Some(&first), Some(&last)) => legs + self.dist.d(last, first),
            _ => legs,
        }
    }

    /// The positions a move may take out of a tour of `len` nodes: any of a closed
    /// tour (a cycle, turned to start in cluster 0 at the end), all but the start and
    /// the end of an open one.
    pub(crate) fn movable(&self, len: usize) -> std::ops::Range<usize> {
        match self.end {
            None => 0..len,
            Some(_) => 1..len.saturating_sub(1),
        }
    }

    /// The most clusters a removal may take out of a tour of `len` nodes (one must stay).
    pub(crate) fn most_removable(&self, len: usize) -> usize {
        self.movable(len).len().min(len.saturating_sub(1))
    }

    /// The tour turned to start with its node of cluster 0 (a closed tour is a cycle).
    pub(crate) fn turned_to_start(&self, mut order: Vec<usize>) -> Vec<usize> {
        if let Some(p) = order.iter().position(|&v| self.clusters.of(v) == 0) {
            order.rotate_left(p);
        }
        order
    }

    /// The legs a node may be inserted into, as the position of their first node.
    fn insertion_legs(&self, len: usize) -> std::ops::Range<usize> {
        match self.end {
            None => 0..len,
            Some(_) => 0..len.saturating_sub(1),
        }
    }

    /// Cost of the leg leaving position `p` (the closed tour's last leg wraps).
    pub(crate) fn leg(&self, order: &[usize], p: usize) -> f64 {
        self.dist.d(order[p], order[(p + 1) % order.len()])
    }

    /// The cheapest node of cluster `c` and position to insert it at, with each
    /// insertion cost raised by a random amount in `[0, noise)`: `(position, node,
    /// true added cost)`.
    pub(crate) fn best_insertion(
        &self,
        order: &[usize],
        c: usize,
        noise: f64,
        rng: &mut StageRng,
    ) -> (usize, usize, f64) {
        let mut best = (1, self.clusters.members(c)[0], f64::INFINITY, f64::INFINITY);
        for p in self.insertion_legs(order.len()) {
            let (a, b) = (order[p], order[(p + 1) % order.len()]);
            let removed = self.dist.d(a, b);
            for &v in self.clusters.members(c) {
                let added = self.dist.d(a, v) + self.dist.d_into(v, b) - removed;
                let noisy = if noise > 0.0 {
                    added + noise * rng.random::<f64>()
                } else {
                    added
                };
                if noisy < best.3 {
                    best = (p + 1, v, added, noisy);
                }
            }
        }
        (best.0, best.1, best.2)
    }

    /// Inserts every cluster of `removed`, in that order, at its cheapest place.
    pub(crate) fn insert_all(
        &self,
        order: &mut Vec<usize>,
        removed: &[usize],
        noise: f64,
        rng: &mut StageRng,
    ) {
        for &c in removed {
            let (p, v, _) = self.best_insertion(order, c, noise, rng);
            order.insert(p, v);
        }
    }

    /// The best choice of node per cluster for the order of `order`'s clusters (one
    /// layered DP per node of the first cluster; a closed tour is rotated so that its
    /// smallest cluster comes first), and its cost.
    pub(crate) fn sweep(&self, order: &[usize]) -> (Vec<usize>, f64) {
        let len = order.len();
        if len < 2 {
            return (order.to_vec(), self.cost(order));
        }
        let shift = match self.end {
            Some(_) => 0,
            None => (0..len)
                .min_by_key(|&p| self.clusters.members(self.clusters.of(order[p])).len())
                .unwrap_or(0),
        };
        let cluster_at = |p: usize| self.clusters.of(order[(p + shift) % len]);
        let groups: Vec<Vec<usize>> = (1..len)
            .map(|p| self.clusters.members(cluster_at(p)).to_vec())
            .collect();
        let mut best = (Vec::new(), f64::INFINITY);
        for &s in self.clusters.members(cluster_at(0)) {
            let problem = SelectionProblem {
                start: s,
                groups: groups.clone(),
                end: if self.end.is_some() { ANYWHERE } else { s },
            };
            let solved = problem.solve_layers(|i, j| {
                Ok(if j == ANYWHERE {
                    0.0
                } else {
                    self.dist.d(i, j)
                })
            });
            // The cost closure never fails.
            if let Ok((chosen, cost)) = solved {
                if cost < best.1 || best.0.is_empty() {
                    best = (std::iter::once(s).chain(chosen).collect(), cost);
                }
            }
        }
        let (mut nodes, cost) = best;
        nodes.rotate_right(shift);
        (nodes, cost)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::CostMatrix;

    #[test]
    fn sweep_repicks_nodes_and_keeps_the_start_cluster_first() {
        // Clusters {0, 1}, {2, 3}, {4}; x positions make 1, 3 the right picks.
        let x = [9.0, 0.0, 9.0, 1.0, 2.0_f64];
        let costs = CostMatrix::from_fn(5, |i, j| (x[i] - x[j]).abs()).unwrap();
        let clusters = Clusters::new(5, vec![vec![0, 1], vec![2, 3], vec![4]]).unwrap();
        let problem = Problem::new(Dist::new(&costs), &clusters, TourKind::Closed);
        let (nodes, cost) = problem.sweep(&[0, 2, 4]);
        assert_eq!((nodes, cost), (vec![1, 3, 4], 4.0));
        let open = Problem::new(Dist::new(&costs), &clusters, TourKind::OpenTo(2));
        let (nodes, cost) = open.sweep(&[0, 2, 4]);
        assert_eq!((nodes, cost), (vec![1, 3, 4], 2.0));
        assert_eq!(open.movable(3), 1..2);
        assert_eq!(problem.most_removable(3), 2);
        assert_eq!(problem.turned_to_start(vec![4, 1, 3]), vec![1, 3, 4]);
    }
}
