//! PLY `ascii 1.0`, `binary_little_endian 1.0` and `binary_big_endian 1.0`: the
//! `vertex` element's `x`, `y`, `z` (other elements and properties skipped).

use super::format::{fail_at, header_lines, xyz_columns, PointCloudError, Scalar, MAX_POINTS};

use std::path::Path;

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

pub(super) fn read_ply(bytes: &[u8], path: &Path) -> Result<Vec<[f64; 3]>, PointCloudError> {
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
