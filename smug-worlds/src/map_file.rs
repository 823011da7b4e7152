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

use crate::mission_file::MissionFileError;
use serde::{Deserialize, Deserializer, Serialize};
use smug_core::{BuildContext, Error, GridGeometry, GridLayer, Mission, World};
use std::path::{Path, PathBuf};

/// `map_server`'s default `occupied_thresh`.
pub const DEFAULT_OCCUPIED_THRESH: f64 = 0.65;
/// `map_server`'s default `free_thresh`.
pub const DEFAULT_FREE_THRESH: f64 = 0.196;
/// Default metres per elevation image unit (1 mm).
pub const DEFAULT_ELEVATION_SCALE: f64 = 0.001;
/// The largest image a map may have, in pixels (a unit mistake, not a map, beyond).
pub const MAX_PIXELS: u64 = 100_000_000;
/// Default height given to occupied cells above the ground, metres.
pub const DEFAULT_OBSTACLE_HEIGHT: f64 = 2.0;
/// Default cell size of a rasterised point cloud, metres.
pub const DEFAULT_CELL_SIZE: f64 = 0.1;

/// How pixel values become occupancy (`map_server`'s `mode`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MapMode {
    /// Occupied, free or unknown by the two thresholds.
    #[default]
    Trinary,
    /// Like trinary, but values between the thresholds are free with a graded traversability.
    Scale,
    /// The 8-bit value is an occupancy percentage (0–100); larger values are unknown.
    Raw,
}

/// The keys of a map YAML file (see the [module documentation](self)).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapYaml {
    /// Occupancy image, relative to the YAML file.
    pub image: PathBuf,
    /// Metres per pixel.
    pub resolution: f64,
    /// Lower-left corner `[x, y, yaw]`; yaw must be 0.
    pub origin: [f64; 3],
    /// Occupancy probability above which a pixel is occupied.
    #[serde(default = "default_occupied_thresh")]
    pub occupied_thresh: f64,
    /// Occupancy probability below which a pixel is free.
    #[serde(default = "default_free_thresh")]
    pub free_thresh: f64,
    /// White means occupied instead of free (0/1 or a boolean).
    #[serde(default, deserialize_with = "negate_flag")]
    pub negate: bool,
    /// How pixel values become occupancy.
    #[serde(default)]
    pub mode: MapMode,
    /// Ground height image (16-bit gray PNG), relative to the YAML file.
    #[serde(default)]
    pub elevation_image: Option<PathBuf>,
    /// Metres per elevation image unit.
    #[serde(default = "default_elevation_scale")]
    pub elevation_scale: f64,
    /// Height of elevation sample 0, metres.
    #[serde(default)]
    pub elevation_offset: f64,
    /// The elevation image already holds the obstacles' height (as `smug worlds export`
    /// writes it): occupied cells keep it instead of getting `obstacle_height` added.
    #[serde(default)]
    pub elevation_includes_obstacles: bool,
    /// Traversability image (8-bit gray PNG), relative to the YAML file.
    #[serde(default)]
    pub traversability_image: Option<PathBuf>,
    /// Traversability sample value meaning "no data".
    #[serde(default)]
    pub traversability_nodata: Option<u16>,
    /// Mission file (TOML or JSON), relative to the YAML file.
    #[serde(default)]
    pub mission: Option<PathBuf>,
}

fn default_occupied_thresh() -> f64 {
    DEFAULT_OCCUPIED_THRESH
}

fn default_free_thresh() -> f64 {
    DEFAULT_FREE_THRESH
}

fn default_elevation_scale() -> f64 {
    DEFAULT_ELEVATION_SCALE
}

/// `negate` is an integer 0/1 in ROS files; accept booleans too.
fn negate_flag<'de, D: Deserializer<'de>>(deserializer: D) -> Result<bool, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Flag {
        Bool(bool),
        Int(i64),
    }
    match Flag::deserialize(deserializer)? {
        Flag::Bool(flag) => Ok(flag),
        Flag::Int(0) => Ok(false),
        Flag::Int(1) => Ok(true),
        Flag::Int(other) => Err(serde::de::Error::custom(format!(
            "negate must be 0 or 1, got {other}"
        ))),
    }
}

/// `path` as a YAML scalar, quoted when needed.
fn yaml_path(path: &Path) -> Result<String, String> {
    let text = path
        .to_str()
        .ok_or_else(|| format!("file name {} is not UTF-8", path.display()))?;
    serde_norway::to_string(text)
        .map(|scalar| scalar.trim_end().to_string())
        .map_err(|e| e.to_string())
}

