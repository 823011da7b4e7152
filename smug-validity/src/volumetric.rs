//! `volumetric`: the robot base box against the ESDF by iterative sphere subdivision.
//!
//! For a (sub-)box with half extents `h` and centre distance `D` (a lower bound of the
//! distance to the nearest occupied voxel): `D > |h|` (outer sphere) → free;
//! `D < min(h)` (inner sphere) → collision; otherwise split the box in two along its
//! longest side and check both halves. At the maximum depth or minimum size only the
//! outer sphere decides. Unknown space (outside the grid, no terrain data) is invalid.

use crate::robot_box::{PlacedBox, RobotBox};
use crate::volumes::{SharedVolumes, Volumes};
use serde::{Deserialize, Serialize};
use smug_core::Counter;
use smug_core::{BuildContext, Counters, Error, Pose2, StateValidityChecker, World};
use std::sync::Arc;

/// Parameters of the volumetric checker.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct VolumetricParams {
    /// Subdivision levels below the whole box (the paper stops at 2; 4 rejects about
    /// half as many free states on the lunar world for a few more queries).
    pub max_depth: u32,
    /// Sub-boxes whose longest side is below this (metres) are not split further.
    pub min_size: f64,
}

impl Default for VolumetricParams {
    fn default() -> Self {
        Self {
            max_depth: 4,
            min_size: 0.05,
        }
    }
}

/// Box-vs-ESDF validity by sphere subdivision.
pub struct VolumetricChecker {
    world: Arc<World>,
    volumes: SharedVolumes,
    robot: RobotBox,
    /// The subdivision's levels, the whole box first.
    levels: Vec<Level>,
    checks: Counter,
    /// Distance-field queries of this checker (the volumes may be shared).
    esdf_queries: Counter,
}

impl VolumetricChecker {
    /// A checker for `robot` in `world` over its `volumes`.
    pub fn new(
        world: Arc<World>,
        volumes: Arc<Volumes>,
        robot: RobotBox,
        params: VolumetricParams,
    ) -> Result<Self, Error> {
        let volumes = SharedVolumes::ready(world.clone(), volumes);
        Self::with_shared_volumes(world, volumes, robot, params)
    }

    /// A checker for `robot` in `world` over `volumes` that may not be derived yet
    /// (they are on the first check that needs them).
    pub fn with_shared_volumes(
        world: Arc<World>,
        volumes: SharedVolumes,
        robot: RobotBox,
        params: VolumetricParams,
    ) -> Result<Self, Error> {
        if !(params.min_size.is_finite() && params.min_size >= 0.0) {
            return Err(Error::invalid_param(
                "validity",
                format!("min_size must be ≥ 0, got {}", params.min_size),
            ));
        }
        Ok(Self {
            world,
            volumes,
            levels: levels(robot.half, &params),
            robot,
            checks: Counter::new(),
            esdf_queries: Counter::new(),
        })
    }

    /// The distance field it queries (derived now if not yet).
    pub fn volumes(&self) -> &Arc<Volumes> {
        self.volumes.volumes()
    }

    /// True when the sub-box of subdivision level `depth` at body offset `offset` is
    /// free.
    fn sub_box_free(
        &self,
        volumes: &Volumes,
        placed: &PlacedBox,
        offset: [f64; 3],
        depth: usize,
    ) -> bool {
        let level = &self.levels[depth];
        let center = placed.to_world(offset);
        self.esdf_queries.increment();
        let Some(distance) = volumes.distance_lower_bound(center) else {
            return false;
        };
        if distance > level.outer {
            return true;
        }
        if distance < level.inner {
            return false;
        }
        let Some(axis) = level.split else {
            return false;
        };
        let step = self.levels[depth + 1].half[axis];
        [-1.0, 1.0].iter().all(|side| {
            let mut o = offset;
            o[axis] += side * step;
            self.sub_box_free(volumes, placed, o, depth + 1)
        })
    }
}

/// The sub-boxes of one subdivision level: all the same size, as each level halves
/// its parent along the parent's longest side.
#[derive(Clone, Copy, Debug)]
struct Level {
    /// Half extents.
    half: [f64; 3],
    /// The outer sphere's radius (half diagonal): a centre farther from every occupied
    /// voxel leaves the sub-box free.
    outer: f64,
    /// The inner sphere's radius (least half extent): a centre nearer to an occupied
    /// voxel puts it inside the sub-box.
    inner: f64,
    /// The axis the level is split along, `None` at the last level (depth or size).
    split: Option<usize>,
}

/// Subdivision levels below the whole box at most, whatever `max_depth` says: after
/// 64 halvings a sub-box's sides are a two-millionth of the box's (and `max_depth`
/// near `u32::MAX` would otherwise build a table of billions of levels).
const MAX_LEVELS: u32 = 64;

