//! The `dubins` space: a car that only drives forwards, turning no tighter than a
//! minimum radius. The distance is the length of the shortest Dubins curve (Dubins
//! 1957: one of the words LSL, RSR, LSR, RSL, RLR, LRL), which is not symmetric.

use crate::curvature::{CurvatureSpace, Solver};
use crate::curve::{unit_length, Curve, Steer};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Parameters of the `dubins` space.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DubinsParams {
    /// Minimum turning radius, metres (> 0).
    pub turning_radius: f64,
}

impl Default for DubinsParams {
    fn default() -> Self {
        Self {
            turning_radius: 1.0,
        }
    }
}

/// The Dubins solver: forward-only shortest curves (asymmetric).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dubins;

impl Solver for Dubins {
    const KIND: u8 = 0;
    const SYMMETRIC: bool = false;

    fn shortest(x: f64, y: f64, phi: f64) -> Curve {
        shortest(x, y, phi)
    }
}

/// Forward-only curvature-limited motion: shortest Dubins curves of a turning radius.
pub type DubinsSpace = CurvatureSpace<Dubins>;

/// Rounding slack: a squared length or cosine this far outside its domain is taken as
/// on its boundary (a tangent case).
const SLACK: f64 = 1e-9;

/// An arc this close to a full turn is a zero arc gone round by rounding: at a tangency
/// of two arcs the straight piece `p = √p²` is ~1e-8 of pure rounding and moves the
/// arcs by as much (OMPL snaps at 5e-7). A shortest curve never turns a full circle.
const FULL_TURN_SLACK: f64 = 1e-6;

/// `x` in `[0, 2π)`; values within [`FULL_TURN_SLACK`] below `2π` are 0.
fn mod2pi(x: f64) -> f64 {
    let v = x.rem_euclid(TAU);
    if TAU - v < FULL_TURN_SLACK {
        0.0
    } else {
        v
    }
}

/// The shortest Dubins curve to `(x, y, phi)` from the origin facing +x, unit radius.
pub(crate) fn shortest(x: f64, y: f64, phi: f64) -> Curve {
    use Steer::{Left as L, Right as R, Straight as S};
    let d = x.hypot(y);
    let theta = if d > 0.0 { y.atan2(x) } else { 0.0 };
    let alpha = mod2pi(-theta);
    let beta = mod2pi(phi - theta);
    let (sa, ca) = alpha.sin_cos();
    let (sb, cb) = beta.sin_cos();
    let cab = (alpha - beta).cos();
    // The best word so far and its unit length; only the winner is built into a curve.
    let mut best: Option<([Steer; 3], [f64; 3], f64)> = None;
    let mut consider = |steers: [Steer; 3], lengths: Option<[f64; 3]>| {
        if let Some(lengths) = lengths {
            let length = unit_length(lengths);
            if best.is_none_or(|(_, _, b)| length < b) {
                best = Some((steers, lengths, length));
            }
        }
    };
    let sqrt_slack = |p2: f64| (p2 >= -SLACK).then(|| p2.max(0.0).sqrt());

    // LSL
    consider(
        [L, S, L],
        sqrt_slack(2.0 + d * d - 2.0 * cab + 2.0 * d * (sa - sb)).map(|p| {
            let tmp = (cb - ca).atan2(d + sa - sb);
            [mod2pi(tmp - alpha), p, mod2pi(beta - tmp)]
        }),
    );
    // RSR
    consider(
        [R, S, R],
        sqrt_slack(2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa)).map(|p| {
            let tmp = (ca - cb).atan2(d - sa + sb);
            [mod2pi(alpha - tmp), p, mod2pi(tmp - beta)]
        }),
    );
    // LSR
    consider(
        [L, S, R],
        sqrt_slack(-2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb)).map(|p| {
            let tmp = (-ca - cb).atan2(d + sa + sb) - (-2.0f64).atan2(p);
            [mod2pi(tmp - alpha), p, mod2pi(tmp - beta)]
        }),
    );
    // RSL
    consider(
        [R, S, L],
        sqrt_slack(-2.0 + d * d + 2.0 * cab - 2.0 * d * (sa + sb)).map(|p| {
            let tmp = (ca + cb).atan2(d - sa - sb) - 2.0f64.atan2(p);
            [mod2pi(alpha - tmp), p, mod2pi(beta - tmp)]
        }),
    );
    let acos_slack = |c: f64| (c.abs() <= 1.0 + SLACK).then(|| c.clamp(-1.0, 1.0).acos());
    // RLR
    consider(
        [R, L, R],
        acos_slack((6.0 - d * d + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0).map(|a| {
            let phi = (ca - cb).atan2(d - sa + sb);
            let p = (TAU - a).rem_euclid(TAU);
            let t = mod2pi(alpha - phi + p / 2.0);
            [t, p, mod2pi(alpha - beta - t + p)]
        }),
    );
    // LRL
    consider(
        [L, R, L],
        acos_slack((6.0 - d * d + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0).map(|a| {
            let phi = (ca - cb).atan2(d + sa - sb);
            let p = (TAU - a).rem_euclid(TAU);
            let t = mod2pi(-alpha - phi + p / 2.0);
            [t, p, mod2pi(beta - alpha - t + p)]
        }),
    );
    let (steers, lengths, _) = best.expect("LSL or RSR always exists");
    Curve::from_word(&steers, &lengths)
}

smug_core::register_plugin!(
    smug_core::registry::SpaceStage,
    name = "dubins",
    summary = "car-like, forward only: shortest Dubins curves of turning_radius (asymmetric)",
    params = DubinsParams,
    build = |params, _ctx| Ok(Box::new(DubinsSpace::new(params.turning_radius)?)),
);

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::pose::Pose2;
    use smug_core::space::StateSpace;
    use std::f64::consts::PI;

    fn space(r: f64) -> DubinsSpace {
        DubinsSpace::new(r).unwrap()
    }

    #[test]
    fn straight_ahead_is_the_euclidean_distance() {
        let d = space(1.0).distance(
            &Pose2::new(0.0, 0.0, 0.3),
            &Pose2::new(3.0 * 0.3f64.cos(), 3.0 * 0.3f64.sin(), 0.3),
        );
        assert!((d - 3.0).abs() < 1e-12, "{d}");
    }

    #[test]
    fn a_u_turn_is_half_a_circle_and_going_back_costs_more() {
        let s = space(2.0);
        let a = Pose2::new(0.0, 0.0, 0.0);
        let b = Pose2::new(0.0, 4.0, PI);
        assert!((s.distance(&a, &b) - 2.0 * PI).abs() < 1e-9);
        let extent = s.motion_extent(&a, &b);
        assert!((extent.turning - PI).abs() < 1e-9);
        // Backwards by one metre: turn around and come back (asymmetric).
        let behind = Pose2::new(-1.0, 0.0, 0.0);
        assert!(s.distance(&a, &behind) > 2.0 * PI * 2.0 - 1e-9);
        assert!((s.distance(&behind, &a) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_radii() {
        for r in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let message = DubinsSpace::new(r).unwrap_err().to_string();
            assert!(
                message.contains("turning_radius must be finite and > 0"),
                "{message}"
            );
        }
    }
}
