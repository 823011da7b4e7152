//! Traversability estimator stage: a `[0, 1]` layer from the world's maps.

use crate::error::Result;
use crate::grid::GridLayer;
use crate::world::World;

/// Estimates how safely the robot can walk on each cell; 1 = safe, 0 = not, NaN = no data.
pub trait TraversabilityEstimator: Send + Sync {
    /// The traversability layer for `world`; it should share the elevation layer's geometry.
    fn estimate(&self, world: &World) -> Result<GridLayer>;
}
