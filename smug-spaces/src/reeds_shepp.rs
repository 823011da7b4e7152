//! The `reeds-shepp` space: a car that drives forwards and in reverse, turning no
//! tighter than a minimum radius. The distance is the length of the shortest
//! Reeds–Shepp curve (one of 48 words, see [`words`]), a symmetric metric.

pub mod words;

use crate::curve::{relative, Curve};
use serde::{Deserialize, Serialize};
use smug_core::pose::Pose2;
use smug_core::space::{MotionExtent, StateSpace};

/// Parameters of the `reeds-shepp` space.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ReedsSheppParams {
    /// Minimum turning radius, metres (> 0).
    pub turning_radius: f64,
}

impl Default for ReedsSheppParams {
    fn default() -> Self {
        Self {
            turning_radius: 1.0,
        }
    }
}

/// Forward-and-reverse curvature-limited motion: shortest Reeds–Shepp curves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReedsSheppSpace {
    radius: f64,
}

impl ReedsSheppSpace {
    /// A space of turning radius `turning_radius` (finite and > 0).
    pub fn new(turning_radius: f64) -> smug_core::Result<Self> {
        Ok(Self {
            radius: crate::check_turning_radius(turning_radius)?,
        })
    }

    /// The minimum turning radius, metres.
    pub fn turning_radius(&self) -> f64 {
        self.radius
    }

    /// The shortest Reeds–Shepp curve from `a` to `b` (unit-radius form).
    pub fn curve(&self, a: &Pose2, b: &Pose2) -> Curve {
        crate::cached_curve(1, self.radius, a, b, || {
            let (x, y, phi) = relative(a, b, self.radius);
            words::shortest(x, y, phi)
        })
    }
}

impl StateSpace for ReedsSheppSpace {
    fn distance(&self, a: &Pose2, b: &Pose2) -> f64 {
        self.radius * self.curve(a, b).unit_length()
    }

    fn interpolate(&self, a: &Pose2, b: &Pose2, t: f64) -> Pose2 {
        if t <= 0.0 {
            return *a;
        }
        if t >= 1.0 {
            return *b;
        }
        self.curve(a, b).sample(a, self.radius, t)
    }

    fn lower_bound_weights(&self) -> (f64, f64) {
        (1.0, 0.0)
    }

    fn distance_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        // A curve turns at most 1/r per metre: turning d(yaw) takes r·d(yaw) of it.
        a.xy_distance(b)
            .max(self.radius * smug_core::pose::angle_distance(a.yaw, b.yaw))
    }

    fn motion_extent(&self, a: &Pose2, b: &Pose2) -> MotionExtent {
        self.curve(a, b).extent(self.radius)
    }

    fn length_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        self.distance(a, b)
    }

    fn is_reversing(&self, a: &Pose2, b: &Pose2, t: f64) -> bool {
        self.curve(a, b).is_reversing(t)
    }

    fn is_holonomic(&self) -> bool {
        false
    }
}

smug_core::register_plugin!(
    smug_core::registry::SpaceStage,
    name = "reeds-shepp",
    summary = "car-like, forward and reverse: shortest Reeds–Shepp curves of turning_radius",
    params = ReedsSheppParams,
    build = |params, _ctx| Ok(Box::new(ReedsSheppSpace::new(params.turning_radius)?)),
);

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn straight_back_is_reversing_the_euclidean_distance() {
        let s = ReedsSheppSpace::new(1.5).unwrap();
        let a = Pose2::new(1.0, 2.0, PI / 2.0);
        let b = Pose2::new(1.0, -1.0, PI / 2.0);
        assert!((s.distance(&a, &b) - 3.0).abs() < 1e-12);
        assert!(s.is_reversing(&a, &b, 0.5));
        assert!(!s.is_reversing(&b, &a, 0.5));
    }

    #[test]
    fn a_quarter_turn_in_place_is_cheaper_than_dubins() {
        let r = 1.0;
        let rs = ReedsSheppSpace::new(r).unwrap();
        let dubins = crate::DubinsSpace::new(r).unwrap();
        let a = Pose2::new(0.0, 0.0, 0.0);
        let b = Pose2::new(0.0, 0.0, PI / 2.0);
        let (d_rs, d_dubins) = (rs.distance(&a, &b), dubins.distance(&a, &b));
        assert!(d_rs < d_dubins, "{d_rs} vs {d_dubins}");
        assert!(rs.motion_extent(&a, &b).turning >= PI / 2.0 - 1e-12);
    }

    #[test]
    fn rejects_bad_radii() {
        assert!(ReedsSheppSpace::new(0.0).is_err());
        assert!(ReedsSheppSpace::new(f64::NEG_INFINITY).is_err());
    }
}
