//! Where the terrain is too gentle for the inclination limit to matter: one flag per
//! elevation cell, made once, so that the slope check of a motion's short segments
//! reads a byte instead of interpolating two heights.
//!
//! The height at a point is the bilinear interpolation of the four cell centres
//! around it, continuous across cells. Within one patch of four centres the slope
//! in any direction is at most `√(gx² + gy²)`, `gx` the larger of the patch's two
//! differences along x over the cell size (`gy` along y); along a straight segment
//! crossing patches, `|Δz| ≤ max bound × length`. A cell is *gentle* when every patch
//! with a corner within `reach` (plus the interpolation's one cell) of it has a bound
//! below the limit with a margin that covers the rounding of the interpolated
//! heights, has data, and lies on the map: then every segment from a point in that
//! cell, at most `reach` long (and not vanishingly short), passes the exact check of
//! the two interpolated heights — the flag gives the exact check's answer, not an
//! approximation of it.

use smug_core::{GridGeometry, GridLayer, Pose2};

/// Segments shorter than this (metres) are always checked exactly: the margin covers
/// the heights' rounding divided by a length at least this long.
const MIN_SEGMENT: f64 = 1e-3;

/// The gentle cells of an elevation layer under an inclination limit.
pub(super) struct GentleCells {
    geometry: GridGeometry,
    /// One per cell, row-major: 1 when gentle.
    gentle: Vec<u8>,
    /// Longest segment (metres) a gentle cell vouches for.
    reach: f64,
}

impl GentleCells {
    /// The gentle cells of `elevation` for segments up to `reach` metres under the
    /// slope limit `limit`.
    pub(super) fn new(elevation: &GridLayer, limit: f64, reach: f64) -> Self {
        let geometry = elevation.geometry;
        let [w, h] = geometry.size;
        let mut gentle = vec![0u8; w * h];
        let usable = w >= 2 && h >= 2 && limit.is_finite() && limit > 0.0 && reach > 0.0;
        if !usable {
            return Self {
                geometry,
                gentle,
                reach,
            };
        }
        let steep = steep_cells(elevation, limit);
        // Cells whose square of `radius` cells around holds no steep cell and stays on
        // the map, by a prefix sum of the steep flags.
        let radius = (reach / geometry.resolution).ceil() as usize + 2;
        let mut sums = vec![0u32; (w + 1) * (h + 1)];
        for j in 0..h {
            for i in 0..w {
                sums[(j + 1) * (w + 1) + i + 1] = steep[j * w + i] as u32
                    + sums[j * (w + 1) + i + 1]
                    + sums[(j + 1) * (w + 1) + i]
                    - sums[j * (w + 1) + i];
            }
        }
        for j in radius..h.saturating_sub(radius) {
            for i in radius..w.saturating_sub(radius) {
                let (i0, i1, j0, j1) = (i - radius, i + radius + 1, j - radius, j + radius + 1);
                let count = sums[j1 * (w + 1) + i1] + sums[j0 * (w + 1) + i0]
                    - sums[j0 * (w + 1) + i1]
                    - sums[j1 * (w + 1) + i0];
                gentle[j * w + i] = (count == 0) as u8;
            }
        }
        Self {
            geometry,
            gentle,
            reach,
        }
    }

    /// True when the segment from `p`, `horizontal` metres long in the plane, is known
    /// to be within the limit (the exact check of its ends' heights passes); false
    /// means "check it".
    #[inline]
    pub(super) fn vouches(&self, p: &Pose2, horizontal: f64) -> bool {
        if !(MIN_SEGMENT..=self.reach).contains(&horizontal) {
            return false;
        }
        match self.geometry.cell_of(p.x, p.y) {
            Some([i, j]) => self.gentle[self.geometry.index(i, j)] == 1,
            None => false,
        }
    }
}

