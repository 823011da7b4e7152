//! GeoTIFF digital elevation models (DEMs) as elevation layers.
//!
//! Reads the first image of a single-band GeoTIFF whose samples are heights in metres:
//! float32, float64 or integer samples (int16 is common for DEMs), strips or tiles,
//! uncompressed, LZW or Deflate (the `tiff` crate). The georeferencing must be north-up:
//!
//! - `ModelPixelScale` `(sx, sy, _)` with one `ModelTiepoint` `(i, j, _, X, Y, _)`: raster
//!   point `(i, j)` lies at `(X, Y)`, column `c` at `X + (c − i)·sx`, row `r` at
//!   `Y − (r − j)·sy`; or
//! - `ModelTransformation` (a 4 × 4 matrix) without rotation terms and with a negative
//!   y scale.
//!
//! Cells must be square (`sx = sy`, within 1e-9 relative), and the model projected
//! (metres): a DEM in geographic coordinates (`GTModelTypeGeoKey` = 2, degrees) is
//! refused with a hint to reproject it. The raster type
//! (`GTRasterTypeGeoKey`) decides what a raster point is: `PixelIsArea` (default) puts
//! raster point `(0, 0)` at the upper-left corner of the upper-left pixel, `PixelIsPoint`
//! at its centre (as GDAL reads it, half a pixel in from the corner). The `GDAL_NODATA`
//! tag's value becomes NaN. The grid's origin is the lower-left corner of the lower-left
//! pixel, and raster row 0 (north) is the grid's top row.

use smug_core::{GridGeometry, GridLayer, MemoryLimit};
use std::path::{Path, PathBuf};
use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::Tag;

/// The largest DEM read, in pixels (as for map images).
pub const MAX_PIXELS: u64 = crate::limits::MAX_PIXELS;

/// Why a GeoTIFF could not be read; every message names the file.
#[derive(Debug, thiserror::Error)]
#[error("{}: {message}", path.display())]
pub struct GeoTiffError {
    /// The file.
    pub path: PathBuf,
    /// What is wrong.
    pub message: String,
}

/// An error about the GeoTIFF at `path`.
fn fail_at(path: &Path) -> impl Fn(String) -> GeoTiffError + '_ {
    move |message| GeoTiffError {
        path: path.to_path_buf(),
        message,
    }
}

/// How a raster point relates to its pixel (`GTRasterTypeGeoKey`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RasterType {
    /// A raster point is a pixel's upper-left corner (the default).
    PixelIsArea,
    /// A raster point is a pixel's centre.
    PixelIsPoint,
}

/// A DEM read from a GeoTIFF.
#[derive(Clone, Debug, PartialEq)]
pub struct Dem {
    /// Heights in metres, NaN where the file has no data.
    pub elevation: GridLayer,
    /// The file's raster type.
    pub raster_type: RasterType,
    /// The `GDAL_NODATA` value, if any.
    pub nodata: Option<f64>,
}

const GT_RASTER_TYPE_GEO_KEY: u16 = 1025;
const GT_MODEL_TYPE_GEO_KEY: u16 = 1024;

/// Reads the GeoTIFF DEM at `path` (see the [module documentation](self)).
pub fn read_geotiff(path: &Path) -> Result<Dem, GeoTiffError> {
    read_geotiff_within(path, MemoryLimit::default())
}

