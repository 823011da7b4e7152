//! Newly seen obstacles (a mission state's `[[obstacles]]`) added to a world.
//!
//! A disc obstacle raises the terrain of every cell whose centre lies in the disc by its
//! height (so a volumetric check built from the elevation sees a column, and an
//! estimator working on the elevation sees its steep sides), fills the world's own
//! occupancy voxels and lowers its distance field (when it carries them), and marks
//! the traversability of those cells as missing (invalid for every traversability-based
//! check, whatever the estimator thinks of the column's flat top).

use crate::error::Result;
use crate::grid::{GridGeometry, GridLayer, VoxelGeometry, VoxelGrid};
use crate::stages::CellRect;
use crate::stages::TraversabilityEstimator;
use crate::world::World;
use serde::{Deserialize, Serialize};

/// A vertical cylinder standing on the terrain: the obstacle a mapper reports.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscObstacle {
    /// Centre `[x, y]`, metres.
    pub center: [f64; 2],
    /// Radius, metres (> 0).
    pub radius: f64,
    /// Height above the terrain, metres (> 0).
    pub height: f64,
}

impl DiscObstacle {
    /// Whether `(x, y)` lies in the disc (border included).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        (x - self.center[0]).hypot(y - self.center[1]) <= self.radius
    }

    /// The rectangle of `geometry`'s cells that may have their centre in the disc
    /// (clipped to the grid; empty when the disc lies off it).
    pub fn cell_rect(&self, geometry: &GridGeometry) -> CellRect {
        let r = geometry.resolution;
        let lo = |c: f64, o: f64| ((c - self.radius - o) / r).floor().max(0.0) as usize;
        let hi = |c: f64, o: f64, n: usize| {
            (((c + self.radius - o) / r).ceil().max(0.0) as usize).min(n)
        };
        let [nx, ny] = geometry.size;
        CellRect {
            i0: lo(self.center[0], geometry.origin[0]),
            i1: hi(self.center[0], geometry.origin[0], nx),
            j0: lo(self.center[1], geometry.origin[1]),
            j1: hi(self.center[1], geometry.origin[1], ny),
        }
    }

    /// The cells of `geometry` whose centres lie in the disc.
    pub fn cells(&self, geometry: &GridGeometry) -> Vec<[usize; 2]> {
        let rect = self.cell_rect(geometry);
        let mut cells = Vec::new();
        for j in rect.j0..rect.j1 {
            for i in rect.i0..rect.i1 {
                let [x, y] = geometry.center_of(i, j);
                if self.contains(x, y) {
                    cells.push([i, j]);
                }
            }
        }
        cells
    }
}

/// Adds `obstacles` to `world` (elevation, own occupancy and distance field, and
/// traversability when present).
pub fn add_obstacles(world: &mut World, obstacles: &[DiscObstacle]) {
    for obstacle in obstacles {
        let geometry = world.elevation.geometry;
        let mut top = f64::NEG_INFINITY;
        for [i, j] in obstacle.cells(&geometry) {
            let z = world.elevation.get(i, j);
            if z.is_finite() {
                let raised = z + obstacle.height as f32;
                world.elevation.set(i, j, raised);
                top = top.max(raised as f64);
            }
        }
        if !top.is_finite() {
            continue;
        }
        if let Some(occupancy) = world.occupancy.as_mut() {
            fill_column(occupancy, obstacle, top);
        }
        if let Some(esdf) = world.esdf.as_mut() {
            lower_distances(esdf, obstacle, top);
        }
    }
    if let Some(layer) = world.traversability.as_mut() {
        mask_layer(layer, obstacles);
    }
}

/// Sets every cell of `layer` under an obstacle to NaN (no data).
pub fn mask_layer(layer: &mut GridLayer, obstacles: &[DiscObstacle]) {
    for obstacle in obstacles {
        for [i, j] in obstacle.cells(&layer.geometry) {
            layer.set(i, j, f32::NAN);
        }
    }
}

