//! Tests of the SE(2) space: metric axioms, interpolation, bounds.

use super::*;
use crate::testing::{arb_pose, check_metric_axioms};
use proptest::prelude::*;
use std::f64::consts::PI;

proptest! {
    #[test]
    fn default_se2_metric_satisfies_axioms(a in arb_pose(50.0), b in arb_pose(50.0), c in arb_pose(50.0), t in 0.0f64..=1.0) {
        check_metric_axioms(&Se2Space::default(), &a, &b, &c, t)?;
    }

    #[test]
    fn weighted_se2_metric_satisfies_axioms(w_t in 0.01f64..10.0, w_r in 0.0f64..10.0,
            a in arb_pose(50.0), b in arb_pose(50.0), c in arb_pose(50.0), t in 0.0f64..=1.0) {
        check_metric_axioms(&Se2Space::new(w_t, w_r).unwrap(), &a, &b, &c, t)?;
    }
}

#[test]
fn matches_ompl_formula_not_squared_norm() {
    let m = Se2Space::default();
    let a = Pose2::new(0.0, 0.0, 0.0);
    let b = Pose2::new(3.0, 4.0, PI / 2.0);
    assert!((m.distance(&a, &b) - (5.0 + 0.5 * PI / 2.0)).abs() < 1e-12);
}

#[test]
fn interpolation_takes_the_short_yaw_arc() {
    let m = Se2Space::default();
    let a = Pose2::new(0.0, 0.0, 3.0);
    let b = Pose2::new(2.0, 0.0, -3.0);
    let mid = m.interpolate(&a, &b, 0.5);
    assert!((mid.x - 1.0).abs() < 1e-12);
    assert!(angle_distance(mid.yaw, PI) < 1e-9, "yaw {}", mid.yaw);
}

#[test]
fn rejects_bad_weights() {
    assert!(Se2Space::new(0.0, 0.5).is_err());
    assert!(Se2Space::new(1.0, -0.1).is_err());
    assert!(Se2Space::new(f64::NAN, 0.5).is_err());
}
