//! The cheapest insertion of a cluster into a GTSP tour. The [`ClusterBounds`] bound
//! what any member of the cluster can add on a leg, so most legs are skipped unseen;
//! the answer (and the random noise drawn on the way) is the one a scan of every leg and
//! member would give.
//!
//! [`ClusterBounds`]: super::bounds::ClusterBounds

use super::tour::Problem;
use rand::{Rng, RngCore};
use smug_core::rng::StageRng;
use std::cell::Cell;

/// Random access to the noise draws of one insertion: draw `k` is the `k`-th `f64` the
/// generator would give from where the insertion began, whichever draws are skipped.
struct Draws<'r> {
    rng: &'r mut StageRng,
    /// The generator's word position at draw 0 (a draw takes two 32-bit words).
    base: u128,
    /// The draw the generator gives next.
    next: u128,
}

/// Skips of at most this many draws are drawn and dropped rather than sought.
const DROP_AT_MOST: u128 = 32;

impl<'r> Draws<'r> {
    fn new(rng: &'r mut StageRng) -> Self {
        let base = rng.get_word_pos();
        Self { rng, base, next: 0 }
    }

    fn seek(&mut self, k: u128) {
        if k == self.next {
            return;
        }
        if k > self.next && k - self.next <= DROP_AT_MOST {
            for _ in self.next..k {
                self.rng.next_u64();
            }
        } else {
            self.rng.set_word_pos(self.base + 2 * k);
        }
        self.next = k;
    }

    fn at(&mut self, k: u128) -> f64 {
        self.seek(k);
        self.next = k + 1;
        self.rng.random::<f64>()
    }
}

/// The best candidate so far: position, member index, true and noisy added cost.
#[derive(Clone, Copy)]
struct Candidate {
    p: usize,
    k: usize,
    added: f64,
    noisy: f64,
}

/// The scan's state: the cheapest noisy insertion so far (ties go to the earliest leg
/// and member), and the bound below which the first must lie.
struct Best {
    found: Option<Candidate>,
    below: f64,
}

impl Best {
    fn beats(&self, noisy: f64, p: usize, k: usize) -> bool {
        match self.found {
            None => noisy < self.below,
            Some(b) => noisy < b.noisy || (noisy == b.noisy && (p, k) < (b.p, b.k)),
        }
    }

    /// Whether a leg whose every member costs at least `bound` can be skipped.
    fn rules_out(&self, bound: f64, p: usize) -> bool {
        match self.found {
            None => bound >= self.below,
            Some(b) => bound > b.noisy || (bound == b.noisy && p > b.p),
        }
    }
}

