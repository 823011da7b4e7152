//! State validity stage: is the robot safe at this pose?

use crate::grid::GridGeometry;
use crate::pose::Pose2;
use std::collections::BTreeMap;

/// Named counters a stage reports (validity queries, ESDF lookups, …).
pub type Counters = BTreeMap<String, u64>;

/// Decides whether the robot may stand at a pose.
pub trait StateValidityChecker: Send + Sync {
    /// True when the robot at `state` is safe (traversable and collision-free).
    fn is_valid(&self, state: &Pose2) -> bool;

    /// How far the robot can move from `state`, in any direction in the plane and
    /// with any yaw, and stay valid: a lower bound, ≤ 0 when `state` is invalid; `None`
    /// when the checker cannot tell (the default). A disc robot can: motion validators
    /// then check motions continuously, in steps of this clearance.
    fn clearance(&self, state: &Pose2) -> Option<f64> {
        let _ = state;
        None
    }

    /// Whether the robot is valid at every point of the straight x–y segment from `a`
    /// to `b` (any yaw), decided exactly, when the checker can (a disc on a grid: the
    /// segment keeps the radius from every blocked cell); `None` (the default) when it
    /// cannot, and motion validators check states along the motion instead. The
    /// verdict for `b → a` is the same.
    fn segment_valid(&self, a: &Pose2, b: &Pose2) -> Option<bool> {
        let _ = (a, b);
        None
    }

    /// Counters accumulated so far (e.g. `"checks"`, `"esdf_queries"`).
    fn counters(&self) -> Counters {
        Counters::new()
    }

    /// The robot as a disc on a 2D occupancy grid, when that is exactly what the
    /// checker checks (a state is valid iff the disc lies inside the grid and keeps
    /// its distance to every blocked cell); `None` (the default) for any other robot
    /// or world. Exact planners read the obstacles from it.
    fn disc_on_grid(&self) -> Option<DiscOnGrid> {
        None
    }
}

/// A disc robot on a 2D occupancy grid: valid states are the centres whose disc of
/// `radius` lies inside the grid and touches no blocked cell (a closed square).
#[derive(Clone, Debug, PartialEq)]
pub struct DiscOnGrid {
    /// Disc radius, metres (≥ 0).
    pub radius: f64,
    /// The grid.
    pub geometry: GridGeometry,
    /// One flag per cell, row-major (`GridGeometry::index`): true = blocked.
    pub blocked: Vec<bool>,
}

/// Why an endpoint is invalid for a disc on a grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EndpointFault {
    /// The disc does not lie inside the grid.
    OffMap,
    /// The disc touches a blocked cell: the centre is inside an obstacle inflated by
    /// the radius; `distance` (metres) from the centre to the nearest blocked cell.
    InInflatedObstacle {
        /// Distance from the centre to the nearest blocked cell, metres.
        distance: f64,
    },
}

impl std::fmt::Display for EndpointFault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EndpointFault::OffMap => f.write_str("off the map (the disc leaves the grid)"),
            EndpointFault::InInflatedObstacle { distance } => write!(
                f,
                "inside an inflated obstacle ({distance:.3} m from the nearest blocked cell)"
            ),
        }
    }
}

impl DiscOnGrid {
    /// Whether the cell `(i, j)` (possibly outside the grid) is blocked; cells outside
    /// the grid count as blocked.
    pub fn blocked_at(&self, i: i64, j: i64) -> bool {
        let [nx, ny] = self.geometry.size;
        if i < 0 || j < 0 || i >= nx as i64 || j >= ny as i64 {
            return true;
        }
        self.blocked[self.geometry.index(i as usize, j as usize)]
    }

    /// Why the disc at `pose` is invalid, when it is by this description: off the map
    /// or inside an inflated obstacle (the nearest blocked cell measured exactly);
    /// `None` when the disc keeps its distance (a checker may still refuse the pose
    /// within rounding of the boundary).
    pub fn fault(&self, pose: &Pose2) -> Option<EndpointFault> {
        let g = &self.geometry;
        let b = g.bounds();
        let r = self.radius;
        let border = (pose.x - b.min[0])
            .min(b.max[0] - pose.x)
            .min(pose.y - b.min[1])
            .min(b.max[1] - pose.y);
        if border.is_nan() || border < r {
            return Some(EndpointFault::OffMap);
        }
        let res = g.resolution;
        let (fx, fy) = ((pose.x - g.origin[0]) / res, (pose.y - g.origin[1]) / res);
        let reach = r / res + 1.0;
        let mut nearest = f64::INFINITY;
        for j in (fy - reach).floor() as i64..=(fy + reach).floor() as i64 {
            for i in (fx - reach).floor() as i64..=(fx + reach).floor() as i64 {
                if i < 0 || j < 0 || i >= g.size[0] as i64 || j >= g.size[1] as i64 {
                    continue;
                }
                if self.blocked_at(i, j) {
                    let dx = (i as f64 - fx).max(0.0).max(fx - i as f64 - 1.0);
                    let dy = (j as f64 - fy).max(0.0).max(fy - j as f64 - 1.0);
                    nearest = nearest.min(dx.hypot(dy) * res);
                }
            }
        }
        (nearest <= r).then_some(EndpointFault::InInflatedObstacle { distance: nearest })
    }
}
