//! 2D grid layers and 3D voxel grids with their geometry.
//!
//! Cell `(i, j)` covers `[origin.x + i·res, origin.x + (i+1)·res) × [origin.y + j·res, …)`;
//! its value is taken at the cell centre. Data is row-major: index `j·nx + i`.

use crate::limits::MemoryLimit;
use crate::pose::Bounds2;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Why a grid geometry or layer is invalid.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GridError {
    /// The resolution is not finite and > 0.
    #[error("{grid} resolution must be > 0, got {resolution}")]
    Resolution {
        /// `grid` or `voxel`.
        grid: &'static str,
        /// The resolution given.
        resolution: f64,
    },
    /// The origin is not finite.
    #[error("{grid} origin must be finite, got {origin}")]
    Origin {
        /// `grid` or `voxel grid`.
        grid: &'static str,
        /// The origin given, as written.
        origin: String,
    },
    /// The grid would not fit the memory limit.
    #[error(transparent)]
    Memory(#[from] crate::limits::MemoryLimitError),
    /// A layer's data does not match its geometry.
    #[error("grid data has {got} values, geometry {}×{} needs {}", size[0], size[1], size[0] * size[1])]
    DataLength {
        /// Values given.
        got: usize,
        /// The geometry's cells along x and y.
        size: [usize; 2],
    },
}

/// Geometry of a 2D grid: lower-left corner, square cell size, number of cells.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridGeometry {
    /// World coordinates of the lower-left corner of cell `(0, 0)`.
    pub origin: [f64; 2],
    /// Cell edge length in metres.
    pub resolution: f64,
    /// Number of cells along x and y.
    pub size: [usize; 2],
}

impl GridGeometry {
    /// A geometry; the resolution must be finite and > 0, the grid within the default
    /// memory limit (see [`new_within`](Self::new_within)).
    pub fn new(origin: [f64; 2], resolution: f64, size: [usize; 2]) -> Result<Self, GridError> {
        Self::new_within(origin, resolution, size, MemoryLimit::default())
    }

    /// A geometry whose grid (4 bytes a cell) fits `memory`.
    pub fn new_within(
        origin: [f64; 2],
        resolution: f64,
        size: [usize; 2],
        memory: MemoryLimit,
    ) -> Result<Self, GridError> {
        if !(resolution.is_finite() && resolution > 0.0) {
            return Err(GridError::Resolution {
                grid: "grid",
                resolution,
            });
        }
        if !(origin[0].is_finite() && origin[1].is_finite()) {
            return Err(GridError::Origin {
                grid: "grid",
                origin: format!("{origin:?}"),
            });
        }
        let cells = size.iter().map(|&n| n as u128).product::<u128>();
        memory.check(&format!("a {}×{} grid", size[0], size[1]), cells, 4)?;
        Ok(Self {
            origin,
            resolution,
            size,
        })
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.size[0] * self.size[1]
    }

    /// True when the grid has no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The rectangle the grid covers.
    pub fn bounds(&self) -> Bounds2 {
        Bounds2 {
            min: self.origin,
            max: [
                self.origin[0] + self.size[0] as f64 * self.resolution,
                self.origin[1] + self.size[1] as f64 * self.resolution,
            ],
        }
    }

    /// The cell containing `(x, y)`, if inside the grid.
    #[inline]
    pub fn cell_of(&self, x: f64, y: f64) -> Option<[usize; 2]> {
        let fx = (x - self.origin[0]) / self.resolution;
        let fy = (y - self.origin[1]) / self.resolution;
        if !(fx >= 0.0 && fy >= 0.0) {
            return None;
        }
        let (i, j) = (fx as usize, fy as usize);
        (i < self.size[0] && j < self.size[1]).then_some([i, j])
    }

    /// World coordinates of the centre of cell `(i, j)`.
    pub fn center_of(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.origin[0] + (i as f64 + 0.5) * self.resolution,
            self.origin[1] + (j as f64 + 0.5) * self.resolution,
        ]
    }

    /// Row-major index of cell `(i, j)`.
    #[inline]
    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.size[0] + i
    }
}

/// A 2D layer of `f32` values (NaN = no data), e.g. elevation or traversability.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridLayer {
    /// Where the cells are.
    pub geometry: GridGeometry,
    /// One value per cell, row-major.
    pub data: Vec<f32>,
}

