//! Occupancy voxels and their Euclidean signed distance field, derived from a world's
//! elevation layer: every voxel whose centre lies at or below the terrain (or in a
//! column without data) is occupied. The union of occupied voxel cubes is the
//! geometry both box checkers test against.

use crate::edt::squared_edt_3d;
use crate::ValidityError;
use smug_core::{VoxelGeometry, VoxelGrid, World};
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

/// Largest voxel count derived automatically (≈ 1.6 GB of distances).
const MAX_VOXELS: usize = 400_000_000;

/// Occupancy and signed distances of a world, with a query counter.
#[derive(Debug)]
pub struct Volumes {
    /// Occupied voxels.
    pub occupancy: VoxelGrid<bool>,
    /// Signed distance (metres) from each voxel centre to the nearest occupied voxel
    /// centre (positive), or minus the distance to the nearest free one (inside).
    pub esdf: VoxelGrid<f32>,
    queries: AtomicU64,
}

impl Volumes {
    /// Volumes of `world`: its own occupancy/ESDF when it carries both, otherwise derived
    /// from the elevation with `headroom` metres of free space above the highest terrain.
    pub fn from_world(world: &World, headroom: f64) -> Result<Self, ValidityError> {
        if let (Some(occupancy), Some(esdf)) = (&world.occupancy, &world.esdf) {
            if occupancy.geometry != esdf.geometry {
                return Err(ValidityError::Map(
                    "the world's occupancy and ESDF grids differ in geometry".into(),
                ));
            }
            return Ok(Self::new(occupancy.clone(), esdf.clone()));
        }
        Ok(Self::from_occupancy(occupancy_from_elevation(
            world, headroom,
        )?))
    }

    /// Volumes of an occupancy grid (computes the ESDF).
    pub fn from_occupancy(occupancy: VoxelGrid<bool>) -> Self {
        let esdf = signed_distance_field(&occupancy);
        Self::new(occupancy, esdf)
    }

    fn new(occupancy: VoxelGrid<bool>, esdf: VoxelGrid<f32>) -> Self {
        Self {
            occupancy,
            esdf,
            queries: AtomicU64::new(0),
        }
    }

    /// The voxel geometry.
    pub fn geometry(&self) -> &VoxelGeometry {
        &self.occupancy.geometry
    }

    /// A lower bound of the distance from `p` to the occupied voxel cubes (≤ 0 when
    /// `p` may be inside); `None` outside the grid (unknown space). Counts one query.
    pub fn distance_lower_bound(&self, p: [f64; 3]) -> Option<f64> {
        self.queries.fetch_add(1, Relaxed);
        let g = &self.occupancy.geometry;
        let v = g.voxel_of(p)?;
        let c = g.center_of(v);
        let offset = ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt();
        let d = *self.esdf.get(v) as f64;
        // Distances run between voxel centres; a cube reaches √3/2·res closer than its
        // centre, and the distance field is 1-Lipschitz (the offset from the centre).
        Some(d - 0.5 * 3f64.sqrt() * g.resolution - offset)
    }

    /// Distance-field queries so far.
    pub fn queries(&self) -> u64 {
        self.queries.load(Relaxed)
    }

    /// True when the axis-aligned box `[min, max]` lies inside the grid.
    pub fn contains_box(&self, min: [f64; 3], max: [f64; 3]) -> bool {
        let g = &self.occupancy.geometry;
        (0..3).all(|a| {
            min[a] >= g.origin[a] && max[a] <= g.origin[a] + g.size[a] as f64 * g.resolution
        })
    }
}

/// Voxelises the terrain: ground and everything below it occupied, columns without
/// elevation data occupied (unknown space is not free).
pub fn occupancy_from_elevation(
    world: &World,
    headroom: f64,
) -> Result<VoxelGrid<bool>, ValidityError> {
    let elevation = &world.elevation;
    let (low, high) = elevation
        .data
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v as f64), hi.max(v as f64))
        });
    if !low.is_finite() {
        return Err(ValidityError::Map(format!(
            "world `{}` has no elevation data",
            world.name
        )));
    }
    let g = elevation.geometry;
    let res = g.resolution;
    let z0 = low - 2.0 * res;
    let nz = ((high + headroom.max(0.0) - z0) / res).ceil() as usize + 1;
    let [nx, ny] = g.size;
    if nx.saturating_mul(ny).saturating_mul(nz) > MAX_VOXELS {
        return Err(ValidityError::Map(format!(
            "world `{}` needs {nx}×{ny}×{nz} voxels at {res} m (more than {MAX_VOXELS}); use a coarser map",
            world.name
        )));
    }
    let geometry = VoxelGeometry::new([g.origin[0], g.origin[1], z0], res, [nx, ny, nz])
        .map_err(ValidityError::Map)?;
    let mut grid = VoxelGrid::filled(geometry, false);
    for j in 0..ny {
        for i in 0..nx {
            let h = elevation.get(i, j) as f64;
            for k in 0..nz {
                let z = z0 + (k as f64 + 0.5) * res;
                if h.is_nan() || z <= h {
                    grid.set([i, j, k], true);
                } else {
                    break;
                }
            }
        }
    }
    Ok(grid)
}

/// The signed distance field of `occupancy` in metres.
pub fn signed_distance_field(occupancy: &VoxelGrid<bool>) -> VoxelGrid<f32> {
    let g = occupancy.geometry;
    let outside = squared_edt_3d(&occupancy.data, g.size);
    let free: Vec<bool> = occupancy.data.iter().map(|o| !o).collect();
    let inside = squared_edt_3d(&free, g.size);
    let data = occupancy
        .data
        .iter()
        .zip(outside.iter().zip(&inside))
        .map(|(&occupied, (&out, &ins))| {
            let d = if occupied { -ins.sqrt() } else { out.sqrt() };
            (d * g.resolution).clamp(-1e6, 1e6) as f32
        })
        .collect();
    VoxelGrid { geometry: g, data }
}
