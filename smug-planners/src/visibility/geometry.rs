//! Geometry of the `visibility` planner, in grid units (one cell = 1, cell `(i, j)`
//! covers `[i, i+1] × [j, j+1]`): blocked cells, their convex corners with the quadrant
//! of normals where the inflated obstacle is a quarter circle, which cells a point may
//! see (a conservative shadowcast), exact clearance of segments, and the tangents
//! between equal circles.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Tolerance on angles and distances in grid units.
pub const EPS: f64 = 1e-9;

/// A 2D point in grid units.
pub type Pt = [f64; 2];

/// The travel direction around a corner's circle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Lane {
    /// Counter-clockwise: the normal angle grows, the obstacle is on the left.
    Ccw,
    /// Clockwise: the normal angle shrinks, the obstacle is on the right.
    Cw,
}

impl Lane {
    /// The lane of a motion along `t` touching the circle where its outward normal is `n`.
    pub fn of(n: Pt, t: Pt) -> Lane {
        if n[0] * t[1] - n[1] * t[0] > 0.0 {
            Lane::Ccw
        } else {
            Lane::Cw
        }
    }

    /// 0 for `Ccw`, 1 for `Cw`.
    pub fn index(self) -> usize {
        self as usize
    }
}

/// A convex corner of the blocked cells: a grid vertex with exactly one blocked cell
/// among the four around it. The inflated obstacle's boundary there is the quarter
/// circle of normals pointing away from that cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    /// The vertex, grid units.
    pub at: Pt,
    /// Angle where the quadrant of free normals starts (it spans `[q0, q0 + π/2]`).
    pub q0: f64,
}

impl Corner {
    /// The angle of normal `n` relative to the quadrant's start, in `[0, π/2]`, or
    /// `None` when `n` points outside the quadrant (beyond a tolerance).
    pub fn relative_angle(&self, n: Pt) -> Option<f64> {
        // Most normals are far outside: a dot product with the quadrant's bisector
        // (a bound slightly looser than the tolerance below) spares their atan2.
        // (q0 is 0, π/2, −π/2 or −π: the bisector's signs.)
        let (c, s) = if self.q0 == 0.0 {
            (1.0, 1.0)
        } else if self.q0 > 0.0 {
            (-1.0, 1.0)
        } else if self.q0 > -2.0 {
            (1.0, -1.0)
        } else {
            (-1.0, -1.0)
        };
        let len2 = n[0] * n[0] + n[1] * n[1];
        // cos(π/4 + 1e-6)·√2 = 1 − 1e-6 (to first order): n·(c, s)/√2 against it.
        let dot = n[0] * c + n[1] * s;
        if dot < 0.0 || dot * dot < len2 * (1.0 - 2.1e-6) {
            return None;
        }
        let mut rel = n[1].atan2(n[0]) - self.q0;
        while rel < -PI {
            rel += TAU;
        }
        while rel >= PI {
            rel -= TAU;
        }
        (-1e-7..=FRAC_PI_2 + 1e-7)
            .contains(&rel)
            .then(|| rel.clamp(0.0, FRAC_PI_2))
    }

    /// The point of the circle of radius `r` at relative normal angle `rel`.
    pub fn point(&self, r: f64, rel: f64) -> Pt {
        let a = self.q0 + rel;
        [self.at[0] + r * a.cos(), self.at[1] + r * a.sin()]
    }
}

/// The blocked cells (cells outside the grid count as blocked) and their convex corners.
#[derive(Clone, Debug)]
pub struct Grid {
    /// Cells along x and y.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    blocked: Vec<bool>,
    /// Every convex corner.
    pub corners: Vec<Corner>,
    /// Corner id of each grid vertex (`(ny+1)` rows of `(nx+1)`), `u32::MAX` if none.
    corner_at: Vec<u32>,
    /// Per cell, a lower bound of its points' clearance (see `clearance_bounds`).
    pub(super) clearance_bounds: Vec<f32>,
}

