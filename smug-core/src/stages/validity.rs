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
