//! PCD v0.7 `DATA ascii` and `DATA binary` (`x`, `y`, `z` fields); `binary_compressed`
//! refused with a hint.

use super::format::{fail_at, header_lines, xyz_columns, PointCloudError, Scalar, MAX_POINTS};
use std::io::Read;
use std::path::Path;

pub(super) fn read_pcd(bytes: &[u8], path: &Path) -> Result<Vec<[f64; 3]>, PointCloudError> {
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
