//! `exact`: the robot box against every occupied voxel cube it may touch, with
//! `parry3d` — slow, exact for the voxelised world; the reference the volumetric
//! checker is tested against.

use crate::robot_box::{PlacedBox, RobotBox};
use crate::volumes::Volumes;
use parry3d::math::{Pose, Vector};
use parry3d::query::intersection_test;
use parry3d::shape::Cuboid;
use serde::{Deserialize, Serialize};
use smug_core::{BuildContext, Error, Pose2, StateValidityChecker, World};
use std::sync::Arc;

/// Parameters of the exact checker (none).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExactParams {}

/// Box-vs-voxel-cubes validity with parry3d.
pub struct ExactChecker {
    world: Arc<World>,
    volumes: Arc<Volumes>,
    robot: RobotBox,
}

impl ExactChecker {
    /// A checker for `robot` in `world` over its `volumes`.
    pub fn new(world: Arc<World>, volumes: Arc<Volumes>, robot: RobotBox) -> Self {
        Self {
            world,
            volumes,
            robot,
        }
    }

    fn collides(&self, placed: &PlacedBox) -> bool {
        let g = self.volumes.geometry();
        let (min, max) = placed.aabb();
        let half = placed.half.map(|h| h as f32);
        let robot = Cuboid::new(Vector::new(half[0], half[1], half[2]));
        let c = placed.center;
        let robot_pose = Pose::new(
            Vector::new(c[0] as f32, c[1] as f32, c[2] as f32),
            Vector::new(0.0, 0.0, placed.yaw as f32),
        );
        let r = g.resolution as f32 / 2.0;
        let voxel = Cuboid::new(Vector::new(r, r, r));
        let range = |a: usize| {
            let lo = ((min[a] - g.origin[a]) / g.resolution).floor().max(0.0) as usize;
            let hi = (((max[a] - g.origin[a]) / g.resolution).floor() as usize).min(g.size[a] - 1);
            lo..=hi
        };
        for k in range(2) {
            for j in range(1) {
                for i in range(0) {
                    if !*self.volumes.occupancy.get([i, j, k]) {
                        continue;
                    }
                    let v = g.center_of([i, j, k]);
                    let voxel_pose =
                        Pose::from_translation(Vector::new(v[0] as f32, v[1] as f32, v[2] as f32));
                    if intersection_test(&robot_pose, &robot, &voxel_pose, &voxel)
                        .map_or(true, |hit| hit.intersecting)
                    {
                        return true;
                    }
                }
            }
        }
        false
    }
}

impl StateValidityChecker for ExactChecker {
    fn is_valid(&self, state: &Pose2) -> bool {
        let Some(placed) = self.robot.place(&self.world, state) else {
            return false;
        };
        let (min, max) = placed.aabb();
        self.volumes.contains_box(min, max) && !self.collides(&placed)
    }
}

/// Builds the checker for the context's world and robot.
pub fn build_exact(ctx: &BuildContext) -> Result<ExactChecker, Error> {
    let world = ctx.world()?;
    let robot = RobotBox::from_robot(ctx.robot());
    let volumes =
        Volumes::from_world(&world, robot.headroom()).map_err(|e| Error::stage("validity", e))?;
    Ok(ExactChecker::new(world, Arc::new(volumes), robot))
}

smug_core::register_plugin!(
    smug_core::registry::ValidityStage,
    name = "exact",
    summary = "robot box vs occupied voxel cubes with parry3d (slow reference)",
    params = ExactParams,
    build = |_params, ctx| Ok(Box::new(build_exact(ctx)?)),
);
