//! Checks shared by the property tests of the curvature-limited spaces: the local motion
//! sampled through the `StateSpace` API at 1000 steps.

use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use smug_core::pose::{wrap_angle, Pose2};
use smug_core::space::StateSpace;

/// Steps of the sampled curve.
pub const STEPS: usize = 1000;

/// Sub-steps of a step across a gear change (its chord cuts the cusp).
const CUSP_STEPS: usize = 256;

/// Turning radii the properties run with.
pub fn arb_radius() -> impl Strategy<Value = f64> {
    prop_oneof![Just(1.0), Just(2.5), 0.2f64..5.0]
}

fn chord(p: &Pose2, q: &Pose2) -> f64 {
    p.xy_distance(q)
}

/// Checks the motion `a → b` sampled at [`STEPS`] steps: the chords add up to the
/// distance (within 1e-3 relative), no step turns tighter than `radius`, and every
/// step away from a gear change moves along the heading when driving forwards and
/// against it when reversing (`forward_only`: the motion never reverses); and the curve
/// ends at `b`.
pub fn check_sampled_curve(
    space: &dyn StateSpace,
    radius: f64,
    a: &Pose2,
    b: &Pose2,
    forward_only: bool,
) -> Result<(), TestCaseError> {
    let distance = space.distance(a, b);
    let at = |t: f64| space.interpolate(a, b, t);
    let mut length = 0.0;
    let mut prev = at(0.0);
    for i in 1..=STEPS {
        let (t0, t1) = ((i - 1) as f64 / STEPS as f64, i as f64 / STEPS as f64);
        let next = at(t1);
        let gears = [t0, 0.5 * (t0 + t1), t1].map(|t| space.is_reversing(a, b, t));
        let steady = gears.iter().all(|&g| g == gears[0]);
        if forward_only {
            prop_assert!(!gears.iter().any(|&g| g), "a forward-only model reverses");
        }
        if steady {
            length += chord(&prev, &next);
            let c = chord(&prev, &next);
            if c > 1e-9 * (1.0 + distance) {
                let turn = wrap_angle(next.yaw - prev.yaw).abs();
                prop_assert!(
                    turn / c <= (1.0 / radius) * (1.0 + 1e-3) + 1e-9,
                    "step {i} turns {turn} rad over {c} m: tighter than radius {radius}"
                );
                let (s, co) = prev.yaw.sin_cos();
                let along = ((next.x - prev.x) * co + (next.y - prev.y) * s) / c;
                if gears[0] {
                    prop_assert!(
                        along <= 1e-6,
                        "step {i} reverses along the heading: {along}"
                    );
                } else {
                    prop_assert!(along >= -1e-6, "step {i} moves backwards: {along}");
                }
            }
        } else {
            let mut p = prev;
            for k in 1..=CUSP_STEPS {
                let q = at(t0 + (t1 - t0) * k as f64 / CUSP_STEPS as f64);
                length += chord(&p, &q);
                p = q;
            }
        }
        prev = next;
    }
    prop_assert!(
        (length - distance).abs() <= 1e-3 * distance + 1e-9,
        "sampled length {length} vs distance {distance}"
    );
    // The curve itself reaches the goal (interpolate(a, b, 1) is b by fiat).
    let near_end = at(1.0 - 1e-9);
    let miss =
        near_end.xy_distance(b) + radius * smug_core::pose::angle_distance(near_end.yaw, b.yaw);
    prop_assert!(
        miss <= 1e-6 * (1.0 + distance),
        "the curve ends {miss} away from the goal"
    );
    let extent = space.motion_extent(a, b);
    prop_assert!(
        (extent.length - distance).abs() <= 1e-9 * (1.0 + distance),
        "motion length {} vs distance {distance}",
        extent.length
    );
    prop_assert!(extent.turning >= smug_core::pose::angle_distance(a.yaw, b.yaw) - 1e-9);
    prop_assert!(
        distance >= a.xy_distance(b) - 1e-9,
        "distance {distance} < ‖Δxy‖ {}",
        a.xy_distance(b)
    );
    Ok(())
}

/// `a` moved `d` metres along its heading.
pub fn ahead(a: &Pose2, d: f64) -> Pose2 {
    Pose2::new(a.x + d * a.yaw.cos(), a.y + d * a.yaw.sin(), a.yaw)
}