impl MapMode {
    /// The name used in YAML files.
    pub fn name(self) -> &'static str {
        match self {
            MapMode::Trinary => "trinary",
            MapMode::Scale => "scale",
            MapMode::Raw => "raw",
        }
    }
}

impl MapYaml {
    /// A trinary map description with `map_server`'s default thresholds.
    pub fn new(image: impl Into<PathBuf>, resolution: f64, origin: [f64; 2]) -> Self {
        Self {
            image: image.into(),
            resolution,
            origin: [origin[0], origin[1], 0.0],
            occupied_thresh: DEFAULT_OCCUPIED_THRESH,
            free_thresh: DEFAULT_FREE_THRESH,
            negate: false,
            mode: MapMode::Trinary,
            elevation_image: None,
            elevation_scale: DEFAULT_ELEVATION_SCALE,
            elevation_offset: 0.0,
            elevation_includes_obstacles: false,
            traversability_image: None,
            traversability_nodata: None,
            mission: None,
        }
    }

    /// Reads and checks a YAML map description.
    pub fn read(path: &Path) -> Result<Self, MapFileError> {
        let text = std::fs::read_to_string(path).map_err(|source| MapFileError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let yaml: MapYaml = serde_norway::from_str(&text).map_err(|e| MapFileError::Yaml {
            path: path.to_path_buf(),
            message: one_line(&e.to_string()),
        })?;
        yaml.check().map_err(|message| MapFileError::Invalid {
            path: path.to_path_buf(),
            message,
        })?;
        Ok(yaml)
    }

    /// The YAML text of this description, with a comment line on top. Keys that hold
    /// their default and do not matter to `map_server` are left out.
    pub fn to_yaml(&self, comment: &str) -> Result<String, String> {
        let mut lines = vec![
            format!("# {comment}"),
            format!("image: {}", yaml_path(&self.image)?),
            format!("resolution: {:?}", self.resolution),
            format!(
                "origin: [{:?}, {:?}, {:?}]",
                self.origin[0], self.origin[1], self.origin[2]
            ),
            format!("occupied_thresh: {:?}", self.occupied_thresh),
            format!("free_thresh: {:?}", self.free_thresh),
            format!("negate: {}", u8::from(self.negate)),
            format!("mode: {}", self.mode.name()),
        ];
        if let Some(image) = &self.elevation_image {
            lines.push(format!("elevation_image: {}", yaml_path(image)?));
            lines.push(format!("elevation_scale: {:?}", self.elevation_scale));
            lines.push(format!("elevation_offset: {:?}", self.elevation_offset));
        }
        if self.elevation_includes_obstacles {
            lines.push("elevation_includes_obstacles: true".into());
        }
        if let Some(image) = &self.traversability_image {
            lines.push(format!("traversability_image: {}", yaml_path(image)?));
        }
        if let Some(nodata) = self.traversability_nodata {
            lines.push(format!("traversability_nodata: {nodata}"));
        }
        if let Some(mission) = &self.mission {
            lines.push(format!("mission: {}", yaml_path(mission)?));
        }
        Ok(lines.join("\n") + "\n")
    }

    /// The first value out of its domain, described.
    pub fn check(&self) -> Result<(), String> {
        if !(self.resolution.is_finite() && self.resolution > 0.0) {
            return Err(format!(
                "`resolution` must be a finite number > 0, got {}",
                self.resolution
            ));
        }
        let [x, y, yaw] = self.origin;
        if !(x.is_finite() && y.is_finite() && yaw.is_finite()) {
            return Err(format!("`origin` must be finite, got {:?}", self.origin));
        }
        if yaw != 0.0 {
            return Err(format!(
                "`origin` yaw must be 0 (rotated maps are not supported), got {yaw}"
            ));
        }
        let in_unit = |v: f64| (0.0..=1.0).contains(&v);
        if !(in_unit(self.free_thresh)
            && in_unit(self.occupied_thresh)
            && self.free_thresh <= self.occupied_thresh)
        {
            return Err(format!(
                "thresholds need 0 ≤ free_thresh ≤ occupied_thresh ≤ 1, got free_thresh {} and \
                 occupied_thresh {}",
                self.free_thresh, self.occupied_thresh
            ));
        }
        if !(self.elevation_scale.is_finite() && self.elevation_scale != 0.0) {
            return Err(format!(
                "`elevation_scale` must be finite and non-zero, got {}",
                self.elevation_scale
            ));
        }
        if !self.elevation_offset.is_finite() {
            return Err(format!(
                "`elevation_offset` must be finite, got {}",
                self.elevation_offset
            ));
        }
        Ok(())
    }
}

/// Why a map could not be imported. Every message names the file at fault.
#[derive(Debug, thiserror::Error)]
pub enum MapFileError {
    /// The YAML file could not be read.
    #[error("{}: cannot read map: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The YAML file is malformed or has unknown keys.
    #[error("{}: invalid map YAML: {message}", path.display())]
    Yaml {
        /// The file.
        path: PathBuf,
        /// The parser's message (with line and column).
        message: String,
    },
    /// A value is out of its domain.
    #[error("{}: {message}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// An image is missing, unreadable, or of an unusable kind.
    #[error("{}: {what} `{}`: {message}", yaml.display(), image.display())]
    Image {
        /// The YAML file naming the image.
        yaml: PathBuf,
        /// Which image (`image`, `elevation_image`, …).
        what: &'static str,
        /// The image file.
        image: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// Two images differ in size.
    #[error(
        "{}: image sizes differ: `{}` is {}×{} pixels but `{}` is {}×{}",
        yaml.display(), first.display(), first_size[0], first_size[1],
        other.display(), other_size[0], other_size[1]
    )]
    SizeMismatch {
        /// The YAML file.
        yaml: PathBuf,
        /// The occupancy image.
        first: PathBuf,
        /// Its width and height.
        first_size: [u32; 2],
        /// The other image.
        other: PathBuf,
        /// Its width and height.
        other_size: [u32; 2],
    },
    /// A pose of the mission lies outside the map.
    #[error(
        "{}: {what} lies outside the map (bounds [{}, {}] to [{}, {}])",
        path.display(), min[0], min[1], max[0], max[1]
    )]
    OutsideMap {
        /// The map's YAML file.
        path: PathBuf,
        /// The culprit, e.g. "PoI 3 of target `stone-2`".
        what: String,
        /// Lower-left corner of the map.
        min: [f64; 2],
        /// Upper-right corner of the map.
        max: [f64; 2],
    },
    /// The mission file could not be loaded.
    #[error(transparent)]
    Mission(#[from] MissionFileError),
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The layers read from a map file.
#[derive(Clone, Debug, PartialEq)]
pub struct MapLayers {
    /// Terrain height, NaN where unknown.
    pub elevation: GridLayer,
    /// Traversability, when the map provides one.
    pub traversability: Option<GridLayer>,
    /// The mission file the YAML names (resolved), if any.
    pub mission_file: Option<PathBuf>,
}

impl MapLayers {
    /// Layers of an elevation alone (a DEM or a rasterised point cloud).
    pub fn from_elevation(elevation: GridLayer) -> Self {
        Self {
            elevation,
            traversability: None,
            mission_file: None,
        }
    }

    /// A world of these layers and `mission`; errors when a pose lies outside the map.
    /// `yaml` names the map in errors.
    pub fn into_world(
        self,
        name: impl Into<String>,
        mission: Mission,
        yaml: &Path,
    ) -> Result<World, MapFileError> {
        check_mission_inside(&mission, &self.elevation.geometry, yaml)?;
        let mut world = World::new(name, self.elevation, mission);
        world.traversability = self.traversability;
        Ok(world)
    }
}

/// Checks that the start, the end and every PoI of `mission` lie inside `geometry`;
/// the error names the culprit and `file`.
pub fn check_mission_inside(
    mission: &Mission,
    geometry: &GridGeometry,
    file: &Path,
) -> Result<(), MapFileError> {
    let bounds = geometry.bounds();
    let culprit = mission.first_pose_outside(&bounds);
    match culprit {
        Some(what) => Err(MapFileError::OutsideMap {
            path: file.to_path_buf(),
            what,
            min: bounds.min,
            max: bounds.max,
        }),
        None => Ok(()),
    }
}

/// A decoded single-channel image: raw samples (top row first), their maximum value
/// (255 or 65535) and an opacity mask when the image has an alpha channel.
struct GrayImage {
    width: u32,
    height: u32,
    samples: Vec<u16>,
    max: u16,
    transparent: Option<Vec<bool>>,
}

impl GrayImage {
    fn size(&self) -> [u32; 2] {
        [self.width, self.height]
    }

    fn is_transparent(&self, k: usize) -> bool {
        self.transparent.as_ref().is_some_and(|t| t[k])
    }

    /// Sample `k` normalised to `[0, 1]`.
    fn normalised(&self, k: usize) -> f64 {
        f64::from(self.samples[k]) / f64::from(self.max)
    }
}

/// Whether colour images are converted to luma or rejected.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Colour {
    ToLuma,
    Reject,
}

