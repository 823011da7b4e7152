//! Reusable property suites for plugin authors (feature `testing`).
//!
//! ```ignore
//! proptest! {
//!     #[test]
//!     fn my_metric_is_a_metric(a in arb_pose(10.0), b in arb_pose(10.0), c in arb_pose(10.0), t in 0.0f64..=1.0) {
//!         check_metric_axioms(&MyMetric::default(), &a, &b, &c, t)?;
//!     }
//! }
//! ```

use crate::metric::CostMetric;
use crate::pose::{angle_distance, Pose2};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use std::f64::consts::PI;

/// Relative tolerance of the metric checks.
const TOL: f64 = 1e-9;

/// Poses with |x|, |y| ≤ `half_extent` and yaw in `[-π, π)`, plus some
/// coincident and yaw-boundary cases that random sampling rarely hits.
pub fn arb_pose(half_extent: f64) -> impl Strategy<Value = Pose2> {
    let coordinate = prop_oneof![
        4 => -half_extent..half_extent,
        1 => Just(0.0),
    ];
    let yaw = prop_oneof![
        4 => -PI..PI,
        1 => Just(-PI),
        1 => Just(PI - 1e-12),
        1 => Just(0.0),
    ];
    (coordinate.clone(), coordinate, yaw).prop_map(|(x, y, yaw)| Pose2::new(x, y, yaw))
}

fn tolerance(scale: f64) -> f64 {
    TOL * (1.0 + scale.abs())
}

/// Checks the axioms every SMUG cost metric must satisfy on the poses `a`, `b`, `c`
/// and the interpolation fraction `t`: non-negativity, identity, symmetry, triangle
/// inequality, the additive lower bound of `lower_bound_weights`, interpolation
/// endpoints, and that interpolation splits the cost (`c(a, m) + c(m, b) = c(a, b)`).
pub fn check_metric_axioms(
    metric: &dyn CostMetric,
    a: &Pose2,
    b: &Pose2,
    c: &Pose2,
    t: f64,
) -> Result<(), TestCaseError> {
    let ab = metric.distance(a, b);
    let ba = metric.distance(b, a);
    let bc = metric.distance(b, c);
    let ac = metric.distance(a, c);
    prop_assert!(
        ab.is_finite() && ab >= 0.0,
        "non-negativity: c(a, b) = {ab}"
    );
    prop_assert!(
        metric.distance(a, a).abs() <= tolerance(0.0),
        "identity: c(a, a) ≠ 0"
    );
    if a.xy_distance(b) > 1e-6 {
        prop_assert!(ab > 0.0, "distinct positions at zero cost: c(a, b) = 0");
    }
    prop_assert!((ab - ba).abs() <= tolerance(ab), "symmetry: {ab} vs {ba}");
    prop_assert!(
        ac <= ab + bc + tolerance(ac),
        "triangle: c(a,c) = {ac} > {ab} + {bc}"
    );

    let (w_t, w_r) = metric.lower_bound_weights();
    let bound = w_t * a.xy_distance(b) + w_r * angle_distance(a.yaw, b.yaw);
    prop_assert!(
        bound <= ab + tolerance(ab),
        "lower bound {bound} > c(a, b) = {ab}"
    );

    let start = metric.interpolate(a, b, 0.0);
    let end = metric.interpolate(a, b, 1.0);
    prop_assert!(
        metric.distance(&start, a) <= tolerance(ab),
        "interpolate(a, b, 0) ≠ a"
    );
    prop_assert!(
        metric.distance(&end, b) <= tolerance(ab),
        "interpolate(a, b, 1) ≠ b"
    );
    let mid = metric.interpolate(a, b, t);
    let split = metric.distance(a, &mid) + metric.distance(&mid, b);
    prop_assert!(
        (split - ab).abs() <= 1e-6 * (1.0 + ab),
        "interpolation leaves the geodesic: c(a, m) + c(m, b) = {split} vs c(a, b) = {ab}"
    );
    Ok(())
}