/// The subdivision levels of a box with half extents `half` under `params`.
fn levels(half: [f64; 3], params: &VolumetricParams) -> Vec<Level> {
    let mut levels = Vec::new();
    let mut half = half;
    let deepest = params.max_depth.min(MAX_LEVELS);
    for depth in 0.. {
        let axis = longest_axis(half);
        let split = depth < deepest && 2.0 * half[axis] >= params.min_size;
        levels.push(Level {
            half,
            outer: (half[0] * half[0] + half[1] * half[1] + half[2] * half[2]).sqrt(),
            inner: half[0].min(half[1]).min(half[2]),
            split: split.then_some(axis),
        });
        if !split {
            break;
        }
        half[axis] /= 2.0;
    }
    levels
}

fn longest_axis(half: [f64; 3]) -> usize {
    (0..3).fold(0, |best, a| if half[a] > half[best] { a } else { best })
}

impl StateValidityChecker for VolumetricChecker {
    fn is_valid(&self, state: &Pose2) -> bool {
        self.checks.increment();
        let Some(placed) = self.robot.place(&self.world, state) else {
            return false;
        };
        let (min, max) = placed.aabb();
        let volumes = self.volumes.volumes();
        volumes.contains_box(min, max) && self.sub_box_free(volumes, &placed, [0.0; 3], 0)
    }

    fn counters(&self) -> Counters {
        Counters::from([
            ("checks".to_string(), self.checks.total()),
            ("esdf_queries".to_string(), self.esdf_queries.total()),
        ])
    }
}

/// The volumes of the context's world for `robot`, shared with the other checkers of
/// that world (derived on first use).
/// After a world change ([`BuildContext::world_change`]), the previous world's volumes
/// updated in place when they can be ([`SharedVolumes::updated`]).
pub(crate) fn shared_volumes(ctx: &BuildContext, robot: &RobotBox) -> Result<SharedVolumes, Error> {
    let world = ctx.world()?;
    if let Some(change) = ctx.world_change() {
        let updated = SharedVolumes::updated(
            &change.previous,
            &world,
            robot.headroom(),
            &change.obstacles,
        );
        if let Some(volumes) = updated {
            return Ok(volumes);
        }
    }
    SharedVolumes::for_world_within(&world, robot.headroom(), ctx.memory())
        .map_err(|e| Error::stage("validity", e))
}

/// Builds the checker for the context's world and robot, deriving the volumes now
/// (every check needs them; shared with the world's other checkers).
pub fn build_volumetric(
    params: VolumetricParams,
    ctx: &BuildContext,
) -> Result<VolumetricChecker, Error> {
    let robot = RobotBox::from_robot(ctx.robot());
    let volumes = shared_volumes(ctx, &robot)?;
    volumes.volumes();
    VolumetricChecker::with_shared_volumes(ctx.world()?, volumes, robot, params)
}

smug_core::register_plugin!(
    smug_core::registry::ValidityStage,
    name = "volumetric",
    summary = "robot box vs ESDF by sphere subdivision (full collision checking)",
    params = VolumetricParams,
    build = |params, ctx| Ok(Box::new(build_volumetric(params, ctx)?)),
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_halve_the_longest_side_down_to_the_depth_or_the_size() {
        // The rover's box (1.2 × 0.8 × 0.5 m), the default depth 4 and size 0.05 m.
        let rover = levels([0.6, 0.4, 0.25], &VolumetricParams::default());
        let halves: Vec<[f64; 3]> = rover.iter().map(|l| l.half).collect();
        assert_eq!(
            halves,
            vec![
                [0.6, 0.4, 0.25],
                [0.3, 0.4, 0.25],
                [0.3, 0.2, 0.25],
                [0.15, 0.2, 0.25],
                [0.15, 0.2, 0.125],
            ]
        );
        let splits: Vec<Option<usize>> = rover.iter().map(|l| l.split).collect();
        assert_eq!(splits, vec![Some(0), Some(1), Some(0), Some(2), None]);
        assert_eq!(rover[0].inner, 0.25);
        let small = VolumetricParams {
            max_depth: 4,
            min_size: 0.7,
        };
        assert_eq!(
            levels([0.6, 0.4, 0.25], &small).len(),
            3,
            "sides below 0.7 m stop"
        );
        let endless = VolumetricParams {
            max_depth: u32::MAX,
            min_size: 0.0,
        };
        assert_eq!(
            levels([0.6, 0.4, 0.25], &endless).len(),
            MAX_LEVELS as usize + 1
        );
    }
}
