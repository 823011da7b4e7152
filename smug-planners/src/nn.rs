//! Exact k-nearest neighbours under an SE(2) metric with an xy bucket grid.
//!
//! The metric is bounded below by `w_t·‖Δxy‖`, so rings of buckets are searched in
//! order of growing xy distance until the ring's xy lower bound exceeds the current
//! k-th best full distance: the result is exactly the k nearest.

use smug_core::{Bounds2, Pose2, StateSpace};
use std::cmp::Ordering;

/// Points per bucket the grid aims for; it is rebuilt finer as points arrive.
const TARGET_PER_BUCKET: f64 = 2.0;

/// A candidate neighbour: distance then id (ids break ties deterministically).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Neighbour {
    /// Metric distance to the query.
    pub distance: f64,
    /// Vertex id.
    pub id: u32,
}

impl Eq for Neighbour {}

impl Ord for Neighbour {
    fn cmp(&self, other: &Self) -> Ordering {
        self.distance
            .total_cmp(&other.distance)
            .then(self.id.cmp(&other.id))
    }
}

impl PartialOrd for Neighbour {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// The `k` smallest neighbours: candidates are gathered, and cut down to the `k`
/// smallest (by selection, no sorting) whenever the search finishes a ring, which
/// gives the bound the next ring is pruned with. Candidates are kept as one integer
/// each, ordered like [`Neighbour`] (distance by `total_cmp`, then id).
struct KBest {
    k: usize,
    keys: Vec<u128>,
    /// The k-th smallest distance at the last cut (infinite before there were k).
    worst: f64,
    /// `worst²`, rounded up a little so that a squared test never rejects a candidate
    /// that the exact comparison keeps.
    worst_squared: f64,
}

impl KBest {
    /// The `k` best within `radius` (`INFINITY`: any distance).
    fn within(k: usize, radius: f64) -> Self {
        let mut best = Self::new(k);
        if radius.is_finite() {
            best.worst = radius;
            best.worst_squared = radius * radius * (1.0 + 1e-12);
        }
        best
    }

    fn new(k: usize) -> Self {
        Self {
            k,
            keys: Vec::with_capacity(4 * k + 16),
            worst: f64::INFINITY,
            worst_squared: f64::INFINITY,
        }
    }

    /// True once `k` candidates were kept at a cut, or from the start with a finite
    /// radius (the bounds are finite).
    fn is_full(&self) -> bool {
        self.worst.is_finite()
    }

    /// The k-th smallest distance at the last cut (infinite before there were k).
    fn worst(&self) -> f64 {
        self.worst
    }

    /// [`KBest::worst`] squared (a bound compared without a square root).
    fn worst_squared(&self) -> f64 {
        self.worst_squared
    }

    /// Keeps `candidate` unless it is farther than the k-th smallest at the last cut
    /// (ties are kept: the id decides them at the next cut).
    fn offer(&mut self, candidate: Neighbour) {
        if candidate.distance <= self.worst {
            let key = (total_order_key(candidate.distance) as u128) << 32 | candidate.id as u128;
            self.keys.push(key);
        }
    }

    /// Keeps only the `k` smallest candidates and updates the bounds.
    fn cut(&mut self) {
        if self.keys.len() < self.k {
            return;
        }
        if self.keys.len() > self.k {
            self.keys.select_nth_unstable(self.k - 1);
            self.keys.truncate(self.k);
        }
        let worst = from_total_order_key((self.keys.iter().max().expect("k ≥ 1") >> 32) as u64);
        self.worst = worst;
        self.worst_squared = worst * worst * (1.0 + 1e-12);
    }

    /// The `k` smallest, nearest first.
    fn into_sorted(mut self) -> Vec<Neighbour> {
        self.cut();
        self.keys.sort_unstable();
        self.keys
            .iter()
            .map(|&key| Neighbour {
                distance: from_total_order_key((key >> 32) as u64),
                id: key as u32,
            })
            .collect()
    }
}

/// An integer with the order `f64::total_cmp` gives `x`: negative numbers have every
/// bit flipped (larger magnitudes first), the others only their sign bit.
pub(crate) fn total_order_key(x: f64) -> u64 {
    let bits = x.to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | 1 << 63
    }
}

/// The inverse of [`total_order_key`].
pub(crate) fn from_total_order_key(key: u64) -> f64 {
    f64::from_bits(if key >> 63 == 1 {
        key & !(1 << 63)
    } else {
        !key
    })
}

/// Buckets of vertex ids over the map bounds.
#[derive(Clone, Debug)]
pub struct XyGrid {
    bounds: Bounds2,
    cell: f64,
    size: [usize; 2],
    buckets: Vec<Vec<u32>>,
    count: usize,
}

