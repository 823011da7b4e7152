//! Why a map could not be imported.

use crate::mission_file::MissionFileError;
use std::path::PathBuf;

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