fn decode_gray(path: &Path, colour: Colour) -> Result<GrayImage, String> {
    let reader = image::ImageReader::open(path)
        .map_err(|e| format!("cannot read: {e}"))?
        .with_guessed_format()
        .map_err(|e| format!("cannot read: {e}"))?;
    if reader.format().is_none() {
        return Err("unknown image format (PGM or PNG expected)".into());
    }
    let decoded = reader.decode().map_err(|e| format!("cannot decode: {e}"))?;
    let (width, height) = (decoded.width(), decoded.height());
    if width == 0 || height == 0 {
        return Err("the image is empty".into());
    }
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(format!(
            "{width}×{height} pixels is more than the {MAX_PIXELS} a map may have"
        ));
    }
    use image::DynamicImage as D;
    let is_colour = !matches!(
        decoded,
        D::ImageLuma8(_) | D::ImageLumaA8(_) | D::ImageLuma16(_) | D::ImageLumaA16(_)
    );
    if is_colour && colour == Colour::Reject {
        return Err(format!(
            "must be a grayscale image, got {:?} pixels",
            decoded.color()
        ));
    }
    let has_alpha = decoded.color().has_alpha();
    let (samples, max, alpha): (Vec<u16>, u16, Vec<bool>) = match decoded {
        D::ImageLuma8(_) | D::ImageLumaA8(_) | D::ImageRgb8(_) | D::ImageRgba8(_) => {
            let la = decoded.to_luma_alpha8();
            let samples = la.pixels().map(|p| u16::from(p.0[0])).collect();
            let alpha = la.pixels().map(|p| p.0[1] == 0).collect();
            (samples, u8::MAX.into(), alpha)
        }
        _ => {
            let la = decoded.to_luma_alpha16();
            let samples = la.pixels().map(|p| p.0[0]).collect();
            let alpha = la.pixels().map(|p| p.0[1] == 0).collect();
            (samples, u16::MAX, alpha)
        }
    };
    Ok(GrayImage {
        width,
        height,
        samples,
        max,
        transparent: has_alpha.then_some(alpha),
    })
}

