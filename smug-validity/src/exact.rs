//! `exact`: the robot box against every occupied voxel cube it may touch, with
//! `parry3d` — slow, exact for the voxelised world; the reference the volumetric
//! checker is tested against.

use crate::robot_box::{PlacedBox, RobotBox};
use crate::volumes::{box_inside, SharedVolumes, Volumes};
use crate::volumetric::shared_volumes;
use parry3d::math::{Pose, Vector};
use parry3d::query::intersection_test;
use parry3d::shape::Cuboid;
use serde::{Deserialize, Serialize};
use smug_core::{BuildContext, Error, Pose2, StateValidityChecker, VoxelGrid, World};
use std::sync::Arc;

/// Parameters of the exact checker (none).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExactParams {}

/// Box-vs-voxel-cubes validity with parry3d.
pub struct ExactChecker {
    world: Arc<World>,
    volumes: SharedVolumes,
    robot: RobotBox,
}

impl ExactChecker {
    /// A checker for `robot` in `world` over its `volumes`.
    pub fn new(world: Arc<World>, volumes: Arc<Volumes>, robot: RobotBox) -> Self {
        let volumes = SharedVolumes::ready(world.clone(), volumes);
        Self::with_shared_volumes(world, volumes, robot)
    }

    /// A checker for `robot` in `world` over `volumes` that may not be derived yet (it
    /// needs only their occupancy, derived on the first check).
    pub fn with_shared_volumes(world: Arc<World>, volumes: SharedVolumes, robot: RobotBox) -> Self {
        Self {
            world,
            volumes,
            robot,
        }
    }

    fn collides(&self, occupancy: &VoxelGrid<bool>, placed: &PlacedBox) -> bool {
        let g = &occupancy.geometry;
        let (min, max) = placed.aabb();
        let half = placed.half.map(|h| h as f32);
        let robot = Cuboid::new(Vector::new(half[0], half[1], half[2]));
        let c = placed.center;
        let robot_pose = Pose::new(
            Vector::new(c[0] as f32, c[1] as f32, c[2] as f32),
            Vector::new(0.0, 0.0, placed.yaw() as f32),
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
                    if !*occupancy.get([i, j, k]) {
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
        let occupancy = self.volumes.occupancy();
        box_inside(&occupancy.geometry, min, max) && !self.collides(occupancy, &placed)
    }
}

/// Builds the checker for the context's world and robot, deriving the occupancy now
/// (shared with the world's other checkers; the distance field is not needed).
pub fn build_exact(ctx: &BuildContext) -> Result<ExactChecker, Error> {
    let robot = RobotBox::from_robot(ctx.robot());
    let volumes = shared_volumes(ctx, &robot)?;
    volumes.occupancy();
    Ok(ExactChecker::with_shared_volumes(
        ctx.world()?,
        volumes,
        robot,
    ))
}

smug_core::register_plugin!(
    smug_core::registry::ValidityStage,
    name = "exact",
    summary = "robot box vs occupied voxel cubes with parry3d (slow reference)",
    params = ExactParams,
    build = |_params, ctx| Ok(Box::new(build_exact(ctx)?)),
);
