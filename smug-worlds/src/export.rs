//! World export to the map format [`crate::map_file`] reads back.
//!
//! [`export_world`] writes, into one folder:
//!
//! - `STEM.yaml`: the `map_server`-style description naming the files below;
//! - `STEM.pgm`: the occupancy image (8-bit binary PGM, `map_saver`'s values: 0 occupied,
//!   254 free, 205 unknown). A cell is **unknown** when its elevation is NaN and
//!   **occupied** when its elevation exceeds the world's lowest elevation by more than
//!   [`ExportOptions::obstacle_threshold`] (default 0.5 m). This is a simple, faithful
//!   rule for floors with obstacles; on hilly terrain it marks high ground as occupied,
//!   which only matters to tools reading the PGM alone: SMUG itself reads the elevation;
//! - `STEM.elevation.png`: the elevation as a 16-bit gray PNG, with
//!   `elevation_offset` (the lowest elevation) and `elevation_scale` (1 mm, or coarser
//!   when the range exceeds 65.535 m) in the YAML, and `elevation_includes_obstacles:
//!   true`, so a round trip restores every elevation to within half a scale step;
//! - `STEM.traversability.png` when the world has a traversability layer: 8-bit gray
//!   with alpha (`value / 255`, transparent = no data);
//! - `STEM.mission.toml`: the mission (when given), named by the YAML's `mission` key.

use crate::map_file::{MapYaml, DEFAULT_ELEVATION_SCALE};
use image::{ImageBuffer, Luma, LumaA};
use smug_core::{GridGeometry, GridLayer, Mission, World};
use std::io::Cursor;
use std::path::{Path, PathBuf};

/// Occupancy image value of a free cell.
pub const FREE_VALUE: u8 = 254;
/// Occupancy image value of an occupied cell.
pub const OCCUPIED_VALUE: u8 = 0;
/// Occupancy image value of an unknown cell.
pub const UNKNOWN_VALUE: u8 = 205;
/// Default height above the lowest elevation beyond which a cell is exported as occupied.
pub const DEFAULT_OBSTACLE_THRESHOLD: f64 = 0.5;

/// How a world is exported.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExportOptions {
    /// Cells higher than the lowest elevation plus this (metres) are occupied.
    pub obstacle_threshold: f64,
}

impl Default for ExportOptions {
    fn default() -> Self {
        Self {
            obstacle_threshold: DEFAULT_OBSTACLE_THRESHOLD,
        }
    }
}

/// Why an export failed. Every message names the file at fault.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A file or folder could not be written.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Data could not be encoded (image, YAML or TOML).
    #[error("{}: cannot encode: {message}", path.display())]
    Encode {
        /// The file.
        path: PathBuf,
        /// The encoder's message.
        message: String,
    },
    /// The request itself is unusable (empty world, bad stem, bad option).
    #[error("{}: {message}", path.display())]
    Invalid {
        /// The folder or file concerned.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
}

/// Exports `world` and `mission` (when given) into `dir` as `stem.yaml` and its
/// companions, with default options; returns the YAML's path.
pub fn export_world(
    world: &World,
    mission: Option<&Mission>,
    dir: &Path,
    stem: &str,
) -> Result<PathBuf, ExportError> {
    export_world_with(world, mission, dir, stem, &ExportOptions::default())
}

/// Exports `world` and `mission` (when given) into `dir` as `stem.yaml` and its
/// companions (see the [module documentation](self)); returns the YAML's path.
pub fn export_world_with(
    world: &World,
    mission: Option<&Mission>,
    dir: &Path,
    stem: &str,
    options: &ExportOptions,
) -> Result<PathBuf, ExportError> {
    check_request(world, dir, stem, options)?;
    std::fs::create_dir_all(dir).map_err(|source| ExportError::Write {
        path: dir.to_path_buf(),
        source,
    })?;
    let geometry = world.elevation.geometry;
    let name = |suffix: &str| format!("{stem}.{suffix}");

    let mut yaml = MapYaml::new(name("pgm"), geometry.resolution, geometry.origin);
    let occupancy = occupancy_pixels(&world.elevation, options.obstacle_threshold);
    write_pgm(&dir.join(name("pgm")), geometry.size, &occupancy)?;

    let encoding = ElevationEncoding::for_layer(&world.elevation);
    write_png(
        &dir.join(name("elevation.png")),
        gray16(geometry, &encoding.encode(&world.elevation)),
    )?;
    yaml.elevation_image = Some(name("elevation.png").into());
    yaml.elevation_scale = encoding.scale;
    yaml.elevation_offset = encoding.offset;
    yaml.elevation_includes_obstacles = true;

    if let Some(layer) = &world.traversability {
        write_png(
            &dir.join(name("traversability.png")),
            traversability_image(layer),
        )?;
        yaml.traversability_image = Some(name("traversability.png").into());
    }

    if let Some(mission) = mission {
        let mission_path = dir.join(name("mission.toml"));
        let text = toml::to_string_pretty(mission).map_err(|e| ExportError::Encode {
            path: mission_path.clone(),
            message: e.to_string(),
        })?;
        write_file(&mission_path, text.as_bytes())?;
        yaml.mission = Some(name("mission.toml").into());
    }

    let yaml_path = dir.join(name("yaml"));
    write_map_yaml(
        &yaml_path,
        &yaml,
        &format!("world `{}` exported by smug", world.name),
    )?;
    Ok(yaml_path)
}