/// The voxel columns `[i0, i1) × [j0, j1)` of `g` within `margin` (metres) of the
/// obstacle's disc, horizontally (clipped to the grid).
fn voxel_window(g: &VoxelGeometry, obstacle: &DiscObstacle, margin: f64) -> [usize; 4] {
    let reach = obstacle.radius + margin;
    let lo = |c: f64, o: f64| {
        let v = ((c - reach - o) / g.resolution).floor() - 1.0;
        if v.is_nan() {
            0
        } else {
            v.max(0.0) as usize
        }
    };
    let hi = |c: f64, o: f64, n: usize| {
        let v = ((c + reach - o) / g.resolution).ceil() + 1.0;
        if v.is_nan() {
            n
        } else {
            (v.max(0.0) as usize).min(n)
        }
    };
    [
        lo(obstacle.center[0], g.origin[0]),
        hi(obstacle.center[0], g.origin[0], g.size[0]),
        lo(obstacle.center[1], g.origin[1]),
        hi(obstacle.center[1], g.origin[1], g.size[1]),
    ]
}

/// Marks the voxels of the obstacle's column (up to `top`) occupied: only the voxel
/// columns around the disc are visited.
fn fill_column(occupancy: &mut VoxelGrid<bool>, obstacle: &DiscObstacle, top: f64) {
    let g = occupancy.geometry;
    let [i0, i1, j0, j1] = voxel_window(&g, obstacle, 0.0);
    for k in 0..g.size[2] {
        for j in j0..j1 {
            for i in i0..i1 {
                let [x, y, z] = g.center_of([i, j, k]);
                if z <= top && obstacle.contains(x, y) {
                    occupancy.set([i, j, k], true);
                }
            }
        }
    }
}

/// Signed distance from `p` to the obstacle's column (a cylinder up to `top`,
/// unbounded below: the ground fills what lies under it).
fn column_distance(p: [f64; 3], obstacle: &DiscObstacle, top: f64) -> f64 {
    let radial = (p[0] - obstacle.center[0]).hypot(p[1] - obstacle.center[1]) - obstacle.radius;
    let above = p[2] - top;
    if radial <= 0.0 && above <= 0.0 {
        radial.max(above)
    } else {
        radial.max(0.0).hypot(above.max(0.0))
    }
}

/// The distance field of the union: each voxel keeps the nearer of its obstacle and
/// the new column. Only voxels horizontally nearer the disc than the largest distance
/// in the field can get nearer, so only their columns are visited.
fn lower_distances(esdf: &mut VoxelGrid<f32>, obstacle: &DiscObstacle, top: f64) {
    let g = esdf.geometry;
    let largest = esdf.data.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    if largest == f32::NEG_INFINITY {
        return;
    }
    let [i0, i1, j0, j1] = voxel_window(&g, obstacle, largest as f64);
    for k in 0..g.size[2] {
        for j in j0..j1 {
            for i in i0..i1 {
                let d = column_distance(g.center_of([i, j, k]), obstacle, top) as f32;
                let old = *esdf.get([i, j, k]);
                if d < old {
                    esdf.set([i, j, k], d);
                }
            }
        }
    }
}

/// A traversability estimator whose layer has the obstacles' cells masked (missing).
pub struct MaskedEstimator {
    /// The config's estimator.
    pub inner: Box<dyn TraversabilityEstimator>,
    /// The obstacles to mask.
    pub obstacles: Vec<DiscObstacle>,
}

