//! What every solver shares: input validation, a finite working copy of the cost matrix,
//! and turning an order into a [`Tour`] with its true cost.

use crate::error::SequencingError;
use smug_core::{Clusters, CostMatrix, Tour, TourKind};

/// Checks that `kind` makes sense for `n` nodes: at least one node, and an open path's end
/// is a node other than the start (`OpenTo(0)` is accepted for a single node).
pub(crate) fn validate(n: usize, kind: TourKind) -> Result<(), SequencingError> {
    if n == 0 {
        return Err(SequencingError::Empty);
    }
    match kind {
        TourKind::OpenTo(end) if end >= n || (end == 0 && n > 1) => {
            Err(SequencingError::BadEnd { end, n })
        }
        _ => Ok(()),
    }
}

/// Checks a GTSP: the clusters partition the matrix's nodes, there is at least one, and
/// an open tour's end cluster is one other than the start cluster 0 (`OpenTo(0)` is
/// accepted for a single cluster).
pub(crate) fn validate_clusters(
    costs: &CostMatrix,
    clusters: &Clusters,
    kind: TourKind,
) -> Result<(), SequencingError> {
    if clusters.node_count() != costs.len() {
        return Err(SequencingError::ClusterMismatch {
            clustered: clusters.node_count(),
            n: costs.len(),
        });
    }
    let m = clusters.len();
    if m == 0 {
        return Err(SequencingError::Empty);
    }
    match kind {
        TourKind::OpenTo(end) if end >= m || (end == 0 && m > 1) => {
            Err(SequencingError::BadEndCluster { end, m })
        }
        _ => Ok(()),
    }
}

/// The tour visiting `order` with its cost under the caller's (original) matrix.
pub(crate) fn tour_of(costs: &CostMatrix, order: Vec<usize>, kind: TourKind) -> Tour {
    let cost = costs.tour_cost(&order, kind);
    Tour { order, cost }
}

/// The only tours there are for one or two nodes.
pub(crate) fn trivial_tour(costs: &CostMatrix, kind: TourKind) -> Option<Tour> {
    (costs.len() <= 2).then(|| tour_of(costs, (0..costs.len()).collect(), kind))
}

/// A dense, finite copy of a cost matrix for the solvers' inner loops.
///
/// `INFINITY` (no path) becomes a penalty larger than any tour made of finite legs, so a
/// tour using `k` missing legs always costs more than one using `k - 1`; the diagonal is 0.
/// Solvers compare costs with [`Dist::eps`] so rounding never makes them cycle.
#[derive(Clone, Debug)]
pub(crate) struct Dist {
    n: usize,
    data: Vec<f64>,
    /// `data` transposed (the costs into node `j` are row `j`), or empty when `data`
    /// is exactly symmetric: then its own row `j` holds them.
    into: Vec<f64>,
    symmetric: bool,
    eps: f64,
}

impl Dist {
    /// The working copy of `costs`.
    pub(crate) fn new(costs: &CostMatrix) -> Self {
        let n = costs.len();
        let max_finite = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| costs.get(i, j))
            .filter(|c| c.is_finite())
            .fold(0.0_f64, f64::max);
        let penalty = missing_leg_penalty(n, max_finite);
        let data: Vec<f64> = (0..n * n)
            .map(|k| {
                let (i, j) = (k / n, k % n);
                let c = costs.get(i, j);
                match (i == j, c.is_finite()) {
                    (true, _) => 0.0,
                    (false, true) => c,
                    (false, false) => penalty,
                }
            })
            .collect();
        let eps = (max_finite * 1e-10).max(f64::MIN_POSITIVE);
        let transposed = |k: usize| data[(k % n) * n + k / n];
        let exactly_symmetric = (0..n * n).all(|k| data[k].to_bits() == transposed(k).to_bits());
        let into = if exactly_symmetric {
            Vec::new()
        } else {
            (0..n * n).map(transposed).collect()
        };
        let mut dist = Self {
            n,
            data,
            into,
            symmetric: false,
            eps,
        };
        dist.symmetric = dist.detect_symmetry();
        dist
    }

    fn detect_symmetry(&self) -> bool {
        (0..self.n)
            .all(|i| (i + 1..self.n).all(|j| (self.d(i, j) - self.d(j, i)).abs() <= self.eps))
    }

    /// Number of nodes.
    pub(crate) fn len(&self) -> usize {
        self.n
    }

    /// Cost from `i` to `j`.
    #[inline]
    pub(crate) fn d(&self, i: usize, j: usize) -> f64 {
        self.data[i * self.n + j]
    }

    /// Cost from `i` to `j` (the same as [`d`](Self::d)), read where the costs into
    /// `j` lie side by side: cheap when `i` runs over nearby nodes, e.g. a cluster.
    #[inline]
    pub(crate) fn d_into(&self, i: usize, j: usize) -> f64 {
        if self.into.is_empty() {
            self.data[j * self.n + i]
        } else {
            self.into[j * self.n + i]
        }
    }

    /// True when `d(i, j) == d(j, i)` for every pair (within `eps`).
    pub(crate) fn is_symmetric(&self) -> bool {
        self.symmetric
    }

    /// The smallest gain that counts as an improvement.
    pub(crate) fn eps(&self) -> f64 {
        self.eps
    }
}

/// A leg cost that exceeds every tour of `n` finite legs of at most `max_finite` each.
fn missing_leg_penalty(n: usize, max_finite: f64) -> f64 {
    let penalty = (n as f64 + 1.0) * (max_finite + 1.0);
    if penalty.is_finite() {
        penalty
    } else {
        f64::MAX / (4.0 * (n as f64 + 1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn costs_into_a_node_read_the_same_as_costs_from_it() {
        let asymmetric =
            CostMatrix::from_fn(7, |i, j| (i * 31 + j * 17 % 5) as f64 + 0.25 * j as f64).unwrap();
        let symmetric = CostMatrix::from_fn(7, |i, j| (i * j + i + j) as f64 * 0.1).unwrap();
        for (costs, is_symmetric) in [(asymmetric, false), (symmetric, true)] {
            let dist = Dist::new(&costs);
            assert_eq!(dist.is_symmetric(), is_symmetric);
            for i in 0..7 {
                for j in 0..7 {
                    assert_eq!(
                        dist.d(i, j).to_bits(),
                        dist.d_into(i, j).to_bits(),
                        "{i} → {j}"
                    );
                }
            }
        }
    }

    #[test]
    fn missing_legs_cost_more_than_any_finite_tour() {
        let m = CostMatrix::from_fn(3, |i, j| if (i, j) == (0, 2) { f64::INFINITY } else { 5.0 })
            .unwrap();
        let dist = Dist::new(&m);
        assert!(dist.d(0, 2) > 3.0 * 5.0);
        assert_eq!(dist.d(1, 1), 0.0);
        assert!(!dist.is_symmetric());
    }

    #[test]
    fn validates_the_end_node() {
        assert_eq!(validate(0, TourKind::Closed), Err(SequencingError::Empty));
        assert!(validate(1, TourKind::OpenTo(0)).is_ok());
        assert!(validate(3, TourKind::OpenTo(0)).is_err());
        assert!(validate(3, TourKind::OpenTo(3)).is_err());
        assert!(validate(3, TourKind::OpenTo(2)).is_ok());
    }
}
