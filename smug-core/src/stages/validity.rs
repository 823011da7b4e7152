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
    fn blocked_at(&self, i: i64, j: i64) -> bool {
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

/// The 4-connected components of a [`DiscOnGrid`]'s free cells: a superset of each
/// connected component of the disc's free space (a valid centre lies in the union
/// of the free cells, away from every blocked cell, so it can only pass from a free
/// cell to another through a side they share). Two poses in different components
/// have no path between them: a proof of "no path", never a false one.
#[derive(Clone, Debug)]
pub struct FreeRegions {
    geometry: GridGeometry,
    /// Component of each cell, row-major; `u32::MAX` for a blocked cell.
    label: Vec<u32>,
}

impl FreeRegions {
    /// The components of `disc`'s free cells (a flood fill, linear in the cells).
    pub fn new(disc: &DiscOnGrid) -> Self {
        let [nx, ny] = disc.geometry.size;
        let mut label = vec![u32::MAX; nx * ny];
        let mut next = 0u32;
        let mut stack = Vec::new();
        for first in 0..nx * ny {
            if disc.blocked[first] || label[first] != u32::MAX {
                continue;
            }
            label[first] = next;
            stack.push(first);
            while let Some(k) = stack.pop() {
                let (i, j) = (k % nx, k / nx);
                let mut visit = |n: usize| {
                    if !disc.blocked[n] && label[n] == u32::MAX {
                        label[n] = next;
                        stack.push(n);
                    }
                };
                if i > 0 {
                    visit(k - 1);
                }
                if i + 1 < nx {
                    visit(k + 1);
                }
                if j > 0 {
                    visit(k - nx);
                }
                if j + 1 < ny {
                    visit(k + nx);
                }
            }
            next += 1;
        }
        Self {
            geometry: disc.geometry,
            label,
        }
    }

    /// The components of the free cells within a rounding margin of `pose`, sorted
    /// (empty off the grid or in blocked cells only).
    fn near(&self, pose: &Pose2) -> Vec<u32> {
        let g = &self.geometry;
        let (fx, fy) = (
            (pose.x - g.origin[0]) / g.resolution,
            (pose.y - g.origin[1]) / g.resolution,
        );
        const MARGIN: f64 = 1e-6;
        let mut out = Vec::new();
        if !(fx.is_finite() && fy.is_finite()) {
            return out;
        }
        for j in (fy - MARGIN).floor() as i64..=(fy + MARGIN).floor() as i64 {
            for i in (fx - MARGIN).floor() as i64..=(fx + MARGIN).floor() as i64 {
                if i < 0 || j < 0 || i >= g.size[0] as i64 || j >= g.size[1] as i64 {
                    continue;
                }
                let l = self.label[g.index(i as usize, j as usize)];
                if l != u32::MAX {
                    out.push(l);
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// True when no path joins `a` and `b` because they lie in different components
    /// (proved); false when they may be joined, or when either lies in no free cell
    /// (invalid poses: nothing is claimed about them).
    pub fn disconnected(&self, a: &Pose2, b: &Pose2) -> bool {
        let (la, lb) = (self.near(a), self.near(b));
        !la.is_empty() && !lb.is_empty() && !la.iter().any(|l| lb.contains(l))
    }

    /// Number of components.
    pub fn count(&self) -> usize {
        self.label
            .iter()
            .filter(|&&l| l != u32::MAX)
            .max()
            .map_or(0, |&m| m as usize + 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 5×3 grid, 1 m cells, with a wall at column 2.
    fn walled() -> DiscOnGrid {
        let geometry = GridGeometry::new([0.0, 0.0], 1.0, [5, 3]).unwrap();
        let blocked = (0..15).map(|k| k % 5 == 2).collect();
        DiscOnGrid {
            radius: 0.25,
            geometry,
            blocked,
        }
    }

    #[test]
    fn a_wall_splits_the_free_cells() {
        let disc = walled();
        let regions = FreeRegions::new(&disc);
        assert_eq!(regions.count(), 2);
        let (a, b, c) = (
            Pose2::new(0.5, 0.5, 0.0),
            Pose2::new(4.5, 2.5, 0.0),
            Pose2::new(1.5, 2.5, 1.0),
        );
        assert!(regions.disconnected(&a, &b));
        assert!(!regions.disconnected(&a, &c));
        // On the wall or off the grid: nothing claimed.
        assert!(!regions.disconnected(&Pose2::new(2.5, 0.5, 0.0), &b));
        assert!(!regions.disconnected(&Pose2::new(-3.0, 0.5, 0.0), &b));
    }

    #[test]
    fn a_diagonal_gap_joins_nothing() {
        // Cells (0,0) and (1,1) free, (1,0) and (0,1) blocked: no disc passes the vertex.
        let geometry = GridGeometry::new([0.0, 0.0], 1.0, [2, 2]).unwrap();
        let disc = DiscOnGrid {
            radius: 0.0,
            geometry,
            blocked: vec![false, true, true, false],
        };
        let regions = FreeRegions::new(&disc);
        assert!(regions.disconnected(&Pose2::new(0.5, 0.5, 0.0), &Pose2::new(1.5, 1.5, 0.0)));
    }

    #[test]
    fn faults_name_the_map_border_and_the_inflated_obstacle() {
        let disc = walled();
        assert_eq!(disc.fault(&Pose2::new(1.5, 1.5, 0.0)), None);
        assert_eq!(
            disc.fault(&Pose2::new(0.1, 1.5, 0.0)),
            Some(EndpointFault::OffMap)
        );
        match disc.fault(&Pose2::new(1.9, 1.5, 0.0)) {
            Some(EndpointFault::InInflatedObstacle { distance }) => {
                assert!((distance - 0.1).abs() < 1e-12)
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            disc.fault(&Pose2::new(2.5, 1.5, 0.0)),
            Some(EndpointFault::InInflatedObstacle { distance }) if distance == 0.0
        ));
    }
}
