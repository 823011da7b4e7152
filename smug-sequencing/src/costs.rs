//! What every solver shares: input validation, a finite working copy of the cost matrix,
//! and turning an order into a [`Tour`] with its true cost.

use crate::error::SequencingError;
use rayon::prelude::*;
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

/// Rows of a matrix one parallel task copies at least.
pub(crate) const ROWS_PER_TASK: usize = 64;

/// Side of the square tiles in which [`symmetry`] and [`transposed`] walk an `n × n`
/// matrix, so that the transposed reads stay in cache.
const TILE: usize = 64;

/// Calls `f(i, j)` on the pairs `i < j` of an `n × n` matrix, tile by tile; stops
/// when `f` returns false.
fn for_upper_pairs_by_tile(n: usize, mut f: impl FnMut(usize, usize) -> bool) {
    for ti in (0..n).step_by(TILE) {
        for tj in (ti..n).step_by(TILE) {
            for i in ti..(ti + TILE).min(n) {
                for j in (i + 1).max(tj)..(tj + TILE).min(n) {
                    if !f(i, j) {
                        return;
                    }
                }
            }
        }
    }
}

/// Whether the row-major `n × n` `data` is symmetric bit for bit, and within `eps`.
fn symmetry(data: &[f64], n: usize, eps: f64) -> (bool, bool) {
    let (mut exact, mut within) = (true, true);
    for_upper_pairs_by_tile(n, |i, j| {
        let (a, b) = (data[i * n + j], data[j * n + i]);
        exact &= a.to_bits() == b.to_bits();
        within &= (a - b).abs() <= eps;
        within
    });
    (exact && within, within)
}

/// The row-major `n × n` `data` transposed.
fn transposed(data: &[f64], n: usize) -> Vec<f64> {
    let mut out = data.to_vec();
    for_upper_pairs_by_tile(n, |i, j| {
        out.swap(i * n + j, j * n + i);
        true
    });
    out
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
    /// The largest finite leg (it sets the penalty and `eps`: [`refill`](Self::refill)
    /// keeps it or starts afresh).
    max_finite: f64,
}

impl Dist {
    /// The working copy of `costs`.
    pub(crate) fn new(costs: &CostMatrix) -> Self {
        let n = costs.len();
        let mut data = vec![0.0; n * n];
        // Rows side by side (on the caller's rayon pool); the maximum and whether a leg
        // is missing do not depend on the order the rows are looked at.
        let (max_finite, missing) = data
            .par_chunks_mut(n.max(1))
            .with_min_len(ROWS_PER_TASK)
            .enumerate()
            .map(|(i, row)| {
                let (mut max_finite, mut missing) = (0.0_f64, false);
                for (j, slot) in row.iter_mut().enumerate() {
                    let c = if i == j { 0.0 } else { costs.get(i, j) };
                    if c.is_finite() {
                        max_finite = max_finite.max(c);
                    } else {
                        missing = true;
                    }
                    *slot = c;
                }
                (max_finite, missing)
            })
            .reduce(|| (0.0, false), |a, b| (a.0.max(b.0), a.1 || b.1));
        if missing {
            let penalty = missing_leg_penalty(n, max_finite);
            for c in data.iter_mut().filter(|c| !c.is_finite()) {
                *c = penalty;
            }
        }
        let eps = (max_finite * 1e-10).max(f64::MIN_POSITIVE);
        let (exactly_symmetric, symmetric) = symmetry(&data, n, eps);
        let into = if exactly_symmetric {
            Vec::new()
        } else {
            transposed(&data, n)
        };
        Self {
            n,
            data,
            into,
            symmetric,
            eps,
            max_finite,
        }
    }

