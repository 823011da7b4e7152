//! Map import: ROS `map_server`-style YAML with a PGM or PNG occupancy image, plus
//! optional elevation and traversability images, and the `map` world plugin.
//!
//! # The YAML file
//!
//! ```yaml
//! image: lab.pgm             # occupancy image (PGM P2/P5 8/16-bit, or PNG gray/RGB/RGBA)
//! resolution: 0.05           # metres per pixel
//! origin: [-10.0, -5.0, 0.0] # lower-left corner [x, y, yaw]; yaw must be 0
//! occupied_thresh: 0.65      # default 0.65
//! free_thresh: 0.196         # default 0.196
//! negate: 0                  # 0/1 or false/true, default 0
//! mode: trinary              # trinary (default), scale or raw
//! # SMUG extensions, all optional:
//! elevation_image: lab.elevation.png   # 16-bit (or 8-bit) gray PNG: ground height
//! elevation_scale: 0.001               # metres per unit, default 0.001
//! elevation_offset: 0.0                # metres, default 0
//! elevation_includes_obstacles: false  # true: the image is the whole surface
//! traversability_image: lab.trav.png   # 8-bit gray PNG, value / 255 ∈ [0, 1]
//! traversability_nodata: 255           # this sample value means "no data"
//! mission: lab.mission.toml            # mission file used when none is given
//! ```
//!
//! Relative image and mission paths resolve against the YAML file's folder. Unknown keys
//! are errors (they are usually typos).
//!
//! # Semantics (those of `map_server`)
//!
//! Each pixel's value `v` is normalised to `[0, 1]` (`v / 255` for 8-bit images; PGM
//! samples are scaled to the full 8- or 16-bit range by the decoder, colour pixels are
//! converted to luma). Its occupancy probability is `p = 1 − v` (`p = v` when `negate`).
//! In `trinary` and `scale` modes `p > occupied_thresh` is occupied, `p < free_thresh`
//! free, anything else unknown — except in `scale` mode, where values between the
//! thresholds are free ground with a reduced traversability (below). In `raw` mode the
//! 8-bit value (after `negate`) is an occupancy percentage: `0..=100` is classified with
//! the thresholds, larger values are unknown. A fully transparent pixel is unknown in
//! every mode.
//!
//! Image row 0 is the top of the map (largest y); the grid's row 0 is the bottom.
//!
//! The world's elevation: free cells have the ground height (0 m, or
//! `elevation_offset + elevation_scale · sample` of the elevation image), occupied cells
//! the ground plus `obstacle_height` (or the elevation image's value as is when
//! `elevation_includes_obstacles`), unknown cells NaN (no data). A transparent pixel of
//! the elevation image is NaN too.
//!
//! The traversability layer comes from `traversability_image` (sample / max; transparent
//! pixels and the `traversability_nodata` sample are NaN). Without one, a `scale`-mode map
//! gets a layer from its occupancy: 1 on free cells, 0 on occupied ones, NaN on unknown
//! ones and `1 − (p − free_thresh) / (occupied_thresh − free_thresh)` in between; other
//! maps get none (a traversability estimator may fill it in the pipeline).

mod error;
mod image;
mod layers;
mod plugin;
mod terrain;
mod yaml;

pub use crate::limits::MAX_PIXELS;
pub use error::MapFileError;
pub use layers::{check_mission_inside, file_stem, load_map, load_map_within, MapLayers};
pub use plugin::MapParams;
pub use terrain::{load_terrain, TerrainError, TerrainKind};
pub use yaml::{
    MapMode, MapYaml, MapYamlError, DEFAULT_CELL_SIZE, DEFAULT_ELEVATION_SCALE,
    DEFAULT_FREE_THRESH, DEFAULT_OBSTACLE_HEIGHT, DEFAULT_OCCUPIED_THRESH,
};
