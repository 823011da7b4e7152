//! Point clouds (PLY, PCD) rasterised into an elevation layer, as elevation_mapping and
//! grid_map users produce one.
//!
//! Readers: PLY `ascii 1.0`, `binary_little_endian 1.0` and `binary_big_endian 1.0`
//! (the `vertex` element's `x`, `y`, `z` of any scalar type; other elements and
//! properties, list properties included, are skipped); PCD v0.7 `DATA ascii` and
//! `DATA binary` (`x`, `y`, `z` fields of type F 4/8, I or U; `binary_compressed` is
//! refused with a message saying how to convert). Points with a NaN or infinite
//! coordinate are dropped (PCD marks invalid points so).
//!
//! Both readers are small and written here: the PLY crates on crates.io are unmaintained
//! or pull in a general mesh library, and PCD has no maintained reader without PCL.
//!
//! Rasterising: cell `(i, j)` of size `cell_size` covers
//! `[i·s, (i+1)·s) × [j·s, (j+1)·s)` in grid-aligned coordinates (the grid's origin is a
//! multiple of the cell size, so two clouds of the same place share cells); its height is
//! the highest (`max`) or the mean (`mean`) z of its points; cells without points are NaN.

use serde::{Deserialize, Serialize};
use smug_core::{GridGeometry, GridLayer, MemoryLimit};
use std::io::{BufRead, Read};
use std::path::{Path, PathBuf};

/// The most points read from one file (a unit mistake, not a cloud, beyond).
pub const MAX_POINTS: u64 = 200_000_000;

/// Why a point cloud could not be read or rasterised; every message names the file.
#[derive(Debug, thiserror::Error)]
#[error("{}: {message}", path.display())]
pub struct PointCloudError {
    /// The file.
    pub path: PathBuf,
    /// What is wrong (with the header line where it applies).
    pub message: String,
}

/// An error about the point cloud at `path`.
fn fail_at(path: &Path) -> impl Fn(String) -> PointCloudError + '_ {
    move |message| PointCloudError {
        path: path.to_path_buf(),
        message,
    }
}

/// How the points of one cell make its height.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Reduce {
    /// The highest point (conservative: the top of anything in the cell).
    #[default]
    Max,
    /// The mean z.
    Mean,
}

/// Reads the points of a `.ply` or `.pcd` file (by extension, else by its first line).
pub fn read_point_cloud(path: &Path) -> Result<Vec<[f64; 3]>, PointCloudError> {
    let fail = |message: String| PointCloudError {
        path: path.to_path_buf(),
        message,
    };
    let bytes = std::fs::read(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    let points = if bytes.starts_with(b"ply") {
        read_ply(&bytes, path)
    } else if is_pcd(&bytes) {
        read_pcd(&bytes, path)
    } else {
        Err(fail(
            "neither a PLY file (first line `ply`) nor a PCD file (a `# .PCD` or \
             `VERSION` header)"
                .to_string(),
        ))
    }?;
    Ok(points
        .into_iter()
        .filter(|p| p.iter().all(|v| v.is_finite()))
        .collect())
}

fn is_pcd(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(64)];
    head.starts_with(b"# .PCD") || head.starts_with(b"VERSION") || head.starts_with(b"FIELDS")
}

/// Rasterises `points` into cells of `cell_size` metres (see the [module
/// documentation](self)); `path` names the cloud in errors.
pub fn rasterise(
    points: &[[f64; 3]],
    cell_size: f64,
    reduce: Reduce,
    path: &Path,
) -> Result<GridLayer, PointCloudError> {
    rasterise_within(points, cell_size, reduce, path, MemoryLimit::default())
}

