//! Candidate lists: each node's K cheapest successors (and predecessors).

use crate::costs::Dist;

/// For every node, the `k` nodes with the cheapest legs out of it (`out`) and into it
/// (`into`), cheapest first; for a symmetric matrix both lists are the same.
#[derive(Clone, Debug)]
pub(crate) struct Neighbours {
    k: usize,
    out: Vec<usize>,
    into: Option<Vec<usize>>,
}

impl Neighbours {
    /// Lists of `k` (at most n − 1) candidates per node.
    pub(crate) fn new(dist: &Dist, k: usize) -> Self {
        let n = dist.len();
        let k = k.min(n.saturating_sub(1));
        let out = Self::cheapest(n, k, |i, j| dist.d(i, j));
        let into = (!dist.is_symmetric()).then(|| Self::cheapest(n, k, |i, j| dist.d(j, i)));
        Self { k, out, into }
    }

    fn cheapest(n: usize, k: usize, cost: impl Fn(usize, usize) -> f64) -> Vec<usize> {
        let mut lists = Vec::with_capacity(n * k);
        // Each other node with its cost from `i`, looked up once.
        let mut others: Vec<(f64, usize)> = Vec::with_capacity(n);
        for i in 0..n {
            others.clear();
            others.extend((0..n).filter(|&j| j != i).map(|j| (cost(i, j), j)));
            let by_cost =
                |a: &(f64, usize), b: &(f64, usize)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
            if k < others.len() {
                others.select_nth_unstable_by(k, by_cost);
            }
            others.truncate(k);
            others.sort_unstable_by(by_cost);
            lists.extend(others.iter().map(|&(_, j)| j));
        }
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