impl Grid {
    /// The grid of `blocked` (row-major, `nx × ny`).
    pub fn new(nx: usize, ny: usize, blocked: Vec<bool>) -> Self {
        let clearance_bounds = super::clearance_bounds::clearance_bounds(nx, ny, &blocked);
        let mut grid = Self {
            nx,
            ny,
            blocked,
            clearance_bounds,
            corners: Vec::new(),
            corner_at: vec![u32::MAX; (nx + 1) * (ny + 1)],
        };
        for y in 0..=ny as i64 {
            for x in 0..=nx as i64 {
                let around = [(x - 1, y - 1), (x, y - 1), (x - 1, y), (x, y)];
                let b = around.map(|(i, j)| grid.blocked(i, j));
                if b.iter().filter(|&&v| v).count() != 1 {
                    continue;
                }
                // Normals point away from the blocked cell: its quadrant's opposite.
                let q0 = match b.iter().position(|&v| v) {
                    Some(0) => 0.0,        // blocked lower-left: normals (+, +)
                    Some(1) => FRAC_PI_2,  // lower-right: (−, +)
                    Some(2) => -FRAC_PI_2, // upper-left: (+, −)
                    _ => -PI,              // upper-right: (−, −)
                };
                let id = grid.corners.len() as u32;
                grid.corners.push(Corner {
                    at: [x as f64, y as f64],
                    q0,
                });
                let k = grid.vertex_index(x as usize, y as usize);
                grid.corner_at[k] = id;
            }
        }
        grid
    }

    fn vertex_index(&self, x: usize, y: usize) -> usize {
        y * (self.nx + 1) + x
    }

    /// True when cell `(i, j)` is blocked or outside the grid.
    pub fn blocked(&self, i: i64, j: i64) -> bool {
        if i < 0 || j < 0 || i >= self.nx as i64 || j >= self.ny as i64 {
            return true;
        }
        self.blocked[j as usize * self.nx + i as usize]
    }

    /// The corner at grid vertex `(x, y)`, if it is a convex corner.
    pub fn corner_at(&self, x: i64, y: i64) -> Option<u32> {
        if x < 0 || y < 0 || x > self.nx as i64 || y > self.ny as i64 {
            return None;
        }
        let id = self.corner_at[self.vertex_index(x as usize, y as usize)];
        (id != u32::MAX).then_some(id)
    }

    /// The distance from `p` to the nearest blocked cell (or the outside of the grid),
    /// exactly, looking no farther than `reach`; `reach` when nothing is nearer.
    pub fn clearance(&self, p: Pt, reach: f64) -> f64 {
        let mut best = reach;
        let (i0, i1) = ((p[0] - reach).floor() as i64, (p[0] + reach).floor() as i64);
        let (j0, j1) = ((p[1] - reach).floor() as i64, (p[1] + reach).floor() as i64);
        for j in j0..=j1 {
            for i in i0..=i1 {
                if self.blocked(i, j) {
                    best = best.min(point_box_distance(p, i, j));
                }
            }
        }
        best
    }

    /// True when every point of the segment `p → q` is at least `r` from every blocked
    /// cell (cells outside the grid included), checked exactly against each cell
    /// within `r` of the segment.
    pub fn segment_clear_exact(&self, p: Pt, q: Pt, r: f64) -> bool {
        // Walk along the major axis; `swap` exchanges x and y.
        let swap = (q[1] - p[1]).abs() > (q[0] - p[0]).abs();
        let (a, b) = if swap {
            ([p[1], p[0]], [q[1], q[0]])
        } else {
            (p, q)
        };
        let (a, b) = if a[0] <= b[0] { (a, b) } else { (b, a) };
        let slope = if b[0] > a[0] {
            (b[1] - a[1]) / (b[0] - a[0])
        } else {
            0.0
        };
        let y_at = |x: f64| a[1] + slope * (x - a[0]);
        let r2 = r * r;
        let (c0, c1) = ((a[0] - r).floor() as i64, (b[0] + r).floor() as i64);
        for c in c0..=c1 {
            let xa = (c as f64 - r).max(a[0]);
            let xb = (c as f64 + 1.0 + r).min(b[0]);
            let (xa, xb) = if xa > xb { (xb, xb) } else { (xa, xb) };
            let (ya, yb) = (y_at(xa), y_at(xb));
            let (lo, hi) = (ya.min(yb) - r, ya.max(yb) + r);
            for row in lo.floor() as i64..=hi.floor() as i64 {
                let (i, j) = if swap { (row, c) } else { (c, row) };
                if self.blocked(i, j) && segment_box_distance2(p, q, i, j) < r2 {
                    return false;
                }
            }
        }
        true
    }

