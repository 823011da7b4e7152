//! An out-of-tree SMUG plugin: a traversability estimator written outside the
//! framework crates, registered by name, selectable from any config:
//!
//! ```toml
//! [traversability]
//! type = "example-slope"
//! params = { critical_slope = 0.6 }
//! ```
//!
//! A binary picks it up by linking this crate (`use smug_example_traversability as _;`).

#![warn(missing_docs)]

use serde::{Deserialize, Serialize};
use smug_core::{Error, GridLayer, TraversabilityEstimator, World};

/// Parameters: the slope at which the terrain stops being traversable.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SlopeParams {
    /// Slope (rise over run) at which traversability reaches 0.
    pub critical_slope: f64,
}

impl Default for SlopeParams {
    fn default() -> Self {
        Self {
            critical_slope: 0.6,
        }
    }
}

/// Traversability `1 − slope / critical_slope`, clamped to `[0, 1]`; the slope is the
/// central-difference gradient of the elevation layer. No data where elevation has none.
#[derive(Clone, Copy, Debug)]
pub struct SlopeEstimator {
    critical_slope: f64,
}

impl SlopeEstimator {
    /// An estimator; `critical_slope` must be > 0.
    pub fn new(params: SlopeParams) -> Result<Self, Error> {
        if !(params.critical_slope.is_finite() && params.critical_slope > 0.0) {
            return Err(Error::invalid_param(
                "traversability",
                format!("critical_slope must be > 0, got {}", params.critical_slope),
            ));
        }
        Ok(Self {
            critical_slope: params.critical_slope,
        })
    }
}

/// Central-difference derivative along one axis (one-sided at the borders).
fn derivative(
    lower: f32,
    centre: f32,
    upper: f32,
    has_lower: bool,
    has_upper: bool,
    h: f64,
) -> f64 {
    match (has_lower, has_upper) {
        (true, true) => (upper - lower) as f64 / (2.0 * h),
        (true, false) => (centre - lower) as f64 / h,
        (false, true) => (upper - centre) as f64 / h,
        (false, false) => 0.0,
    }
}

impl TraversabilityEstimator for SlopeEstimator {
    fn estimate(&self, world: &World) -> Result<GridLayer, Error> {
        let e = &world.elevation;
        let g = e.geometry;
        let [nx, ny] = g.size;
        Ok(GridLayer::from_fn(g, |i, j| {
            let z = e.get(i, j);
            let (has_w, has_e) = (i > 0, i + 1 < nx);
            let (has_s, has_n) = (j > 0, j + 1 < ny);
            let west = if has_w { e.get(i - 1, j) } else { z };
            let east = if has_e { e.get(i + 1, j) } else { z };
            let south = if has_s { e.get(i, j - 1) } else { z };
            let north = if has_n { e.get(i, j + 1) } else { z };
            let dx = derivative(west, z, east, has_w, has_e, g.resolution);
            let dy = derivative(south, z, north, has_s, has_n, g.resolution);
            let slope = dx.hypot(dy);
            if slope.is_nan() {
                f32::NAN
            } else {
                (1.0 - slope / self.critical_slope).clamp(0.0, 1.0) as f32
            }
        }))
    }
}

smug_core::register_plugin!(
    smug_core::registry::TraversabilityStage,
    name = "example-slope",
    summary = "out-of-tree example: 1 − slope / critical_slope from the elevation gradient",
    params = SlopeParams,
    build = |params, _ctx| Ok(Box::new(SlopeEstimator::new(params)?)),
);
