//! A GTSP tour as the list of its nodes, and what the search does to it: cost,
//! cluster removal and the cluster sweep.

use super::bounds::ClusterBounds;
use crate::costs::Dist;
use smug_core::{Clusters, TourKind};

/// The instance as the search sees it: the working matrix, the clusters and whether
/// the last position is fixed (an open tour's end cluster).
pub(crate) struct Problem<'a> {
    /// Finite working copy of the costs.
    pub(crate) dist: Dist,
    /// The clusters; cluster 0 is the start.
    pub(crate) clusters: &'a Clusters,
    /// The end cluster of an open tour.
    pub(crate) end: Option<usize>,
    /// Bounds on the legs into and out of each cluster (none for single-node clusters).
    pub(crate) bounds: Option<ClusterBounds>,
}

impl<'a> Problem<'a> {
    pub(crate) fn new(dist: Dist, clusters: &'a Clusters, kind: TourKind) -> Self {
        let end = match kind {
            TourKind::OpenTo(c) if clusters.len() > 1 => Some(c),
            _ => None,
        };
        let bounds = ClusterBounds::new(&dist, clusters);
        Self {
            dist,
            clusters,
            end,
            bounds,
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
    pub(crate) fn insertion_legs(&self, len: usize) -> std::ops::Range<usize> {
        match self.end {
            None => 0..len,
            Some(_) => 0..len.saturating_sub(1),
        }
    }

    /// Cost of the leg leaving position `p` (the closed tour's last leg wraps).
    pub(crate) fn leg(&self, order: &[usize], p: usize) -> f64 {
        self.dist.d(order[p], order[(p + 1) % order.len()])
    }

    /// The best choice of node per cluster for the order of `order`'s clusters (one
    /// layered DP per node of the first cluster, the `dp` selector's; a closed tour is
    /// rotated so that its smallest cluster comes first), and its cost.
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
        let layers: Vec<&[usize]> = (1..len)
            .map(|p| self.clusters.members(cluster_at(p)))
            .collect();
        // back[offsets[g] + q]: position in layer g − 1 of the best predecessor of layer
        // g's node q (as `SelectionProblem::solve_layers`, whose ties and sums it keeps).
        let mut offsets = Vec::with_capacity(layers.len());
        let mut total_nodes = 0;
        for layer in &layers {
            offsets.push(total_nodes);
            total_nodes += layer.len();
        }
        let mut back = vec![0_usize; total_nodes];
        let (mut reach, mut next) = (Vec::new(), Vec::new());
        let mut best = (Vec::new(), f64::INFINITY);
        for &s in self.clusters.members(cluster_at(0)) {
            reach.clear();
            reach.extend(layers[0].iter().map(|&p| self.dist.d(s, p)));
            for g in 1..layers.len() {
                next.clear();
                for (q_at, &q) in layers[g].iter().enumerate() {
                    let into_q = self.dist.row_into(q);
                    let mut arg = (0, f64::INFINITY);
                    for (k, &p) in layers[g - 1].iter().enumerate() {
                        let via = reach[k] + into_q[p];
                        if via < arg.1 {
                            arg = (k, via);
                        }
                    }
                    next.push(arg.1);
                    back[offsets[g] + q_at] = arg.0;
                }
                std::mem::swap(&mut reach, &mut next);
            }
            let mut arg = (0, f64::INFINITY);
            for (k, &p) in layers[layers.len() - 1].iter().enumerate() {
                let leg = if self.end.is_some() {
                    0.0
                } else {
                    self.dist.d(p, s)
                };
                let total = reach[k] + leg;
                if total < arg.1 {
                    arg = (k, total);
                }
            }
            if arg.1 < best.1 || best.0.is_empty() {
                let mut nodes = vec![s; len];
                let mut k = arg.0;
                for g in (0..layers.len()).rev() {
                    nodes[g + 1] = layers[g][k];
                    if g > 0 {
                        k = back[offsets[g] + k];
                    }
                }
                best = (nodes, arg.1);
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