fn check_request(
    world: &World,
    dir: &Path,
    stem: &str,
    options: &ExportOptions,
) -> Result<(), ExportError> {
    let invalid = |message: String| ExportError::Invalid {
        path: dir.to_path_buf(),
        message,
    };
    if stem.is_empty() || stem == "." || stem == ".." || stem.contains(['/', '\\']) {
        return Err(invalid(format!("`{stem}` is not a usable file name stem")));
    }
    let elevation = &world.elevation;
    if elevation.geometry.is_empty() || elevation.data.len() != elevation.geometry.len() {
        return Err(invalid(format!(
            "world `{}` has no cells or an elevation layer of the wrong length",
            world.name
        )));
    }
    if let Some(layer) = &world.traversability {
        if layer.geometry.size != elevation.geometry.size
            || layer.data.len() != elevation.data.len()
        {
            return Err(invalid(format!(
                "world `{}`: the traversability layer is {}×{} cells, the elevation {}×{}",
                world.name,
                layer.geometry.size[0],
                layer.geometry.size[1],
                elevation.geometry.size[0],
                elevation.geometry.size[1]
            )));
        }
    }
    if !(options.obstacle_threshold.is_finite() && options.obstacle_threshold >= 0.0) {
        return Err(invalid(format!(
            "obstacle threshold must be finite and ≥ 0, got {}",
            options.obstacle_threshold
        )));
    }
    Ok(())
}

/// A cell's occupancy by the export's rule (see the [module documentation](self)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellOccupancy {
    /// Free.
    Free,
    /// Higher than the lowest elevation by more than the obstacle threshold.
    Occupied,
    /// No elevation.
    Unknown,
}

/// Each cell's occupancy, row-major from the origin as the layer's data: unknown where
/// the elevation is NaN, occupied where it exceeds the lowest elevation by more than
/// `obstacle_threshold` metres, free elsewhere.
pub fn cell_occupancy(elevation: &GridLayer, obstacle_threshold: f64) -> Vec<CellOccupancy> {
    let lowest = finite_range(&elevation.data).map_or(0.0, |(min, _)| min);
    elevation
        .data
        .iter()
        .map(|&z| {
            if z.is_nan() {
                CellOccupancy::Unknown
            } else if f64::from(z) - lowest > obstacle_threshold {
                CellOccupancy::Occupied
            } else {
                CellOccupancy::Free
            }
        })
        .collect()
}

/// The occupancy pixels of `elevation`, top image row first.
fn occupancy_pixels(elevation: &GridLayer, obstacle_threshold: f64) -> Vec<u8> {
    let cells = cell_occupancy(elevation, obstacle_threshold);
    image_rows(elevation.geometry, |k| match cells[k] {
        CellOccupancy::Unknown => UNKNOWN_VALUE,
        CellOccupancy::Occupied => OCCUPIED_VALUE,
        CellOccupancy::Free => FREE_VALUE,
    })
}

