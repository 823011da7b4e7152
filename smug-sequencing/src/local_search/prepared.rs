//! The working copy and candidate lists of a solver's last search, kept for its next
//! one: a lazy loop solves a thousand-node matrix a dozen times, each time with a few
//! legs changed, and building the copy (eight megabytes of fresh pages) and every
//! node's candidate list again cost as much as the warm search itself. What is kept
//! never changes a result: the copy is refilled to what [`Dist::new`] would give and
//! only the candidate lists of changed rows are rebuilt.

use super::neighbours::Neighbours;
use crate::costs::Dist;
use smug_core::CostMatrix;
use std::sync::Mutex;

/// A working copy of a matrix and its candidate lists.
pub(super) struct Prepared {
    /// The finite working copy.
    pub dist: Dist,
    /// Its candidate lists.
    pub neighbours: Neighbours,
}

impl Prepared {
    /// Built afresh from `costs`, with `k` candidates per node.
    fn new(costs: &CostMatrix, k: usize) -> Self {
        let dist = Dist::new(costs);
        let neighbours = Neighbours::new(&dist, k);
        Self { dist, neighbours }
    }
}

/// The [`Prepared`] a solver kept from its last search (none while a search borrows
/// it; a clone of the solver starts without one).
#[derive(Default)]
pub(super) struct PreparedCache(Mutex<Option<Prepared>>);

impl PreparedCache {
    /// The working copy of `costs` with `k` candidates per node: the kept one brought
    /// up to date when it has the same size and list length, else built afresh.
    pub fn take(&self, costs: &CostMatrix, k: usize) -> Prepared {
        let kept = self.0.try_lock().ok().and_then(|mut kept| kept.take());
        let k = k.min(costs.len().saturating_sub(1));
        match kept {
            Some(mut prepared) if prepared.neighbours.k() == k => {
                match prepared.dist.refill(costs) {
                    Some(rows) => prepared.neighbours.refresh_rows(&prepared.dist, &rows),
                    None => prepared.neighbours = Neighbours::new(&prepared.dist, k),
                }
                prepared
            }
            _ => Prepared::new(costs, k),
        }
    }

    /// Keeps `prepared` for the next search (dropped when another search's is kept
    /// already or the lock is busy).
    pub fn keep(&self, prepared: Prepared) {
        if let Ok(mut kept) = self.0.try_lock() {
            kept.get_or_insert(prepared);
        }
    }
}

impl Clone for PreparedCache {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for PreparedCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("PreparedCache")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A symmetric matrix on `n` nodes from `values` (cycled), some legs missing.
    fn symmetric(n: usize, values: &[f64]) -> Vec<f64> {
        let mut data = vec![0.0; n * n];
        let mut k = 0;
        for i in 0..n {
            for j in i + 1..n {
                let v = values[k % values.len()];
                k += 1;
                data[i * n + j] = v;
                data[j * n + i] = v;
            }
        }
        data
    }

    fn matrix(n: usize, data: &[f64]) -> CostMatrix {
        CostMatrix::from_fn(n, |i, j| data[i * n + j]).unwrap()
    }

    /// Everything a search reads of a copy and its lists, bit for bit.
    fn seen(p: &Prepared) -> (Vec<u64>, Vec<u64>, bool, u64, Vec<usize>) {
        let n = p.dist.len();
        let bits = |f: &dyn Fn(usize, usize) -> f64| {
            (0..n * n)
                .map(|k| f(k / n, k % n).to_bits())
                .collect::<Vec<u64>>()
        };
        let lists = (0..n)
            .flat_map(|i| {
                let mut both = p.neighbours.out_of(i).to_vec();
                both.extend_from_slice(Neighbours::into(&p.neighbours, i));
                both
            })
            .collect();
        (
            bits(&|i, j| p.dist.d(i, j)),
            bits(&|i, j| p.dist.d_into(i, j)),
            p.dist.is_symmetric(),
            p.dist.eps().to_bits(),
            lists,
        )
    }

    proptest! {
        /// A kept copy refilled with a changed matrix (legs changed both ways or one
        /// way, legs lost, a new longest leg, another size) reads exactly as one built
        /// afresh, candidate lists included.
        #[test]
        fn a_kept_copy_reads_as_a_fresh_one(
            n in 2usize..40,
            k in 1usize..12,
            values in proptest::collection::vec(
                prop_oneof![8 => 1.0f64..50.0, 1 => Just(f64::INFINITY), 1 => Just(7.0)], 1..60),
            changes in proptest::collection::vec(
                proptest::collection::vec(
                    (0usize..40, 0usize..40, prop_oneof![
                        6 => 1.0f64..50.0, 1 => Just(f64::INFINITY), 1 => Just(80.0)],
                     0u8..4),
                    0..6),
                1..5),
            resize in 0usize..4,
        ) {
            let cache = PreparedCache::default();
            let mut data = symmetric(n, &values);
            cache.keep(cache.take(&matrix(n, &data), k));
            let mut n = n;
            for (round, legs) in changes.iter().enumerate() {
                if round == resize {
                    n += 1;
                    data = symmetric(n, &values);
                }
                for &(i, j, v, how) in legs {
                    let (i, j) = (i % n, j % n);
                    if i == j {
                        continue;
                    }
                    data[i * n + j] = v;
                    // Mostly both ways; now and then one way only (asymmetric).
                    if how > 0 {
                        data[j * n + i] = v;
                    }
                }
                let costs = matrix(n, &data);
                let kept = cache.take(&costs, k);
                prop_assert_eq!(seen(&kept), seen(&Prepared::new(&costs, k.min(n - 1))));
                cache.keep(kept);
            }
        }
    }
}
