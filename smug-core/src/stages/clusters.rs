//! Clusters of a generalized TSP (GTSP): the nodes of a cost matrix partitioned into
//! sets, of which a tour visits exactly one node each.

use super::tour::{Tour, TourKind};
use crate::error::{Error, Result};

/// A partition of the nodes `0..n` of a cost matrix into non-empty clusters.
///
/// A GTSP tour starts in cluster 0 and visits one node of every cluster;
/// `TourKind::OpenTo(c)` names the cluster `c` it ends in.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Clusters {
    of_node: Vec<usize>,
    members: Vec<Vec<usize>>,
}

impl Clusters {
    /// Clusters from their member lists; every node of `0..n` must be in exactly one.
    pub fn new(n: usize, members: Vec<Vec<usize>>) -> Result<Self> {
        let mut of_node = vec![usize::MAX; n];
        for (c, nodes) in members.iter().enumerate() {
            if nodes.is_empty() {
                return Err(Error::InvalidInput(format!("cluster {c} is empty")));
            }
            for &v in nodes {
                let slot = of_node.get_mut(v).ok_or_else(|| {
                    Error::InvalidInput(format!("cluster {c}: node {v} is not in 0..{n}"))
                })?;
                if *slot != usize::MAX {
                    return Err(Error::InvalidInput(format!(
                        "node {v} is in clusters {} and {c}",
                        *slot
                    )));
                }
                *slot = c;
            }
        }
        if let Some(v) = of_node.iter().position(|&c| c == usize::MAX) {
            return Err(Error::InvalidInput(format!("node {v} is in no cluster")));
        }
        Ok(Self { of_node, members })
    }

    /// Every node its own cluster (a plain TSP).
    pub fn singletons(n: usize) -> Self {
        Self {
            of_node: (0..n).collect(),
            members: (0..n).map(|v| vec![v]).collect(),
        }
    }

    /// Number of clusters.
    pub fn len(&self) -> usize {
        self.members.len()
    }

    /// True when there is no cluster.
    pub fn is_empty(&self) -> bool {
        self.members.is_empty()
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.of_node.len()
    }

    /// The nodes of cluster `c`.
    pub fn members(&self, c: usize) -> &[usize] {
        &self.members[c]
    }

    /// The cluster of node `v`.
    pub fn of(&self, v: usize) -> usize {
        self.of_node[v]
    }

    /// True when `tour` visits exactly one node of every cluster, starts in cluster 0
    /// and, for `OpenTo(c)`, ends in cluster `c`.
    pub fn is_valid_tour(&self, tour: &Tour, kind: TourKind) -> bool {
        let mut seen = vec![false; self.len()];
        let one_each = tour.order.len() == self.len()
            && tour
                .order
                .iter()
                .all(|&v| v < self.node_count() && !std::mem::replace(&mut seen[self.of(v)], true));
        let starts = tour.order.first().map(|&v| self.of(v)) == Some(0);
        let ends = match kind {
            TourKind::Closed => true,
            TourKind::OpenTo(c) => tour.order.last().map(|&v| self.of(v)) == Some(c),
        };
        one_each && starts && ends
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partitions_are_checked() {
        assert!(Clusters::new(3, vec![vec![0], vec![1, 2]]).is_ok());
        let err = |m: Vec<Vec<usize>>| Clusters::new(3, m).unwrap_err().to_string();
        assert!(err(vec![vec![0], vec![1]]).contains("node 2 is in no cluster"));
        assert!(err(vec![vec![0, 1], vec![1, 2]]).contains("node 1 is in clusters 0 and 1"));
        assert!(err(vec![vec![0, 1, 2], vec![]]).contains("cluster 1 is empty"));
        assert!(err(vec![vec![0, 1, 7]]).contains("node 7"));
    }

    #[test]
    fn tours_visit_one_node_per_cluster() {
        let clusters = Clusters::new(4, vec![vec![0, 3], vec![1], vec![2]]).unwrap();
        let tour = |order: Vec<usize>| Tour { order, cost: 0.0 };
        assert!(clusters.is_valid_tour(&tour(vec![3, 2, 1]), TourKind::Closed));
        assert!(clusters.is_valid_tour(&tour(vec![3, 2, 1]), TourKind::OpenTo(1)));
        assert!(!clusters.is_valid_tour(&tour(vec![3, 2, 1]), TourKind::OpenTo(2)));
        assert!(!clusters.is_valid_tour(&tour(vec![1, 2, 3]), TourKind::Closed));
        assert!(!clusters.is_valid_tour(&tour(vec![0, 3, 1, 2]), TourKind::Closed));
        assert!(!clusters.is_valid_tour(&tour(vec![0, 1]), TourKind::Closed));
        assert_eq!(Clusters::singletons(2).members(1), &[1]);
    }
}
