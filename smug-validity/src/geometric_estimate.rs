//! The geometric estimator's layer: estimated as a whole, or updated where the
//! elevation changed (the cells whose fitting window holds a changed cell).

use super::{GeometricEstimator, TerrainFeatures, Window};
use smug_core::{CellRect, Error, GridLayer, TraversabilityEstimator, World};

impl GeometricEstimator {
    /// The layer's value at cell `(i, j)`.
    fn value(&self, window: &Window, elevation: &GridLayer, i: usize, j: usize) -> f32 {
        self.layer_value(window.features(elevation, i, j))
    }

    /// The layer's value of a cell with these features (NaN without).
    fn layer_value(&self, features: Option<TerrainFeatures>) -> f32 {
        features.map_or(f32::NAN, |f| self.score(&f) as f32)
    }
}

impl TraversabilityEstimator for GeometricEstimator {
    fn estimate(&self, world: &World) -> Result<GridLayer, Error> {
        let elevation = &world.elevation;
        let window = Window::new(self.window_radius, elevation.geometry.resolution);
        Ok(GridLayer::from_rows_par(elevation.geometry, |j, row| {
            window.row_features(elevation, j, |i, features| {
                row[i] = self.layer_value(features);
            });
        }))
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
        for j in area.j0..area.j1 {
            for i in area.i0..area.i1 {
                layer.set(i, j, self.value(&window, elevation, i, j));
            }
        }
        Ok(true)
    }
}