/// [`rasterise`] into a grid that must fit `memory` (a run's limit).
pub fn rasterise_within(
    points: &[[f64; 3]],
    cell_size: f64,
    reduce: Reduce,
    path: &Path,
    memory: MemoryLimit,
) -> Result<GridLayer, PointCloudError> {
    let fail = |message: String| PointCloudError {
        path: path.to_path_buf(),
        message,
    };
    if !(cell_size.is_finite() && cell_size > 0.0) {
        return Err(fail(format!("cell_size must be > 0, got {cell_size}")));
    }
    if points.is_empty() {
        return Err(fail("has no valid points".into()));
    }
    let cell = |v: f64| (v / cell_size).floor();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(cell(p[k]));
            hi[k] = hi[k].max(cell(p[k]));
        }
    }
    let size = [(hi[0] - lo[0]) as u64 + 1, (hi[1] - lo[1]) as u64 + 1];
    if size[0] * size[1] > crate::limits::MAX_PIXELS {
        return Err(fail(format!(
            "covers {} × {} cells of {cell_size} m, more than the {} SMUG rasterises \
             (a larger cell_size, or a cloud in metres?)",
            size[0],
            size[1],
            crate::limits::MAX_PIXELS
        )));
    }
    let geometry = GridGeometry::new_within(
        [lo[0] * cell_size, lo[1] * cell_size],
        cell_size,
        [size[0] as usize, size[1] as usize],
        memory,
    )
    .map_err(|e| fail(e.to_string()))?;
    let mut sum = vec![0.0f64; geometry.len()];
    let mut top = vec![f64::NEG_INFINITY; geometry.len()];
    let mut count = vec![0u32; geometry.len()];
    for p in points {
        let i = (cell(p[0]) - lo[0]) as usize;
        let j = (cell(p[1]) - lo[1]) as usize;
        let k = geometry.index(i, j);
        sum[k] += p[2];
        top[k] = top[k].max(p[2]);
        count[k] += 1;
    }
    let data = (0..geometry.len())
        .map(|k| match (count[k], reduce) {
            (0, _) => f32::NAN,
            (_, Reduce::Max) => top[k] as f32,
            (n, Reduce::Mean) => (sum[k] / f64::from(n)) as f32,
        })
        .collect();
    Ok(GridLayer { geometry, data })
}

/// A scalar type of PLY or PCD.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
}

impl Scalar {
    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::I64 | Scalar::U64 | Scalar::F64 => 8,
        }
    }

    fn ply(name: &str) -> Option<Self> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn pcd(kind: &str, size: usize) -> Option<Self> {
        Some(match (kind, size) {
            ("I", 1) => Scalar::I8,
            ("U", 1) => Scalar::U8,
            ("I", 2) => Scalar::I16,
            ("U", 2) => Scalar::U16,
            ("I", 4) => Scalar::I32,
            ("U", 4) => Scalar::U32,
            ("I", 8) => Scalar::I64,
            ("U", 8) => Scalar::U64,
            ("F", 4) => Scalar::F32,
            ("F", 8) => Scalar::F64,
            _ => return None,
        })
    }

    /// The value at the start of `b` (which holds at least `size()` bytes).
    fn read(self, b: &[u8], little: bool) -> f64 {
        macro_rules! get {
            ($t:ty, $n:expr) => {{
                let mut a = [0u8; $n];
                a.copy_from_slice(&b[..$n]);
                (if little {
                    <$t>::from_le_bytes(a)
                } else {
                    <$t>::from_be_bytes(a)
                }) as f64
            }};
        }
        match self {
            Scalar::I8 => get!(i8, 1),
            Scalar::U8 => get!(u8, 1),
            Scalar::I16 => get!(i16, 2),
            Scalar::U16 => get!(u16, 2),
            Scalar::I32 => get!(i32, 4),
            Scalar::U32 => get!(u32, 4),
            Scalar::I64 => get!(i64, 8),
            Scalar::U64 => get!(u64, 8),
            Scalar::F32 => get!(f32, 4),
            Scalar::F64 => get!(f64, 8),
        }
    }
}

