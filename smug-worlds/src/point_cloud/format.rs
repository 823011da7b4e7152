//! What both readers share: the error naming the file, the point limit, the scalar
//! types of PLY and PCD, header lines, and finding the `x`, `y`, `z` columns.

use std::io::BufRead;
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
pub(super) fn fail_at(path: &Path) -> impl Fn(String) -> PointCloudError + '_ {
    move |message| PointCloudError {
        path: path.to_path_buf(),
        message,
    }
}

/// A scalar type of PLY or PCD.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Scalar {
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
    pub(super) fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::I64 | Scalar::U64 | Scalar::F64 => 8,
        }
    }

    pub(super) fn ply(name: &str) -> Option<Self> {
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

    pub(super) fn pcd(kind: &str, size: usize) -> Option<Self> {
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
    pub(super) fn read(self, b: &[u8], little: bool) -> f64 {
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

/// Reads the header lines up to `end_header`; returns them (1-based line numbers) and
/// the body's offset.
pub(super) fn header_lines(
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

/// The indices of `x`, `y`, `z` among `names`.
pub(super) fn xyz_columns<'a>(
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
