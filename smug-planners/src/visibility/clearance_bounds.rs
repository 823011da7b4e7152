//! A lower bound of every cell's clearance: the distance from any point of the cell to
//! the nearest blocked cell or the outside of the grid (what lets the segment check of
//! `clearance.rs` step over open ground).

/// Largest ratio of the octile distance to the Euclidean one (at 22.5°: √(4 − 2√2)),
/// rounded up.
const OCTILE_OVER_EUCLID: f64 = 1.082_393;

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