    /// Every free cell a point at `s` may see (a superset of the cells some segment
    /// from `s` reaches without entering a blocked cell's interior), as `(i, j)`, by
    /// shadowcasting in four cones (right, left, up, down) with slopes in `[−1, 1]`.
    /// `visit` gets each such cell (possibly more than once).
    pub fn visible_cells(&self, s: Pt, mut visit: impl FnMut(i64, i64)) {
        for cone in 0..4 {
            self.shadowcast(s, cone, &mut visit);
        }
    }

    fn shadowcast(&self, s: Pt, cone: u8, visit: &mut impl FnMut(i64, i64)) {
        // (u, w) coordinates of the cone: u along its axis, w across.
        let (su, sw) = match cone {
            0 => (s[0], s[1]),
            1 => (-s[0], s[1]),
            2 => (s[1], s[0]),
            _ => (-s[1], s[0]),
        };
        let to_cell = |iu: i64, iw: i64| match cone {
            0 => (iu, iw),
            1 => (-iu - 1, iw),
            2 => (iw, iu),
            _ => (iw, -iu - 1),
        };
        let mut windows: Vec<(f64, f64)> = vec![(-1.0 - EPS, 1.0 + EPS)];
        let mut next: Vec<(f64, f64)> = Vec::new();
        let mut cuts: Vec<(f64, f64)> = Vec::new();
        // A source on a grid line sends a ray along it (slope 0), which no cell's
        // interior holds: it is cut where both cells beside it are blocked (a zero-width
        // gap no disc passes), else it would run to the border along every wall.
        let on_line = sw.fract() == 0.0;
        let mut iu = su.floor() as i64;
        let limit = (self.nx.max(self.ny) as i64) * 2 + 4;
        while !windows.is_empty() && iu.abs() <= limit {
            let u0 = (iu as f64).max(su) - su;
            let u1 = (iu + 1) as f64 - su;
            next.clear();
            for &(lo, hi) in &windows {
                let wmin = sw + (lo * u0).min(lo * u1);
                let wmax = sw + (hi * u0).max(hi * u1);
                cuts.clear();
                for iw in (wmin - EPS).floor() as i64..=(wmax + EPS).floor() as i64 {
                    let (i, j) = to_cell(iu, iw);
                    if !self.blocked(i, j) {
                        visit(i, j);
                        continue;
                    }
                    // The slopes of rays entering this blocked cell's interior.
                    cuts.extend(slopes_into(
                        [su, sw],
                        iu as f64,
                        [iw as f64, iw as f64 + 1.0],
                    ));
                    if on_line && iw as f64 == sw && {
                        let (bi, bj) = to_cell(iu, iw - 1);
                        self.blocked(bi, bj)
                    } {
                        cuts.push((-2.0 * EPS, 2.0 * EPS));
                    }
                }
                push_uncut(lo, hi, &mut cuts, &mut next);
            }
            std::mem::swap(&mut windows, &mut next);
            iu += 1;
        }
    }
}

/// The open interval of slopes (across over along, in a shadowcast's cone) of the rays
/// from `s` that enter the interior of the box spanning `[u, u + 1]` along and `w`
/// across, narrowed by `EPS` at both ends; `None` when it is that thin or thinner.
pub(super) fn slopes_into(s: Pt, u: f64, w: [f64; 2]) -> Option<(f64, f64)> {
    let (mut smin, mut smax) = (f64::INFINITY, f64::NEG_INFINITY);
    for (cu, cw) in [(u, w[0]), (u + 1.0, w[0]), (u, w[1]), (u + 1.0, w[1])] {
        let (du, dw) = (cu - s[0], cw - s[1]);
        let m = if du > 0.0 {
            dw / du
        } else if dw > 0.0 {
            f64::INFINITY
        } else if dw < 0.0 {
            f64::NEG_INFINITY
        } else {
            continue;
        };
        smin = smin.min(m);
        smax = smax.max(m);
    }
    (smax - smin > 2.0 * EPS).then_some((smin + EPS, smax - EPS))
}

