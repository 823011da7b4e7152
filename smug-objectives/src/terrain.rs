//! The world's layers as the objectives read them.

use smug_core::{Error, Result, World};
use std::sync::Arc;

/// Traversability and height lookups on a world, with the conventions the objectives
/// share: unknown traversability counts as 0 (worst), unknown height as no climb.
#[derive(Clone, Debug)]
pub struct Terrain {
    world: Arc<World>,
}

impl Terrain {
    /// The terrain of `world`; `needs_traversability`: the objective `name` reads the
    /// traversability layer, so a world without one is an error naming both.
    pub fn new(world: Arc<World>, name: &str, needs_traversability: bool) -> Result<Self> {
        if needs_traversability && world.traversability.is_none() {
            return Err(Error::invalid_param(
                "objective",
                format!(
                    "objective `{name}` needs a traversability layer, and world `{}` has none \
                     (add a [traversability] stage, e.g. type = \"geometric\")",
                    world.name
                ),
            ));
        }
        Ok(Self { world })
    }

    /// Traversability in the cell containing `(x, y)`, in [0, 1]; 0 where unknown.
    pub fn traversability(&self, x: f64, y: f64) -> f64 {
        self.world
            .traversability
            .as_ref()
            .and_then(|layer| layer.nearest(x, y))
            .map_or(0.0, |t| t.clamp(0.0, 1.0))
    }

    /// Terrain height at `(x, y)` (bilinear), if known.
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
        self.world.height_at(x, y)
    }

    /// Height gained from `(xa, ya)` to `(xb, yb)` (`0` when either is unknown).
    pub fn rise(&self, (xa, ya): (f64, f64), (xb, yb): (f64, f64)) -> f64 {
        match (self.height(xa, ya), self.height(xb, yb)) {
            (Some(za), Some(zb)) => zb - za,
            _ => 0.0,
        }
    }
}
