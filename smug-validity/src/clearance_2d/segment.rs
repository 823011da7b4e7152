//! The exact straight-motion test of `clearance-2d`: a disc moving along a segment
//! stays valid iff it stays inside the map and the segment keeps at least the radius
//! from every blocked cell's square. Only the cells within the radius of the segment
//! are looked at, column by column (linear in the segment's length), and the first
//! one touched ends the test.

use super::Clearance2dChecker;
use smug_core::Pose2;

/// A point in the plane, metres.
type Pt = [f64; 2];

impl Clearance2dChecker {
    /// True when the disc is valid at every point of the segment `a → b` (the same
    /// verdict for `b → a`): both ends keep the radius from the map border (the map is
    /// convex) and no blocked cell lies within the radius of the segment.
    pub(super) fn segment_clear(&self, a: &Pose2, b: &Pose2) -> bool {
        let (p, q) = ordered([a.x, a.y], [b.x, b.y]);
        self.inside_border(p) && self.inside_border(q) && !self.segment_touches_obstacle(p, q)
    }

    /// True when a blocked cell's square lies within the radius of the segment `p → q`
    /// (`p.x ≤ q.x`): the columns the widened segment spans, and in each the rows of
    /// its part there, widened by the radius.
    fn segment_touches_obstacle(&self, p: Pt, q: Pt) -> bool {
        let g = &self.geometry;
        let (res, r) = (g.resolution, self.radius);
        let [nx, ny] = g.size;
        let column = |x: f64| ((x - g.origin[0]) / res).floor();
        let row = |y: f64| ((y - g.origin[1]) / res).floor();
        let clamp = |k: f64, n: usize| k.clamp(0.0, n as f64 - 1.0) as usize;
        let (first, last) = (clamp(column(p[0] - r), nx), clamp(column(q[0] + r), nx));
        for i in first..=last {
            let x0 = g.origin[0] + i as f64 * res;
            // The segment's y-range over the column widened by the radius.
            let (y_lo, y_hi) = y_range(p, q, x0 - r, x0 + res + r);
            let (lo, hi) = (clamp(row(y_lo - r), ny), clamp(row(y_hi + r), ny));
            for j in lo..=hi {
                if self.obstacles[g.index(i, j)] {
                    let y0 = g.origin[1] + j as f64 * res;
                    let square = ([x0, y0], [x0 + res, y0 + res]);
                    let d2 = segment_square_distance2(p, q, square);
                    if self.within_radius(d2, || d2.sqrt()) {
                        return true;
                    }
                }
            }
        }
        false
    }
}

/// The two ends ordered by `(x, y)`, so that a segment and its reverse are tested the
/// same way.
fn ordered(a: Pt, b: Pt) -> (Pt, Pt) {
    if a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])).is_le() {
        (a, b)
    } else {
        (b, a)
    }
}

/// The range of `y` over the part of the segment `p → q` (`p.x ≤ q.x`) with `x` in
/// `[x_lo, x_hi]` (the whole segment's range for a vertical one; an empty part gives
/// the nearest end's `y`, harmless: its cells are then too far to touch).
fn y_range(p: Pt, q: Pt, x_lo: f64, x_hi: f64) -> (f64, f64) {
    let dx = q[0] - p[0];
    let y_at = |x: f64| {
        if dx <= 0.0 {
            p[1]
        } else {
            let t = ((x - p[0]) / dx).clamp(0.0, 1.0);
            p[1] + t * (q[1] - p[1])
        }
    };
    let (y0, y1) = if dx <= 0.0 {
        (p[1], q[1])
    } else {
        (y_at(x_lo), y_at(x_hi))
    };
    (y0.min(y1), y0.max(y1))
}

/// The squared distance between the segment `p → q` and the square `(min, max)`
/// (0 when they meet): between two disjoint convex polygons, the nearest pair holds a
/// vertex of one of them.
fn segment_square_distance2(p: Pt, q: Pt, (min, max): (Pt, Pt)) -> f64 {
    if segment_meets_square(p, q, (min, max)) {
        return 0.0;
    }
    let to_square = |[x, y]: Pt| {
        let dx = (min[0] - x).max(0.0).max(x - max[0]);
        let dy = (min[1] - y).max(0.0).max(y - max[1]);
        dx * dx + dy * dy
    };
    let corners = [min, [max[0], min[1]], [min[0], max[1]], max];
    corners
        .iter()
        .map(|&c| point_segment_distance2(c, p, q))
        .fold(to_square(p).min(to_square(q)), f64::min)
}

/// True when the segment `p → q` meets the closed square (separating axes: the two
/// coordinate axes and the segment's normal).
fn segment_meets_square(p: Pt, q: Pt, (min, max): (Pt, Pt)) -> bool {
    for k in 0..2 {
        if p[k].max(q[k]) < min[k] || p[k].min(q[k]) > max[k] {
            return false;
        }
    }
    let normal = [p[1] - q[1], q[0] - p[0]];
    let offset = normal[0] * p[0] + normal[1] * p[1];
    let side = |[x, y]: Pt| normal[0] * x + normal[1] * y - offset;
    let corners = [min, [max[0], min[1]], [min[0], max[1]], max].map(side);
    let (lo, hi) = corners
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &s| {
            (lo.min(s), hi.max(s))
        });
    lo <= 0.0 && hi >= 0.0
}

/// The squared distance from `c` to the segment `p → q`.
fn point_segment_distance2(c: Pt, p: Pt, q: Pt) -> f64 {
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((c[0] - p[0]) * dx + (c[1] - p[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (ex, ey) = (p[0] + t * dx - c[0], p[1] + t * dy - c[1]);
    ex * ex + ey * ey
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn distances_of_a_segment_to_a_unit_square() {
        let square = ([0.0, 0.0], [1.0, 1.0]);
        // Through it, beside it, past a corner.
        assert_eq!(
            segment_square_distance2([-1.0, 0.5], [2.0, 0.5], square),
            0.0
        );
        let beside = segment_square_distance2([-1.0, 1.5], [2.0, 1.5], square);
        assert!((beside - 0.25).abs() < 1e-12);
        let corner = segment_square_distance2([1.5, 2.0], [2.0, 1.5], square);
        assert!((corner - 1.125).abs() < 1e-12, "{corner}"); // (1,1) to x+y=3.5: 1.5/√2
    }

    proptest! {
        #[test]
        fn the_distance_is_the_smallest_over_dense_points(
            p in (-3.0..4.0f64, -3.0..4.0f64), q in (-3.0..4.0f64, -3.0..4.0f64),
        ) {
            let (p, q) = ([p.0, p.1], [q.0, q.1]);
            let square = ([0.0, 0.0], [1.0, 1.0]);
            let d2 = segment_square_distance2(p, q, square);
            let dense = (0..=2000)
                .map(|k| {
                    let t = k as f64 / 2000.0;
                    let [x, y] = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
                    let dx = (0.0 - x).max(0.0).max(x - 1.0);
                    let dy = (0.0 - y).max(0.0).max(y - 1.0);
                    (dx * dx + dy * dy).sqrt()
                })
                .fold(f64::INFINITY, f64::min);
            let len = (q[0] - p[0]).hypot(q[1] - p[1]);
            // Dense points are at most half a step from the segment's nearest point.
            prop_assert!(d2.sqrt() <= dense + 1e-12);
            prop_assert!(dense <= d2.sqrt() + len / 4000.0 + 1e-12);
        }
    }
}