/// What a pixel of the occupancy image says about its cell.
#[derive(Clone, Copy, Debug, PartialEq)]
enum CellClass {
    Free,
    Occupied,
    Unknown,
    /// `scale` mode, between the thresholds: free, with this traversability.
    Partial(f64),
}

fn classify(yaml: &MapYaml, image: &GrayImage, k: usize) -> CellClass {
    if image.is_transparent(k) {
        return CellClass::Unknown;
    }
    let value = image.normalised(k);
    let value = if yaml.negate { 1.0 - value } else { value };
    let p = match yaml.mode {
        MapMode::Raw => {
            let percent = (value * 255.0).round();
            if percent > 100.0 {
                return CellClass::Unknown;
            }
            percent / 100.0
        }
        MapMode::Trinary | MapMode::Scale => 1.0 - value,
    };
    if p > yaml.occupied_thresh {
        CellClass::Occupied
    } else if p < yaml.free_thresh {
        CellClass::Free
    } else if yaml.mode == MapMode::Scale {
        let span = yaml.occupied_thresh - yaml.free_thresh;
        let q = if span > 0.0 {
            (p - yaml.free_thresh) / span
        } else {
            1.0
        };
        CellClass::Partial((1.0 - q).clamp(0.0, 1.0))
    } else {
        CellClass::Unknown
    }
}

