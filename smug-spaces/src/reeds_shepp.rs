//! The `reeds-shepp` space: a car that drives forwards and in reverse, turning no
//! tighter than a minimum radius. The distance is the length of the shortest
//! Reeds–Shepp curve (one of 48 words, see [`words`]), a symmetric metric.

pub mod words;

use crate::curvature::{CurvatureSpace, Solver};
use crate::curve::Curve;
use serde::{Deserialize, Serialize};

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

/// The Reeds–Shepp solver: shortest curves forwards and in reverse (a metric).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReedsShepp;

impl Solver for ReedsShepp {
    const KIND: u8 = 1;
    const SYMMETRIC: bool = true;

    fn shortest(x: f64, y: f64, phi: f64) -> Curve {
        words::shortest(x, y, phi)
    }

    fn shortest_within(x: f64, y: f64, phi: f64, bound: f64) -> Option<Curve> {
        words::shortest_within(x, y, phi, bound)
    }
}

/// Forward-and-reverse curvature-limited motion: shortest Reeds–Shepp curves.
pub type ReedsSheppSpace = CurvatureSpace<ReedsShepp>;

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
    use smug_core::pose::Pose2;
    use smug_core::space::StateSpace;
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
    fn curves_moved_by_a_whole_number_of_lattice_steps_cost_the_same_bit_for_bit() {
        // What lets the lattice cost each primitive once (`is_translation_invariant`).
        let rs = ReedsSheppSpace::new(1.5).unwrap();
        let dubins = crate::DubinsSpace::new(1.5).unwrap();
        let spaces: [&dyn StateSpace; 2] = [&rs, &dubins];
        for space in spaces {
            assert!(space.is_translation_invariant());
            for k in 0..64 {
                let yaw = k as f64 * PI / 32.0;
                let (dx, dy) = (0.25 * (k % 7) as f64, -0.25 * (k % 5) as f64);
                let a = Pose2::new(0.0, 0.0, yaw);
                let b = Pose2::new(dx, dy, yaw + 0.3);
                let length = space.motion_extent(&a, &b).length;
                for (tx, ty) in [(0.125, 0.0), (17.5, 3.25), (29.875, 28.75)] {
                    let a2 = Pose2::new(tx, ty, yaw);
                    let b2 = Pose2::new(tx + dx, ty + dy, yaw + 0.3);
                    assert_eq!(
                        space.motion_extent(&a2, &b2).length.to_bits(),
                        length.to_bits()
                    );
                }
            }
        }
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
