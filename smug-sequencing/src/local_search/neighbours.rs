//! Candidate lists: each node's K cheapest successors (and predecessors).

use crate::costs::{Dist, ROWS_PER_TASK};
use rayon::prelude::*;

/// Fewest nodes for which the rows are split between threads: below, one row costs
/// less than handing it to another thread (the joint mode's LNS reorders a few hundred
/// nodes many times a second).
const PARALLEL_FROM: usize = 512;

/// For every node, the `k` nodes with the cheapest legs out of it (`out`) and into it
/// (`into`), cheapest first; for a symmetric matrix both lists are the same.
#[derive(Clone, Debug)]
pub(crate) struct Neighbours {
    k: usize,
    out: Vec<usize>,
    into: Option<Vec<usize>>,
}

impl Neighbours {
    /// Lists of `k` (at most n − 1) candidates per node; from [`PARALLEL_FROM`] nodes
    /// on, rows side by side on the caller's rayon pool (the same lists on any number of
    /// threads).
    pub(crate) fn new(dist: &Dist, k: usize) -> Self {
        let n = dist.len();
        let k = k.min(n.saturating_sub(1));
        let out = Self::cheapest(n, k, |i| dist.row(i));
        let into = (!dist.is_symmetric()).then(|| Self::cheapest(n, k, |j| dist.row_into(j)));
        Self { k, out, into }
    }

    /// The lists of a copy whose `rows` changed (as [`Dist::refill`] reports them),
    /// brought up to date: the same lists as [`new`](Self::new) gives. Only for an
    /// exactly symmetric copy (a changed leg changes both its rows).
    pub(crate) fn refresh_rows(&mut self, dist: &Dist, rows: &[usize]) {
        debug_assert!(self.into.is_none() && dist.is_symmetric());
        if self.k == 0 {
            return;
        }
        let mut best = Vec::with_capacity(self.k + 1);
        for &i in rows {
            let list = &mut self.out[i * self.k..(i + 1) * self.k];
            nearest(dist.row(i), i, &mut best, list);
        }
    }

    /// Number of candidates per node.
    pub(crate) fn k(&self) -> usize {
        self.k
    }

    /// For each `i < n`, the `k` cheapest nodes of `row(i)` other than `i` itself.
    fn cheapest<'d>(n: usize, k: usize, row: impl Fn(usize) -> &'d [f64] + Sync) -> Vec<usize> {
        let mut lists = vec![0; n * k];
        if k == 0 {
            return lists;
        }
        if n < PARALLEL_FROM {
            let mut best = Vec::with_capacity(k + 1);
            for (i, list) in lists.chunks_mut(k).enumerate() {
                nearest(row(i), i, &mut best, list);
            }
            return lists;
        }
        lists
            .par_chunks_mut(k)
            .with_min_len(ROWS_PER_TASK)
            .enumerate()
            .for_each_init(
                || Vec::with_capacity(k + 1),
                |best, (i, list)| nearest(row(i), i, best, list),
            );
        lists
    }

    /// Cheapest successors of `i`.
    #[inline]
    pub(crate) fn out_of(&self, i: usize) -> &[usize] {
        &self.out[i * self.k..(i + 1) * self.k]
    }

    /// Cheapest predecessors of `i`.
    #[inline]
    pub(crate) fn into(&self, i: usize) -> &[usize] {
        let lists = self.into.as_ref().unwrap_or(&self.out);
        &lists[i * self.k..(i + 1) * self.k]
    }
}

/// Fills `list` with the indices of the `list.len()` cheapest entries of `row` other
/// than `skip`, cheapest first, equal costs by index (the order of sorting `(cost,
/// index)` pairs), in one pass over the row; `best` is scratch space.
fn nearest(row: &[f64], skip: usize, best: &mut Vec<(f64, usize)>, list: &mut [usize]) {
    let k = list.len();
    best.clear();
    for (j, &c) in row.iter().enumerate() {
        // Indices only grow, so an equal cost never displaces an earlier entry.
        let full = best.len() == k;
        if j == skip || full && best[k - 1].0.total_cmp(&c).is_le() {
            continue;
        }
        let at = best.partition_point(|b| b.0.total_cmp(&c).is_le());
        if full {
            best.pop();
        }
        best.insert(at, (c, j));
    }
    for (slot, &(_, j)) in list.iter_mut().zip(best.iter()) {
        *slot = j;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use smug_core::CostMatrix;

    /// The lists as a full sort of every row makes them.
    fn sorted_lists(n: usize, k: usize, cost: impl Fn(usize, usize) -> f64) -> Vec<usize> {
        (0..n)
            .flat_map(|i| {
                let mut others: Vec<(f64, usize)> = (0..n)
                    .filter(|&j| j != i)
                    .map(|j| (cost(i, j), j))
                    .collect();
                others.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                others.into_iter().take(k).map(|(_, j)| j)
            })
            .collect()
    }

    fn random_matrix(n: usize, levels: u32, symmetric: bool, seed: u64) -> CostMatrix {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut data: Vec<f64> = (0..n * n)
            .map(|_| f64::from(rng.random_range(1..=levels)))
            .collect();
        if symmetric {
            for i in 0..n {
                for j in 0..i {
                    data[i * n + j] = data[j * n + i];
                }
            }
        }
        CostMatrix::from_fn(n, |i, j| data[i * n + j]).unwrap()
    }

    #[test]
    fn one_pass_lists_equal_a_full_sort_ties_included() {
        for (case, &(n, levels, symmetric)) in [
            (2, 3, true),
            (5, 2, false),
            (12, 3, false),
            (40, 4, true),
            (40, 1000, false),
            (300, 5, false),
        ]
        .iter()
        .enumerate()
        {
            let costs = random_matrix(n, levels, symmetric, case as u64);
            let dist = Dist::new(&costs);
            for k in [0, 1, 3, 10, n] {
                let lists = Neighbours::new(&dist, k);
                let k = k.min(n - 1);
                let out = sorted_lists(n, k, |i, j| dist.d(i, j));
                let into = sorted_lists(n, k, |i, j| dist.d(j, i));
                for i in 0..n {
                    assert_eq!(
                        lists.out_of(i),
                        &out[i * k..(i + 1) * k],
                        "out, n {n} k {k}"
                    );
                    assert_eq!(
                        Neighbours::into(&lists, i),
                        &into[i * k..(i + 1) * k],
                        "into, n {n} k {k}"
                    );
                }
            }
        }
    }

    #[test]
    fn one_thread_and_two_threads_make_the_same_lists() {
        let costs = random_matrix(PARALLEL_FROM + 100, 50, false, 7);
        let dist = Dist::new(&costs);
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| Neighbours::new(&dist, 10))
        };
        let (one, two) = (on(1), on(2));
        assert_eq!(one.out, two.out);
        assert_eq!(one.into, two.into);
        assert!(one.into.is_some());
    }
}