impl XyGrid {
    /// An empty grid over `bounds` with buckets of side `cell`.
    pub fn new(bounds: Bounds2, cell: f64) -> Self {
        let [w, h] = bounds.extent();
        let cell = cell.max(1e-6).max(w.max(h) / 4096.0);
        let size = [
            ((w / cell).ceil() as usize).max(1),
            ((h / cell).ceil() as usize).max(1),
        ];
        Self {
            bounds,
            cell,
            size,
            buckets: vec![Vec::new(); size[0] * size[1]],
            count: 0,
        }
    }

    /// Number of stored ids.
    pub fn len(&self) -> usize {
        self.count
    }

    /// True when empty.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    fn inside(&self, p: &Pose2) -> bool {
        self.bounds.contains(p.x, p.y)
    }

    fn bucket_of(&self, p: &Pose2) -> [usize; 2] {
        let fx = ((p.x - self.bounds.min[0]) / self.cell).floor();
        let fy = ((p.y - self.bounds.min[1]) / self.cell).floor();
        [
            (fx.max(0.0) as usize).min(self.size[0] - 1),
            (fy.max(0.0) as usize).min(self.size[1] - 1),
        ]
    }

    /// Adds `id` at `p`; rebuilds finer when crowded (`poses` gives every id's pose).
    pub fn insert(&mut self, id: u32, p: &Pose2, poses: &[Pose2]) {
        let [i, j] = self.bucket_of(p);
        self.buckets[j * self.size[0] + i].push(id);
        self.count += 1;
        if self.count as f64 > TARGET_PER_BUCKET * 4.0 * self.buckets.len() as f64 {
            self.rebuild(poses);
        }
    }

    /// Removes `id` at `p`.
    pub fn remove(&mut self, id: u32, p: &Pose2) {
        let [i, j] = self.bucket_of(p);
        let bucket = &mut self.buckets[j * self.size[0] + i];
        if let Some(k) = bucket.iter().position(|&v| v == id) {
            bucket.swap_remove(k);
            self.count -= 1;
        }
    }

    fn rebuild(&mut self, poses: &[Pose2]) {
        let [w, h] = self.bounds.extent();
        let cell = (w * h * TARGET_PER_BUCKET / self.count as f64).sqrt();
        let mut ids: Vec<u32> = self.buckets.iter().flatten().copied().collect();
        ids.sort_unstable();
        *self = XyGrid::new(self.bounds, cell);
        for id in ids {
            let [i, j] = self.bucket_of(&poses[id as usize]);
            self.buckets[j * self.size[0] + i].push(id);
            self.count += 1;
        }
    }

    /// The `k` nearest stored ids to `q` under `metric` within `radius` (`INFINITY`:
    /// any distance), excluding `exclude`, nearest first. `w_t` must satisfy
    /// `metric(a, b) ≥ w_t·‖Δxy‖`.
    #[allow(clippy::too_many_arguments)]
    pub fn k_nearest(
        &self,
        q: &Pose2,
        k: usize,
        poses: &[Pose2],
        metric: &dyn StateSpace,
        w_t: f64,
        radius: f64,
        exclude: Option<u32>,
    ) -> Vec<Neighbour> {
        let mut best = KBest::within(k, radius);
        let curved = !metric.is_holonomic();
        if k == 0 {
            return best.into_sorted();
        }
        let consider = |id: u32, best: &mut KBest| {
            if Some(id) == exclude {
                return;
            }
            let p = &poses[id as usize];
            // The xy lower bound rejects most candidates without the full metric.
            let (dx, dy) = (q.x - p.x, q.y - p.y);
            if w_t * w_t * (dx * dx + dy * dy) > best.worst_squared() {
                return;
            }
            if !curved {
                best.offer(Neighbour {
                    distance: metric.distance(q, p),
                    id,
                });
                return;
            }
            // Curved models' distances are costly: try their cheaper bound first, then
            // ask only for distances that can still make the k nearest.
            if metric.distance_bound(q, p) > best.worst() {
                return;
            }
            if let Some(distance) = metric.distance_within(q, p, best.worst()) {
                best.offer(Neighbour { distance, id });
            }
        };
        if !self.inside(q) {
            self.buckets
                .iter()
                .flatten()
                .for_each(|&id| consider(id, &mut best));
            return best.into_sorted();
        }
        let [ci, cj] = self.bucket_of(q);
        let max_ring = self.size[0].max(self.size[1]);
        for ring in 0..=max_ring {
            if best.is_full() && w_t * self.ring_lower_bound(q, [ci, cj], ring) > best.worst() {
                break;
            }
            self.for_ring(ci, cj, ring, |[i, j], bucket| {
                if bucket.is_empty()
                    || best.is_full() && w_t * self.bucket_lower_bound(q, [i, j]) > best.worst()
                {
                    return;
                }
                bucket.iter().for_each(|&id| consider(id, &mut best))
            });
            best.cut();
        }
        best.into_sorted()
    }

    /// A lower bound of the xy distance from `q` to any point in bucket `(i, j)`.
    fn bucket_lower_bound(&self, q: &Pose2, [i, j]: [usize; 2]) -> f64 {
        let gap = |v: f64, lo: f64| (lo - v).max(v - (lo + self.cell)).max(0.0);
        let dx = gap(q.x, self.bounds.min[0] + i as f64 * self.cell);
        let dy = gap(q.y, self.bounds.min[1] + j as f64 * self.cell);
        (dx * dx + dy * dy).sqrt()
    }

    /// A lower bound of the xy distance from `q` to any point in a bucket of `ring`.
    fn ring_lower_bound(&self, q: &Pose2, [ci, cj]: [usize; 2], ring: usize) -> f64 {
        if ring == 0 {
            return 0.0;
        }
        let r = ring as f64 - 1.0;
        let x_lo = self.bounds.min[0] + (ci as f64 - r) * self.cell;
        let x_hi = self.bounds.min[0] + (ci as f64 + r + 1.0) * self.cell;
        let y_lo = self.bounds.min[1] + (cj as f64 - r) * self.cell;
        let y_hi = self.bounds.min[1] + (cj as f64 + r + 1.0) * self.cell;
        (q.x - x_lo)
            .min(x_hi - q.x)
            .min(q.y - y_lo)
            .min(y_hi - q.y)
            .max(0.0)
    }

    /// Calls `f` on every bucket (with its index) at Chebyshev distance exactly `ring`
    /// from `(ci, cj)`.
    fn for_ring(&self, ci: usize, cj: usize, ring: usize, mut f: impl FnMut([usize; 2], &[u32])) {
        let (ci, cj, r) = (ci as isize, cj as isize, ring as isize);
        let (nx, ny) = (self.size[0] as isize, self.size[1] as isize);
        let mut visit = |i: isize, j: isize| {
            if i >= 0 && j >= 0 && i < nx && j < ny {
                f(
                    [i as usize, j as usize],
                    &self.buckets[(j * nx + i) as usize],
                );
            }
        };
        if r == 0 {
            visit(ci, cj);
            return;
        }
        for i in ci - r..=ci + r {
            visit(i, cj - r);
            visit(i, cj + r);
        }
        for j in cj - r + 1..=cj + r - 1 {
            visit(ci - r, j);
            visit(ci + r, j);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use smug_core::Se2Space;

    proptest! {
        #[test]
        fn k_nearest_equals_brute_force(
            points in proptest::collection::vec((0.0f64..20.0, 0.0f64..10.0, -3.0f64..3.0), 1..300),
            q in (-2.0f64..22.0, -2.0f64..12.0, -3.0f64..3.0),
            k in 1usize..20, w_r in 0.0f64..3.0, cell in 0.05f64..5.0,
        ) {
            let metric = Se2Space::new(1.0, w_r).unwrap();
            let bounds = Bounds2 { min: [0.0, 0.0], max: [20.0, 10.0] };
            let poses: Vec<Pose2> = points.iter().map(|&(x, y, t)| Pose2::new(x, y, t)).collect();
            let mut grid = XyGrid::new(bounds, cell);
            for (id, p) in poses.iter().enumerate() {
                grid.insert(id as u32, p, &poses);
            }
            let q = Pose2::new(q.0, q.1, q.2);
            let fast = grid.k_nearest(&q, k, &poses, &metric, 1.0, f64::INFINITY, Some(0));
            let mut slow: Vec<Neighbour> = (1..poses.len() as u32)
                .map(|id| Neighbour { distance: metric.distance(&q, &poses[id as usize]), id })
                .collect();
            slow.sort();
            slow.truncate(k);
            prop_assert_eq!(fast, slow);
        }
    }

    #[test]
    fn removal_hides_ids() {
        let metric = Se2Space::default();
        let bounds = Bounds2 {
            min: [0.0, 0.0],
            max: [10.0, 10.0],
        };
        let poses = vec![
            Pose2::new(1.0, 1.0, 0.0),
            Pose2::new(2.0, 2.0, 0.0),
            Pose2::new(9.0, 9.0, 0.0),
        ];
        let mut grid = XyGrid::new(bounds, 1.0);
        for (id, p) in poses.iter().enumerate() {
            grid.insert(id as u32, p, &poses);
        }
        grid.remove(1, &poses[1]);
        let got = grid.k_nearest(&poses[0], 1, &poses, &metric, 1.0, f64::INFINITY, Some(0));
        assert_eq!(got[0].id, 2);
        assert_eq!(grid.len(), 2);
    }
}
