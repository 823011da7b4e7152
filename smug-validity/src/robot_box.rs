//! The robot base as an oriented box standing on the terrain.

use smug_core::{Pose2, RobotConfig, World};

/// The robot's base box: extents and height of its centre above the terrain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotBox {
    /// Half extents along the heading, across it, and vertically.
    pub half: [f64; 3],
    /// Height of the box centre above the terrain under the state.
    pub base_height: f64,
}

/// A box placed in the world: centre and heading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlacedBox {
    /// Centre in world coordinates.
    pub center: [f64; 3],
    /// Heading ([`yaw`](Self::yaw): read only, its sine and cosine are kept beside it).
    yaw: f64,
    /// Half extents (body frame).
    pub half: [f64; 3],
    /// The heading's sine and cosine (every corner and sub-box centre turns by them).
    sin_cos: (f64, f64),
}

impl RobotBox {
    /// The box of `robot`.
    pub fn from_robot(robot: &RobotConfig) -> Self {
        Self {
            half: [robot.length / 2.0, robot.width / 2.0, robot.height / 2.0],
            base_height: robot.base_height,
        }
    }

    /// The box at `state`, its centre `base_height` above the terrain; `None` where the
    /// terrain height is unknown.
    pub fn place(&self, world: &World, state: &Pose2) -> Option<PlacedBox> {
        let ground = world.height_at(state.x, state.y)?;
        Some(PlacedBox {
            center: [state.x, state.y, ground + self.base_height],
            yaw: state.yaw,
            half: self.half,
            sin_cos: state.yaw.sin_cos(),
        })
    }

    /// Free space the box needs above the highest terrain (for deriving voxel grids).
    pub fn headroom(&self) -> f64 {
        self.base_height + self.half[2] + 1.0
    }
}

impl PlacedBox {
    /// The heading.
    pub fn yaw(&self) -> f64 {
        self.yaw
    }

    /// Axis-aligned bounds `(min, max)`.
    pub fn aabb(&self) -> ([f64; 3], [f64; 3]) {
        let (s, c) = self.sin_cos;
        let hx = self.half[0] * c.abs() + self.half[1] * s.abs();
        let hy = self.half[0] * s.abs() + self.half[1] * c.abs();
        let h = [hx, hy, self.half[2]];
        (
            std::array::from_fn(|a| self.center[a] - h[a]),
            std::array::from_fn(|a| self.center[a] + h[a]),
        )
    }

    /// The point at body-frame offset `local` from the centre.
    pub fn to_world(&self, local: [f64; 3]) -> [f64; 3] {
        let (s, c) = self.sin_cos;
        [
            self.center[0] + c * local[0] - s * local[1],
            self.center[1] + s * local[0] + c * local[1],
            self.center[2] + local[2],
        ]
    }
}
