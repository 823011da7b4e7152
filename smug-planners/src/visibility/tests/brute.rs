//! Independent brute force for the planner's tests: Dijkstra on explicit graphs, the
//! point visibility graph with exact rational line of sight, the disc's graph of every
//! tangent between every pair of corners.

use crate::visibility::geometry::{circle_tangents, point_tangents, Grid, Pt};
use smug_core::{Pose2, StateValidityChecker};
use std::collections::BinaryHeap;

/// A disc of radius `r` on a grid at 1 m per cell, checked by brute force.
pub(super) struct DiscCheck {
    pub(super) nx: usize,
    pub(super) ny: usize,
    pub(super) blocked: Vec<bool>,
    pub(super) r: f64,
}

impl DiscCheck {
    pub(super) fn is_blocked(&self, i: i64, j: i64) -> bool {
        i < 0
            || j < 0
            || i >= self.nx as i64
            || j >= self.ny as i64
            || self.blocked[j as usize * self.nx + i as usize]
    }

    /// Distance from `(x, y)` to the nearest blocked cell or the outside, every cell.
    pub(super) fn distance(&self, x: f64, y: f64) -> f64 {
        let mut best = x.min(y).min(self.nx as f64 - x).min(self.ny as f64 - y);
        for j in 0..self.ny as i64 {
            for i in 0..self.nx as i64 {
                if self.is_blocked(i, j) {
                    let dx = (i as f64 - x).max(0.0).max(x - i as f64 - 1.0);
                    let dy = (j as f64 - y).max(0.0).max(y - j as f64 - 1.0);
                    best = best.min(dx.hypot(dy));
                }
            }
        }
        best
    }
}

impl StateValidityChecker for DiscCheck {
    fn is_valid(&self, s: &Pose2) -> bool {
        let d = self.distance(s.x, s.y);
        d >= self.r && d > 0.0
    }
}

/// Dijkstra on an explicit graph.
fn dijkstra(n: usize, edges: &[(usize, usize, f64)], s: usize, g: usize) -> Option<f64> {
    let mut adj = vec![Vec::new(); n];
    for &(a, b, w) in edges {
        adj[a].push((b, w));
        adj[b].push((a, w));
    }
    let mut best = vec![f64::INFINITY; n];
    let mut heap = BinaryHeap::new();
    best[s] = 0.0;
    heap.push((std::cmp::Reverse(OrdF(0.0)), s));
    while let Some((std::cmp::Reverse(OrdF(d)), v)) = heap.pop() {
        if d > best[v] {
            continue;
        }
        for &(w, c) in &adj[v] {
            if d + c < best[w] {
                best[w] = d + c;
                heap.push((std::cmp::Reverse(OrdF(d + c)), w));
            }
        }
    }
    best[g].is_finite().then_some(best[g])
}

#[derive(PartialEq)]
struct OrdF(f64);
impl Eq for OrdF {}
impl Ord for OrdF {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&o.0)
    }
}
impl PartialOrd for OrdF {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}

// ---- A point robot (the limit r → 0) with exact rational line of sight ----

/// A rational `n / d`, `d > 0`.
#[derive(Clone, Copy, Debug)]
struct Q(i128, i128);

impl Q {
    fn eq(self, o: Q) -> bool {
        self.0 * o.1 == o.0 * self.1
    }
    fn floor(self) -> i128 {
        self.0.div_euclid(self.1)
    }
    fn is_int(self) -> bool {
        self.0.rem_euclid(self.1) == 0
    }
}

/// The cells (in unit-cell indices) whose closure holds the point `(x, y)` given in
/// half-cells; empty unless the point lies on no vertex.
fn cells_at(x: Q, y: Q) -> Vec<(i64, i64)> {
    let axis = |v: Q| -> Vec<i64> {
        // v in half-cells: cell k covers [2k, 2k + 2].
        let half = Q(v.0, v.1 * 2);
        if half.is_int() {
            let k = half.floor() as i64;
            vec![k - 1, k]
        } else {
            vec![half.floor() as i64]
        }
    };
    let (xs, ys) = (axis(x), axis(y));
    ys.iter()
        .flat_map(|&j| xs.iter().map(move |&i| (i, j)))
        .collect()
}