/// Reads the map described by `yaml_path`: occupancy, and the elevation and
/// traversability images when given. Occupied cells rise `obstacle_height` metres above
/// the ground.
pub fn load_map(yaml_path: &Path, obstacle_height: f64) -> Result<MapLayers, MapFileError> {
    if !(obstacle_height.is_finite() && obstacle_height >= 0.0) {
        return Err(MapFileError::Invalid {
            path: yaml_path.to_path_buf(),
            message: format!("obstacle_height must be finite and ≥ 0, got {obstacle_height}"),
        });
    }
    let yaml = MapYaml::read(yaml_path)?;
    let base = yaml_path.parent().unwrap_or(Path::new(""));
    let occupancy_path = base.join(&yaml.image);
    let occupancy = open_image(yaml_path, "image", &occupancy_path, Colour::ToLuma)?;
    let elevation_image =
        optional_image(yaml_path, base, "elevation_image", &yaml.elevation_image)?;
    let traversability_image = optional_image(
        yaml_path,
        base,
        "traversability_image",
        &yaml.traversability_image,
    )?;
    for (path, image) in [&elevation_image, &traversability_image]
        .into_iter()
        .flatten()
    {
        if image.size() != occupancy.size() {
            return Err(MapFileError::SizeMismatch {
                yaml: yaml_path.to_path_buf(),
                first: occupancy_path.clone(),
                first_size: occupancy.size(),
                other: path.clone(),
                other_size: image.size(),
            });
        }
    }
    let geometry = GridGeometry::new(
        [yaml.origin[0], yaml.origin[1]],
        yaml.resolution,
        [occupancy.width as usize, occupancy.height as usize],
    )
    .map_err(|message| MapFileError::Invalid {
        path: yaml_path.to_path_buf(),
        message,
    })?;
    let class = |k: usize| classify(&yaml, &occupancy, k);
    let ground = |k: usize| match &elevation_image {
        Some((_, image)) if image.is_transparent(k) => f64::NAN,
        Some((_, image)) => {
            yaml.elevation_offset + yaml.elevation_scale * f64::from(image.samples[k])
        }
        None => 0.0,
    };
    let elevation = layer_from_image_rows(geometry, |k| match class(k) {
        CellClass::Unknown => f32::NAN,
        CellClass::Free | CellClass::Partial(_) => ground(k) as f32,
        CellClass::Occupied if yaml.elevation_includes_obstacles => ground(k) as f32,
        CellClass::Occupied => (ground(k) + obstacle_height) as f32,
    });
    let traversability = match &traversability_image {
        Some((_, image)) => Some(layer_from_image_rows(geometry, |k| {
            traversability_sample(image, yaml.traversability_nodata, k)
        })),
        None if yaml.mode == MapMode::Scale => {
            Some(layer_from_image_rows(geometry, |k| match class(k) {
                CellClass::Free => 1.0,
                CellClass::Occupied => 0.0,
                CellClass::Unknown => f32::NAN,
                CellClass::Partial(t) => t as f32,
            }))
        }
        None => None,
    };
    Ok(MapLayers {
        elevation,
        traversability,
        mission_file: yaml.mission.as_ref().map(|m| base.join(m)),
    })
}

fn traversability_sample(image: &GrayImage, nodata: Option<u16>, k: usize) -> f32 {
    if image.is_transparent(k) || nodata == Some(image.samples[k]) {
        f32::NAN
    } else {
        image.normalised(k) as f32
    }
}

fn open_image(
    yaml: &Path,
    what: &'static str,
    path: &Path,
    colour: Colour,
) -> Result<GrayImage, MapFileError> {
    decode_gray(path, colour).map_err(|message| MapFileError::Image {
        yaml: yaml.to_path_buf(),
        what,
        image: path.to_path_buf(),
        message,
    })
}

fn optional_image(
    yaml: &Path,
    base: &Path,
    what: &'static str,
    relative: &Option<PathBuf>,
) -> Result<Option<(PathBuf, GrayImage)>, MapFileError> {
    relative
        .as_ref()
        .map(|relative| {
            let path = base.join(relative);
            open_image(yaml, what, &path, Colour::Reject).map(|image| (path, image))
        })
        .transpose()
}

/// A layer whose cell `(i, j)` takes `value(k)` of image pixel `k` in column `i`, row
/// `ny − 1 − j` (image rows run top-down, grid rows bottom-up).
fn layer_from_image_rows(geometry: GridGeometry, value: impl Fn(usize) -> f32) -> GridLayer {
    let [nx, ny] = geometry.size;
    GridLayer::from_fn(geometry, |i, j| value((ny - 1 - j) * nx + i))
}