/// The smallest and largest finite values, if any.
pub(crate) fn finite_range(data: &[f32]) -> Option<(f64, f64)> {
    data.iter()
        .filter(|v| v.is_finite())
        .map(|&v| f64::from(v))
        .fold(None, |range, v| match range {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// `height = offset + scale · sample` for 16-bit samples.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ElevationEncoding {
    offset: f64,
    scale: f64,
}

impl ElevationEncoding {
    /// Offset at the lowest elevation; 1 mm steps unless the range needs coarser ones.
    fn for_layer(layer: &GridLayer) -> Self {
        let (lo, hi) = finite_range(&layer.data).unwrap_or((0.0, 0.0));
        let max_sample = f64::from(u16::MAX);
        let scale = if (hi - lo) / DEFAULT_ELEVATION_SCALE <= max_sample {
            DEFAULT_ELEVATION_SCALE
        } else {
            (hi - lo) / max_sample
        };
        Self { offset: lo, scale }
    }

    /// The samples of `layer`, top image row first (NaN and infinities become 0: such
    /// cells are unknown in the occupancy image).
    fn encode(&self, layer: &GridLayer) -> Vec<u16> {
        image_rows(layer.geometry, |k| {
            let z = f64::from(layer.data[k]);
            if z.is_finite() {
                ((z - self.offset) / self.scale)
                    .round()
                    .clamp(0.0, f64::from(u16::MAX)) as u16
            } else {
                0
            }
        })
    }
}

/// The traversability image: 8-bit gray plus alpha (transparent = NaN), top row first.
fn traversability_image(layer: &GridLayer) -> ImageBuffer<LumaA<u8>, Vec<u8>> {
    let pixels = image_rows(layer.geometry, |k| {
        let t = layer.data[k];
        if t.is_finite() {
            [(t.clamp(0.0, 1.0) * 255.0).round() as u8, u8::MAX]
        } else {
            [0, 0]
        }
    });
    let [w, h] = image_size(layer.geometry);
    ImageBuffer::from_fn(w, h, |x, y| {
        LumaA(pixels[y as usize * layer.geometry.size[0] + x as usize])
    })
}

fn gray16(geometry: GridGeometry, samples: &[u16]) -> ImageBuffer<Luma<u16>, Vec<u16>> {
    let [w, h] = image_size(geometry);
    ImageBuffer::from_fn(w, h, |x, y| {
        Luma([samples[y as usize * geometry.size[0] + x as usize]])
    })
}

fn image_size(geometry: GridGeometry) -> [u32; 2] {
    geometry.size.map(|n| u32::try_from(n).unwrap_or(u32::MAX))
}

/// `value(k)` for every cell, ordered as image pixels: top row (largest y) first.
pub(crate) fn image_rows<T>(geometry: GridGeometry, value: impl Fn(usize) -> T) -> Vec<T> {
    let [nx, ny] = geometry.size;
    (0..ny)
        .rev()
        .flat_map(|j| (0..nx).map(move |i| j * nx + i))
        .map(value)
        .collect()
}

/// Writes an 8-bit binary PGM (P5) of `size` = `[width, height]`, top row first.
pub(crate) fn write_pgm(path: &Path, size: [usize; 2], pixels: &[u8]) -> Result<(), ExportError> {
    let mut bytes = format!("P5\n# written by smug\n{} {}\n255\n", size[0], size[1]).into_bytes();
    bytes.extend_from_slice(pixels);
    write_file(path, &bytes)
}

/// Writes `yaml` with a comment line on top.
pub(crate) fn write_map_yaml(
    path: &Path,
    yaml: &MapYaml,
    comment: &str,
) -> Result<(), ExportError> {
    let text = yaml
        .to_yaml(comment)
        .map_err(|message| ExportError::Encode {
            path: path.to_path_buf(),
            message: message.to_string(),
        })?;
    write_file(path, text.as_bytes())
}

fn write_png<P>(path: &Path, image: ImageBuffer<P, Vec<P::Subpixel>>) -> Result<(), ExportError>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
{
    let mut bytes = Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::Png)
        .map_err(|e| ExportError::Encode {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    write_file(path, bytes.get_ref())
}

fn write_file(path: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    smug_core::output::write_atomic(path, bytes).map_err(|source| ExportError::Write {
        path: path.to_path_buf(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn image_rows_run_top_down() {
        let g = GridGeometry::new([0.0, 0.0], 1.0, [2, 3]).unwrap();
        assert_eq!(image_rows(g, |k| k), [4, 5, 2, 3, 0, 1]);
    }

    #[test]
    fn elevation_encoding_uses_millimetres_when_it_can() {
        let g = GridGeometry::new([0.0, 0.0], 1.0, [3, 1]).unwrap();
        let layer = GridLayer::from_data(g, vec![-1.0, f32::NAN, 2.5]).unwrap();
        let e = ElevationEncoding::for_layer(&layer);
        assert_eq!(
            e,
            ElevationEncoding {
                offset: -1.0,
                scale: 0.001
            }
        );
        assert_eq!(e.encode(&layer), [0, 0, 3500]);
        let tall = GridLayer::from_data(g, vec![0.0, 100.0, 200.0]).unwrap();
        let e = ElevationEncoding::for_layer(&tall);
        assert_eq!(e.encode(&tall)[2], u16::MAX);
    }
}
