//! Point clouds (PLY, PCD) rasterised into an elevation layer, as elevation_mapping and
//! grid_map users produce one.
//!
//! Readers: PLY `ascii 1.0`, `binary_little_endian 1.0` and `binary_big_endian 1.0`
//! (the `vertex` element's `x`, `y`, `z` of any scalar type; other elements and
//! properties, list properties included, are skipped); PCD v0.7 `DATA ascii` and
//! `DATA binary` (`x`, `y`, `z` fields of type F 4/8, I or U; `binary_compressed` is
//! refused with a message saying how to convert). Points with a NaN or infinite
//! coordinate are dropped (PCD marks invalid points so).
//!
//! Both readers are small and written here: the PLY crates on crates.io are unmaintained
//! or pull in a general mesh library, and PCD has no maintained reader without PCL.
//!
//! Rasterising: cell `(i, j)` of size `cell_size` covers
//! `[i·s, (i+1)·s) × [j·s, (j+1)·s)` in grid-aligned coordinates (the grid's origin is a
//! multiple of the cell size, so two clouds of the same place share cells); its height is
//! the highest (`max`) or the mean (`mean`) z of its points; cells without points are NaN.

mod format;
mod pcd;
mod ply;

pub use format::{PointCloudError, MAX_POINTS};

use pcd::read_pcd;
use ply::read_ply;
use serde::{Deserialize, Serialize};
use smug_core::{GridGeometry, GridLayer, MemoryLimit};
use std::path::Path;

/// How the points of one cell make its height.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Reduce {
    /// The highest point (conservative: the top of anything in the cell).
    #[default]
    Max,
    /// The mean z.
    Mean,
}

/// Reads the points of a `.ply` or `.pcd` file (by extension, else by its first line).
pub fn read_point_cloud(path: &Path) -> Result<Vec<[f64; 3]>, PointCloudError> {
    let fail = |message: String| PointCloudError {
        path: path.to_path_buf(),
        message,
    };
    let bytes = std::fs::read(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    let points = if bytes.starts_with(b"ply") {
        read_ply(&bytes, path)
    } else if is_pcd(&bytes) {
        read_pcd(&bytes, path)
    } else {
        Err(fail(
            "neither a PLY file (first line `ply`) nor a PCD file (a `# .PCD` or \
             `VERSION` header)"
                .to_string(),
        ))
    }?;
    Ok(points
        .into_iter()
        .filter(|p| p.iter().all(|v| v.is_finite()))
        .collect())
}

fn is_pcd(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(64)];
    head.starts_with(b"# .PCD") || head.starts_with(b"VERSION") || head.starts_with(b"FIELDS")
}

/// Rasterises `points` into cells of `cell_size` metres (see the [module
/// documentation](self)); `path` names the cloud in errors.
pub fn rasterise(
    points: &[[f64; 3]],
    cell_size: f64,
    reduce: Reduce,
    path: &Path,
) -> Result<GridLayer, PointCloudError> {
    rasterise_within(points, cell_size, reduce, path, MemoryLimit::default())
}

/// [`rasterise`] into a grid that must fit `memory` (a run's limit).
pub fn rasterise_within(
    points: &[[f64; 3]],
    cell_size: f64,
    reduce: Reduce,
    path: &Path,
    memory: MemoryLimit,
) -> Result<GridLayer, PointCloudError> {
    let fail = |message: String| PointCloudError {
        path: path.to_path_buf(),
        message,
    };
    if !(cell_size.is_finite() && cell_size > 0.0) {
        return Err(fail(format!("cell_size must be > 0, got {cell_size}")));
    }
    if points.is_empty() {
        return Err(fail("has no valid points".into()));
    }
    let cell = |v: f64| (v / cell_size).floor();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(cell(p[k]));
            hi[k] = hi[k].max(cell(p[k]));
        }
    }
    let size = [(hi[0] - lo[0]) as u64 + 1, (hi[1] - lo[1]) as u64 + 1];
    if size[0] * size[1] > crate::limits::MAX_PIXELS {
        return Err(fail(format!(
            "covers {} × {} cells of {cell_size} m, more than the {} SMUG rasterises \
             (a larger cell_size, or a cloud in metres?)",
            size[0],
            size[1],
            crate::limits::MAX_PIXELS
        )));
    }
    let geometry = GridGeometry::new_within(
        [lo[0] * cell_size, lo[1] * cell_size],
        cell_size,
        [size[0] as usize, size[1] as usize],
        memory,
    )
    .map_err(|e| fail(e.to_string()))?;
    let mut sum = vec![0.0f64; geometry.len()];
    let mut top = vec![f64::NEG_INFINITY; geometry.len()];
    let mut count = vec![0u32; geometry.len()];
    for p in points {
        let i = (cell(p[0]) - lo[0]) as usize;
        let j = (cell(p[1]) - lo[1]) as usize;
        let k = geometry.index(i, j);
        sum[k] += p[2];
        top[k] = top[k].max(p[2]);
        count[k] += 1;
    }
    let data = (0..geometry.len())
        .map(|k| match (count[k], reduce) {
            (0, _) => f32::NAN,
            (_, Reduce::Max) => top[k] as f32,
            (n, Reduce::Mean) => (sum[k] / f64::from(n)) as f32,
        })
        .collect();
    Ok(GridLayer { geometry, data })
}
