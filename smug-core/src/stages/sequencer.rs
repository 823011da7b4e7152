//! Sequencer stage: the visiting order of the targets (a TSP over a cost matrix).

use super::clusters::Clusters;
pub use super::tour::{Tour, TourKind};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// A dense `n × n` matrix of travel costs, possibly asymmetric; `INFINITY` = no path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CostMatrix {
    n: usize,
    data: Vec<f64>,
}

impl CostMatrix {
    /// A matrix from row-major data of length `n²`; entries must not be NaN or negative.
    pub fn from_rows(n: usize, data: Vec<f64>) -> Result<Self> {
        if data.len() != n * n {
            return Err(Error::InvalidInput(format!(
                "cost matrix of size {n} needs {} entries, got {}",
                n * n,
                data.len()
            )));
        }
        if let Some(k) = data.iter().position(|c| c.is_nan() || *c < 0.0) {
            return Err(Error::InvalidInput(format!(
                "cost matrix entry ({}, {}) is {}; costs must be ≥ 0 (INFINITY for no path)",
                k / n,
                k % n,
                data[k]
            )));
        }
        Ok(Self { n, data })
    }

    /// A matrix with entries `cost(i, j)`, within the default memory limit.
    pub fn from_fn(n: usize, cost: impl FnMut(usize, usize) -> f64) -> Result<Self> {
        Self::from_fn_within(n, crate::limits::MemoryLimit::default(), cost)
    }

    /// A matrix with entries `cost(i, j)` whose entries (8 bytes each) fit `memory`.
    pub fn from_fn_within(
        n: usize,
        memory: crate::limits::MemoryLimit,
        mut cost: impl FnMut(usize, usize) -> f64,
    ) -> Result<Self> {
        let entries = (n as u128) * (n as u128);
        memory
            .check(&format!("a {n}×{n} cost matrix"), entries, 8)
            .map_err(|e| Error::InvalidInput(e.to_string()))?;
        let data = (0..n * n).map(|k| cost(k / n, k % n)).collect();
        Self::from_rows(n, data)
    }

    /// Sets the cost from `i` to `j`; it must not be NaN or negative (`INFINITY` for
    /// no path).
    pub fn set(&mut self, i: usize, j: usize, cost: f64) -> Result<()> {
        if cost.is_nan() || cost < 0.0 {
            return Err(Error::InvalidInput(format!(
                "cost matrix entry ({i}, {j}) is {cost}; costs must be ≥ 0 (INFINITY for no path)"
            )));
        }
        self.data[i * self.n + j] = cost;
        Ok(())
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.n
    }

    /// True when there are no nodes.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Cost from `i` to `j`.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.data[i * self.n + j]
    }

    /// True when `get(i, j) == get(j, i)` for all pairs (within `tolerance`).
    pub fn is_symmetric(&self, tolerance: f64) -> bool {
        (0..self.n).all(|i| {
            (i + 1..self.n).all(|j| {
                let (a, b) = (self.get(i, j), self.get(j, i));
                a == b || (a - b).abs() <= tolerance
            })
        })
    }

    /// Cost of visiting `order` (which starts at node 0) as a tour of kind `kind`.
    pub fn tour_cost(&self, order: &[usize], kind: TourKind) -> f64 {
        let legs: f64 = order.windows(2).map(|w| self.get(w[0], w[1])).sum();
        match (kind, order.first(), order.last()) {
            (TourKind::Closed, Some(&first), Some(&last)) if order.len() > 1 => {
                legs + self.get(last, first)
            }
            _ => legs,
        }
    }
}

/// Orders the nodes of a cost matrix: a TSP solver.
pub trait Sequencer: Send + Sync {
    /// The best order it finds within its budget, starting at node 0.
    fn solve(&self, costs: &CostMatrix, kind: TourKind) -> Result<Tour>;

    /// [`solve`](Self::solve) warm-started from `initial`, a tour of the same nodes
    /// found on a matrix that differs in some costs (the previous round of a lazy
    /// loop). A solver that can start from a tour does (with its warm budget); the
    /// default solves from scratch.
    fn solve_from(&self, costs: &CostMatrix, kind: TourKind, initial: &Tour) -> Result<Tour> {
        let _ = initial;
        self.solve(costs, kind)
    }

    /// [`solve_from`](Self::solve_from) told which nodes' legs (in or out) changed
    /// since `initial` was found: every other leg costs what it did, so a solver may
    /// look for improvements around `changed` only (the lazy loop's rounds, each of
    /// which plans a few legs of a large tour). The default ignores the hint.
    fn solve_from_changed(
        &self,
        costs: &CostMatrix,
        kind: TourKind,
        initial: &Tour,
        changed: &[usize],
    ) -> Result<Tour> {
        let _ = changed;
        self.solve_from(costs, kind, initial)
    }

    /// The generalized TSP (GTSP): the best tour it finds that visits one node of every
    /// cluster, starting in cluster 0 (and ending in cluster `c` for `OpenTo(c)`); the
    /// tour's `order` lists the visited nodes. Solvers that only order nodes refuse it.
    fn solve_clusters(
        &self,
        costs: &CostMatrix,
        clusters: &Clusters,
        kind: TourKind,
    ) -> Result<Tour> {
        let _ = (costs, clusters, kind);
        Err(Error::invalid_param(
            "sequencer",
            "this solver orders nodes only; a generalized (clustered) problem needs a GTSP \
             solver (`gtsp-exact`, `gtsp-lns`)",
        ))
    }

    /// [`solve_clusters`](Self::solve_clusters) warm-started from `initial`, a tour of
    /// the same clusters found on a matrix that differs in some costs (the previous
    /// round of a lazy loop, whose bounds were since replaced by planned costs). A
    /// solver that can start from a tour does (with its warm budget); the default
    /// solves from scratch.
    fn solve_clusters_from(
        &self,
        costs: &CostMatrix,
        clusters: &Clusters,
        kind: TourKind,
        initial: &Tour,
    ) -> Result<Tour> {
        let _ = initial;
        self.solve_clusters(costs, clusters, kind)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tour_cost_and_validity() {
        let m = CostMatrix::from_fn(3, |i, j| (10 * i + j) as f64).unwrap();
        assert_eq!(m.tour_cost(&[0, 1, 2], TourKind::Closed), 1.0 + 12.0 + 20.0);
        assert_eq!(m.tour_cost(&[0, 1, 2], TourKind::OpenTo(2)), 13.0);
        assert!(!m.is_symmetric(0.0));
        let tour = Tour {
            order: vec![0, 2, 1],
            cost: 0.0,
        };
        assert!(tour.is_valid_for(3, TourKind::Closed));
        assert!(!tour.is_valid_for(3, TourKind::OpenTo(2)));
        assert!(!Tour {
            order: vec![0, 1, 1],
            cost: 0.0
        }
        .is_valid_for(3, TourKind::Closed));
        assert!(!Tour {
            order: vec![1, 0, 2],
            cost: 0.0
        }
        .is_valid_for(3, TourKind::Closed));
    }

    #[test]
    fn rejects_nan_and_wrong_sizes() {
        assert!(CostMatrix::from_rows(2, vec![0.0; 3]).is_err());
        assert!(CostMatrix::from_rows(1, vec![f64::NAN]).is_err());
        assert!(CostMatrix::from_rows(1, vec![f64::INFINITY]).is_ok());
    }
}
