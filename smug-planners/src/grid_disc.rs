//! Grid-disc geometry the planners use: where shortest paths of a disc among grid cells
//! bend (corner and corridor waypoints LazyPRM* seeds its roadmap with) and the
//! components of the free cells (a cheap proof that no path exists).

use smug_core::{DiscOnGrid, GridGeometry, Pose2};

/// Waypoints where shortest paths bend: one point beside each convex corner of the
/// blocked cells (a grid vertex with exactly one blocked cell among its four),
/// on the corner's outward diagonal, `radius · (1 + 1e-3)` plus a hundredth of a cell
/// out along each axis. From there, every straight motion that turns the corner by
/// up to 90° keeps the disc clear of the corner's rounded, inflated edge, so a
/// roadmap through these points holds paths that bend where the optimum bends.
/// Points off the grid are left out; the others may still be invalid (near other
/// obstacles): check them before use.
pub fn corner_waypoints(disc: &DiscOnGrid) -> Vec<[f64; 2]> {
    let g = &disc.geometry;
    let [nx, ny] = g.size;
    let offset = disc.radius * (1.0 + 1e-3) + 0.01 * g.resolution;
    let bounds = g.bounds();
    let mut out = Vec::new();
    for y in 0..=ny as i64 {
        for x in 0..=nx as i64 {
            let Some([sx, sy]) = convex_corner_outward(disc, x, y) else {
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
/// corners of [`corner_waypoints`] lie only at its ends.
pub fn corridor_waypoints(disc: &DiscOnGrid) -> Vec<[f64; 2]> {
    const EVERY: i64 = 3;
    let g = &disc.geometry;
    let [nx, ny] = g.size;
    let free = |i: i64, j: i64| !disc.blocked_at(i, j);
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
fn convex_corner_outward(disc: &DiscOnGrid, x: i64, y: i64) -> Option<[f64; 2]> {
    let mut blocked = None;
    for (dx, dy) in [(-1, -1), (0, -1), (-1, 0), (0, 0)] {
        if disc.blocked_at(x + dx, y + dy) {
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
    use smug_core::testing::walled_disc as walled;

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
        let found = corner_waypoints(&disc);
        assert_eq!(found.len(), 4, "{found:?}");
        for (f, e) in found.iter().zip(expected) {
            assert!((f[0] - e[0]).abs() < 1e-12 && (f[1] - e[1]).abs() < 1e-12);
            assert!(disc.fault(&Pose2::new(f[0], f[1], 0.0)).is_none());
        }
        assert!(corridor_waypoints(&disc).is_empty());
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
            corridor_waypoints(&disc),
            vec![[0.5, 1.5], [3.5, 1.5], [5.5, 1.5]]
        );
        assert!(corner_waypoints(&disc).is_empty());
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
}
