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
//!
//! Objective authors check their objective the same way with [`check_objective`] on
//! random motions and [`check_objective_path`] on random multi-motion paths.

use crate::grid::GridGeometry;
use crate::objective::Objective;
use crate::pose::{angle_distance, Pose2};
use crate::space::StateSpace;
use crate::stages::DiscOnGrid;
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

/// Checks the contract of an [`Objective`] on the motions between `a`, `b`, `c` of
/// `space`, with `t` a split fraction: costs and bounds are ≥ 0; the bound is below the
/// motion's cost and consistent (`bound(a, c) ≤ cost(a, b) + bound(b, c)`); costs and
/// bounds respect the additive bound of `bound_weights`; a motion split at
/// `space.interpolate(a, b, t)` costs what the whole motion costs, to within
/// `split_tolerance` (relative: integrating objectives sample the terrain in pieces).
pub fn check_objective(
    objective: &dyn Objective,
    space: &dyn StateSpace,
    (a, b, c): (&Pose2, &Pose2, &Pose2),
    t: f64,
    split_tolerance: f64,
) -> Result<(), TestCaseError> {
    let (ab, bc) = (objective.motion_cost(a, b), objective.motion_cost(b, c));
    let bound = |p: &Pose2, q: &Pose2| objective.cost_bound(p, q);
    prop_assert!(
        ab >= 0.0 && ab.is_finite(),
        "motion cost {ab} is not finite and ≥ 0"
    );
    prop_assert!(bound(a, b) >= 0.0, "bound {} < 0", bound(a, b));
    prop_assert!(
        bound(a, b) <= ab + tolerance(ab),
        "bound {} above the motion's cost {ab}",
        bound(a, b)
    );
    prop_assert!(
        bound(a, c) <= ab + bound(b, c) + tolerance(ab + bc),
        "inconsistent bound: b(a, c) = {} > c(a, b) + b(b, c) = {}",
        bound(a, c),
        ab + bound(b, c)
    );
    let (w_t, w_r) = objective.bound_weights();
    let additive = w_t * a.xy_distance(b) + w_r * angle_distance(a.yaw, b.yaw);
    prop_assert!(
        ab >= additive - tolerance(additive) && bound(a, b) >= additive - tolerance(additive),
        "cost {ab} or bound {} below the weighted bound {additive}",
        bound(a, b)
    );
    let mid = space.interpolate(a, b, t);
    let split = objective.motion_cost(a, &mid) + objective.motion_cost(&mid, b);
    prop_assert!(
        (split - ab).abs() <= split_tolerance * (1.0 + ab),
        "not additive: c(a, m) + c(m, b) = {split} vs c(a, b) = {ab}"
    );
    Ok(())
}

/// Checks that the objective's bound between the ends of the path through `states` is
/// not above the path's cost, and that the path's cost is the sum of its motions'.
pub fn check_objective_path(
    objective: &dyn Objective,
    states: &[Pose2],
) -> Result<(), TestCaseError> {
    let (Some(first), Some(last)) = (states.first(), states.last()) else {
        return Ok(());
    };
    let cost = objective.path_cost(states);
    let sum: f64 = states
        .windows(2)
        .map(|w| objective.motion_cost(&w[0], &w[1]))
        .sum();
    prop_assert!(
        (cost - sum).abs() <= tolerance(sum),
        "path cost {cost} ≠ Σ motions {sum}"
    );
    let bound = objective.cost_bound(first, last);
    prop_assert!(
        bound <= cost + tolerance(cost),
        "bound {bound} above the cost {cost} of a {}-state path",
        states.len()
    );
    Ok(())
}

/// Checks the axioms every SMUG state space must satisfy on the poses `a`, `b`, `c`
/// and the interpolation fraction `t`: non-negativity, identity, symmetry (when the
/// space says it is symmetric), triangle inequality, the additive lower bound of
/// `lower_bound_weights`, `distance_within` the distance exactly when within the bound,
/// `length_bound` between `‖Δxy‖` and the motion's length,
/// interpolation endpoints, and that interpolation splits the distance
/// (`c(a, m) + c(m, b) = c(a, b)`).
pub fn check_metric_axioms(
    metric: &dyn StateSpace,
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
    if metric.is_symmetric() {
        prop_assert!((ab - ba).abs() <= tolerance(ab), "symmetry: {ab} vs {ba}");
    } else {
        prop_assert!(
            ba.is_finite() && ba >= 0.0,
            "non-negativity: c(b, a) = {ba}"
        );
    }
    prop_assert!(
        metric.distance_bound(a, b) <= ab + tolerance(ab),
        "distance bound {} > c(a, b) = {ab}",
        metric.distance_bound(a, b)
    );
    for bound in [
        0.0,
        0.5 * ab,
        ab,
        ab.next_up(),
        ab.next_down(),
        2.0 * ab,
        f64::INFINITY,
    ] {
        let within = metric.distance_within(a, b, bound);
        let expected = (ab <= bound).then_some(ab);
        prop_assert!(
            within.map(f64::to_bits) == expected.map(f64::to_bits),
            "distance_within(a, b, {bound}) = {within:?}, distance {ab}"
        );
    }
    let extent = metric.motion_extent(a, b);
    let length_bound = metric.length_bound(a, b);
    prop_assert!(
        a.xy_distance(b) <= length_bound + tolerance(length_bound)
            && length_bound <= extent.length + tolerance(extent.length),
        "length bound {length_bound} not in [‖Δxy‖ = {}, motion length {}]",
        a.xy_distance(b),
        extent.length
    );
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

/// A disc of radius 0.25 m on a 5×3 grid of 1 m cells with a wall at column 2 (a
/// small map with two free regions, for grid-disc tests).
pub fn walled_disc() -> DiscOnGrid {
    let geometry = GridGeometry::new([0.0, 0.0], 1.0, [5, 3]).unwrap();
    let blocked = (0..15).map(|k| k % 5 == 2).collect();
    DiscOnGrid {
        radius: 0.25,
        geometry,
        blocked,
    }
}
