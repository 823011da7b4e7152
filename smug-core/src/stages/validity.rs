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
    fn blocked_at(&self, i: i64, j: i64) -> bool {
        let [nx, ny] = self.geometry.size;
        if i < 0 || j < 0 || i >= nx as i64 || j >= ny as i64 {
            return true;
        }
        self.blocked[self.geometry.index(i as usize, j as usize)]
    }

    /// Waypoints where shortest paths bend: one point beside each convex corner of the
    /// blocked cells (a grid vertex with exactly one blocked cell among its four),
    /// on the corner's outward diagonal, `radius · (1 + 1e-3)` plus a hundredth of a cell
    /// out along each axis. From there, every straight motion that turns the corner by
    /// up to 90° keeps the disc clear of the corner's rounded, inflated edge, so a
    /// roadmap through these points holds paths that bend where the optimum bends.
    /// Points off the grid are left out; the others may still be invalid (near other
    /// obstacles): check them before use.
    pub fn corner_waypoints(&self) -> Vec<[f64; 2]> {
        let g = &self.geometry;
        let [nx, ny] = g.size;
        let offset = self.radius * (1.0 + 1e-3) + 0.01 * g.resolution;
        let bounds = g.bounds();
        let mut out = Vec::new();
        for y in 0..=ny as i64 {
            for x in 0..=nx as i64 {
                let Some([sx, sy]) = self.convex_corner_outward(x, y) else {
                    continue;
                };
                let p = [
                    g.origin[0] + x as f64 * g.resolution + sx * offset,
                    g.origin[1] + y as f64 * g.resolution + sy * offset,
                ];
                if (0..2).all(|k| p[k] > bounds.min[k] && p[k] < bounds.max[k]) {
                    out.push(p);
                }
            }
        }
        out
    }

    /// Waypoints along one-cell corridors: the centre of every third free cell of a
    /// run of free cells whose neighbours across the run are both blocked (a corridor
    /// or a door one cell wide), and of each run's last cell. A corridor longer than a
    /// roadmap vertex's reach then holds a chain of vertices in a line, where the
    /// corners of [`corner_waypoints`](Self::corner_waypoints) lie only at its ends.
    pub fn corridor_waypoints(&self) -> Vec<[f64; 2]> {
        const EVERY: i64 = 3;
        let g = &self.geometry;
        let [nx, ny] = g.size;
        let free = |i: i64, j: i64| !self.blocked_at(i, j);
        // Across a vertical run the neighbours are left and right, and the reverse.
        let vertical = |i: i64, j: i64| free(i, j) && !free(i - 1, j) && !free(i + 1, j);
        let horizontal = |i: i64, j: i64| free(i, j) && !free(i, j - 1) && !free(i, j + 1);
        let mut out = Vec::new();
        for j in 0..ny as i64 {
            for i in 0..nx as i64 {
                let keep_vertical = vertical(i, j) && (j % EVERY == 0 || !vertical(i, j + 1));
                let keep_horizontal = horizontal(i, j) && (i % EVERY == 0 || !horizontal(i + 1, j));
                if keep_vertical || keep_horizontal {
                    out.push(g.center_of(i as usize, j as usize));
                }
            }
        }
        out
    }

    /// The outward diagonal `(±1, ±1)` of grid vertex `(x, y)` when it is a convex
    /// corner of the blocked cells (exactly one of its four cells blocked, cells off
    /// the grid counting as blocked): the signs point away from the blocked cell.
    fn convex_corner_outward(&self, x: i64, y: i64) -> Option<[f64; 2]> {
        let mut blocked = None;
        for (dx, dy) in [(-1, -1), (0, -1), (-1, 0), (0, 0)] {
            if self.blocked_at(x + dx, y + dy) {
                if blocked.is_some() {
                    return None;
                }
                blocked = Some((dx, dy));
            }
        }
        let (dx, dy) = blocked?;
        let away = |d: i64| if d < 0 { 1.0 } else { -1.0 };
        Some([away(dx), away(dy)])
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
    fn one_blocked_cell_has_four_corner_waypoints_outside_its_inflation() {
        let geometry = GridGeometry::new([0.0, 0.0], 1.0, [7, 7]).unwrap();
        let blocked = (0..49).map(|k| k == 3 * 7 + 3).collect();
        let disc = DiscOnGrid {
            radius: 0.25,
            geometry,
            blocked,
        };
        let o = 0.25 * 1.001 + 0.01;
        let expected = [
            [3.0 - o, 3.0 - o],
            [4.0 + o, 3.0 - o],
            [3.0 - o, 4.0 + o],
            [4.0 + o, 4.0 + o],
        ];
        let found = disc.corner_waypoints();
        assert_eq!(found.len(), 4, "{found:?}");
        for (f, e) in found.iter().zip(expected) {
            assert!((f[0] - e[0]).abs() < 1e-12 && (f[1] - e[1]).abs() < 1e-12);
            assert!(disc.fault(&Pose2::new(f[0], f[1], 0.0)).is_none());
        }
        assert!(disc.corridor_waypoints().is_empty());
    }

    #[test]
    fn a_corridor_gets_every_third_cell_and_its_last() {
        // Rows 0 and 2 blocked: row 1 is a corridor one cell wide.
        let geometry = GridGeometry::new([0.0, 0.0], 1.0, [6, 3]).unwrap();
        let blocked = (0..18).map(|k| k / 6 != 1).collect();
        let disc = DiscOnGrid {
            radius: 0.25,
            geometry,
            blocked,
        };
        assert_eq!(
            disc.corridor_waypoints(),
            vec![[0.5, 1.5], [3.5, 1.5], [5.5, 1.5]]
        );
        assert!(disc.corner_waypoints().is_empty());
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