/// [`read_geotiff`] into a grid that must fit `memory` (a run's limit).
pub fn read_geotiff_within(path: &Path, memory: MemoryLimit) -> Result<Dem, GeoTiffError> {
    let fail = |message: String| GeoTiffError {
        path: path.to_path_buf(),
        message,
    };
    let bytes = std::fs::read(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    let mut decoder = Decoder::new(std::io::Cursor::new(&bytes[..]))
        .map_err(|e| fail(format!("not a readable TIFF: {e}")))?;
    let (width, height) = decoder
        .dimensions()
        .map_err(|e| fail(format!("not a readable TIFF: {e}")))?;
    if width == 0 || height == 0 {
        return Err(fail(format!(
            "the image is empty ({width}×{height} pixels)"
        )));
    }
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(fail(format!(
            "{width}×{height} pixels is more than the {MAX_PIXELS} SMUG reads"
        )));
    }
    let samples: u16 = decoder
        .find_tag_unsigned(Tag::SamplesPerPixel)
        .map_err(|e| fail(format!("bad SamplesPerPixel tag: {e}")))?
        .unwrap_or(1);
    if samples != 1 {
        return Err(fail(format!(
            "has {samples} samples per pixel; a DEM has one band (heights)"
        )));
    }
    let raster_type = raster_type(&mut decoder, path)?;
    let (corner, scale) = georeference(&mut decoder, raster_type, path)?;
    let nodata = match decoder.find_tag(Tag::GdalNodata) {
        Ok(Some(value)) => {
            let text = value
                .into_string()
                .map_err(|e| fail(format!("bad GDAL_NODATA tag: {e}")))?;
            let text = text.trim_matches(char::from(0)).trim();
            Some(
                text.parse::<f64>()
                    .map_err(|_| fail(format!("GDAL_NODATA `{text}` is not a number")))?,
            )
        }
        Ok(None) => None,
        Err(e) => return Err(fail(format!("bad GDAL_NODATA tag: {e}"))),
    };
    let image = match read_lzw(&mut decoder, &bytes, [width, height], path)? {
        Some(image) => image,
        None => {
            let mut limits = Limits::default();
            limits.decoding_buffer_size = (MAX_PIXELS * 8) as usize;
            limits.intermediate_buffer_size = (MAX_PIXELS * 8) as usize;
            let mut decoder = decoder.with_limits(limits);
            decoder
                .read_image()
                .map_err(|e| fail(format!("cannot decode the image: {e}")))?
        }
    };
    let values = heights(image, nodata, path)?;
    let expected = width as usize * height as usize;
    if values.len() != expected {
        return Err(fail(format!(
            "decoded {} samples for {width}×{height} pixels",
            values.len()
        )));
    }
    let origin = [corner[0], corner[1] - f64::from(height) * scale];
    let geometry =
        GridGeometry::new_within(origin, scale, [width as usize, height as usize], memory)
            .map_err(|m| fail(format!("bad georeferencing: {m}")))?;
    let (nx, ny) = (width as usize, height as usize);
    let elevation = GridLayer::from_fn(geometry, |i, j| values[(ny - 1 - j) * nx + i]);
    Ok(Dem {
        elevation,
        raster_type,
        nodata,
    })
}

const COMPRESSION_LZW: u16 = 5;

fn u64_tags<R: std::io::Read + std::io::Seek>(
    decoder: &mut Decoder<R>,
    tag: Tag,
    path: &Path,
) -> Result<Option<Vec<u64>>, GeoTiffError> {
    match decoder.find_tag(tag) {
        Ok(Some(value)) => value
            .into_u64_vec()
            .map(Some)
            .map_err(|e| fail_at(path)(format!("bad {tag:?} tag: {e}"))),
        Ok(None) => Ok(None),
        Err(e) => Err(fail_at(path)(format!("bad {tag:?} tag: {e}"))),
    }
}

fn u16_tag<R: std::io::Read + std::io::Seek>(
    decoder: &mut Decoder<R>,
    tag: Tag,
    default: u16,
    path: &Path,
) -> Result<u16, GeoTiffError> {
    decoder
        .find_tag_unsigned::<u16>(tag)
        .map(|v| v.unwrap_or(default))
        .map_err(|e| fail_at(path)(format!("bad {tag:?} tag: {e}")))
}