impl GridLayer {
    /// A layer filled with `value`.
    pub fn filled(geometry: GridGeometry, value: f32) -> Self {
        Self {
            geometry,
            data: vec![value; geometry.len()],
        }
    }

    /// A layer from data; its length must match the geometry.
    pub fn from_data(geometry: GridGeometry, data: Vec<f32>) -> Result<Self, GridError> {
        if data.len() != geometry.len() {
            return Err(GridError::DataLength {
                got: data.len(),
                size: geometry.size,
            });
        }
        Ok(Self { geometry, data })
    }

    /// A layer whose cell values are `f(i, j)`.
    pub fn from_fn(geometry: GridGeometry, mut f: impl FnMut(usize, usize) -> f32) -> Self {
        let mut data = Vec::with_capacity(geometry.len());
        for j in 0..geometry.size[1] {
            for i in 0..geometry.size[0] {
                data.push(f(i, j));
            }
        }
        Self { geometry, data }
    }

    /// A layer whose cell values are `f(i, j)`, rows filled side by side on rayon's
    /// threads: the same layer as [`from_fn`](Self::from_fn) with the same `f`, for
    /// any number of threads (each cell's value is `f`'s alone).
    pub fn from_fn_par(geometry: GridGeometry, f: impl Fn(usize, usize) -> f32 + Sync) -> Self {
        Self::from_rows_par(geometry, |j, row| {
            for (i, cell) in row.iter_mut().enumerate() {
                *cell = f(i, j);
            }
        })
    }

    /// A layer whose row `j` is filled by `fill(j, row)`, rows side by side on rayon's
    /// threads: the same layer for any number of threads (each row is `fill`'s alone).
    pub fn from_rows_par(geometry: GridGeometry, fill: impl Fn(usize, &mut [f32]) + Sync) -> Self {
        let nx = geometry.size[0];
        let mut data = vec![0.0f32; geometry.len()];
        if nx > 0 {
            data.par_chunks_mut(nx)
                .enumerate()
                .for_each(|(j, row)| fill(j, row));
        }
        Self { geometry, data }
    }

    /// Value of cell `(i, j)`; panics when out of range.
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> f32 {
        self.data[self.geometry.index(i, j)]
    }

    /// Sets cell `(i, j)`.
    pub fn set(&mut self, i: usize, j: usize, value: f32) {
        let k = self.geometry.index(i, j);
        self.data[k] = value;
    }

    /// Value of the cell containing `(x, y)`: `None` outside the grid or where NaN.
    #[inline]
    pub fn nearest(&self, x: f64, y: f64) -> Option<f64> {
        let [i, j] = self.geometry.cell_of(x, y)?;
        let v = self.get(i, j);
        (!v.is_nan()).then_some(v as f64)
    }

    /// Bilinear interpolation between cell centres (clamped at the border):
    /// `None` outside the grid or when a contributing cell is NaN.
    #[inline]
    pub fn bilinear(&self, x: f64, y: f64) -> Option<f64> {
        self.geometry.cell_of(x, y)?;
        let g = &self.geometry;
        let (i0, i1, tx) = interpolation_axis(x, g.origin[0], g.resolution, g.size[0]);
        let (j0, j1, ty) = interpolation_axis(y, g.origin[1], g.resolution, g.size[1]);
        let v00 = self.get(i0, j0) as f64;
        let v10 = self.get(i1, j0) as f64;
        let v01 = self.get(i0, j1) as f64;
        let v11 = self.get(i1, j1) as f64;
        let v = (v00 * (1.0 - tx) + v10 * tx) * (1.0 - ty) + (v01 * (1.0 - tx) + v11 * tx) * ty;
        (!v.is_nan()).then_some(v)
    }
}

/// The two cell indices around `coordinate` along one axis and the weight of the upper one.
#[inline]
fn interpolation_axis(
    coordinate: f64,
    origin: f64,
    resolution: f64,
    n: usize,
) -> (usize, usize, f64) {
    let f = (coordinate - origin) / resolution - 0.5;
    if f <= 0.0 || n == 1 {
        return (0, 0, 0.0);
    }
    // `f > 0`: truncation is the floor (no libm call on the slope checks' hot path).
    let lower = f as usize;
    if lower + 1 >= n {
        return (n - 1, n - 1, 0.0);
    }
    (lower, lower + 1, f - lower as f64)
}

