//! The geometric estimator's layer: estimated as a whole (bands of rows side by side
//! on rayon's pool), or updated where the elevation changed (the cells whose fitting
//! window holds a changed cell). Both compute each cell as [`GeometricEstimator::fill`]
//! does, so an updated layer equals the layer estimated again, bit for bit.

use super::rows::RowRuns;
use super::{GeometricEstimator, TerrainFeatures, Window};
use rayon::prelude::*;
use smug_core::{CellRect, Error, GridLayer, TraversabilityEstimator, World};

/// Rows estimated together (their windows' row sums are shared).
const BAND_ROWS: usize = 32;

impl GeometricEstimator {
    /// The layer's value of a cell with these features (NaN without).
    fn layer_value(&self, features: Option<TerrainFeatures>) -> f32 {
        features.map_or(f32::NAN, |f| self.score(&f) as f32)
    }

    /// Gives `set` the layer's value of every cell of `rect`: from the window's row
    /// runs (`runs`, [`RowRuns::new`] of `window`) where it has them.
    fn fill(
        &self,
        window: &Window,
        runs: Option<&RowRuns>,
        elevation: &GridLayer,
        rect: CellRect,
        mut set: impl FnMut(usize, usize, f32),
    ) {
        match runs {
            Some(runs) => runs.rect_features(window, elevation, rect, |i, j, f| {
                set(i, j, self.layer_value(f))
            }),
            None => {
                for j in rect.j0..rect.j1 {
                    for i in rect.i0..rect.i1 {
                        set(i, j, self.layer_value(window.features(elevation, i, j)));
                    }
                }
            }
        }
    }
}

impl TraversabilityEstimator for GeometricEstimator {
    fn estimate(&self, world: &World) -> Result<GridLayer, Error> {
        let elevation = &world.elevation;
        let window = Window::new(self.window_radius, elevation.geometry.resolution);
        let runs = RowRuns::new(&window);
        let mut layer = GridLayer::filled(elevation.geometry, f32::NAN);
        let nx = elevation.geometry.size[0];
        if nx > 0 {
            layer
                .data
                .par_chunks_mut(nx * BAND_ROWS)
                .enumerate()
                .for_each(|(band, values)| {
                    let j0 = band * BAND_ROWS;
                    let rect = CellRect {
                        i0: 0,
                        i1: nx,
                        j0,
                        j1: j0 + values.len() / nx,
                    };
                    self.fill(&window, runs.as_ref(), elevation, rect, |i, j, v| {
                        values[(j - j0) * nx + i] = v
                    });
                });
        }
        Ok(layer)
    }

    /// The fitting window's radius: a cell reads the elevation within it.
    fn reach(&self) -> Option<f64> {
        Some(self.window_radius)
    }

    /// Estimates again the cells whose window holds a changed cell (the changed
    /// rectangle grown by the window's reach); each cell's value is computed as in
    /// [`estimate`](TraversabilityEstimator::estimate), so the layer is the same.
    fn update_layer(
        &self,
        world: &World,
        layer: &mut GridLayer,
        changed: CellRect,
    ) -> Result<bool, Error> {
        let elevation = &world.elevation;
        if layer.geometry != elevation.geometry {
            return Ok(false);
        }
        let window = Window::new(self.window_radius, elevation.geometry.resolution);
        let area = changed.grown(window.reach.max(0) as usize, elevation.geometry.size);
        let runs = RowRuns::new(&window);
        self.fill(&window, runs.as_ref(), elevation, area, |i, j, v| {
            layer.set(i, j, v)
        });
        Ok(true)
    }
}
