//! What the traversability thresholds alone decide, per cell, one byte per cell: the
//! hierarchical check reads a cell per state, at random places on big maps, and a
//! byte per cell stays in the cache where the `f32` layer (four times larger) does
//! not. The verdicts are the thresholds' comparisons made once per cell, on the very
//! values [`GridLayer::nearest`] returns, so every state gets the verdict the layer
//! would give.

use rayon::prelude::*;
use smug_core::{GridGeometry, GridLayer};

/// The cell has no data (NaN) or a traversability below `t_low`: invalid.
const INVALID: u8 = 0;
/// The traversability is above `t_high`: valid without a collision check.
const VALID: u8 = 1;
/// In the band `[t_low, t_high]`: the volumetric check decides.
const UNSURE: u8 = 2;

/// Cells of one parallel task when the verdicts are computed.
const CHUNK: usize = 1 << 16;

/// Per-cell verdicts of the traversability thresholds.
#[derive(Clone, Debug)]
pub struct ThresholdVerdicts {
    geometry: GridGeometry,
    cells: Vec<u8>,
}

impl ThresholdVerdicts {
    /// The verdicts of `t_low` and `t_high` on every cell of `layer`.
    pub fn new(layer: &GridLayer, t_low: f64, t_high: f64) -> Self {
        let mut cells = vec![INVALID; layer.data.len()];
        cells
            .par_chunks_mut(CHUNK)
            .zip(layer.data.par_chunks(CHUNK))
            .for_each(|(out, values)| {
                for (verdict, &value) in out.iter_mut().zip(values) {
                    *verdict = cell_verdict(value, t_low, t_high);
                }
            });
        Self {
            geometry: layer.geometry,
            cells,
        }
    }

    /// The thresholds' verdict at `(x, y)`: `Some(false)` off the grid, without data
    /// or below `t_low`, `Some(true)` above `t_high`, `None` in between (as the
    /// thresholds on `layer.nearest(x, y)`).
    #[inline]
    pub fn verdict(&self, x: f64, y: f64) -> Option<bool> {
        let Some([i, j]) = self.geometry.cell_of(x, y) else {
            return Some(false);
        };
        match self.cells[self.geometry.index(i, j)] {
            VALID => Some(true),
            UNSURE => None,
            _ => Some(false),
        }
    }
}

/// The verdict on one cell's value (as [`GridLayer::nearest`] reads it: NaN is no data).
fn cell_verdict(value: f32, t_low: f64, t_high: f64) -> u8 {
    if value.is_nan() {
        return INVALID;
    }
    let t = value as f64;
    if t < t_low {
        INVALID
    } else if t > t_high {
        VALID
    } else {
        UNSURE
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The thresholds on the layer itself, as the checker made them before.
    fn on_layer(layer: &GridLayer, x: f64, y: f64, t_low: f64, t_high: f64) -> Option<bool> {
        match layer.nearest(x, y) {
            None => Some(false),
            Some(t) if t < t_low => Some(false),
            Some(t) if t > t_high => Some(true),
            Some(_) => None,
        }
    }

    proptest! {
        /// Random layers with holes and values on the thresholds, points on and off
        /// the grid.
        #[test]
        fn the_verdicts_are_the_thresholds_on_the_layer(
            nx in 1usize..40, ny in 1usize..40, resolution in 0.05f64..0.5,
            values in proptest::collection::vec(
                prop_oneof![Just(f32::NAN), Just(0.3f32), Just(0.8f32), 0.0f32..1.0], 1..64),
            thresholds in (0.0f64..1.0, 0.0f64..1.0),
            points in proptest::collection::vec((-2.0f64..25.0, -2.0f64..25.0), 1..200),
        ) {
            let (t_low, t_high) = if thresholds.0 <= thresholds.1 { thresholds } else { (thresholds.1, thresholds.0) };
            let g = GridGeometry::new([0.5, -0.25], resolution, [nx, ny]).unwrap();
            let layer = GridLayer::from_fn(g, |i, j| values[(i * 7 + j * 13) % values.len()]);
            let verdicts = ThresholdVerdicts::new(&layer, t_low, t_high);
            for (x, y) in points {
                prop_assert_eq!(verdicts.verdict(x, y), on_layer(&layer, x, y, t_low, t_high));
            }
            // Every cell centre, with the paper's thresholds (values on them) too.
            for (lo, hi) in [(t_low, t_high), (0.3, 0.3), (0.3, 0.8)] {
                let verdicts = ThresholdVerdicts::new(&layer, lo, hi);
                for j in 0..ny {
                    for i in 0..nx {
                        let [x, y] = g.center_of(i, j);
                        prop_assert_eq!(verdicts.verdict(x, y), on_layer(&layer, x, y, lo, hi));
                    }
                }
            }
        }
    }
}