/// Exact line of sight of a point robot between half-cell points `p` and `q`: every
/// piece of the segment lies in (or on the edge of) a free cell, and at every grid
/// vertex it passes, the free cells before and after are joined around the vertex.
fn los0(check: &DiscCheck, p: [i64; 2], q: [i64; 2]) -> bool {
    let d = [q[0] - p[0], q[1] - p[1]];
    let mut ts = vec![Q(0, 1), Q(1, 1)];
    for k in 0..2 {
        if d[k] == 0 {
            continue;
        }
        let (lo, hi) = (p[k].min(q[k]), p[k].max(q[k]));
        for line in (lo..=hi).filter(|v| v % 2 == 0) {
            let (mut n, mut den) = ((line - p[k]) as i128, d[k] as i128);
            if den < 0 {
                n = -n;
                den = -den;
            }
            if n > 0 && n < den {
                ts.push(Q(n, den));
            }
        }
    }
    ts.sort_by(|a, b| (a.0 * b.1).cmp(&(b.0 * a.1)));
    ts.dedup_by(|a, b| a.eq(*b));
    let at = |t: Q| {
        (
            Q(p[0] as i128 * t.1 + t.0 * d[0] as i128, t.1),
            Q(p[1] as i128 * t.1 + t.0 * d[1] as i128, t.1),
        )
    };
    let mid = |a: Q, b: Q| Q(a.0 * b.1 + b.0 * a.1, 2 * a.1 * b.1);
    let pieces: Vec<Vec<(i64, i64)>> = ts
        .windows(2)
        .map(|w| {
            let (x, y) = at(mid(w[0], w[1]));
            cells_at(x, y)
        })
        .collect();
    let free = |c: &(i64, i64)| !check.is_blocked(c.0, c.1);
    if !pieces.iter().all(|cells| cells.iter().any(free)) {
        return false;
    }
    for (k, t) in ts
        .iter()
        .enumerate()
        .skip(1)
        .take(ts.len().saturating_sub(2))
    {
        let (x, y) = at(*t);
        let (hx, hy) = (Q(x.0, x.1 * 2), Q(y.0, y.1 * 2));
        if !(hx.is_int() && hy.is_int()) {
            continue;
        }
        let (vx, vy) = (hx.floor() as i64, hy.floor() as i64);
        // Quadrants around the vertex in cyclic order.
        let ring = [(vx - 1, vy - 1), (vx, vy - 1), (vx, vy), (vx - 1, vy)];
        let joined = |a: usize, b: usize| -> bool {
            for dir in [1usize, 3] {
                let mut i = a;
                loop {
                    if !free(&ring[i]) {
                        break;
                    }
                    if i == b {
                        return true;
                    }
                    i = (i + dir) % 4;
                    if i == a {
                        break;
                    }
                }
            }
            false
        };
        let ids = |cells: &Vec<(i64, i64)>| -> Vec<usize> {
            cells
                .iter()
                .filter_map(|c| ring.iter().position(|r| r == c))
                .collect()
        };
        let (before, after) = (ids(&pieces[k - 1]), ids(&pieces[k]));
        if !before.iter().any(|&a| after.iter().any(|&b| joined(a, b))) {
            return false;
        }
    }
    true
}

/// The shortest path of a point robot from `s` to `g` (half-cell coordinates): Dijkstra
/// on the visibility graph of every convex corner, exact line of sight.
pub(super) fn brute_force_point(check: &DiscCheck, s: [i64; 2], g: [i64; 2]) -> Option<f64> {
    let mut nodes = vec![s, g];
    for y in 0..=check.ny as i64 {
        for x in 0..=check.nx as i64 {
            let around = [(x - 1, y - 1), (x, y - 1), (x - 1, y), (x, y)];
            if around.iter().filter(|c| check.is_blocked(c.0, c.1)).count() == 1 {
                nodes.push([2 * x, 2 * y]);
            }
        }
    }
    let mut edges = Vec::new();
    for a in 0..nodes.len() {
        for b in a + 1..nodes.len() {
            if los0(check, nodes[a], nodes[b]) {
                let (dx, dy) = (nodes[b][0] - nodes[a][0], nodes[b][1] - nodes[a][1]);
                edges.push((a, b, (dx as f64).hypot(dy as f64) / 2.0));
            }
        }
    }
    dijkstra(nodes.len(), &edges, 0, 1)
}

// ---- A disc: every tangent between every pair of corner circles ----

/// The shortest path of a disc of radius `r` from `s` to `g` on the explicit graph of
/// all tangent points (every corner pair, no visibility pruning) joined by arcs.
pub(super) fn brute_force_disc(check: &DiscCheck, s: Pt, g: Pt, r: f64) -> Option<f64> {
    let grid = Grid::new(check.nx, check.ny, check.blocked.clone());
    let (rc, need) = (r + 2e-7, r + 1e-7);
    let mut points: Vec<(Option<usize>, f64)> = vec![(None, 0.0), (None, 0.0)];
    let mut edges = Vec::new();
    let clear = |p: Pt, q: Pt, need: f64| grid.segment_clear(p, q, need);
    let cs = check.distance(s[0], s[1]).min(need);
    let cg = check.distance(g[0], g[1]).min(need);
    if clear(s, g, cs.min(cg)) {
        edges.push((0, 1, crate::visibility::geometry::dist(s, g)));
    }
    let corners = grid.corners.clone();
    for (a, ca) in corners.iter().enumerate() {
        for (end, pt, c_end) in [(0usize, s, cs), (1, g, cg)] {
            for n in point_tangents(pt, ca.at, rc) {
                if let Some(rel) = ca.relative_angle(n) {
                    let p = ca.point(rc, rel);
                    if clear(p, pt, c_end) {
                        points.push((Some(a), rel));
                        edges.push((
                            end,
                            points.len() - 1,
                            crate::visibility::geometry::dist(p, pt),
                        ));
                    }
                }
            }
        }
        for (b, cb) in corners.iter().enumerate().skip(a + 1) {
            for (na, nb) in circle_tangents(ca.at, cb.at, rc) {
                let (Some(ra), Some(rb)) = (ca.relative_angle(na), cb.relative_angle(nb)) else {
                    continue;
                };
                let (pa, pb) = (ca.point(rc, ra), cb.point(rc, rb));
                if clear(pa, pb, need) {
                    points.push((Some(a), ra));
                    points.push((Some(b), rb));
                    let n = points.len();
                    edges.push((n - 2, n - 1, crate::visibility::geometry::dist(pa, pb)));
                }
            }
        }
    }
    for (a, corner) in corners.iter().enumerate() {
        let mut on: Vec<(f64, usize)> = points
            .iter()
            .enumerate()
            .filter(|(_, p)| p.0 == Some(a))
            .map(|(i, p)| (p.1, i))
            .collect();
        on.sort_by(|x, y| x.0.total_cmp(&y.0));
        for w in on.windows(2) {
            if grid.arc_clear(corner, rc, w[0].0, w[1].0, need) {
                edges.push((w[0].1, w[1].1, rc * (w[1].0 - w[0].0)));
            }
        }
    }
    dijkstra(points.len(), &edges, 0, 1)
}