/// Pushes onto `next` the parts of the window `[lo, hi]` that no cut covers (the
/// window less the open intervals `cuts`, in order); sorts `cuts`.
pub(super) fn push_uncut(lo: f64, hi: f64, cuts: &mut [(f64, f64)], next: &mut Vec<(f64, f64)>) {
    cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut from = lo;
    for &(a, b) in cuts.iter() {
        if a > hi {
            break;
        }
        if a >= from {
            next.push((from, a));
        }
        from = from.max(b);
        if from > hi {
            return;
        }
    }
    next.push((from, hi));
}

/// Distance from `p` to cell `(i, j)`.
pub fn point_box_distance(p: Pt, i: i64, j: i64) -> f64 {
    let (x0, y0) = (i as f64, j as f64);
    let dx = (x0 - p[0]).max(0.0).max(p[0] - x0 - 1.0);
    let dy = (y0 - p[1]).max(0.0).max(p[1] - y0 - 1.0);
    dx.hypot(dy)
}

fn point_segment_distance2(c: Pt, p: Pt, q: Pt) -> f64 {
    let d = [q[0] - p[0], q[1] - p[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let t = if len2 > 0.0 {
        (((c[0] - p[0]) * d[0] + (c[1] - p[1]) * d[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (x, y) = (p[0] + t * d[0] - c[0], p[1] + t * d[1] - c[1]);
    x * x + y * y
}

/// Squared distance from segment `p → q` to cell `(i, j)` (0 when they meet).
pub fn segment_box_distance2(p: Pt, q: Pt, i: i64, j: i64) -> f64 {
    let (lo, hi) = ([i as f64, j as f64], [i as f64 + 1.0, j as f64 + 1.0]);
    // Liang–Barsky: does the segment meet the closed box?
    let d = [q[0] - p[0], q[1] - p[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    let mut meets = true;
    for k in 0..2 {
        if d[k] == 0.0 {
            if p[k] < lo[k] || p[k] > hi[k] {
                meets = false;
                break;
            }
        } else {
            let (mut a, mut b) = ((lo[k] - p[k]) / d[k], (hi[k] - p[k]) / d[k]);
            if a > b {
                std::mem::swap(&mut a, &mut b);
            }
            t0 = t0.max(a);
            t1 = t1.min(b);
            if t0 > t1 {
                meets = false;
                break;
            }
        }
    }
    if meets {
        return 0.0;
    }
    let mut best = point_box_distance(p, i, j)
        .powi(2)
        .min(point_box_distance(q, i, j).powi(2));
    for c in [lo, [hi[0], lo[1]], [lo[0], hi[1]], hi] {
        best = best.min(point_segment_distance2(c, p, q));
    }
    best
}

/// The tangent segments between the circles of radius `r` around `a` and `b`: for each,
/// the outward normals at `a` and at `b` (the contact points are `a + r·n_a`,
/// `b + r·n_b`). Two outer tangents (`n_a = n_b`) and, when the circles are apart,
/// two inner ones (`n_b = −n_a`).
pub fn circle_tangents(a: Pt, b: Pt, r: f64) -> Vec<(Pt, Pt)> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let d = dx.hypot(dy);
    if d <= 0.0 {
        return Vec::new();
    }
    let u = [dx / d, dy / d];
    let perp = [-u[1], u[0]];
    let mut out = vec![(perp, perp), ([-perp[0], -perp[1]], [-perp[0], -perp[1]])];
    let c = 2.0 * r / d;
    if c < 1.0 {
        let s = (1.0 - c * c).sqrt();
        for sign in [1.0, -1.0] {
            let n = [c * u[0] + sign * s * perp[0], c * u[1] + sign * s * perp[1]];
            out.push((n, [-n[0], -n[1]]));
        }
    }
    out
}

/// The outward normals at which the tangents from point `s` touch the circle of radius
/// `r` around `b` (none when `s` is inside or on the circle).
pub fn point_tangents(s: Pt, b: Pt, r: f64) -> Vec<Pt> {
    let (dx, dy) = (b[0] - s[0], b[1] - s[1]);
    let d = dx.hypot(dy);
    if d <= r {
        return Vec::new();
    }
    let u = [dx / d, dy / d];
    let perp = [-u[1], u[0]];
    let c = -r / d;
    let s2 = (1.0 - c * c).sqrt();
    [1.0, -1.0]
        .iter()
        .map(|sign| {
            [
                c * u[0] + sign * s2 * perp[0],
                c * u[1] + sign * s2 * perp[1],
            ]
        })
        .collect()
}

/// Euclidean distance.
pub fn dist(p: Pt, q: Pt) -> f64 {
    (q[0] - p[0]).hypot(q[1] - p[1])
}

impl Grid {
    /// True when the arc of the circle of radius `r` around `corner`, between the
    /// relative normal angles `a` and `b`, keeps at least `need` from every blocked
    /// cell. Each cell's inflated square (by `need`) can only be entered where the
    /// circle crosses its boundary: the angles of every such crossing split the arc
    /// into pieces, and one point per piece decides it.
    pub fn arc_clear(&self, corner: &Corner, r: f64, a: f64, b: f64, need: f64) -> bool {
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        let v = corner.at;
        let reach = r + need;
        let rel = |theta: f64| {
            let mut x = theta - corner.q0;
            while x < -PI {
                x += TAU;
            }
            while x >= PI {
                x -= TAU;
            }
            x
        };
        let mut cuts: Vec<f64> = Vec::new();
        for j in (v[1] - reach).floor() as i64..=(v[1] + reach).floor() as i64 {
            for i in (v[0] - reach).floor() as i64..=(v[0] + reach).floor() as i64 {
                if !self.blocked(i, j) {
                    continue;
                }
                cuts.clear();
                cuts.extend([lo, hi]);
                let (x0, x1, y0, y1) = (i as f64, i as f64 + 1.0, j as f64, j as f64 + 1.0);
                // The inflated square's edge lines: x = x0 − need, x1 + need; y likewise.
                for x in [x0 - need, x1 + need] {
                    let c = (x - v[0]) / r;
                    if c.abs() <= 1.0 {
                        let t = c.acos();
                        cuts.extend([rel(t), rel(-t)]);
                    }
                }
                for y in [y0 - need, y1 + need] {
                    let s = (y - v[1]) / r;
                    if s.abs() <= 1.0 {
                        let t = s.asin();
                        cuts.extend([rel(t), rel(PI - t)]);
                    }
                }
                // Its rounded corners: circles of radius `need` around the cell's corners.
                for w in [[x0, y0], [x1, y0], [x0, y1], [x1, y1]] {
                    let d = dist(v, w);
                    if d > 0.0 && d <= r + need && d >= (r - need).abs() {
                        let base = (w[1] - v[1]).atan2(w[0] - v[0]);
                        let c = ((r * r + d * d - need * need) / (2.0 * r * d)).clamp(-1.0, 1.0);
                        let t = c.acos();
                        cuts.extend([rel(base + t), rel(base - t)]);
                    }
                }
                cuts.retain(|&t| t >= lo && t <= hi);
                cuts.sort_by(f64::total_cmp);
                for w in cuts.windows(2) {
                    let p = corner.point(r, 0.5 * (w[0] + w[1]));
                    if point_box_distance(p, i, j) < need - EPS {
                        return false;
                    }
                }
                for &t in &cuts {
                    if point_box_distance(corner.point(r, t), i, j) < need - EPS {
                        return false;
                    }
                }
            }
        }
        true
    }
}