/// A PLY property: a scalar, or a list with its count type.
#[derive(Clone, Debug)]
struct Property {
    name: String,
    kind: Scalar,
    list_count: Option<Scalar>,
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: u64,
    properties: Vec<Property>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum PlyFormat {
    Ascii,
    Binary { little: bool },
}

/// Reads the header lines up to `end_header`; returns them (1-based line numbers) and
/// the body's offset.
fn header_lines(
    bytes: &[u8],
    end: &str,
    path: &Path,
) -> Result<(Vec<(usize, String)>, usize), PointCloudError> {
    let mut lines = Vec::new();
    let mut reader = std::io::Cursor::new(bytes);
    let mut line = Vec::new();
    loop {
        line.clear();
        let n = reader
            .read_until(b'\n', &mut line)
            .map_err(|e| fail_at(path)(e.to_string()))?;
        if n == 0 {
            return Err(fail_at(path)(format!("the header has no `{end}` line")));
        }
        let text = String::from_utf8_lossy(&line).trim().to_string();
        let number = lines.len() + 1;
        let done = text.split_whitespace().next() == Some(end);
        lines.push((number, text));
        if done {
            return Ok((lines, reader.position() as usize));
        }
        if lines.len() > 10_000 {
            return Err(fail_at(path)(format!(
                "no `{end}` line in the first 10000 lines"
            )));
        }
    }
}

fn read_ply(bytes: &[u8], path: &Path) -> Result<Vec<[f64; 3]>, PointCloudError> {
    let (lines, body) = header_lines(bytes, "end_header", path)?;
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    for (number, text) in &lines[1..] {
        let words: Vec<&str> = text.split_whitespace().collect();
        let bad = |what: &str| format!("line {number}: {what}: `{text}`");
        match words.as_slice() {
            ["format", kind, _version] => {
                format = Some(match *kind {
                    "ascii" => PlyFormat::Ascii,
                    "binary_little_endian" => PlyFormat::Binary { little: true },
                    "binary_big_endian" => PlyFormat::Binary { little: false },
                    _ => return Err(fail_at(path)(bad("unknown PLY format"))),
                })
            }
            ["element", name, count] => elements.push(Element {
                name: name.to_string(),
                count: count
                    .parse()
                    .map_err(|_| fail_at(path)(bad("bad element count")))?,
                properties: Vec::new(),
            }),
            ["property", "list", count, kind, name] => {
                let element = elements
                    .last_mut()
                    .ok_or_else(|| fail_at(path)(bad("property before any element")))?;
                element.properties.push(Property {
                    name: name.to_string(),
                    kind: Scalar::ply(kind)
                        .ok_or_else(|| fail_at(path)(bad("unknown property type")))?,
                    list_count: Some(
                        Scalar::ply(count)
                            .ok_or_else(|| fail_at(path)(bad("unknown list count type")))?,
                    ),
                });
            }
            ["property", kind, name] => {
                let element = elements
                    .last_mut()
                    .ok_or_else(|| fail_at(path)(bad("property before any element")))?;
                element.properties.push(Property {
                    name: name.to_string(),
                    kind: Scalar::ply(kind)
                        .ok_or_else(|| fail_at(path)(bad("unknown property type")))?,
                    list_count: None,
                });
            }
            ["comment", ..] | ["obj_info", ..] | ["end_header"] | [] => {}
            _ => return Err(fail_at(path)(bad("unknown header line"))),
        }
    }
    let format = format.ok_or_else(|| fail_at(path)("the header has no `format` line".into()))?;
    let vertex = elements
        .iter()
        .position(|e| e.name == "vertex")
        .ok_or_else(|| fail_at(path)("no `vertex` element".into()))?;
    let columns = xyz_columns(
        &elements[vertex]
            .properties
            .iter()
            .map(|p| p.name.as_str())
            .collect::<Vec<_>>(),
        "vertex property",
        path,
    )?;
    if elements[vertex].count > MAX_POINTS {
        return Err(fail_at(path)(format!(
            "{} vertices is more than the {MAX_POINTS} SMUG reads",
            elements[vertex].count
        )));
    }
    let data = &bytes[body..];
    match format {
        PlyFormat::Ascii => {
            let text = std::str::from_utf8(data)
                .map_err(|_| fail_at(path)("the ASCII body is not text".into()))?;
            let mut rows = text
                .lines()
                .enumerate()
                .filter(|(_, l)| !l.trim().is_empty());
            let skip: u64 = elements[..vertex].iter().map(|e| e.count).sum();
            for _ in 0..skip {
                rows.next()
                    .ok_or_else(|| fail_at(path)("the file ends before the vertices".into()))?;
            }
            let element = &elements[vertex];
            let mut points = Vec::with_capacity(element.count as usize);
            for k in 0..element.count {
                let (n, row) = rows.next().ok_or_else(|| {
                    fail_at(path)({
                        format!("the file ends after {k} of {} vertices", element.count)
                    })
                })?;
                let line = lines.len() + n + 1;
                let values: Vec<f64> = row
                    .split_whitespace()
                    .map(|w| w.parse::<f64>())
                    .collect::<Result<_, _>>()
                    .map_err(|_| fail_at(path)(format!("line {line}: not a number in `{row}`")))?;
                // Only scalar properties precede x, y, z in position when lists come
                // last; with lists before them the columns shift, so walk the row.
                let mut column = 0;
                let mut xyz = [f64::NAN; 3];
                for p in &element.properties {
                    let width = match p.list_count {
                        Some(_) => 1 + *values.get(column).unwrap_or(&0.0) as usize,
                        None => 1,
                    };
                    if let Some(c) = columns.iter().position(|&c| c == p.name) {
                        xyz[c] = *values.get(column).ok_or_else(|| {
                            fail_at(path)(format!("line {line}: too few values in `{row}`"))
                        })?;
                    }
                    column += width;
                }
                points.push(xyz);
            }
            Ok(points)
        }
        PlyFormat::Binary { little } => {
            let mut offset = 0usize;
            for element in &elements[..vertex] {
                for _ in 0..element.count {
                    offset = skip_binary_row(data, offset, &element.properties, little, path)?;
                }
            }
            let element = &elements[vertex];
            let mut points = Vec::with_capacity(element.count.min(1 << 24) as usize);
            for k in 0..element.count {
                let mut xyz = [f64::NAN; 3];
                for p in &element.properties {
                    let start = offset;
                    offset = skip_binary_row(data, offset, std::slice::from_ref(p), little, path)
                        .map_err(|_| {
                        fail_at(path)({
                            format!(
                                "the file ends in vertex {k} of {} (binary body of {} bytes)",
                                element.count,
                                data.len()
                            )
                        })
                    })?;
                    if let Some(c) = columns.iter().position(|&c| c == p.name) {
                        if p.list_count.is_none() {
                            xyz[c] = p.kind.read(&data[start..], little);
                        }
                    }
                }
                points.push(xyz);
            }
            Ok(points)
        }
    }
}

/// The offset after one binary row of `properties` starting at `offset`.
fn skip_binary_row(
    data: &[u8],
    mut offset: usize,
    properties: &[Property],
    little: bool,
    path: &Path,
) -> Result<usize, PointCloudError> {
    let short = || fail_at(path)("the file ends inside the binary body".into());
    for p in properties {
        let width = match p.list_count {
            None => p.kind.size(),
            Some(count) => {
                let b = data.get(offset..offset + count.size()).ok_or_else(short)?;
                let n = count.read(b, little);
                if !(0.0..=1e9).contains(&n) {
                    return Err(fail_at(path)(format!(
                        "list property `{}` has count {n}",
                        p.name
                    )));
                }
                offset += count.size();
                n as usize * p.kind.size()
            }
        };
        if offset + width > data.len() {
            return Err(short());
        }
        offset += width;
    }
    Ok(offset)
}

/// The indices of `x`, `y`, `z` among `names`.
fn xyz_columns<'a>(
    names: &[&'a str],
    what: &str,
    path: &Path,
) -> Result<[&'a str; 3], PointCloudError> {
    let mut out = [""; 3];
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        out[k] = names.iter().find(|n| *n == axis).copied().ok_or_else(|| {
            fail_at(path)(format!("no {what} `{axis}` (found: {})", names.join(", ")))
        })?;
    }
    Ok(out)
}