/// One flag per cell: 1 when a patch it is a corner of is too steep (or has no data).
fn steep_cells(elevation: &GridLayer, limit: f64) -> Vec<u8> {
    let geometry = elevation.geometry;
    let [w, h] = geometry.size;
    let highest = elevation
        .data
        .iter()
        .filter(|v| v.is_finite())
        .fold(0.0f64, |m, &v| m.max((v as f64).abs()));
    // The interpolated heights are exact to a few ulps of the highest value; over a
    // segment of at least MIN_SEGMENT that is far below this slack.
    let slack = 1e-6 * limit + 1e-9 * (1.0 + highest);
    let mut steep = vec![0u8; w * h];
    for j in 0..h - 1 {
        for i in 0..w - 1 {
            let v00 = elevation.get(i, j) as f64;
            let v10 = elevation.get(i + 1, j) as f64;
            let v01 = elevation.get(i, j + 1) as f64;
            let v11 = elevation.get(i + 1, j + 1) as f64;
            let gx = (v10 - v00).abs().max((v11 - v01).abs()) / geometry.resolution;
            let gy = (v01 - v00).abs().max((v11 - v10).abs()) / geometry.resolution;
            // The bound `√(gx² + gy²) ≤ limit − slack`, squared (no libm `hypot` per
            // cell); a corner without data is steep (`f64::max` would skip its NaN).
            let allowed = limit - slack;
            let has_data = [v00, v10, v01, v11].iter().all(|v| !v.is_nan());
            let within = has_data && allowed > 0.0 && gx * gx + gy * gy <= allowed * allowed;
            if !within {
                for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    steep[(j + dj) * w + i + di] = 1;
                }
            }
        }
    }
    steep
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The exact check the flag stands for (the validator's `slope_ok`).
    fn exact(layer: &GridLayer, p: &Pose2, q: &Pose2, limit: f64) -> bool {
        super::super::slope_ok(
            p.xy_distance(q),
            (layer.bilinear(p.x, p.y), layer.bilinear(q.x, q.y)),
            limit,
        )
    }

    proptest! {
        #[test]
        fn a_vouched_segment_passes_the_exact_check(
            base in -50.0f64..50.0,
            tilt in (-0.6f64..0.6, -0.6f64..0.6),
            bumps in proptest::collection::vec((0usize..30, 0usize..30, -1.0f32..1.0), 0..6),
            holes in proptest::collection::vec((0usize..30, 0usize..30), 0..3),
            limit in 0.05f64..1.0,
            starts in proptest::collection::vec((0.0f64..6.0, 0.0f64..6.0, 0.0f64..1.0, -3.2f64..3.2), 1..40),
        ) {
            let geometry = GridGeometry::new([0.0, 0.0], 0.2, [30, 30]).unwrap();
            let mut layer = GridLayer::from_fn(geometry, |i, j| {
                (base + tilt.0 * 0.2 * i as f64 + tilt.1 * 0.2 * j as f64) as f32
            });
            for &(i, j, dz) in &bumps {
                layer.set(i, j, layer.get(i, j) + dz);
            }
            for &(i, j) in &holes {
                layer.set(i, j, f32::NAN);
            }
            let reach = 0.5;
            let gentle = GentleCells::new(&layer, limit, reach);
            for &(x, y, length, angle) in &starts {
                let p = Pose2::new(x, y, 0.0);
                let q = Pose2::new(x + length * angle.cos(), y + length * angle.sin(), 0.0);
                if gentle.vouches(&p, p.xy_distance(&q)) {
                    prop_assert!(exact(&layer, &p, &q, limit));
                }
            }
        }
    }

    #[test]
    fn a_gentle_plane_is_vouched_for_and_a_step_or_the_border_is_not() {
        let geometry = GridGeometry::new([0.0, 0.0], 0.1, [100, 100]).unwrap();
        // Slope 0.3 along x; a 1 m step at x ≥ 8.
        let layer = GridLayer::from_fn(geometry, |i, _| {
            (0.3 * 0.1 * i as f64 + if i >= 80 { 1.0 } else { 0.0 }) as f32
        });
        let gentle = GentleCells::new(&layer, 0.58, 0.5);
        assert!(gentle.vouches(&Pose2::new(4.0, 5.0, 0.0), 0.5));
        // Too long, too short, near the step, near the border.
        assert!(!gentle.vouches(&Pose2::new(4.0, 5.0, 0.0), 0.6));
        assert!(!gentle.vouches(&Pose2::new(4.0, 5.0, 0.0), 1e-4));
        assert!(!gentle.vouches(&Pose2::new(7.5, 5.0, 0.0), 0.5));
        assert!(!gentle.vouches(&Pose2::new(0.3, 5.0, 0.0), 0.5));
        // A limit below the slope vouches for nothing.
        let strict = GentleCells::new(&layer, 0.2, 0.5);
        assert!(!strict.vouches(&Pose2::new(4.0, 5.0, 0.0), 0.5));
    }
}