/// Geometry of a 3D voxel grid: lower corner, cube edge, number of voxels.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VoxelGeometry {
    /// World coordinates of the lower corner of voxel `(0, 0, 0)`.
    pub origin: [f64; 3],
    /// Voxel edge length in metres.
    pub resolution: f64,
    /// Number of voxels along x, y, z.
    pub size: [usize; 3],
}

impl VoxelGeometry {
    /// A geometry; the resolution must be finite and > 0, the grid within the default
    /// memory limit (see [`new_within`](Self::new_within)).
    pub fn new(origin: [f64; 3], resolution: f64, size: [usize; 3]) -> Result<Self, GridError> {
        Self::new_within(origin, resolution, size, MemoryLimit::default())
    }

    /// A geometry whose grid (4 bytes a voxel) fits `memory`.
    pub fn new_within(
        origin: [f64; 3],
        resolution: f64,
        size: [usize; 3],
        memory: MemoryLimit,
    ) -> Result<Self, GridError> {
        if !(resolution.is_finite() && resolution > 0.0) {
            return Err(GridError::Resolution {
                grid: "voxel",
                resolution,
            });
        }
        if !origin.iter().all(|c| c.is_finite()) {
            return Err(GridError::Origin {
                grid: "voxel grid",
                origin: format!("{origin:?}"),
            });
        }
        let voxels = size.iter().map(|&n| n as u128).product::<u128>();
        let shown = format!("a {}×{}×{} voxel grid", size[0], size[1], size[2]);
        memory.check(&shown, voxels, 4)?;
        Ok(Self {
            origin,
            resolution,
            size,
        })
    }

    /// Number of voxels.
    pub fn len(&self) -> usize {
        self.size[0] * self.size[1] * self.size[2]
    }

    /// True when the grid has no voxels.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The voxel containing `p`, if inside.
    pub fn voxel_of(&self, p: [f64; 3]) -> Option<[usize; 3]> {
        let mut cell = [0usize; 3];
        for axis in 0..3 {
            let f = (p[axis] - self.origin[axis]) / self.resolution;
            if f.is_nan() || f < 0.0 || f as usize >= self.size[axis] {
                return None;
            }
            cell[axis] = f as usize;
        }
        Some(cell)
    }

    /// World coordinates of the centre of voxel `v`.
    pub fn center_of(&self, v: [usize; 3]) -> [f64; 3] {
        std::array::from_fn(|axis| self.origin[axis] + (v[axis] as f64 + 0.5) * self.resolution)
    }

    /// Index of voxel `(i, j, k)`: x fastest, then y, then z.
    pub fn index(&self, v: [usize; 3]) -> usize {
        (v[2] * self.size[1] + v[1]) * self.size[0] + v[0]
    }
}

/// A 3D grid of values (occupancy, signed distances, …).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VoxelGrid<T> {
    /// Where the voxels are.
    pub geometry: VoxelGeometry,
    /// One value per voxel, x fastest.
    pub data: Vec<T>,
}

impl<T: Clone> VoxelGrid<T> {
    /// A grid filled with `value`.
    pub fn filled(geometry: VoxelGeometry, value: T) -> Self {
        Self {
            geometry,
            data: vec![value; geometry.len()],
        }
    }

    /// Value of voxel `v`; panics when out of range.
    pub fn get(&self, v: [usize; 3]) -> &T {
        &self.data[self.geometry.index(v)]
    }

    /// Sets voxel `v`.
    pub fn set(&mut self, v: [usize; 3], value: T) {
        let k = self.geometry.index(v);
        self.data[k] = value;
    }

    /// Value of the voxel containing `p`, if inside.
    pub fn at(&self, p: [f64; 3]) -> Option<&T> {
        self.geometry.voxel_of(p).map(|v| self.get(v))
    }
}

