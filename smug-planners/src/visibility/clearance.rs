//! A lower bound of every cell's clearance (the distance from any point of the cell to
//! the nearest blocked cell or the outside of the grid), and the segment check that
//! uses it to step over open ground: where the bound exceeds the clearance asked by
//! `δ`, every point within `δ` is clear, so the check jumps `δ` along the segment and
//! checks cell by cell ([`Grid::segment_clear_exact`]) only the stretches near
//! obstacles. On a 2000 × 2000 map most tangent segments cross open ground.

use super::geometry::{dist, Grid, Pt};

/// Largest ratio of the octile distance to the Euclidean one (at 22.5°: √(4 − 2√2)),
/// rounded up.
const OCTILE_OVER_EUCLID: f64 = 1.082_393;

/// Jumps shorter than this (cells) are not taken: the stretch is checked exactly.
const MIN_JUMP: f64 = 1.0;

/// Per cell (row-major), a lower bound of the distance from any of its points to the
/// nearest blocked cell or the grid's outside: 0 for blocked cells; else the smaller
/// of the distance to the outside and the octile distance between cell centres to the
/// nearest blocked cell (two raster passes) over √(4 − 2√2), less √2 (the point and
/// the blocked cell each within √2/2 of their centres).
pub(super) fn clearance_bounds(nx: usize, ny: usize, blocked: &[bool]) -> Vec<f32> {
    const DIAG: f64 = std::f64::consts::SQRT_2;
    let mut d = vec![f64::INFINITY; nx * ny];
    for (k, &b) in blocked.iter().enumerate() {
        if b {
            d[k] = 0.0;
        }
    }
    let at = |x: usize, y: usize| y * nx + x;
    for y in 0..ny {
        for x in 0..nx {
            let mut v = d[at(x, y)];
            if x > 0 {
                v = v.min(d[at(x - 1, y)] + 1.0);
            }
            if y > 0 {
                v = v.min(d[at(x, y - 1)] + 1.0);
                if x > 0 {
                    v = v.min(d[at(x - 1, y - 1)] + DIAG);
                }
                if x + 1 < nx {
                    v = v.min(d[at(x + 1, y - 1)] + DIAG);
                }
            }
            d[at(x, y)] = v;
        }
    }
    for y in (0..ny).rev() {
        for x in (0..nx).rev() {
            let mut v = d[at(x, y)];
            if x + 1 < nx {
                v = v.min(d[at(x + 1, y)] + 1.0);
            }
            if y + 1 < ny {
                v = v.min(d[at(x, y + 1)] + 1.0);
                if x + 1 < nx {
                    v = v.min(d[at(x + 1, y + 1)] + DIAG);
                }
                if x > 0 {
                    v = v.min(d[at(x - 1, y + 1)] + DIAG);
                }
            }
            d[at(x, y)] = v;
        }
    }
    let mut out = vec![0f32; nx * ny];
    for y in 0..ny {
        for x in 0..nx {
            let k = at(x, y);
            if blocked[k] {
                continue;
            }
            let border = x.min(y).min(nx - 1 - x).min(ny - 1 - y) as f64;
            let inner = d[k] / OCTILE_OVER_EUCLID - DIAG;
            // f32 rounds down to stay a lower bound.
            let bound = border.min(inner).max(0.0) * (1.0 - 1e-6);
            out[k] = bound as f32;
        }
    }
    out
}

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