/// Parameters of the `map` world plugin.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MapParams {
    /// The map's YAML file (relative to the config file).
    pub yaml: PathBuf,
    /// The mission from a TOML or JSON file (relative to the config file).
    pub mission_file: Option<PathBuf>,
    /// The mission, inline.
    pub mission: Option<Mission>,
    /// Height of occupied cells above the ground, metres.
    pub obstacle_height: f64,
    /// Name in reports (default: the YAML file's stem).
    pub name: Option<String>,
    /// A GeoTIFF DEM instead of `yaml` (relative to the config file): heights,
    /// resolution and origin come from the file.
    pub dem: Option<PathBuf>,
    /// A point cloud (PLY or PCD) instead of `yaml` (relative to the config file),
    /// rasterised into cells of `cell_size`.
    pub point_cloud: Option<PathBuf>,
    /// Cell size of a rasterised point cloud, metres.
    pub cell_size: f64,
    /// How a cell's points make its height: `max` (default) or `mean`.
    pub reduce: crate::point_cloud::Reduce,
}

impl Default for MapParams {
    fn default() -> Self {
        Self {
            yaml: PathBuf::new(),
            mission_file: None,
            mission: None,
            obstacle_height: DEFAULT_OBSTACLE_HEIGHT,
            name: None,
            dem: None,
            point_cloud: None,
            cell_size: DEFAULT_CELL_SIZE,
            reduce: crate::point_cloud::Reduce::default(),
        }
    }
}

/// The mission of a `map` world: inline, from `mission_file`, or from the YAML's
/// `mission` key, in that order of preference (inline and file together are an error).
fn map_mission(
    params: &MapParams,
    layers: &MapLayers,
    yaml: &Path,
    ctx: &BuildContext,
) -> Result<Mission, Error> {
    let from_file = |path: &Path| crate::load_mission(path).map_err(|e| Error::stage("world", e));
    match (&params.mission, &params.mission_file, &layers.mission_file) {
        (Some(_), Some(_), _) => Err(Error::invalid_param(
            "world",
            "give either `mission` or `mission_file`, not both",
        )),
        (Some(mission), None, _) => Ok(mission.clone()),
        (None, Some(path), _) => from_file(&ctx.resolve_path(path)),
        (None, None, Some(path)) => from_file(path),
        (None, None, None) => Err(Error::invalid_param(
            "world",
            format!(
                "needs a `mission` table or a `mission_file` (or a `mission` key in {})",
                yaml.display()
            ),
        )),
    }
}

/// Builds the `map` world described by `params`.
fn build_map_world(params: &MapParams, ctx: &BuildContext) -> Result<World, Error> {
    let given = [
        !params.yaml.as_os_str().is_empty(),
        params.dem.is_some(),
        params.point_cloud.is_some(),
    ];
    match given.iter().filter(|g| **g).count() {
        0 => {
            return Err(Error::invalid_param(
                "world",
                "`yaml` is required: the map's YAML file (or `dem`, a GeoTIFF, or \
                 `point_cloud`, a PLY or PCD file)",
            ))
        }
        1 => {}
        _ => {
            return Err(Error::invalid_param(
                "world",
                "give one of `yaml`, `dem` and `point_cloud`",
            ))
        }
    }
    let terrain = params.dem.as_ref().or(params.point_cloud.as_ref());
    let (yaml, layers) = if let Some(file) = terrain {
        let path = ctx.resolve_path(file);
        let kind = match params.dem {
            Some(_) => TerrainKind::Dem,
            None => TerrainKind::PointCloud,
        };
        let layers = load_terrain(&path, kind, params.cell_size, params.reduce)
            .map_err(|e| Error::stage("world", e))?;
        (path, layers)
    } else {
        let yaml = ctx.resolve_path(&params.yaml);
        let layers =
            load_map(&yaml, params.obstacle_height).map_err(|e| Error::stage("world", e))?;
        (yaml, layers)
    };
    let mission = map_mission(params, &layers, &yaml, ctx)?;
    let name = params.name.clone().unwrap_or_else(|| file_stem(&yaml));
    layers
        .into_world(name, mission, &yaml)
        .map_err(|e| Error::stage("world", e))
}

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
/// `cell_size` with `reduce` (see [`crate::geotiff`] and [`crate::point_cloud`]).
pub fn load_terrain(
    path: &Path,
    kind: TerrainKind,
    cell_size: f64,
    reduce: crate::point_cloud::Reduce,
) -> Result<MapLayers, TerrainError> {
    let elevation = match kind {
        TerrainKind::Dem => crate::geotiff::read_geotiff(path)?.elevation,
        TerrainKind::PointCloud => {
            let points = crate::point_cloud::read_point_cloud(path)?;
            crate::point_cloud::rasterise(&points, cell_size, reduce, path)?
        }
    };
    Ok(MapLayers::from_elevation(elevation))
}

