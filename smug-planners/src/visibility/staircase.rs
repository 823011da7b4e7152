//! Staircase corners a taut path cannot touch unless it starts or ends beside them.
//!
//! A rasterised diagonal edge is a staircase: convex corners `a, c, b, …`, each the
//! next one's step down. When `c` lies strictly on the blocked side of the chord
//! `a → b` of its two staircase neighbours, or on it, the *lid* (the outer tangent of the
//! circles of `a` and `b` on the free side, the chord moved out by `r`) closes a pocket
//! P: the free points below the lid, between the lid and the staircase from `a` to
//! `b` (blocked cells, one connected obstacle once inflated). Every point of `c`'s
//! circle is strictly below the lid (`c` below the chord), so inside P, but its top
//! when `c` is on the chord: there a path only grazes the lid, straight, and the
//! graph keeps the tangent from `a`'s side to `b`'s through it (tangents are left out
//! for passing a corner only when that corner is in the graph).
//!
//! Claim: when the lid is clear, a shortest path whose endpoints are both outside P
//! never touches `c`'s circle below the lid. It could enter P only through the lid, and leave only
//! through it: the part inside runs from a lid point `x` to a lid point `y` and
//! touches a point strictly below the lid, so it is longer than the straight lid piece
//! `x → y`, which is clear, a contradiction with the path being shortest.
//!
//! So the graph leaves such *hidden* corners out, and a query activates the hidden
//! corners whose pocket may hold one of its endpoints (a superset: below the lid's
//! line, within `|ab| + r + 2` of `c`) before it searches. The tests check lengths
//! against the full tangent graph and brute force on staircase maps.

use super::geometry::{dist, Grid, Pt};

/// The pocket of a hidden corner: the lid's line `n · (p − a) = r` (`n` the unit
/// normal of the chord on the free side) and how far from the corner the pocket may
/// reach.
#[derive(Clone, Copy, Debug)]
pub struct Pocket {
    /// The chord's first end (a grid vertex).
    pub a: Pt,
    /// The chord's unit normal towards the free side.
    pub n: Pt,
    /// Farthest a pocket point may be from the corner.
    pub reach: f64,
}

impl Pocket {
    /// True when `q` may lie in the pocket of the corner at `c`, for circles of
    /// radius `r` (a superset of the pocket).
    pub fn may_hold(&self, c: Pt, q: Pt, r: f64) -> bool {
        let below = self.n[0] * (q[0] - self.a[0]) + self.n[1] * (q[1] - self.a[1]);
        below <= r + 1e-9 && dist(c, q) <= self.reach
    }
}

/// Longest run (cells) a staircase step is followed.
const MAX_RUN: i64 = 4096;

/// The mirror of a corner's frame: `(fx, fy)` such that in local coordinates
/// `(fx·x, fy·y)` its blocked cell is the lower-right one.
fn flips(grid: &Grid, c: u32) -> (i64, i64) {
    let q0 = grid.corners[c as usize].q0;
    // q0: 0 blocked lower-left, π/2 lower-right, −π/2 upper-left, −π upper-right.
    if q0 == 0.0 {
        (-1, 1)
    } else if q0 > 0.0 {
        (1, 1)
    } else if q0 > -2.0 {
        (-1, -1)
    } else {
        (1, -1)
    }
}

/// The next corner up corner `c`'s staircase (in its local frame: along the top of
/// its blocked cell's row to the right, then up the next column), if the staircase
/// goes on: a corner of the same orientation.
fn next_step(grid: &Grid, c: u32) -> Option<u32> {
    let (fx, fy) = flips(grid, c);
    let at = grid.corners[c as usize].at;
    let (x, y) = (fx * at[0] as i64, fy * at[1] as i64);
    let cell = |i: i64, j: i64| {
        let gi = if fx == 1 { i } else { -i - 1 };
        let gj = if fy == 1 { j } else { -j - 1 };
        grid.blocked(gi, gj)
    };
    // Along the row: blocked below, free above.
    let mut i = x;
    while cell(i, y - 1) && !cell(i, y) {
        i += 1;
        if i - x > MAX_RUN {
            return None;
        }
    }
    // A rise: blocked at (i, y) over a blocked (i, y − 1).
    if i == x || !cell(i, y) || !cell(i, y - 1) {
        return None;
    }
    // Up the column: blocked on the right, free on the left.
    let mut j = y;
    while cell(i, j) && !cell(i - 1, j) {
        j += 1;
        if j - y > MAX_RUN {
            return None;
        }
    }
    if cell(i, j) || cell(i - 1, j) {
        return None;
    }
    grid.corner_at(fx * i, fy * j)
}

/// The pocket of every hidden corner (`None`: the corner stays in the graph), for
/// circles of radius `r` and segments kept `r_check` clear.
pub fn hidden_corners(grid: &Grid, r: f64, r_check: f64) -> Vec<Option<Pocket>> {
    let n = grid.corners.len();
    let next: Vec<Option<u32>> = (0..n as u32).map(|c| next_step(grid, c)).collect();
    let mut prev: Vec<Option<u32>> = vec![None; n];
    for (c, b) in next.iter().enumerate() {
        if let Some(b) = *b {
            prev[b as usize] = Some(c as u32);
        }
    }
    (0..n)
        .map(|c| {
            let (a, b) = (prev[c]?, next[c]?);
            let (pa, pb, pc) = (
                grid.corners[a as usize].at,
                grid.corners[b as usize].at,
                grid.corners[c].at,
            );
            // Integer vertices: the cross product is exact.
            let cross = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0]);
            let len = dist(pa, pb);
            if len == 0.0 {
                return None;
            }
            // The free side is where c is not (on the chord: where its normals are).
            let normal = |side: f64| [side * -(pb[1] - pa[1]) / len, side * (pb[0] - pa[0]) / len];
            let on_chord_side =
                cross == 0.0 && grid.corners[c].relative_angle(normal(1.0)).is_none();
            let nrm = normal(if cross > 0.0 || on_chord_side {
                -1.0
            } else {
                1.0
            });
            // c must be below the chord on the blocked side of the staircase: the free
            // side's normal points into the quadrant of free normals of a, b and c.
            let ca = &grid.corners[a as usize];
            let cc = &grid.corners[c];
            let cb = &grid.corners[b as usize];
            if ca.relative_angle(nrm).is_none()
                || cb.relative_angle(nrm).is_none()
                || cc.relative_angle(nrm).is_none()
            {
                return None;
            }
            let lid_a = [pa[0] + r * nrm[0], pa[1] + r * nrm[1]];
            let lid_b = [pb[0] + r * nrm[0], pb[1] + r * nrm[1]];
            grid.segment_clear(lid_a, lid_b, r_check).then_some(Pocket {
                a: pa,
                n: nrm,
                reach: len + r + 2.0,
            })
        })
        .collect()
}