/// Decodes an LZW-compressed image (strips or tiles, no predictor or horizontal
/// differencing of integers) chunk by chunk; `None` for anything else.
///
/// The `tiff` crate 0.11 fails on some valid LZW tiles ("no lzw end code found", e.g.
/// GDAL's int16 DEMs in 256 × 256 tiles): this path decodes each chunk's bytes with
/// `weezl` without requiring the end code, as libtiff does.
fn read_lzw<R: std::io::Read + std::io::Seek>(
    decoder: &mut Decoder<R>,
    file: &[u8],
    [width, height]: [u32; 2],
    path: &Path,
) -> Result<Option<DecodingResult>, GeoTiffError> {
    if u16_tag(decoder, Tag::Compression, 1, path)? != COMPRESSION_LZW {
        return Ok(None);
    }
    let predictor = u16_tag(decoder, Tag::Predictor, 1, path)?;
    let bits = u16_tag(decoder, Tag::BitsPerSample, 1, path)?;
    let format = u16_tag(decoder, Tag::SampleFormat, 1, path)?;
    if !matches!(bits, 8 | 16 | 32 | 64) || !matches!(format, 1..=3) {
        return Ok(None);
    }
    let integer = format == 1 || format == 2;
    if !(predictor == 1 || (predictor == 2 && integer)) {
        return Ok(None);
    }
    let (tiled, chunk) = match decoder.find_tag_unsigned::<u32>(Tag::TileWidth) {
        Ok(Some(tw)) => {
            let th = decoder
                .find_tag_unsigned::<u32>(Tag::TileLength)
                .map_err(|e| fail_at(path)(format!("bad TileLength tag: {e}")))?
                .ok_or_else(|| fail_at(path)("has TileWidth but no TileLength".to_string()))?;
            (true, [tw, th])
        }
        Ok(None) => {
            let rows = decoder
                .find_tag_unsigned::<u32>(Tag::RowsPerStrip)
                .map_err(|e| fail_at(path)(format!("bad RowsPerStrip tag: {e}")))?
                .unwrap_or(height);
            (false, [width, rows.min(height)])
        }
        Err(e) => return Err(fail_at(path)(format!("bad TileWidth tag: {e}"))),
    };
    if chunk[0] == 0 || chunk[1] == 0 || u64::from(chunk[0]) * u64::from(chunk[1]) > MAX_PIXELS {
        return Err(fail_at(path)(format!(
            "bad chunk size {}×{}",
            chunk[0], chunk[1]
        )));
    }
    let (offsets, counts) = if tiled {
        (Tag::TileOffsets, Tag::TileByteCounts)
    } else {
        (Tag::StripOffsets, Tag::StripByteCounts)
    };
    let offsets = u64_tags(decoder, offsets, path)?
        .ok_or_else(|| fail_at(path)("has no chunk offsets".to_string()))?;
    let counts = u64_tags(decoder, counts, path)?
        .ok_or_else(|| fail_at(path)("has no chunk byte counts".to_string()))?;
    let across = width.div_ceil(chunk[0]) as usize;
    let down = height.div_ceil(chunk[1]) as usize;
    if offsets.len() < across * down || counts.len() < across * down {
        return Err(fail_at(path)(format!(
            "has {} chunk offsets and {} byte counts for {} chunks",
            offsets.len(),
            counts.len(),
            across * down
        )));
    }
    let little = decoder.byte_order() == tiff::tags::ByteOrder::LittleEndian;
    let size = bits as usize / 8;
    let (w, h) = (width as usize, height as usize);
    // Raw samples as u64 bit patterns (the predictor adds them modulo 2^bits).
    let mut raw = vec![0u64; w * h];
    for cy in 0..down {
        for cx in 0..across {
            let k = cy * across + cx;
            let (start, count) = (offsets[k] as usize, counts[k] as usize);
            let compressed = file
                .get(start..start.saturating_add(count))
                .ok_or_else(|| {
                    fail_at(path)(format!("chunk {k} lies beyond the end of the file"))
                })?;
            let mut bytes = Vec::new();
            let result = weezl::decode::Decoder::with_tiff_size_switch(weezl::BitOrder::Msb, 8)
                .into_vec(&mut bytes)
                .decode(compressed);
            result
                .status
                .map_err(|e| fail_at(path)(format!("chunk {k}: bad LZW data: {e}")))?;
            let (cw, x0, y0) = (
                chunk[0] as usize,
                cx * chunk[0] as usize,
                cy * chunk[1] as usize,
            );
            // Tiles are padded to full size; the last strip holds only the rows left.
            let rows = if tiled {
                chunk[1] as usize
            } else {
                (chunk[1] as usize).min(h - y0)
            };
            if bytes.len() < cw * rows * size {
                return Err(fail_at(path)(format!(
                    "chunk {k} decodes to {} bytes; {cw}×{rows} samples of {size} bytes need {}",
                    bytes.len(),
                    cw * rows * size
                )));
            }
            let mask = if bits == 64 {
                u64::MAX
            } else {
                (1u64 << bits) - 1
            };
            for r in 0..rows.min(h - y0) {
                let mut previous = 0u64;
                for c in 0..cw {
                    let at = (r * cw + c) * size;
                    let mut v = 0u64;
                    for b in 0..size {
                        let byte = u64::from(bytes[at + if little { size - 1 - b } else { b }]);
                        v = (v << 8) | byte;
                    }
                    if predictor == 2 {
                        v = v.wrapping_add(previous) & mask;
                        previous = v;
                    }
                    if x0 + c < w {
                        raw[(y0 + r) * w + x0 + c] = v;
                    }
                }
            }
        }
    }
    let image = match (format, bits) {
        (1, 8) => DecodingResult::U8(raw.iter().map(|&v| v as u8).collect()),
        (2, 8) => DecodingResult::I8(raw.iter().map(|&v| v as u8 as i8).collect()),
        (1, 16) => DecodingResult::U16(raw.iter().map(|&v| v as u16).collect()),
        (2, 16) => DecodingResult::I16(raw.iter().map(|&v| v as u16 as i16).collect()),
        (1, 32) => DecodingResult::U32(raw.iter().map(|&v| v as u32).collect()),
        (2, 32) => DecodingResult::I32(raw.iter().map(|&v| v as u32 as i32).collect()),
        (3, 32) => DecodingResult::F32(raw.iter().map(|&v| f32::from_bits(v as u32)).collect()),
        (3, 64) => DecodingResult::F64(raw.iter().map(|&v| f64::from_bits(v)).collect()),
        _ => return Ok(None),
    };
    Ok(Some(image))
}

