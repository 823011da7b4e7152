//! `from-file`: a precomputed traversability layer (what a learned network exports),
//! checked against the world's elevation geometry.
//!
//! Formats, by extension:
//! - `.npy`: a 2D NumPy array (`<f4` or `<f8`, C order) of shape `(rows, columns)`;
//!   row 0 is the top of the map (image order) unless `row_order = "bottom-up"`.
//! - `.json`: a serialised `GridLayer` (`{"geometry": …, "data": […]}`, `null` = no data);
//!   its geometry must match the world's.
//! - `.csv`: one map row per line, comma-separated, same row order rule as `.npy`;
//!   `nan` or an empty field = no data.
//!
//! Values must lie in `[0, 1]` (NaN = no data).

use serde::{Deserialize, Serialize};
use smug_core::{BuildContext, Error, GridGeometry, GridLayer, TraversabilityEstimator, World};
use std::path::{Path, PathBuf};

/// Which end of the map the first row of an array file holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RowOrder {
    /// Row 0 is the top (largest y), as in images.
    #[default]
    TopDown,
    /// Row 0 is the bottom (smallest y), as in SMUG's grids.
    BottomUp,
}

/// Parameters of the from-file estimator.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FromFileParams {
    /// The layer file (`.npy`, `.json` or `.csv`), relative to the config file.
    pub path: PathBuf,
    /// Row order of `.npy` and `.csv` files.
    pub row_order: RowOrder,
}

/// Why a layer file cannot be used.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {message}")]
pub struct LayerFileError {
    /// The file.
    pub path: String,
    /// What is wrong.
    pub message: String,
}

/// Loads a traversability layer from a file.
#[derive(Clone, Debug)]
pub struct FromFileEstimator {
    path: PathBuf,
    row_order: RowOrder,
}

impl FromFileEstimator {
    /// An estimator reading `path`.
    pub fn new(path: PathBuf, row_order: RowOrder) -> Self {
        Self { path, row_order }
    }

    fn error(&self, message: impl Into<String>) -> Error {
        Error::stage(
            "traversability",
            LayerFileError {
                path: self.path.display().to_string(),
                message: message.into(),
            },
        )
    }

    /// Reads the file as rows × columns values (row order as stored).
    fn read_array(&self) -> Result<(usize, usize, Vec<f64>), Error> {
        let bytes =
            std::fs::read(&self.path).map_err(|e| self.error(format!("cannot read: {e}")))?;
        match extension(&self.path).as_str() {
            "npy" => parse_npy(&bytes).map_err(|m| self.error(m.to_string())),
            "csv" => parse_csv(&bytes).map_err(|m| self.error(m.to_string())),
            other => Err(self.error(format!(
                "unsupported extension `.{other}` (use .npy, .json or .csv)"
            ))),
        }
    }

    fn layer_from_array(&self, geometry: GridGeometry) -> Result<GridLayer, Error> {
        let (rows, columns, values) = self.read_array()?;
        let [nx, ny] = geometry.size;
        if rows != ny || columns != nx {
            return Err(self.error(format!(
                "has {rows} rows × {columns} columns; the world's elevation is {ny} rows × {nx} columns"
            )));
        }
        Ok(GridLayer::from_fn(geometry, |i, j| {
            let row = match self.row_order {
                RowOrder::TopDown => ny - 1 - j,
                RowOrder::BottomUp => j,
            };
            values[row * nx + i] as f32
        }))
    }

    fn layer_from_json(&self, geometry: GridGeometry) -> Result<GridLayer, Error> {
        let text = std::fs::read_to_string(&self.path)
            .map_err(|e| self.error(format!("cannot read: {e}")))?;
        #[derive(Deserialize)]
        struct JsonLayer {
            geometry: GridGeometry,
            data: Vec<Option<f32>>,
        }
        let raw: JsonLayer =
            serde_json::from_str(&text).map_err(|e| self.error(format!("invalid layer: {e}")))?;
        if raw.geometry != geometry {
            return Err(self.error(format!(
                "geometry {:?} differs from the world's {:?}",
                raw.geometry, geometry
            )));
        }
        let data = raw
            .data
            .into_iter()
            .map(|v| v.unwrap_or(f32::NAN))
            .collect();
        GridLayer::from_data(geometry, data).map_err(|m| self.error(m.to_string()))
    }
}

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

impl TraversabilityEstimator for FromFileEstimator {
    fn estimate(&self, world: &World) -> Result<GridLayer, Error> {
        let geometry = world.elevation.geometry;
        let layer = if extension(&self.path) == "json" {
            self.layer_from_json(geometry)?
        } else {
            self.layer_from_array(geometry)?
        };
        if let Some(k) = layer
            .data
            .iter()
            .position(|v| !v.is_nan() && !(0.0..=1.0).contains(v))
        {
            return Err(self.error(format!(
                "value {} at cell ({}, {}) is outside [0, 1]",
                layer.data[k],
                k % geometry.size[0],
                k / geometry.size[0]
            )));
        }
        Ok(layer)
    }
}

