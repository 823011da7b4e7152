//! Volumes updated in place after obstacles were added to the terrain: the occupancy
//! of the obstacles' columns voxelised again, and the signed distance field recomputed
//! only in a window around the newly occupied voxels. The result is, bit for bit, the
//! volumes derived from scratch for the updated world (see the tests).
//!
//! Why a window suffices: obstacles only add occupied voxels `N`. A free voxel's
//! distance becomes the smaller of its old one and its distance to `N`, so only free
//! voxels nearer `N` than the largest positive distance in the field change. An occupied
//! voxel's (negative) distance changes only when its nearest free voxels are all in `N`,
//! so only occupied voxels nearer `N` than the deepest negative distance change, and
//! their new distance is found in the window when the ball of that radius fits in it
//! (checked: else the caller derives the field from scratch).

use crate::edt::squared_edt_3d;
use smug_core::mission::DiscObstacle;
use smug_core::{VoxelGrid, World};

/// Voxelises again the columns of `world` (elevation raised by `obstacles`) under the
/// obstacles, as the derivation from the elevation does: every voxel up to the terrain
/// (or the whole column without data) occupied. Returns the newly occupied voxels'
/// indices.
pub(crate) fn update_occupancy(
    occupancy: &mut VoxelGrid<bool>,
    world: &World,
    obstacles: &[DiscObstacle],
) -> Vec<usize> {
    let g = occupancy.geometry;
    let (z0, res) = (g.origin[2], g.resolution);
    let mut added = Vec::new();
    for obstacle in obstacles {
        for [i, j] in obstacle.cells(&world.elevation.geometry) {
            let h = world.elevation.get(i, j) as f64;
            for k in 0..g.size[2] {
                let z = z0 + (k as f64 + 0.5) * res;
                if !(h.is_nan() || z <= h) {
                    break;
                }
                if !*occupancy.get([i, j, k]) {
                    occupancy.set([i, j, k], true);
                    added.push(g.index([i, j, k]));
                }
            }
        }
    }
    added
}

/// The signed distance of the field's formula (`signed_distance_field`) for a squared
/// distance in voxels², outside (`sign = 1`) or inside (`sign = -1`).
fn metres(squared: f64, sign: f64, resolution: f64) -> f32 {
    ((sign * squared.sqrt()) * resolution).clamp(-1e6, 1e6) as f32
}

/// The largest squared distance (voxels², an integer) whose inside value is `old`
/// (`INFINITY` when none is found: then any voxel counts as near).
fn squared_depth(old: f32, resolution: f64) -> f64 {
    let guess = ((old as f64) / resolution).powi(2).round();
    (0..5)
        .map(|k| guess + 2.0 - k as f64)
        .find(|&s| s >= 0.0 && metres(s, -1.0, resolution).to_bits() == old.to_bits())
        .unwrap_or(f64::INFINITY)
}

/// Updates `esdf` (the field of the occupancy before `added` were occupied) for
/// `occupancy` (after), in a window around `added`, grown until every changed distance
/// is settled in it (at worst the whole grid); false when the field holds no finite
/// distance to bound the window by (the caller then derives it from scratch).
pub(crate) fn update_distances(
    esdf: &mut VoxelGrid<f32>,
    occupancy: &VoxelGrid<bool>,
    added: &[usize],
) -> bool {
    let size = occupancy.geometry.size;
    if added.is_empty() {
        return true;
    }
    let coords = |idx: usize| {
        [
            idx % size[0],
            (idx / size[0]) % size[1],
            idx / (size[0] * size[1]),
        ]
    };
    let (mut lo, mut hi) = ([usize::MAX; 3], [0usize; 3]);
    for &idx in added {
        let c = coords(idx);
        for a in 0..3 {
            lo[a] = lo[a].min(c[a]);
            hi[a] = hi[a].max(c[a] + 1);
        }
    }
    let (mut outside, mut inside) = (0.0f32, 0.0f32);
    for &d in &esdf.data {
        outside = outside.max(d);
        inside = inside.max(-d);
    }
    let reach = (outside.max(inside) as f64 / occupancy.geometry.resolution).ceil() + 2.0;
    if !reach.is_finite() || reach > 1e7 {
        return false;
    }
    let mut margin = reach as usize;
    loop {
        let w0 = [0, 1, 2].map(|a| lo[a].saturating_sub(margin));
        let w1 = [0, 1, 2].map(|a| (hi[a] + margin).min(size[a]));
        let window = Window { w0, w1, size };
        if let Some(changes) = window.changes(esdf, occupancy, added) {
            for (idx, d) in changes {
                esdf.data[idx] = d;
            }
            return true;
        }
        if w0 == [0; 3] && w1 == size {
            // Cannot happen: in the whole grid every distance is settled.
            return false;
        }
        margin *= 2;
    }
}