/// The raster type from the GeoKey directory (`PixelIsArea` when absent).
fn raster_type<R: std::io::Read + std::io::Seek>(
    decoder: &mut Decoder<R>,
    path: &Path,
) -> Result<RasterType, GeoTiffError> {
    let keys = match decoder.find_tag(Tag::GeoKeyDirectoryTag) {
        Ok(Some(value)) => value
            .into_u16_vec()
            .map_err(|e| fail_at(path)(format!("bad GeoKeyDirectory tag: {e}")))?,
        Ok(None) => return Ok(RasterType::PixelIsArea),
        Err(e) => return Err(fail_at(path)(format!("bad GeoKeyDirectory tag: {e}"))),
    };
    // Header: version, revision, minor, number of keys; then 4 shorts per key:
    // id, location (0 = the value is inline), count, value.
    let count = keys.get(3).copied().unwrap_or(0) as usize;
    let entries = keys.get(4..).unwrap_or(&[]).chunks_exact(4).take(count);
    if entries
        .clone()
        .any(|key| key[0] == GT_MODEL_TYPE_GEO_KEY && key[1] == 0 && key[3] == 2)
    {
        return Err(fail_at(path)(
            "is in geographic coordinates (degrees), SMUG plans in metres: \
                    reproject it to a projected CRS first (e.g. `gdalwarp -t_srs EPSG:326NN`)"
                .into(),
        ));
    }
    for key in entries {
        if key[0] == GT_RASTER_TYPE_GEO_KEY && key[1] == 0 {
            return match key[3] {
                1 => Ok(RasterType::PixelIsArea),
                2 => Ok(RasterType::PixelIsPoint),
                other => Err(fail_at(path)(format!(
                    "GTRasterTypeGeoKey is {other}; expected 1 (PixelIsArea) or 2 (PixelIsPoint)"
                ))),
            };
        }
    }
    Ok(RasterType::PixelIsArea)
}

fn f64_tag<R: std::io::Read + std::io::Seek>(
    decoder: &mut Decoder<R>,
    tag: Tag,
    name: &str,
    path: &Path,
) -> Result<Option<Vec<f64>>, GeoTiffError> {
    match decoder.find_tag(tag) {
        Ok(Some(value)) => value
            .into_f64_vec()
            .map(Some)
            .map_err(|e| fail_at(path)(format!("bad {name} tag: {e}"))),
        Ok(None) => Ok(None),
        Err(e) => Err(fail_at(path)(format!("bad {name} tag: {e}"))),
    }
}

