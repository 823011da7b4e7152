//! SMUG worlds: where the maps and the mission come from.
//!
//! Plugins: `flat` (a flat floor with box obstacles and a mission written in the
//! config), `lunar` and `indoor` (procedural, seeded), `map` (ROS map_server-style
//! YAML + images, a GeoTIFF DEM or a PLY/PCD point cloud, and a mission). Also MovingAI map conversion and writing, seeded
//! grid map generators, optimal octile lengths, world export and SVG rendering.

#![warn(missing_docs)]

mod canvas;
pub mod export;
pub mod flat;
pub mod geotiff;
pub mod grid_gen;
pub mod indoor;
pub mod limits;
pub mod lunar;
pub mod map_file;
pub mod mission_file;
pub mod movingai;
pub mod point_cloud;
pub mod render;

pub use export::{export_world, export_world_with, ExportError, ExportOptions};
pub use geotiff::{read_geotiff, read_geotiff_within, Dem, GeoTiffError};
pub use grid_gen::{generate, GridFamily, GridGenError, GridParams};
pub use map_file::{load_map, MapFileError, MapLayers, MapParams, MapYaml};
pub use mission_file::{load_mission, MissionFileError};
pub use movingai::{convert_movingai, scenario_to_world, MovingAiError};
pub use point_cloud::{rasterise, rasterise_within, read_point_cloud, PointCloudError, Reduce};
pub use render::{render_svg, RenderOptions};