/// A box of voxels `w0..w1` of a grid of `size`.
struct Window {
    w0: [usize; 3],
    w1: [usize; 3],
    size: [usize; 3],
}

impl Window {
    /// The new distances of the window's voxels that change (index, metres), or `None`
    /// when one of them cannot be settled in the window.
    fn changes(
        &self,
        esdf: &VoxelGrid<f32>,
        occupancy: &VoxelGrid<bool>,
        added: &[usize],
    ) -> Option<Vec<(usize, f32)>> {
        let g = occupancy.geometry;
        let (w0, w1, size) = (self.w0, self.w1, self.size);
        let wsize = [0, 1, 2].map(|a| w1[a] - w0[a]);
        let global = |w: [usize; 3]| g.index([w[0] + w0[0], w[1] + w0[1], w[2] + w0[2]]);
        let local = |c: [usize; 3]| (c[2] * wsize[1] + c[1]) * wsize[0] + c[0];
        let mut is_added = vec![false; wsize[0] * wsize[1] * wsize[2]];
        for &idx in added {
            let c = [
                idx % size[0],
                (idx / size[0]) % size[1],
                idx / (size[0] * size[1]),
            ];
            is_added[local([c[0] - w0[0], c[1] - w0[1], c[2] - w0[2]])] = true;
        }
        let mut free = vec![false; is_added.len()];
        for k in 0..wsize[2] {
            for j in 0..wsize[1] {
                for i in 0..wsize[0] {
                    free[local([i, j, k])] = !occupancy.data[global([i, j, k])];
                }
            }
        }
        let to_added = squared_edt_3d(&is_added, wsize);
        let to_free = squared_edt_3d(&free, wsize);
        let res = g.resolution;
        // The ball of radius `r` (voxels) around `c` lies in the window (or the grid's
        // border bounds it): no voxel outside the window is nearer.
        let fits = |c: [usize; 3], r: f64| {
            (0..3).all(|a| {
                (w0[a] == 0 || (c[a] as f64) >= r)
                    && (w1[a] == size[a] || ((wsize[a] - 1 - c[a]) as f64) >= r)
            })
        };
        let mut changes = Vec::new();
        for k in 0..wsize[2] {
            for j in 0..wsize[1] {
                for i in 0..wsize[0] {
                    let (l, idx) = (local([i, j, k]), global([i, j, k]));
                    let old = esdf.data[idx];
                    if free[l] {
                        // Free voxels nearer the new ones than the largest distance lie
                        // in the window: `reach` covers them.
                        let d = metres(to_added[l], 1.0, res);
                        if d < old {
                            changes.push((idx, d));
                        }
                        continue;
                    }
                    if !(is_added[l] || to_added[l] <= squared_depth(old, res)) {
                        continue;
                    }
                    if !fits([i, j, k], to_free[l].sqrt()) {
                        return None;
                    }
                    let d = metres(to_free[l], -1.0, res);
                    if d.to_bits() != old.to_bits() {
                        changes.push((idx, d));
                    }
                }
            }
        }
        Some(changes)
    }
}