/// The file name of `path` without its extension (`map` when there is none).
pub fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "map".into())
}

smug_core::register_plugin!(
    smug_core::registry::WorldStage,
    name = "map",
    summary = "ROS map_server-style YAML + PGM/PNG occupancy (elevation, traversability images), a GeoTIFF DEM or a PLY/PCD point cloud",
    params = MapParams,
    build = |params, ctx| Ok(Box::new(build_map_world(&params, ctx)?)),
);

#[cfg(test)]
mod tests {
    use super::*;

    fn yaml(text: &str) -> Result<MapYaml, String> {
        let parsed: MapYaml = serde_norway::from_str(text).map_err(|e| e.to_string())?;
        parsed.check()?;
        Ok(parsed)
    }

    #[test]
    fn reads_ros_keys_with_defaults() {
        let y =
            yaml("image: a.pgm\nresolution: 0.05\norigin: [1.0, -2.0, 0.0]\nnegate: 1\n").unwrap();
        assert!(y.negate);
        assert_eq!(y.mode, MapMode::Trinary);
        assert_eq!(y.occupied_thresh, DEFAULT_OCCUPIED_THRESH);
        let y =
            yaml("image: a.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: false\nmode: scale\n")
                .unwrap();
        assert!(!y.negate);
        assert_eq!(y.mode, MapMode::Scale);
    }

    #[test]
    fn rejects_bad_values() {
        let base = "image: a.pgm\norigin: [0, 0, 0]\n";
        for (extra, needle) in [
            ("resolution: -1\n", "resolution"),
            ("resolution: .nan\n", "resolution"),
            ("resolution: 0\n", "resolution"),
            ("resolution: 1\norigin_typo: 1\n", "unknown field"),
            ("resolution: 1\nnegate: 2\n", "negate"),
            ("resolution: 1\nfree_thresh: 0.9\n", "free_thresh"),
        ] {
            let err = yaml(&format!("{base}{extra}")).unwrap_err();
            assert!(err.contains(needle), "{extra}: {err}");
        }
        let err = yaml("image: a.pgm\nresolution: 1\norigin: [0, 0, 0.5]\n").unwrap_err();
        assert!(err.contains("yaw must be 0"), "{err}");
    }

    #[test]
    fn written_yaml_reads_back() {
        let mut y = MapYaml::new("odd: name #1.pgm", 0.05, [-1.5, 1e-7]);
        y.negate = true;
        y.mode = MapMode::Scale;
        y.elevation_image = Some("e.png".into());
        y.elevation_offset = -0.1;
        y.elevation_includes_obstacles = true;
        y.traversability_image = Some("t.png".into());
        y.traversability_nodata = Some(7);
        y.mission = Some("m.toml".into());
        let text = y.to_yaml("a comment").unwrap();
        assert!(text.starts_with("# a comment\n"), "{text}");
        assert!(text.contains("origin: [-1.5, 1e-7, 0.0]\n"), "{text}");
        assert_eq!(yaml(&text).unwrap(), y);
        let plain = MapYaml::new("a.pgm", 1.0, [0.0, 0.0]);
        assert!(!plain.to_yaml("c").unwrap().contains("elevation"));
    }

    #[test]
    fn classification_follows_map_server() {
        let image = GrayImage {
            width: 4,
            height: 1,
            samples: vec![0, 254, 205, 128],
            max: 255,
            transparent: None,
        };
        let mut y = MapYaml::new("a.pgm", 1.0, [0.0, 0.0]);
        let classes: Vec<_> = (0..4).map(|k| classify(&y, &image, k)).collect();
        use CellClass::*;
        assert_eq!(classes, [Occupied, Free, Unknown, Unknown]);
        y.negate = true;
        assert_eq!(classify(&y, &image, 0), Free);
        assert_eq!(classify(&y, &image, 1), Occupied);
        y.negate = false;
        y.mode = MapMode::Scale;
        assert!(matches!(classify(&y, &image, 3), Partial(t) if t > 0.0 && t < 1.0));
        y.mode = MapMode::Raw;
        assert_eq!(classify(&y, &image, 0), Free); // 0 % occupied
        assert_eq!(classify(&y, &image, 1), Unknown); // > 100
    }
}
