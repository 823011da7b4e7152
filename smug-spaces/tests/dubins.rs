//! Properties of the `dubins` space.

mod common;

use common::{ahead, arb_radius, check_sampled_curve};
use proptest::prelude::*;
use smug_core::registry::{SpaceStage, Stage};
use smug_core::space::StateSpace;
use smug_core::testing::{arb_pose, check_metric_axioms};
use smug_spaces::{DubinsSpace, ReedsSheppSpace};

proptest! {
    #[test]
    fn satisfies_the_metric_axioms(r in arb_radius(), a in arb_pose(10.0), b in arb_pose(10.0),
            c in arb_pose(10.0), t in 0.0f64..=1.0) {
        let space = DubinsSpace::new(r).unwrap();
        check_metric_axioms(&space, &a, &b, &c, t)?;
        check_metric_axioms(&space, &b, &a, &c, t)?;
    }

    #[test]
    fn near_poses_satisfy_the_metric_axioms(r in arb_radius(), a in arb_pose(1.0), b in arb_pose(1.0),
            c in arb_pose(1.0), t in 0.0f64..=1.0) {
        check_metric_axioms(&DubinsSpace::new(r).unwrap(), &a, &b, &c, t)?;
    }

    #[test]
    fn the_sampled_curve_is_the_distance_long_forward_and_curvature_limited(
            r in arb_radius(), a in arb_pose(10.0), b in arb_pose(10.0)) {
        check_sampled_curve(&DubinsSpace::new(r).unwrap(), r, &a, &b, true)?;
    }

    #[test]
    fn near_sampled_curves_too(r in arb_radius(), a in arb_pose(1.0), b in arb_pose(1.0)) {
        check_sampled_curve(&DubinsSpace::new(r).unwrap(), r, &a, &b, true)?;
    }

    #[test]
    fn straight_ahead_is_the_euclidean_distance(r in arb_radius(), a in arb_pose(10.0), d in 0.0f64..20.0) {
        let b = ahead(&a, d);
        let distance = DubinsSpace::new(r).unwrap().distance(&a, &b);
        prop_assert!((distance - d).abs() <= 1e-9 * (1.0 + d), "{distance} vs {d}");
    }

    #[test]
    fn lies_between_euclid_and_above_reeds_shepp(r in arb_radius(), a in arb_pose(10.0), b in arb_pose(10.0)) {
        let dubins = DubinsSpace::new(r).unwrap();
        let rs = ReedsSheppSpace::new(r).unwrap();
        let (d, d_rs) = (dubins.distance(&a, &b), rs.distance(&a, &b));
        prop_assert!(d_rs <= d + 1e-9 * (1.0 + d), "reeds-shepp {d_rs} > dubins {d}");
        prop_assert!(a.xy_distance(&b) <= d_rs + 1e-9 * (1.0 + d_rs));
        prop_assert!(dubins.length_bound(&a, &b) == d);
        prop_assert!(!dubins.is_symmetric() && !dubins.is_holonomic());
    }
}

#[test]
fn is_registered_with_a_unit_default_radius() {
    let spaces = SpaceStage::registry().unwrap();
    let params = (spaces.get("dubins").unwrap().default_params)();
    assert_eq!(params["turning_radius"].as_float(), Some(1.0));
}