impl Problem<'_> {
    /// The cheapest node of cluster `c` and position to insert it at, with each
    /// insertion cost raised by a random amount in `[0, noise)`: `(position, node,
    /// true added cost)`. Draws one number per leg and member (when `noise > 0`).
    pub(crate) fn best_insertion(
        &self,
        order: &[usize],
        legs: &Legs,
        c: usize,
        noise: f64,
        rng: &mut StageRng,
    ) -> (usize, usize, f64) {
        let found = self.cheapest_insertion(order, legs, c, noise, rng, f64::INFINITY);
        found.unwrap_or((1, self.clusters.members(c)[0], f64::INFINITY))
    }

    /// The cheapest insertion of cluster `c` (no noise) if it adds less than `below`.
    pub(crate) fn insertion_below(
        &self,
        order: &[usize],
        legs: &Legs,
        c: usize,
        below: f64,
        rng: &mut StageRng,
    ) -> Option<(usize, usize, f64)> {
        self.cheapest_insertion(order, legs, c, 0.0, rng, below)
    }

    fn cheapest_insertion(
        &self,
        order: &[usize],
        legs: &Legs,
        c: usize,
        noise: f64,
        rng: &mut StageRng,
        below: f64,
    ) -> Option<(usize, usize, f64)> {
        let members = self.clusters.members(c);
        let places = self.insertion_legs(order.len());
        let len = order.len();
        let mut draws = (noise > 0.0).then(|| Draws::new(rng));
        let mut best = Best { found: None, below };
        let mut try_leg = |p: usize, best: &mut Best| {
            let (a, b) = (order[p], order[next_position(p, len)]);
            let removed = legs.cost[p];
            let first_draw = ((p - places.start) * members.len()) as u128;
            for (k, &v) in members.iter().enumerate() {
                let added = self.dist.d(a, v) + self.dist.d_into(v, b) - removed;
                let noisy = match draws.as_mut() {
                    Some(draws) => added + noise * draws.at(first_draw + k as u128),
                    None => added,
                };
                if best.beats(noisy, p, k) {
                    best.found = Some(Candidate { p, k, added, noisy });
                }
            }
        };
        match &self.bounds {
            None => places.clone().for_each(|p| try_leg(p, &mut best)),
            Some(bounds) => {
                // Per leg, the bound from its clusters (in one pass); the one from its
                // nodes only where that does not rule the leg out.
                let mut coarse = legs.coarse.take();
                bounds.cluster_detours(c, &legs.cluster, &legs.cost, places.end, &mut coarse);
                if below == f64::INFINITY {
                    // The leg with the lowest bound first: its answer rules out most others.
                    let lowest = coarse
                        .iter()
                        .enumerate()
                        .min_by(|(_, a), (_, b)| a.total_cmp(b));
                    if let Some((lowest, _)) = lowest {
                        try_leg(lowest, &mut best);
                    }
                }
                for (p, &bound) in coarse.iter().enumerate() {
                    if best.rules_out(bound, p) || best.found.is_some_and(|b| b.p == p) {
                        continue;
                    }
                    let b = order[next_position(p, len)];
                    let fine = bounds.detour(order[p], c, b, legs.cost[p]);
                    if !best.rules_out(fine, p) {
                        try_leg(p, &mut best);
                    }
                }
                legs.coarse.set(coarse);
            }
        }
        if let Some(draws) = draws.as_mut() {
            draws.seek((places.len() * members.len()) as u128);
        }
        best.found.map(|b| (b.p + 1, members[b.k], b.added))
    }

    /// Inserts every cluster of `removed`, in that order, at its cheapest place.
    pub(crate) fn insert_all(
        &self,
        order: &mut Vec<usize>,
        removed: &[usize],
        noise: f64,
        rng: &mut StageRng,
    ) {
        let mut legs = self.legs(order);
        for &c in removed {
            let (p, v, _) = self.best_insertion(order, &legs, c, noise, rng);
            self.insert_at(order, &mut legs, p, v);
        }
    }

    /// The legs of `order` (a closed tour's last leg wraps; an open tour's last entry is
    /// the leg back to the start, never used).
    pub(crate) fn legs(&self, order: &[usize]) -> Legs {
        Legs {
            cost: (0..order.len()).map(|p| self.leg(order, p)).collect(),
            cluster: order.iter().map(|&v| self.clusters.of(v) as u32).collect(),
            coarse: Cell::new(Vec::new()),
        }
    }

    /// Inserts `v` at position `q` (`0..=len`) of `order`, keeping `legs` in step.
    pub(crate) fn insert_at(&self, order: &mut Vec<usize>, legs: &mut Legs, q: usize, v: usize) {
        order.insert(q, v);
        legs.cost.insert(q, self.leg(order, q));
        legs.cluster.insert(q, self.clusters.of(v) as u32);
        let before = (q + order.len() - 1) % order.len();
        legs.cost[before] = self.leg(order, before);
    }

    /// Takes the node at position `p` out of `order` (at least two long), keeping `legs`
    /// in step; returns it.
    pub(crate) fn remove_at(&self, order: &mut Vec<usize>, legs: &mut Legs, p: usize) -> usize {
        let v = order.remove(p);
        legs.cost.remove(p);
        legs.cluster.remove(p);
        let before = (p + order.len() - 1) % order.len();
        legs.cost[before] = self.leg(order, before);
        v
    }
}

/// Per position of a tour, the cost of the leg leaving it and the cluster of its node,
/// kept in step with the tour's nodes.
pub(crate) struct Legs {
    /// `cost[p]`: the leg from position `p` to the next (the last wraps).
    pub(crate) cost: Vec<f64>,
    /// `cluster[p]`: the cluster of the node at position `p`.
    pub(crate) cluster: Vec<u32>,
    /// Scratch space of the insertion scan (the cluster bound per leg), kept to be reused.
    coarse: Cell<Vec<f64>>,
}