impl VoxelGrid<f32> {
    /// Trilinear interpolation between voxel centres (clamped at the border);
    /// `None` outside the grid or when a contributing voxel is NaN.
    pub fn trilinear(&self, p: [f64; 3]) -> Option<f64> {
        self.geometry.voxel_of(p)?;
        let g = &self.geometry;
        let axes: [(usize, usize, f64); 3] =
            std::array::from_fn(|a| interpolation_axis(p[a], g.origin[a], g.resolution, g.size[a]));
        let mut value = 0.0;
        for corner in 0..8 {
            let mut weight = 1.0;
            let mut v = [0usize; 3];
            for (a, &(lo, hi, t)) in axes.iter().enumerate() {
                if corner >> a & 1 == 1 {
                    v[a] = hi;
                    weight *= t;
                } else {
                    v[a] = lo;
                    weight *= 1.0 - t;
                }
            }
            if weight > 0.0 {
                value += weight * *self.get(v) as f64;
            }
        }
        (!value.is_nan()).then_some(value)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn geometry() -> GridGeometry {
        GridGeometry::new([-1.0, 2.0], 0.5, [8, 6]).unwrap()
    }

    #[test]
    fn world_cell_roundtrip() {
        let g = geometry();
        for j in 0..6 {
            for i in 0..8 {
                let [x, y] = g.center_of(i, j);
                assert_eq!(g.cell_of(x, y), Some([i, j]));
            }
        }
        assert_eq!(g.cell_of(-1.01, 2.1), None);
        assert_eq!(g.cell_of(3.0, 2.1), None);
        assert_eq!(g.cell_of(f64::NAN, 2.1), None);
        assert_eq!(g.bounds().max, [3.0, 5.0]);
    }

    #[test]
    fn rows_side_by_side_fill_the_layer_one_by_one_would() {
        let g = GridGeometry::new([0.0, 0.0], 0.1, [37, 23]).unwrap();
        let f = |i: usize, j: usize| ((i * 31 + j * 17) as f32).sin() * (j as f32 + 0.5);
        let one_by_one = GridLayer::from_fn(g, f);
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let side_by_side = pool.install(|| GridLayer::from_fn_par(g, f));
            assert_eq!(side_by_side, one_by_one, "{threads} threads");
        }
        let empty = GridGeometry::new([0.0, 0.0], 0.1, [0, 4]).unwrap();
        assert_eq!(GridLayer::from_fn_par(empty, f).data.len(), 0);
    }

    proptest! {
        #[test]
        fn bilinear_reproduces_affine_fields(a in -2.0f64..2.0, b in -2.0f64..2.0, c in -5.0f64..5.0,
                x in -0.75f64..2.75, y in 2.25f64..4.75) {
            // Affine fields are exact between cell centres (x, y chosen inside the centre hull).
            let g = geometry();
            let layer = GridLayer::from_fn(g, |i, j| {
                let [cx, cy] = g.center_of(i, j);
                (a * cx + b * cy + c) as f32
            });
            let v = layer.bilinear(x, y).unwrap();
            prop_assert!((v - (a * x + b * y + c)).abs() < 1e-4);
        }

        #[test]
        fn trilinear_reproduces_affine_fields(a in -2.0f64..2.0, b in -2.0f64..2.0, c in -2.0f64..2.0,
                x in 0.25f64..1.75, y in 0.25f64..1.25, z in 0.25f64..0.75) {
            let g = VoxelGeometry::new([0.0, 0.0, 0.0], 0.5, [4, 3, 2]).unwrap();
            let mut grid = VoxelGrid::filled(g, 0.0f32);
            for k in 0..2 { for j in 0..3 { for i in 0..4 {
                let p = g.center_of([i, j, k]);
                grid.set([i, j, k], (a * p[0] + b * p[1] + c * p[2]) as f32);
            }}}
            let v = grid.trilinear([x, y, z]).unwrap();
            prop_assert!((v - (a * x + b * y + c * z)).abs() < 1e-4);
        }
    }

    #[test]
    fn bilinear_is_none_near_missing_data_and_outside() {
        let g = geometry();
        let mut layer = GridLayer::filled(g, 1.0);
        layer.set(3, 3, f32::NAN);
        let [x, y] = g.center_of(3, 3);
        assert_eq!(layer.bilinear(x + 0.1, y + 0.1), None);
        assert_eq!(layer.nearest(x, y), None);
        assert_eq!(layer.bilinear(100.0, 0.0), None);
        let [x, y] = g.center_of(0, 0);
        assert_eq!(layer.bilinear(x, y), Some(1.0));
    }

    #[test]
    fn from_data_checks_length() {
        assert!(GridLayer::from_data(geometry(), vec![0.0; 3]).is_err());
        assert!(GridGeometry::new([0.0, 0.0], 0.0, [1, 1]).is_err());
    }
}