fn read_pcd(bytes: &[u8], path: &Path) -> Result<Vec<[f64; 3]>, PointCloudError> {
    let (lines, body) = header_lines(bytes, "DATA", path)?;
    let mut fields: Vec<String> = Vec::new();
    let mut sizes: Vec<usize> = Vec::new();
    let mut types: Vec<String> = Vec::new();
    let mut counts: Vec<usize> = Vec::new();
    let mut points: Option<u64> = None;
    let (mut width, mut height) = (None, None);
    let mut data_kind = "";
    for (number, text) in &lines {
        let words: Vec<&str> = text.split_whitespace().collect();
        let bad = |what: &str| format!("line {number}: {what}: `{text}`");
        let numbers = |words: &[&str]| -> Result<Vec<usize>, PointCloudError> {
            words
                .iter()
                .map(|w| {
                    w.parse::<usize>()
                        .map_err(|_| fail_at(path)(bad("not a count")))
                })
                .collect()
        };
        match words.as_slice() {
            [] => {}
            [w, ..] if w.starts_with('#') => {}
            ["VERSION", ..] | ["VIEWPOINT", ..] => {}
            ["FIELDS", rest @ ..] => fields = rest.iter().map(|s| s.to_string()).collect(),
            ["SIZE", rest @ ..] => sizes = numbers(rest)?,
            ["TYPE", rest @ ..] => types = rest.iter().map(|s| s.to_string()).collect(),
            ["COUNT", rest @ ..] => counts = numbers(rest)?,
            ["WIDTH", w] => {
                width = Some(
                    w.parse::<u64>()
                        .map_err(|_| fail_at(path)(bad("bad WIDTH")))?,
                )
            }
            ["HEIGHT", h] => {
                height = Some(
                    h.parse::<u64>()
                        .map_err(|_| fail_at(path)(bad("bad HEIGHT")))?,
                )
            }
            ["POINTS", n] => {
                points = Some(
                    n.parse::<u64>()
                        .map_err(|_| fail_at(path)(bad("bad POINTS")))?,
                )
            }
            ["DATA", kind] => {
                data_kind = match *kind {
                    "ascii" => "ascii",
                    "binary" => "binary",
                    "binary_compressed" => {
                        return Err(fail_at(path)(bad(
                            "binary_compressed PCD is not supported; convert it with \
                             `pcl_convert_pcd_ascii_binary IN OUT 1` (binary) or 0 (ascii)",
                        )))
                    }
                    _ => return Err(fail_at(path)(bad("unknown DATA kind"))),
                }
            }
            _ => return Err(fail_at(path)(bad("unknown header line"))),
        }
    }
    if counts.is_empty() {
        counts = vec![1; fields.len()];
    }
    if sizes.len() != fields.len() || types.len() != fields.len() || counts.len() != fields.len() {
        return Err(fail_at(path)(format!(
            "FIELDS has {} entries but SIZE {}, TYPE {}, COUNT {}",
            fields.len(),
            sizes.len(),
            types.len(),
            counts.len()
        )));
    }
    let n = match (points, width, height) {
        (Some(n), _, _) => n,
        (None, Some(w), Some(h)) => w * h,
        _ => {
            return Err(fail_at(path)(
                "the header has no POINTS (or WIDTH and HEIGHT)".into(),
            ))
        }
    };
    if n > MAX_POINTS {
        return Err(fail_at(path)(format!(
            "{n} points is more than the {MAX_POINTS} SMUG reads"
        )));
    }
    let names: Vec<&str> = fields.iter().map(String::as_str).collect();
    let xyz = xyz_columns(&names, "field", path)?;
    let scalars: Vec<Scalar> = types
        .iter()
        .zip(&sizes)
        .zip(&fields)
        .map(|((t, &s), f)| {
            Scalar::pcd(t, s)
                .ok_or_else(|| fail_at(path)(format!("field `{f}` has TYPE {t} SIZE {s}")))
        })
        .collect::<Result<_, _>>()?;
    // Column (value index in a row) and byte offset of each field.
    let mut column = Vec::new();
    let mut byte = Vec::new();
    let (mut c, mut b) = (0usize, 0usize);
    for (k, s) in scalars.iter().enumerate() {
        column.push(c);
        byte.push(b);
        c += counts[k];
        b += counts[k] * s.size();
    }
    let (row_values, row_bytes) = (c, b);
    let field = |axis: &str| names.iter().position(|n| *n == axis).unwrap_or(0);
    let idx = [field(xyz[0]), field(xyz[1]), field(xyz[2])];
    let data = &bytes[body..];
    let mut out = Vec::with_capacity(n.min(1 << 24) as usize);
    if data_kind == "ascii" {
        let mut text = String::new();
        std::io::Cursor::new(data)
            .read_to_string(&mut text)
            .map_err(|_| fail_at(path)("the ASCII body is not text".into()))?;
        let mut rows = text.lines().filter(|l| !l.trim().is_empty());
        for k in 0..n {
            let row = rows
                .next()
                .ok_or_else(|| fail_at(path)(format!("the file ends after {k} of {n} points")))?;
            let values: Vec<&str> = row.split_whitespace().collect();
            if values.len() != row_values {
                return Err(fail_at(path)(format!(
                    "point {k}: {} values, the header's fields need {row_values}: `{row}`",
                    values.len()
                )));
            }
            let mut p = [0.0; 3];
            for (a, &f) in idx.iter().enumerate() {
                p[a] = values[column[f]]
                    .parse::<f64>()
                    .map_err(|_| fail_at(path)(format!("point {k}: not a number in `{row}`")))?;
            }
            out.push(p);
        }
    } else {
        let need = n as usize * row_bytes;
        if data.len() < need {
            return Err(fail_at(path)(format!(
                "the binary body has {} bytes; {n} points of {row_bytes} bytes need {need}",
                data.len()
            )));
        }
        for row in data[..need].chunks_exact(row_bytes) {
            let mut p = [0.0; 3];
            for (a, &f) in idx.iter().enumerate() {
                p[a] = scalars[f].read(&row[byte[f]..], true);
            }
            out.push(p);
        }
    }
    Ok(out)
}