    /// Makes this copy the one [`new`](Self::new) would make of `costs`, in place (no
    /// new allocation, no fresh pages), and returns the rows whose costs changed, in
    /// increasing order; `None` when it had to start afresh instead (another size, an
    /// asymmetric copy, a changed penalty or a change that breaks exact symmetry): then
    /// every row may have changed. A lazy loop solves matrices that differ in a few legs.
    pub(crate) fn refill(&mut self, costs: &CostMatrix) -> Option<Vec<usize>> {
        if costs.len() != self.n || !self.into.is_empty() {
            *self = Self::new(costs);
            return None;
        }
        let n = self.n;
        let penalty = missing_leg_penalty(n, self.max_finite);
        // Per row: the largest finite leg and the columns changed.
        let rows: Vec<(f64, Vec<usize>)> = self
            .data
            .par_chunks_mut(n.max(1))
            .with_min_len(ROWS_PER_TASK)
            .enumerate()
            .map(|(i, row)| {
                let (mut max_finite, mut changed) = (0.0_f64, Vec::new());
                for (j, slot) in row.iter_mut().enumerate() {
                    let c = if i == j { 0.0 } else { costs.get(i, j) };
                    let value = if c.is_finite() {
                        max_finite = max_finite.max(c);
                        c
                    } else {
                        penalty
                    };
                    if slot.to_bits() != value.to_bits() {
                        *slot = value;
                        changed.push(j);
                    }
                }
                (max_finite, changed)
            })
            .collect();
        let max_finite = rows.iter().fold(0.0_f64, |m, r| m.max(r.0));
        // The penalty and `eps` follow from the largest finite leg alone.
        let same_penalty = max_finite.to_bits() == self.max_finite.to_bits();
        let mirrored = rows.iter().enumerate().all(|(i, r)| {
            r.1.iter()
                .all(|&j| self.data[i * n + j].to_bits() == self.data[j * n + i].to_bits())
        });
        if !same_penalty || !mirrored {
            *self = Self::new(costs);
            return None;
        }
        Some(
            rows.iter()
                .enumerate()
                .filter(|(_, r)| !r.1.is_empty())
                .map(|(i, _)| i)
                .collect(),
        )
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

    /// The costs out of `i`: `row(i)[j] == d(i, j)`.
    #[inline]
    pub(crate) fn row(&self, i: usize) -> &[f64] {
        &self.data[i * self.n..(i + 1) * self.n]
    }

    /// The costs into `j`: `row_into(j)[i] == d(i, j)`.
    #[inline]
    pub(crate) fn row_into(&self, j: usize) -> &[f64] {
        let data = if self.into.is_empty() {
            &self.data
        } else {
            &self.into
        };
        &data[j * self.n..(j + 1) * self.n]
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
    fn tiles_cover_every_pair_once_and_transpose_like_the_plain_loop() {
        for n in [0, 1, 2, 63, 64, 65, 130] {
            let mut pairs: Vec<(usize, usize)> = Vec::new();
            for_upper_pairs_by_tile(n, |i, j| {
                pairs.push((i, j));
                true
            });
            let mut sorted = pairs.clone();
            sorted.sort_unstable();
            sorted.dedup();
            let plain: Vec<(usize, usize)> = (0..n)
                .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
                .collect();
            assert_eq!(sorted, plain, "n = {n}");
            assert_eq!(pairs.len(), plain.len());
            let data: Vec<f64> = (0..n * n).map(|k| (k * 7919 % 1009) as f64).collect();
            let t = transposed(&data, n);
            assert!((0..n * n).all(|k| t[k] == data[(k % n) * n + k / n]));
            let symmetric: Vec<f64> = (0..n * n)
                .map(|k| data[k] + data[(k % n) * n + k / n])
                .collect();
            assert_eq!(symmetry(&symmetric, n, 0.0), (true, true));
            let near: Vec<f64> = symmetric
                .iter()
                .enumerate()
                .map(|(k, v)| if k % n > k / n { v + 1e-12 } else { *v })
                .collect();
            assert_eq!(symmetry(&near, n, 1e-9), (n < 2, true));
            assert_eq!(symmetry(&near, n, 0.0).1, n < 2);
        }
    }

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
