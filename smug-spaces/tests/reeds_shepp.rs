//! Properties of the `reeds-shepp` space.

mod common;

use common::{ahead, arb_radius, check_sampled_curve};
use proptest::prelude::*;
use smug_core::registry::{SpaceStage, Stage};
use smug_core::space::StateSpace;
use smug_core::testing::{arb_pose, check_metric_axioms};
use smug_spaces::ReedsSheppSpace;

proptest! {
    #[test]
    fn satisfies_the_metric_axioms(r in arb_radius(), a in arb_pose(10.0), b in arb_pose(10.0),
            c in arb_pose(10.0), t in 0.0f64..=1.0) {
        let space = ReedsSheppSpace::new(r).unwrap();
        prop_assert!(space.is_symmetric());
        check_metric_axioms(&space, &a, &b, &c, t)?;
    }

    #[test]
    fn near_poses_satisfy_the_metric_axioms(r in arb_radius(), a in arb_pose(1.0), b in arb_pose(1.0),
            c in arb_pose(1.0), t in 0.0f64..=1.0) {
        check_metric_axioms(&ReedsSheppSpace::new(r).unwrap(), &a, &b, &c, t)?;
    }

    #[test]
    fn the_sampled_curve_is_the_distance_long_and_reverses_against_the_heading(
            r in arb_radius(), a in arb_pose(10.0), b in arb_pose(10.0)) {
        check_sampled_curve(&ReedsSheppSpace::new(r).unwrap(), r, &a, &b, false)?;
    }

    #[test]
    fn near_sampled_curves_too(r in arb_radius(), a in arb_pose(1.0), b in arb_pose(1.0)) {
        check_sampled_curve(&ReedsSheppSpace::new(r).unwrap(), r, &a, &b, false)?;
    }

    #[test]
    fn straight_ahead_and_straight_back_are_the_euclidean_distance(
            r in arb_radius(), a in arb_pose(10.0), d in -20.0f64..20.0) {
        let space = ReedsSheppSpace::new(r).unwrap();
        let b = ahead(&a, d);
        let distance = space.distance(&a, &b);
        prop_assert!((distance - d.abs()).abs() <= 1e-9 * (1.0 + d.abs()), "{distance} vs {d}");
        if d.abs() > 1e-6 {
            prop_assert_eq!(space.is_reversing(&a, &b, 0.5), d < 0.0);
        }
    }

    #[test]
    fn is_a_metric_bounded_by_euclid(r in arb_radius(), a in arb_pose(10.0), b in arb_pose(10.0)) {
        let space = ReedsSheppSpace::new(r).unwrap();
        let d = space.distance(&a, &b);
        prop_assert!(a.xy_distance(&b) <= d + 1e-9 * (1.0 + d));
        prop_assert!(space.length_bound(&a, &b) == d);
        prop_assert!(!space.is_holonomic());
    }
}

#[test]
fn is_registered_with_a_unit_default_radius() {
    let spaces = SpaceStage::registry().unwrap();
    let params = (spaces.get("reeds-shepp").unwrap().default_params)();
    assert_eq!(params["turning_radius"].as_float(), Some(1.0));
}