/// The position after `p` in a tour of `len` nodes (the last wraps to the first).
#[inline]
fn next_position(p: usize, len: usize) -> usize {
    if p + 1 == len {
        0
    } else {
        p + 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::costs::Dist;
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};
    use smug_core::{Clusters, CostMatrix, TourKind};

    /// A clustered instance: points in a square, clusters of 1..=4 nearby points, costs
    /// the distances times a per-pair detour (asymmetric when `skew`).
    fn instance(
        points: &[(f64, f64)],
        detours: &[f64],
        size: usize,
        skew: bool,
    ) -> (CostMatrix, Clusters) {
        let n = points.len();
        let costs = CostMatrix::from_fn(n, |i, j| {
            let (a, b) = (points[i], points[j]);
            let k = if skew {
                i * n + j
            } else {
                i.min(j) * n + i.max(j)
            };
            (a.0 - b.0).hypot(a.1 - b.1) * detours[k % detours.len()]
        })
        .unwrap();
        let members: Vec<Vec<usize>> = (0..n)
            .collect::<Vec<_>>()
            .chunks(size)
            .map(|c| c.to_vec())
            .collect();
        (costs, Clusters::new(n, members).unwrap())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Insertions, 2-opt and move-opt with the bounds give what the plain scans give,
        /// and leave the generator where the plain scan leaves it.
        #[test]
        fn bounded_scans_equal_plain_scans(
            points in prop::collection::vec((0.0..50.0f64, 0.0..50.0f64), 24..60),
            detours in prop::collection::vec(1.0..1.5f64, 97),
            size in 2usize..=4,
            skew in any::<bool>(),
            open in any::<bool>(),
            noise in prop_oneof![Just(0.0), 0.0..20.0f64],
            seed in any::<u64>(),
        ) {
            let (costs, clusters) = instance(&points, &detours, size, skew);
            let m = clusters.len();
            let kind = if open { TourKind::OpenTo(m - 1) } else { TourKind::Closed };
            let bounded = Problem::new(Dist::new(&costs), &clusters, kind);
            prop_assume!(bounded.bounds.is_some());
            let mut plain = Problem::new(Dist::new(&costs), &clusters, kind);
            plain.bounds = None;
            // A tour of every cluster's first member but one cluster, left out to insert.
            let out = 1 + (seed as usize) % (m - if open { 2 } else { 1 });
            let order: Vec<usize> = (0..m).filter(|&c| c != out).map(|c| clusters.members(c)[0]).collect();
            let legs = plain.legs(&order);
            let (mut r1, mut r2) = (StageRng::seed_from_u64(seed), StageRng::seed_from_u64(seed));
            prop_assert_eq!(
                bounded.best_insertion(&order, &legs, out, noise, &mut r1),
                plain.best_insertion(&order, &legs, out, noise, &mut r2)
            );
            prop_assert_eq!(r1.random::<u64>(), r2.random::<u64>());
            let below = plain.best_insertion(&order, &legs, out, 0.0, &mut r2).2 + 1e-9;
            prop_assert_eq!(
                bounded.insertion_below(&order, &legs, out, below, &mut r1),
                plain.insertion_below(&order, &legs, out, below, &mut r2)
            );
            let mut full: Vec<usize> = (0..m).map(|c| clusters.members(c)[(c + seed as usize) % clusters.members(c).len()]).collect();
            full[1..m - usize::from(open)].reverse();
            let (mut a, mut b) = (full.clone(), full);
            if !skew {
                // 2-opt runs on symmetric costs only (a reversal keeps the legs' costs).
                prop_assert_eq!(bounded.two_opt(&mut a).to_bits(), plain.two_opt(&mut b).to_bits());
                prop_assert_eq!(&a, &b);
            }
            prop_assert_eq!(bounded.move_opt(&mut a, &mut r1).to_bits(), plain.move_opt(&mut b, &mut r2).to_bits());
            prop_assert_eq!(a, b);
        }
    }
}
