//! Traversability estimator stage: a `[0, 1]` layer from the world's maps.

use crate::error::Result;
use crate::grid::GridLayer;
use crate::world::World;

/// A rectangle of grid cells, `i0..i1` by `j0..j1` (ends excluded).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellRect {
    /// First column.
    pub i0: usize,
    /// First row.
    pub j0: usize,
    /// Past the last column.
    pub i1: usize,
    /// Past the last row.
    pub j1: usize,
}

impl CellRect {
    /// True when the rectangle holds no cell.
    pub fn is_empty(&self) -> bool {
        self.i0 >= self.i1 || self.j0 >= self.j1
    }

    /// The smallest rectangle holding both.
    pub fn union(&self, other: &CellRect) -> CellRect {
        if self.is_empty() {
            return *other;
        }
        if other.is_empty() {
            return *self;
        }
        CellRect {
            i0: self.i0.min(other.i0),
            j0: self.j0.min(other.j0),
            i1: self.i1.max(other.i1),
            j1: self.j1.max(other.j1),
        }
    }

    /// Grown by `cells` on every side, clipped to a grid of `size` cells.
    pub fn grown(&self, cells: usize, size: [usize; 2]) -> CellRect {
        CellRect {
            i0: self.i0.saturating_sub(cells),
            j0: self.j0.saturating_sub(cells),
            i1: (self.i1 + cells).min(size[0]),
            j1: (self.j1 + cells).min(size[1]),
        }
    }
}

/// Estimates how safely the robot can walk on each cell; 1 = safe, 0 = not, NaN = no data.
pub trait TraversabilityEstimator: Send + Sync {
    /// The traversability layer for `world`; it should share the elevation layer's geometry.
    fn estimate(&self, world: &World) -> Result<GridLayer>;

    /// How far (metres) a change of the elevation reaches in this estimator's layer: a
    /// cell's value depends only on the elevation of cells whose centres lie within
    /// this distance of its centre. `None` (the default): it may reach anywhere.
    fn reach(&self) -> Option<f64> {
        None
    }

    /// Brings `layer`, this estimator's layer for the world before its elevation changed
    /// in the cells of `changed`, up to date for `world` (after the change) by
    /// estimating again only the cells the change can reach; the result must equal
    /// [`estimate`](Self::estimate) of `world`. Returns false when it cannot (the
    /// default): the caller then estimates the whole layer again.
    fn update_layer(
        &self,
        world: &World,
        layer: &mut GridLayer,
        changed: CellRect,
    ) -> Result<bool> {
        let _ = (world, layer, changed);
        Ok(false)
    }
}
