//! Terrain files that are not a map YAML: a GeoTIFF DEM or a PLY/PCD point cloud,
//! read into an elevation layer.

use super::layers::MapLayers;
use std::path::Path;

/// A terrain file that is not a map YAML.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TerrainKind {
    /// A GeoTIFF DEM.
    Dem,
    /// A PLY or PCD point cloud.
    PointCloud,
}

impl TerrainKind {
    /// The kind a file's extension names: `.tif`/`.tiff` a DEM, `.ply`/`.pcd` a cloud.
    pub fn of(path: &Path) -> Option<Self> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "tif" | "tiff" => Some(TerrainKind::Dem),
            "ply" | "pcd" => Some(TerrainKind::PointCloud),
            _ => None,
        }
    }
}

/// Why a DEM or a point cloud could not be read.
#[derive(Debug, thiserror::Error)]
pub enum TerrainError {
    /// A bad GeoTIFF.
    #[error(transparent)]
    GeoTiff(#[from] crate::geotiff::GeoTiffError),
    /// A bad point cloud.
    #[error(transparent)]
    PointCloud(#[from] crate::point_cloud::PointCloudError),
}

/// The elevation of a GeoTIFF DEM, or of a point cloud rasterised into cells of
/// `cell_size` with `reduce` (see [`crate::geotiff`] and [`crate::point_cloud`]), in a
/// grid that must fit `memory`.
pub fn load_terrain(
    path: &Path,
    kind: TerrainKind,
    cell_size: f64,
    reduce: crate::point_cloud::Reduce,
    memory: smug_core::MemoryLimit,
) -> Result<MapLayers, TerrainError> {
    let elevation = match kind {
        TerrainKind::Dem => crate::geotiff::read_geotiff_within(path, memory)?.elevation,
        TerrainKind::PointCloud => {
            let points = crate::point_cloud::read_point_cloud(path)?;
            crate::point_cloud::rasterise_within(&points, cell_size, reduce, path, memory)?
        }
    };
    Ok(MapLayers::from_elevation(elevation))
}