impl TraversabilityEstimator for MaskedEstimator {
    fn estimate(&self, world: &World) -> Result<GridLayer> {
        let mut layer = self.inner.estimate(world)?;
        mask_layer(&mut layer, &self.obstacles);
        Ok(layer)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat_world() -> World {
        let g = GridGeometry::new([0.0, 0.0], 0.5, [20, 20]).unwrap();
        let mut world = World::new("flat", GridLayer::filled(g, 0.0));
        world.traversability = Some(GridLayer::filled(g, 1.0));
        let vg = VoxelGeometry::new([0.0, 0.0, -1.0], 0.5, [20, 20, 8]).unwrap();
        world.occupancy = Some(VoxelGrid::filled(vg, false));
        world.esdf = Some(VoxelGrid::filled(vg, 100.0));
        world
    }

    #[test]
    fn a_disc_raises_the_terrain_masks_traversability_and_fills_the_volumes() {
        let mut world = flat_world();
        let obstacle = DiscObstacle {
            center: [5.0, 5.0],
            radius: 1.0,
            height: 1.5,
        };
        add_obstacles(&mut world, &[obstacle]);
        assert_eq!(world.height_at(5.1, 5.1), Some(1.5));
        assert_eq!(world.height_at(8.0, 8.0), Some(0.0));
        let t = world.traversability.as_ref().unwrap();
        assert_eq!(t.nearest(5.1, 5.1), None);
        assert_eq!(t.nearest(7.1, 5.1), Some(1.0));
        let occupancy = world.occupancy.as_ref().unwrap();
        assert_eq!(occupancy.at([5.1, 5.1, 1.2]), Some(&true));
        assert_eq!(occupancy.at([5.1, 5.1, 1.8]), Some(&false));
        let esdf = world.esdf.as_ref().unwrap();
        let free = *esdf.at([8.1, 5.1, 0.7]).unwrap();
        assert!((free - 2.0).abs() < 0.3, "{free}");
        assert!(*esdf.at([5.1, 5.1, 0.7]).unwrap() < 0.0);
    }

    /// The whole-grid loops the local updates replace.
    fn global_update(world: &mut World, obstacle: &DiscObstacle, top: f64) {
        let occupancy = world.occupancy.as_mut().unwrap();
        let g = occupancy.geometry;
        let esdf = world.esdf.as_mut().unwrap();
        for k in 0..g.size[2] {
            for j in 0..g.size[1] {
                for i in 0..g.size[0] {
                    let [x, y, z] = g.center_of([i, j, k]);
                    if z <= top && obstacle.contains(x, y) {
                        occupancy.set([i, j, k], true);
                    }
                    let d = column_distance([x, y, z], obstacle, top) as f32;
                    if d < *esdf.get([i, j, k]) {
                        esdf.set([i, j, k], d);
                    }
                }
            }
        }
    }

    #[test]
    fn local_volume_updates_equal_the_whole_grid_loops() {
        let mut world = flat_world();
        // A distance field with structure: distances to a wall at x = 0, capped.
        let esdf = world.esdf.as_mut().unwrap();
        let g = esdf.geometry;
        for k in 0..g.size[2] {
            for j in 0..g.size[1] {
                for i in 0..g.size[0] {
                    let [x, _, z] = g.center_of([i, j, k]);
                    esdf.set([i, j, k], (x.min(z + 1.0)).min(2.5) as f32);
                }
            }
        }
        let mut naive = world.clone();
        for (n, (cx, cy, r, h)) in [
            (5.0, 5.0, 1.0, 1.5),
            (0.2, 9.7, 0.7, 0.5),
            (9.9, 0.1, 2.5, 3.0),
            (3.3, 6.1, 0.26, 0.8),
        ]
        .into_iter()
        .enumerate()
        {
            let obstacle = DiscObstacle {
                center: [cx, cy],
                radius: r,
                height: h,
            };
            add_obstacles(&mut world, &[obstacle]);
            for [i, j] in obstacle.cells(&naive.elevation.geometry) {
                let z = naive.elevation.get(i, j) + h as f32;
                naive.elevation.set(i, j, z);
            }
            let top = obstacle
                .cells(&naive.elevation.geometry)
                .iter()
                .map(|&[i, j]| naive.elevation.get(i, j) as f64)
                .fold(f64::NEG_INFINITY, f64::max);
            global_update(&mut naive, &obstacle, top);
            mask_layer(naive.traversability.as_mut().unwrap(), &[obstacle]);
            assert_eq!(world.occupancy, naive.occupancy, "obstacle {n}");
            let bits = |w: &World| {
                let e = w.esdf.as_ref().unwrap();
                e.data.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
            };
            assert_eq!(bits(&world), bits(&naive), "obstacle {n}");
        }
    }

    #[test]
    fn a_disc_off_the_map_changes_nothing() {
        let mut world = flat_world();
        let before = world.clone();
        let far = DiscObstacle {
            center: [-50.0, 3.0],
            radius: 2.0,
            height: 1.0,
        };
        add_obstacles(&mut world, &[far]);
        assert_eq!(world, before);
    }
}
