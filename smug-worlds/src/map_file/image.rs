//! Decoding the map's images (PGM/PNG, 8/16-bit, gray or colour) and reading their
//! pixels as occupancy classes and layers.

use super::error::MapFileError;
use super::yaml::{MapMode, MapYaml};
use crate::limits::MAX_PIXELS;
use smug_core::{GridGeometry, GridLayer};
use std::path::{Path, PathBuf};

/// A decoded single-channel image: raw samples (top row first), their maximum value
/// (255 or 65535) and an opacity mask when the image has an alpha channel.
pub(super) struct GrayImage {
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) samples: Vec<u16>,
    pub(super) max: u16,
    pub(super) transparent: Option<Vec<bool>>,
}

impl GrayImage {
    pub(super) fn size(&self) -> [u32; 2] {
        [self.width, self.height]
    }

    pub(super) fn is_transparent(&self, k: usize) -> bool {
        self.transparent.as_ref().is_some_and(|t| t[k])
    }

    /// Sample `k` normalised to `[0, 1]`.
    pub(super) fn normalised(&self, k: usize) -> f64 {
        f64::from(self.samples[k]) / f64::from(self.max)
    }
}

/// Whether colour images are converted to luma or rejected.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Colour {
    ToLuma,
    Reject,
}

/// Decodes the image `what` at `path` named by the map file `yaml`.
fn decode_gray(
    yaml: &Path,
    what: &'static str,
    path: &Path,
    colour: Colour,
) -> Result<GrayImage, MapFileError> {
    let fail = |message: String| MapFileError::Image {
        yaml: yaml.to_path_buf(),
        what,
        image: path.to_path_buf(),
        message,
    };
    let reader = image::ImageReader::open(path)
        .map_err(|e| fail(format!("cannot read: {e}")))?
        .with_guessed_format()
        .map_err(|e| fail(format!("cannot read: {e}")))?;
    if reader.format().is_none() {
        return Err(fail("unknown image format (PGM or PNG expected)".into()));
    }
    let decoded = reader
        .decode()
        .map_err(|e| fail(format!("cannot decode: {e}")))?;
    let (width, height) = (decoded.width(), decoded.height());
    if width == 0 || height == 0 {
        return Err(fail("the image is empty".into()));
    }
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(fail(format!(
            "{width}×{height} pixels is more than the {MAX_PIXELS} a map may have"
        )));
    }
    use image::DynamicImage as D;
    let is_colour = !matches!(
        decoded,
        D::ImageLuma8(_) | D::ImageLumaA8(_) | D::ImageLuma16(_) | D::ImageLumaA16(_)
    );
    if is_colour && colour == Colour::Reject {
        return Err(fail(format!(
            "must be a grayscale image, got {:?} pixels",
            decoded.color()
        )));
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
pub(super) enum CellClass {
    Free,
    Occupied,
    Unknown,
    /// `scale` mode, between the thresholds: free, with this traversability.
    Partial(f64),
}

pub(super) fn classify(yaml: &MapYaml, image: &GrayImage, k: usize) -> CellClass {
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

pub(super) fn traversability_sample(image: &GrayImage, nodata: Option<u16>, k: usize) -> f32 {
    if image.is_transparent(k) || nodata == Some(image.samples[k]) {
        f32::NAN
    } else {
        image.normalised(k) as f32
    }
}

pub(super) fn open_image(
    yaml: &Path,
    what: &'static str,
    path: &Path,
    colour: Colour,
) -> Result<GrayImage, MapFileError> {
    decode_gray(yaml, what, path, colour)
}

pub(super) fn optional_image(
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
pub(super) fn layer_from_image_rows(
    geometry: GridGeometry,
    value: impl Fn(usize) -> f32,
) -> GridLayer {
    let [nx, ny] = geometry.size;
    GridLayer::from_fn(geometry, |i, j| value((ny - 1 - j) * nx + i))
}

#[cfg(test)]
mod tests {
    use super::*;

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