/// Why a layer file's contents cannot be read as a 2D array.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
enum FormatError {
    /// The file does not start as a `.npy` file does.
    #[error("not a .npy file (bad magic)")]
    NotNpy,
    /// A `.npy` format version this reader does not know.
    #[error("unsupported .npy version {0}")]
    NpyVersion(u8),
    /// The `.npy` header is cut short or not text.
    #[error("truncated .npy header")]
    TruncatedHeader,
    /// The array's values are not little-endian 32- or 64-bit floats.
    #[error("dtype must be '<f4' or '<f8': {0}")]
    Dtype(String),
    /// The array is in Fortran order.
    #[error("Fortran-ordered arrays are not supported; save with C order")]
    FortranOrder,
    /// The header names no shape.
    #[error("no shape in the .npy header")]
    NoShape,
    /// The shape is not a list of sizes.
    #[error("bad shape `{0}`")]
    BadShape(String),
    /// The array is not 2D.
    #[error("expected a 2D array, got shape {0:?}")]
    NotTwoD(Vec<usize>),
    /// The data does not fill the shape.
    #[error("{bytes} data bytes for a {rows}×{columns} array of {width}-byte floats")]
    DataSize {
        /// Data bytes present.
        bytes: usize,
        /// Rows of the shape.
        rows: usize,
        /// Columns of the shape.
        columns: usize,
        /// Bytes per value.
        width: usize,
    },
    /// A CSV file that is not UTF-8 text.
    #[error("not UTF-8 text")]
    NotText,
    /// A CSV field that is not a number.
    #[error("line {line}: `{text}` is not a number")]
    NotANumber {
        /// 1-based line.
        line: usize,
        /// The field.
        text: String,
    },
    /// A CSV row of another length than the first.
    #[error("line {line} has {got} values, the first row {first}")]
    RowLength {
        /// 1-based line.
        line: usize,
        /// Values on it.
        got: usize,
        /// Values on the first row.
        first: usize,
    },
}

/// Parses a 2D little-endian float NumPy array: `(rows, columns, values)`.
fn parse_npy(bytes: &[u8]) -> Result<(usize, usize, Vec<f64>), FormatError> {
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err(FormatError::NotNpy);
    }
    let (header_len, start) = match bytes[6] {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        v => return Err(FormatError::NpyVersion(v)),
    };
    let header = bytes
        .get(start..start + header_len)
        .and_then(|h| std::str::from_utf8(h).ok())
        .ok_or(FormatError::TruncatedHeader)?;
    let width = if header.contains("'<f4'") {
        4
    } else if header.contains("'<f8'") {
        8
    } else {
        return Err(FormatError::Dtype(header.trim().to_string()));
    };
    if header.contains("'fortran_order': True") {
        return Err(FormatError::FortranOrder);
    }
    let shape = header
        .split("'shape':")
        .nth(1)
        .and_then(|rest| rest.split(')').next())
        .ok_or(FormatError::NoShape)?;
    let dims: Vec<usize> = shape
        .trim_start_matches([' ', '('])
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| {
            s.trim()
                .parse()
                .map_err(|_| FormatError::BadShape(shape.to_string()))
        })
        .collect::<Result<_, _>>()?;
    let [rows, columns] = dims[..] else {
        return Err(FormatError::NotTwoD(dims));
    };
    let body = &bytes[start + header_len..];
    if body.len() != rows * columns * width {
        return Err(FormatError::DataSize {
            bytes: body.len(),
            rows,
            columns,
            width,
        });
    }
    let values = body
        .chunks_exact(width)
        .map(|c| match c.try_into() {
            Ok(b4) if width == 4 => f32::from_le_bytes(b4) as f64,
            _ => f64::from_le_bytes(c.try_into().unwrap_or([0; 8])),
        })
        .collect();
    Ok((rows, columns, values))
}

/// Parses comma-separated rows of numbers (`nan` or empty = no data).
fn parse_csv(bytes: &[u8]) -> Result<(usize, usize, Vec<f64>), FormatError> {
    let text = std::str::from_utf8(bytes).map_err(|_| FormatError::NotText)?;
    let mut values = Vec::new();
    let mut columns = None;
    let mut rows = 0;
    for (n, line) in text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
    {
        let row: Vec<f64> = line
            .split(',')
            .map(|f| match f.trim() {
                "" => Ok(f64::NAN),
                v => v.parse::<f64>().map_err(|_| FormatError::NotANumber {
                    line: n + 1,
                    text: v.to_string(),
                }),
            })
            .collect::<Result<_, _>>()?;
        if *columns.get_or_insert(row.len()) != row.len() {
            return Err(FormatError::RowLength {
                line: n + 1,
                got: row.len(),
                first: columns.unwrap_or(0),
            });
        }
        values.extend(row);
        rows += 1;
    }
    Ok((rows, columns.unwrap_or(0), values))
}

