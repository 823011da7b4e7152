//! The segment check that uses every cell's clearance bound (`clearance_bounds.rs`) to
//! step over open ground: where the bound exceeds the clearance asked by
//! `δ`, every point within `δ` is clear, so the check jumps `δ` along the segment and
//! checks cell by cell ([`Grid::segment_clear_exact`]) only the stretches near
//! obstacles. On a 2000 × 2000 map most tangent segments cross open ground.

use super::geometry::{dist, Grid, Pt};

/// Jumps shorter than this (cells) are not taken: the stretch is checked exactly.
const MIN_JUMP: f64 = 1.0;

impl Grid {
    /// True when every point of the segment `p → q` is at least `r` from every blocked
    /// cell (cells outside the grid included): exact, jumping over open ground by the
    /// cells' clearance bounds and checking the rest cell by cell.
    pub fn segment_clear(&self, p: Pt, q: Pt, r: f64) -> bool {
        let len = dist(p, q);
        if len < 4.0 * MIN_JUMP {
            return self.segment_clear_exact(p, q, r);
        }
        let u = [(q[0] - p[0]) / len, (q[1] - p[1]) / len];
        let point = |t: f64| {
            if t <= 0.0 {
                p
            } else if t >= len {
                q
            } else {
                [p[0] + t * u[0], p[1] + t * u[1]]
            }
        };
        let (mut t, mut near_from) = (0.0, None);
        let mut jumped = false;
        while t < len {
            let jump = self.clearance_bound(point(t)) - r;
            if jump >= MIN_JUMP {
                if let Some(a) = near_from.take() {
                    if !self.segment_clear_exact(point(a), point(t), r) {
                        return false;
                    }
                }
                jumped = true;
                t += jump;
            } else {
                near_from.get_or_insert(t);
                t += MIN_JUMP;
            }
        }
        match near_from {
            // Nothing jumped: the whole segment, as given.
            Some(_) if !jumped => self.segment_clear_exact(p, q, r),
            Some(a) => self.segment_clear_exact(point(a), q, r),
            None => true,
        }
    }

    /// The clearance bound of the cell holding `p` (0 off the grid).
    fn clearance_bound(&self, p: Pt) -> f64 {
        let (x, y) = (p[0].floor(), p[1].floor());
        if x < 0.0 || y < 0.0 || x >= self.nx as f64 || y >= self.ny as f64 {
            return 0.0;
        }
        f64::from(self.clearance_bounds[y as usize * self.nx + x as usize])
    }
}
