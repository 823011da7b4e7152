//! Post-processing a selected route into waypoints for a local planner: the segments
//! concatenated, headings turned to the direction of travel (holonomic models), curved
//! motions sampled (car-like models, with the gear), heights from the terrain.

use smug_core::pipeline::Pipeline;
use smug_core::plan::Plan;
use smug_core::pose::{wrap_angle, Pose2, Waypoint};
use smug_core::space::StateSpace;
use smug_core::stages::{MotionValidator, StateValidityChecker};
use smug_core::world::World;

/// Spacing of the waypoints sampled along a curved model's motions, in space distance.
pub const CURVE_WAYPOINT_STEP: f64 = 0.1;

/// The plan's waypoints and, for models that reverse, whether the robot drives backwards
/// towards each one (empty otherwise). Holonomic models keep the roadmap's states, turned
/// to face the direction of travel unless `keep_headings`; curved models get their
/// motions sampled every [`CURVE_WAYPOINT_STEP`], headings as the curve has them.
pub fn waypoints(
    plan: &Plan,
    pipeline: &Pipeline,
    world: &World,
    keep_headings: bool,
) -> (Vec<Waypoint>, Vec<bool>) {
    let (mut poses, fixed) = concatenate(plan);
    let space = pipeline.space.as_ref();
    let mut reversing = Vec::new();
    if !space.is_holonomic() {
        (poses, reversing) = sample_curves(space, &poses, CURVE_WAYPOINT_STEP);
        if !reversing.iter().any(|&r| r) {
            reversing.clear();
        }
    } else if !keep_headings {
        align_headings(
            &mut poses,
            &fixed,
            pipeline.state_validity.as_deref(),
            pipeline.motion_validator.as_deref(),
        );
    }
    let waypoints = poses
        .iter()
        .map(|p| Waypoint::from_pose(p, world.height_at(p.x, p.y).unwrap_or(f64::NAN)))
        .collect();
    (waypoints, reversing)
}

/// The states of `space`'s motions between consecutive `poses`, every `step` at most,
/// and whether the robot reverses into each (the first: as into the second).
pub fn sample_curves(
    space: &dyn StateSpace,
    poses: &[Pose2],
    step: f64,
) -> (Vec<Pose2>, Vec<bool>) {
    let mut states: Vec<Pose2> = poses.first().copied().into_iter().collect();
    let mut reversing = vec![false; states.len()];
    for w in poses.windows(2) {
        let pieces = (space.distance(&w[0], &w[1]) / step).ceil();
        let n = if pieces.is_finite() {
            (pieces as usize).clamp(1, 100_000)
        } else {
            1
        };
        for k in 1..=n {
            let t = k as f64 / n as f64;
            states.push(if k == n {
                w[1]
            } else {
                space.interpolate(&w[0], &w[1], t)
            });
            reversing.push(space.is_reversing(&w[0], &w[1], (k as f64 - 0.5) / n as f64));
        }
    }
    if reversing.len() > 1 {
        reversing[0] = reversing[1];
    }
    (states, reversing)
}

/// The segments' states in order (shared endpoints once) and which of them are fixed
/// (the start, the PoIs, the end).
pub fn concatenate(plan: &Plan) -> (Vec<Pose2>, Vec<bool>) {
    let mut poses: Vec<Pose2> = Vec::new();
    let mut fixed = Vec::new();
    for segment in &plan.segments {
        for (k, s) in segment.path.states.iter().enumerate() {
            if k == 0 && !poses.is_empty() {
                continue;
            }
            poses.push(*s);
            fixed.push(k == 0 || k + 1 == segment.path.states.len());
        }
    }
    (poses, fixed)
}

/// Turns every free waypoint towards the next one (forward walking) where the checkers
/// accept the turned state and its motions; fixed waypoints keep their yaw.
fn align_headings(
    poses: &mut [Pose2],
    fixed: &[bool],
    states: Option<&dyn StateValidityChecker>,
    motions: Option<&dyn MotionValidator>,
) {
    for k in 1..poses.len().saturating_sub(1) {
        if fixed[k] {
            continue;
        }
        let heading = (poses[k + 1].y - poses[k].y).atan2(poses[k + 1].x - poses[k].x);
        let turned = Pose2::new(poses[k].x, poses[k].y, wrap_angle(heading));
        let accepted = states.is_none_or(|c| c.is_valid(&turned))
            && motions.is_none_or(|m| {
                m.is_valid_motion(&poses[k - 1], &turned)
                    && m.is_valid_motion(&turned, &poses[k + 1])
            });
        if accepted {
            poses[k] = turned;
        }
    }
}