fn build_from_file(params: FromFileParams, ctx: &BuildContext) -> Result<FromFileEstimator, Error> {
    if params.path.as_os_str().is_empty() {
        return Err(Error::invalid_param(
            "traversability",
            "from-file needs a `path`",
        ));
    }
    Ok(FromFileEstimator::new(
        ctx.resolve_path(&params.path),
        params.row_order,
    ))
}

smug_core::register_plugin!(
    smug_core::registry::TraversabilityStage,
    name = "from-file",
    summary = "a precomputed layer (.npy, .json, .csv), e.g. exported by a learned estimator",
    params = FromFileParams,
    build = |params, ctx| Ok(Box::new(build_from_file(params, ctx)?)),
);

#[cfg(test)]
mod tests {
    use super::*;

    fn world() -> World {
        let g = GridGeometry::new([0.0, 0.0], 1.0, [3, 2]).unwrap();
        World::new("t", GridLayer::filled(g, 0.0))
    }

    fn npy(rows: usize, cols: usize, values: &[f32]) -> Vec<u8> {
        let mut header =
            format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({rows}, {cols}), }}");
        while (10 + header.len() + 1) % 64 != 0 {
            header.push(' ');
        }
        header.push('\n');
        let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
        bytes.extend((header.len() as u16).to_le_bytes());
        bytes.extend(header.as_bytes());
        values.iter().for_each(|v| bytes.extend(v.to_le_bytes()));
        bytes
    }

    fn temp(name: &str, bytes: &[u8]) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("smug-from-file-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    }

    #[test]
    fn reads_npy_and_csv_top_down_and_bottom_up() {
        let path = temp("t.npy", &npy(2, 3, &[0.1, 0.2, 0.3, 0.4, f32::NAN, 0.6]));
        let layer = FromFileEstimator::new(path, RowOrder::TopDown)
            .estimate(&world())
            .unwrap();
        assert_eq!(layer.get(0, 1), 0.1, "row 0 of the file is the top");
        assert!(layer.get(1, 0).is_nan());
        let path = temp("t.csv", b"0.1,0.2,0.3\n0.4,,0.6\n");
        let layer = FromFileEstimator::new(path, RowOrder::BottomUp)
            .estimate(&world())
            .unwrap();
        assert_eq!(layer.get(0, 0), 0.1);
        assert!(layer.get(1, 1).is_nan());
    }

    #[test]
    fn rejects_wrong_sizes_values_and_files() {
        let wrong = temp("wrong.npy", &npy(3, 2, &[0.0; 6]));
        let err = FromFileEstimator::new(wrong, RowOrder::TopDown)
            .estimate(&world())
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("wrong.npy") && err.contains("3 rows × 2 columns"),
            "{err}"
        );
        let big = temp("big.csv", b"0,0,2\n0,0,0\n");
        let err = FromFileEstimator::new(big, RowOrder::TopDown)
            .estimate(&world())
            .unwrap_err()
            .to_string();
        assert!(err.contains("outside [0, 1]"), "{err}");
        let missing =
            FromFileEstimator::new(PathBuf::from("/nonexistent/x.npy"), RowOrder::TopDown);
        assert!(missing
            .estimate(&world())
            .unwrap_err()
            .to_string()
            .contains("cannot read"));
        let garbage = temp("g.npy", b"hello world");
        assert!(FromFileEstimator::new(garbage, RowOrder::TopDown)
            .estimate(&world())
            .is_err());
    }

    #[test]
    fn json_layers_must_match_the_geometry() {
        let w = world();
        let layer = GridLayer::filled(w.elevation.geometry, 0.5);
        let path = temp("l.json", serde_json::to_string(&layer).unwrap().as_bytes());
        assert_eq!(
            FromFileEstimator::new(path, RowOrder::TopDown)
                .estimate(&w)
                .unwrap(),
            layer
        );
        let other = GridLayer::filled(GridGeometry::new([1.0, 0.0], 1.0, [3, 2]).unwrap(), 0.5);
        let path = temp("o.json", serde_json::to_string(&other).unwrap().as_bytes());
        assert!(FromFileEstimator::new(path, RowOrder::TopDown)
            .estimate(&w)
            .is_err());
    }
}
