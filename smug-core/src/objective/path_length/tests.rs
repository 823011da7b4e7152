//! Tests of the path-length objective against its contract.

use super::*;
use crate::space::Se2Space;
use crate::testing::arb_pose;
use proptest::prelude::*;

proptest! {
    #[test]
    fn equals_the_se2_distance_bit_for_bit(a in arb_pose(50.0), b in arb_pose(50.0)) {
        let (space, objective) = (Se2Space::default(), PathLength::default());
        prop_assert_eq!(space.distance(&a, &b).to_bits(), objective.motion_cost(&a, &b).to_bits());
        prop_assert_eq!(objective.cost_bound(&a, &b).to_bits(), objective.motion_cost(&a, &b).to_bits());
    }
}

#[test]
fn rejects_bad_weights() {
    let bad = |w_t, w_r| {
        PathLength::from_params(PathLengthParams {
            translation_weight: w_t,
            rotation_weight: w_r,
        })
        .unwrap_err()
        .to_string()
    };
    assert!(bad(0.0, 0.5).contains("translation_weight"));
    assert!(bad(1.0, -1.0).contains("rotation_weight"));
    assert!(bad(f64::NAN, 0.5).contains("translation_weight"));
    assert!(bad(1.0, f64::INFINITY).contains("rotation_weight"));
}

#[test]
fn translation_invariant_only_on_spaces_that_are() {
    // The SE(2) space is; a space that looks at the map (the trait's default) is not.
    #[derive(Debug)]
    struct OnTheMap;
    impl StateSpace for OnTheMap {
        fn distance(&self, a: &Pose2, b: &Pose2) -> f64 {
            a.xy_distance(b) * (1.0 + a.x.abs())
        }
        fn interpolate(&self, a: &Pose2, b: &Pose2, t: f64) -> Pose2 {
            Se2Space::default().interpolate(a, b, t)
        }
        fn lower_bound_weights(&self) -> (f64, f64) {
            (1.0, 0.0)
        }
        fn is_holonomic(&self) -> bool {
            false
        }
    }
    assert!(PathLength::default().is_translation_invariant());
    assert!(PathLength::default()
        .on(Arc::new(Se2Space::default()))
        .is_translation_invariant());
    assert!(!PathLength::default()
        .on(Arc::new(OnTheMap))
        .is_translation_invariant());
}
