//! Point-to-point query files: one `sx,sy,syaw,gx,gy,gyaw` row per query, an optional
//! header row first (what `smug p2p --queries` reads).

use crate::pose::Pose2;
use std::path::Path;

/// A query file that cannot be used, naming the file and the line.
#[derive(Debug, thiserror::Error)]
pub enum QueryFileError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// A row is not six finite numbers.
    #[error("{path}:{line}: expected six finite numbers sx,sy,syaw,gx,gy,gyaw, got `{row}`")]
    Row {
        /// The file.
        path: String,
        /// 1-based line.
        line: usize,
        /// The row as written.
        row: String,
    },
}

/// Reads the queries of the file at `path`.
pub fn read_queries(path: &Path) -> Result<Vec<(Pose2, Pose2)>, QueryFileError> {
    let shown = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| QueryFileError::Read {
        path: shown.clone(),
        source,
    })?;
    parse_queries(&text, &shown)
}

/// Parses query rows from `text`; `path` names the source in errors. Blank lines are
/// skipped; a first row that is not numbers is a header.
pub fn parse_queries(text: &str, path: &str) -> Result<Vec<(Pose2, Pose2)>, QueryFileError> {
    let mut queries = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let numbers: Result<Vec<f64>, _> = line.split(',').map(|f| f.trim().parse()).collect();
        match numbers {
            Ok(v) if v.len() == 6 && v.iter().all(|x| x.is_finite()) => {
                queries.push((Pose2::new(v[0], v[1], v[2]), Pose2::new(v[3], v[4], v[5])))
            }
            Err(_) if n == 0 => continue,
            _ => {
                return Err(QueryFileError::Row {
                    path: path.into(),
                    line: n + 1,
                    row: line.chars().take(120).collect(),
                })
            }
        }
    }
    Ok(queries)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_rows_after_a_header_and_names_a_bad_line() {
        let text = "sx,sy,syaw,gx,gy,gyaw\n1,2,0,3,4,0.5\n\n5,6,0,7,8,0\n";
        let queries = parse_queries(text, "q.csv").unwrap();
        assert_eq!(queries.len(), 2);
        assert_eq!(queries[1].1, Pose2::new(7.0, 8.0, 0.0));
        let err = parse_queries("1,2,0,3,4,0\n1,2,inf,3,4,0\n", "q.csv").unwrap_err();
        assert_eq!(
            err.to_string(),
            "q.csv:2: expected six finite numbers sx,sy,syaw,gx,gy,gyaw, got `1,2,inf,3,4,0`"
        );
        assert!(parse_queries("1,2,3\n", "q.csv").is_err());
    }
}
