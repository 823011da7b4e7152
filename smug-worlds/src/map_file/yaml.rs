//! The map YAML schema (`map_server`'s keys and SMUG's extensions), its defaults,
//! checks and writer.

use super::error::MapFileError;
use serde::{Deserialize, Deserializer};
use std::path::{Path, PathBuf};

/// `map_server`'s default `occupied_thresh`.
pub const DEFAULT_OCCUPIED_THRESH: f64 = 0.65;
/// `map_server`'s default `free_thresh`.
pub const DEFAULT_FREE_THRESH: f64 = 0.196;
/// Default metres per elevation image unit (1 mm).
pub const DEFAULT_ELEVATION_SCALE: f64 = 0.001;
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

/// The keys of a map YAML file (see the module documentation).
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

/// Why a map description cannot be written or is out of its domain.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MapYamlError {
    /// A file name is not UTF-8 (YAML holds text).
    #[error("file name {0} is not UTF-8")]
    NotUtf8(String),
    /// The YAML writer failed.
    #[error("{0}")]
    Write(String),
    /// The resolution is not finite and > 0.
    #[error("`resolution` must be a finite number > 0, got {0}")]
    Resolution(f64),
    /// The origin is not finite.
    #[error("`origin` must be finite, got {0:?}")]
    Origin([f64; 3]),
    /// The origin is rotated.
    #[error("`origin` yaw must be 0 (rotated maps are not supported), got {0}")]
    Rotated(f64),
    /// The thresholds are out of order or out of `[0, 1]`.
    #[error(
        "thresholds need 0 ≤ free_thresh ≤ occupied_thresh ≤ 1, got free_thresh {free} and \
         occupied_thresh {occupied}"
    )]
    Thresholds {
        /// `free_thresh`.
        free: f64,
        /// `occupied_thresh`.
        occupied: f64,
    },
    /// The elevation scale is zero or not finite.
    #[error("`elevation_scale` must be finite and non-zero, got {0}")]
    ElevationScale(f64),
    /// The elevation offset is not finite.
    #[error("`elevation_offset` must be finite, got {0}")]
    ElevationOffset(f64),
}

/// `path` as a YAML scalar, quoted when needed.
fn yaml_path(path: &Path) -> Result<String, MapYamlError> {
    let text = path
        .to_str()
        .ok_or_else(|| MapYamlError::NotUtf8(path.display().to_string()))?;
    serde_norway::to_string(text)
        .map(|scalar| scalar.trim_end().to_string())
        .map_err(|e| MapYamlError::Write(e.to_string()))
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
        yaml.check().map_err(|e| MapFileError::Invalid {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        Ok(yaml)
    }

    /// The YAML text of this description, with a comment line on top. Keys that hold
    /// their default and do not matter to `map_server` are left out.
    pub fn to_yaml(&self, comment: &str) -> Result<String, MapYamlError> {
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
    pub fn check(&self) -> Result<(), MapYamlError> {
        if !(self.resolution.is_finite() && self.resolution > 0.0) {
            return Err(MapYamlError::Resolution(self.resolution));
        }
        let [x, y, yaw] = self.origin;
        if !(x.is_finite() && y.is_finite() && yaw.is_finite()) {
            return Err(MapYamlError::Origin(self.origin));
        }
        if yaw != 0.0 {
            return Err(MapYamlError::Rotated(yaw));
        }
        let in_unit = |v: f64| (0.0..=1.0).contains(&v);
        if !(in_unit(self.free_thresh)
            && in_unit(self.occupied_thresh)
            && self.free_thresh <= self.occupied_thresh)
        {
            return Err(MapYamlError::Thresholds {
                free: self.free_thresh,
                occupied: self.occupied_thresh,
            });
        }
        if !(self.elevation_scale.is_finite() && self.elevation_scale != 0.0) {
            return Err(MapYamlError::ElevationScale(self.elevation_scale));
        }
        if !self.elevation_offset.is_finite() {
            return Err(MapYamlError::ElevationOffset(self.elevation_offset));
        }
        Ok(())
    }
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The map YAML `text`, or the reason it is refused: a parser's or a check's error.
    fn yaml(text: &str) -> Result<MapYaml, YamlTextError> {
        let parsed: MapYaml = serde_norway::from_str(text)?;
        parsed.check()?;
        Ok(parsed)
    }

    /// Why a map YAML text is refused.
    #[derive(Debug, thiserror::Error)]
    enum YamlTextError {
        #[error(transparent)]
        Parse(#[from] serde_norway::Error),
        #[error(transparent)]
        Check(#[from] MapYamlError),
    }

    impl YamlTextError {
        fn contains(&self, needle: &str) -> bool {
            self.to_string().contains(needle)
        }
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
}
