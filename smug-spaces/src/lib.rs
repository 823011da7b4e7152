//! SMUG motion models beyond holonomic SE(2): car-like robots with a minimum turning
//! radius.
//!
//! - `dubins`: forward only; the distance is the length of the shortest Dubins curve
//!   (asymmetric);
//! - `reeds-shepp`: forward and reverse; the distance is the length of the shortest
//!   Reeds–Shepp curve (a symmetric metric).
//!
//! Both are non-holonomic: a plan is its curves sampled, headings untouched. The
//! shortest-path solvers are written here (see [`curve`] for the shared sampling) and
//! cross-checked against OMPL's `DubinsStateSpace` and `ReedsSheppStateSpace`
//! (`tools/ompl-peer/SPACES.md`).

#![warn(missing_docs)]

pub mod curvature;
pub mod curve;
pub mod dubins;
pub mod reeds_shepp;

pub use curvature::{CurvatureSpace, Solver};
pub use curve::{Curve, Segment, Steer};
pub use dubins::{Dubins, DubinsParams, DubinsSpace};
pub use reeds_shepp::{ReedsShepp, ReedsSheppParams, ReedsSheppSpace};

/// Checks a turning radius: finite and > 0, else the `space` stage's parameter error.
pub(crate) fn check_turning_radius(turning_radius: f64) -> smug_core::Result<f64> {
    if turning_radius.is_finite() && turning_radius > 0.0 {
        Ok(turning_radius)
    } else {
        Err(smug_core::Error::invalid_param(
            "space",
            format!("turning_radius must be finite and > 0, got {turning_radius}"),
        ))
    }
}