/// The world coordinates of the upper-left corner of pixel `(0, 0)` and the cell size.
fn georeference<R: std::io::Read + std::io::Seek>(
    decoder: &mut Decoder<R>,
    raster_type: RasterType,
    path: &Path,
) -> Result<([f64; 2], f64), GeoTiffError> {
    let scale = f64_tag(decoder, Tag::ModelPixelScaleTag, "ModelPixelScale", path)?;
    let tiepoint = f64_tag(decoder, Tag::ModelTiepointTag, "ModelTiepoint", path)?;
    let transform = f64_tag(
        decoder,
        Tag::ModelTransformationTag,
        "ModelTransformation",
        path,
    )?;
    // Raster point (i, j) ↦ (x0 + i·sx, y0 − j·sy).
    let (x0, y0, sx, sy) = match (scale, tiepoint, transform) {
        (Some(scale), Some(tie), _) => {
            if scale.len() < 2 || tie.len() < 6 {
                return Err(fail_at(path)(format!(
                    "ModelPixelScale has {} values (needs 3) or ModelTiepoint {} (needs 6)",
                    scale.len(),
                    tie.len()
                )));
            }
            if tie.len() > 6 {
                return Err(fail_at(path)(format!(
                    "ModelTiepoint holds {} tiepoints; SMUG reads north-up DEMs with one",
                    tie.len() / 6
                )));
            }
            let (sx, sy) = (scale[0], scale[1]);
            (tie[3] - tie[0] * sx, tie[4] + tie[1] * sy, sx, sy)
        }
        (_, _, Some(m)) => {
            if m.len() != 16 {
                return Err(fail_at(path)(format!(
                    "ModelTransformation has {} values; it needs 16",
                    m.len()
                )));
            }
            if m[1] != 0.0 || m[4] != 0.0 {
                return Err(fail_at(path)(format!(
                    "ModelTransformation rotates or shears the raster (terms {} and {}); \
                     SMUG reads north-up DEMs",
                    m[1], m[4]
                )));
            }
            (m[3], m[7], m[0], -m[5])
        }
        _ => {
            return Err(fail_at(path)(
                "no georeferencing: needs ModelPixelScale and ModelTiepoint, or \
                 ModelTransformation"
                    .into(),
            ))
        }
    };
    if ![x0, y0, sx, sy].iter().all(|v| v.is_finite()) || sx <= 0.0 || sy <= 0.0 {
        return Err(fail_at(path)(format!(
            "the pixel size must be finite and > 0 with north up, got ({sx}, {}) from ({x0}, {y0})",
            -sy
        )));
    }
    if (sx - sy).abs() > 1e-9 * sx {
        return Err(fail_at(path)(format!(
            "pixels are {sx} × {sy}: SMUG's grids have square cells (resample the DEM)"
        )));
    }
    let half = match raster_type {
        RasterType::PixelIsArea => 0.0,
        RasterType::PixelIsPoint => 0.5,
    };
    Ok(([x0 - half * sx, y0 + half * sy], sx))
}

/// The samples as heights, NaN for the nodata value.
fn heights(
    image: DecodingResult,
    nodata: Option<f64>,
    path: &Path,
) -> Result<Vec<f32>, GeoTiffError> {
    fn convert<T: Copy>(
        samples: Vec<T>,
        nodata: Option<T>,
        to_f32: impl Fn(T) -> f32,
        same: impl Fn(T, T) -> bool,
    ) -> Vec<f32> {
        samples
            .into_iter()
            .map(|v| match nodata {
                Some(n) if same(v, n) => f32::NAN,
                _ => to_f32(v),
            })
            .collect()
    }
    // A nodata value that the sample type cannot hold matches nothing.
    fn exact<T: TryFrom<i64>>(nodata: Option<f64>) -> Option<T> {
        nodata
            .filter(|n| n.fract() == 0.0 && n.abs() < 9.0e15)
            .and_then(|n| T::try_from(n as i64).ok())
    }
    fn eq<T: PartialEq>(a: T, b: T) -> bool {
        a == b
    }
    Ok(match image {
        DecodingResult::F32(v) => convert(
            v,
            nodata.map(|n| n as f32),
            |x| x,
            |a: f32, b: f32| a == b || (a.is_nan() && b.is_nan()),
        ),
        DecodingResult::F64(v) => convert(
            v,
            nodata,
            |x| x as f32,
            |a: f64, b: f64| a == b || (a.is_nan() && b.is_nan()),
        ),
        DecodingResult::I16(v) => convert(v, exact(nodata), f32::from, eq),
        DecodingResult::U16(v) => convert(v, exact(nodata), f32::from, eq),
        DecodingResult::I8(v) => convert(v, exact(nodata), f32::from, eq),
        DecodingResult::U8(v) => convert(v, exact(nodata), f32::from, eq),
        DecodingResult::I32(v) => convert(v, exact(nodata), |x| x as f32, eq),
        DecodingResult::U32(v) => convert(v, exact(nodata), |x| x as f32, eq),
        DecodingResult::I64(_) | DecodingResult::U64(_) | DecodingResult::F16(_) => {
            return Err(fail_at(path)(
                "64-bit integer and 16-bit float samples are not supported; \
                 use float32, float64 or int16"
                    .into(),
            ))
        }
    })
}
