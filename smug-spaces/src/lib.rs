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

pub mod curve;
pub mod dubins;
pub mod reeds_shepp;

pub use curve::{Curve, Segment, Steer};
pub use dubins::{DubinsParams, DubinsSpace};
pub use reeds_shepp::{ReedsSheppParams, ReedsSheppSpace};

/// What a cached curve was computed for: the model, the radius and both poses, as bits.
type CurveKey = (u8, [u64; 7]);

thread_local! {
    /// The last curve computed on this thread: a motion validator, a smoother or an
    /// objective samples one motion many times in a row.
    static LAST_CURVE: std::cell::Cell<Option<(CurveKey, Curve)>> = const { std::cell::Cell::new(None) };
}

/// The curve of model `kind` with `radius` from `a` to `b`: the last one computed on this
/// thread when it was for the same motion, else `compute()` (then remembered).
pub(crate) fn cached_curve(
    kind: u8,
    radius: f64,
    a: &smug_core::Pose2,
    b: &smug_core::Pose2,
    compute: impl FnOnce() -> Curve,
) -> Curve {
    let key = (
        kind,
        [radius, a.x, a.y, a.yaw, b.x, b.y, b.yaw].map(f64::to_bits),
    );
    LAST_CURVE.with(|last| match last.get() {
        Some((k, curve)) if k == key => curve,
        _ => {
            let curve = compute();
            last.set(Some((key, curve)));
            curve
        }
    })
}

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
