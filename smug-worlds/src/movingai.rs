//! MovingAI grid benchmarks (<https://movingai.com/benchmarks/formats.html>): `.map`
//! and `.scen` readers and a converter to the map format of [`crate::map_file`].
//!
//! # Coordinates
//!
//! A MovingAI cell `(x, y)` is column `x` and row `y`, both 0-based, with row 0 at the
//! **top** of the map. [`convert_movingai`] writes the map with origin `[0, 0]` and
//! `resolution` metres per cell, so MovingAI row 0 becomes the top row of the world
//! (largest y). The centre of MovingAI cell `(sx, sy)` of a map `H` rows high lies at
//!
//! ```text
//! world x = (sx + 0.5) · resolution
//! world y = (H − 1 − sy + 0.5) · resolution
//! ```
//!
//! which [`scenario_to_world`] computes (and [`world_to_scenario`] inverts). Scenario
//! path lengths are in cells: multiply by `resolution` for metres.
//!
//! Besides reading, this module writes both formats ([`write_map`],
//! [`write_scenarios`]), computes optimal octile lengths ([`octile_distances`]) and
//! draws scenarios on a map ([`generate_scenarios`]).

mod octile;
mod scen_gen;
mod write;

pub use octile::{octile_distances, octile_length, SQRT_2};
pub use scen_gen::{generate_scenarios, ScenarioGenError};
pub use write::{
    convert_movingai, format_map, format_scenarios, grid_to_map_yaml, write_map, write_scenarios,
};

use crate::export::ExportError;
use std::path::{Path, PathBuf};

/// Why a MovingAI file could not be read or converted.
#[derive(Debug, thiserror::Error)]
pub enum MovingAiError {
    /// The file could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file is malformed.
    #[error("{}:{line}: {message}", path.display())]
    Syntax {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A conversion parameter is out of its domain.
    #[error("{}: {message}", path.display())]
    Invalid {
        /// The file being converted.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// Writing the converted map failed.
    #[error(transparent)]
    Write(#[from] ExportError),
}

/// A MovingAI grid map: which cells are passable, row 0 at the top.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MovingAiMap {
    /// Number of columns.
    pub width: usize,
    /// Number of rows.
    pub height: usize,
    /// Passability of cell `(x, y)` at index `y · width + x` (row 0 = top).
    pub passable: Vec<bool>,
}

impl MovingAiMap {
    /// A `width` × `height` map whose cells are all passable (`true`) or all blocked.
    pub fn filled(width: usize, height: usize, passable: bool) -> Self {
        Self {
            width,
            height,
            passable: vec![passable; width * height],
        }
    }

    /// True when cell `(x, y)` exists and is passable.
    pub fn is_passable(&self, x: usize, y: usize) -> bool {
        x < self.width && y < self.height && self.passable[y * self.width + x]
    }

    /// Makes cell `(x, y)` passable or blocked; cells outside the map are ignored.
    pub fn set_passable(&mut self, x: usize, y: usize, passable: bool) {
        if x < self.width && y < self.height {
            self.passable[y * self.width + x] = passable;
        }
    }

    /// The number of passable cells.
    pub fn passable_count(&self) -> usize {
        self.passable.iter().filter(|&&p| p).count()
    }
}

/// One scenario (one line of a `.scen` file): a start and a goal cell on a map.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Difficulty bucket.
    pub bucket: u32,
    /// The map's file name, as written.
    pub map: String,
    /// The map's width in cells.
    pub width: usize,
    /// The map's height in cells.
    pub height: usize,
    /// Start cell `(x, y)`, row 0 at the top.
    pub start: [usize; 2],
    /// Goal cell `(x, y)`, row 0 at the top.
    pub goal: [usize; 2],
    /// Optimal 8-connected path length (no corner cutting), in cells.
    pub optimal_length: f64,
}

/// The world coordinates of the centre of MovingAI cell `cell = (x, y)` on a map
/// `map_height` rows high, converted at `resolution` metres per cell with origin `[0, 0]`.
pub fn scenario_to_world(cell: [usize; 2], map_height: usize, resolution: f64) -> [f64; 2] {
    let [x, y] = cell;
    [
        (x as f64 + 0.5) * resolution,
        (map_height as f64 - 1.0 - y as f64 + 0.5) * resolution,
    ]
}

/// The MovingAI cell `(x, y)` containing world point `point` (inverse of
/// [`scenario_to_world`]); `None` outside a `width` × `map_height` map.
pub fn world_to_scenario(
    point: [f64; 2],
    width: usize,
    map_height: usize,
    resolution: f64,
) -> Option<[usize; 2]> {
    let column = point[0] / resolution;
    let row_from_bottom = point[1] / resolution;
    if !(column >= 0.0 && row_from_bottom >= 0.0) {
        return None;
    }
    let (x, j) = (column as usize, row_from_bottom as usize);
    (x < width && j < map_height).then(|| [x, map_height - 1 - j])
}

/// Reads a `.map` file.
pub fn read_map(path: &Path) -> Result<MovingAiMap, MovingAiError> {
    parse_map(&read_text(path)?, path)
}

/// Parses the text of a `.map` file; `path` names it in errors.
pub fn parse_map(text: &str, path: &Path) -> Result<MovingAiMap, MovingAiError> {
    let syntax = |line: usize, message: String| MovingAiError::Syntax {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut lines = text.lines().map(|l| l.trim_end_matches('\r')).enumerate();
    let mut next_line = |expected: &str| {
        lines
            .next()
            .map(|(k, line)| (k + 1, line))
            .ok_or_else(|| syntax(text.lines().count() + 1, format!("missing {expected}")))
    };
    let (line, type_line) = next_line("`type octile` line")?;
    if type_line.split_whitespace().collect::<Vec<_>>() != ["type", "octile"] {
        return Err(syntax(
            line,
            format!("expected `type octile`, got `{type_line}`"),
        ));
    }
    let mut width = None;
    let mut height = None;
    let map_line = loop {
        let (line, header) = next_line("`map` line")?;
        let words: Vec<&str> = header.split_whitespace().collect();
        match words.as_slice() {
            ["map"] => break line,
            ["height", n] => {
                height = Some(parse_dimension(n).map_err(|m| syntax(line, m.to_string()))?)
            }
            ["width", n] => {
                width = Some(parse_dimension(n).map_err(|m| syntax(line, m.to_string()))?)
            }
            _ => {
                return Err(syntax(
                    line,
                    format!("expected `height N`, `width N` or `map`, got `{header}`"),
                ))
            }
        }
    };
    let (Some(width), Some(height)) = (width, height) else {
        return Err(syntax(
            map_line,
            "the header needs `height` and `width`".into(),
        ));
    };
    let mut passable = Vec::new();
    for row in 0..height {
        let (line, text) = next_line(&format!("row {row} of {height}"))?;
        passable.extend(parse_row(text, width).map_err(|m| syntax(line, m.to_string()))?);
    }
    if let Some((k, extra)) = lines.find(|(_, l)| !l.trim().is_empty()) {
        return Err(syntax(
            k + 1,
            format!("extra line after {height} rows: `{extra}`"),
        ));
    }
    Ok(MovingAiMap {
        width,
        height,
        passable,
    })
}

/// What is wrong on one line of a `.map` or `.scen` file (the line and the file are
/// added by [`MovingAiError::Syntax`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
enum LineError {
    /// A map size that is not a positive whole number.
    #[error("expected a positive whole number, got `{0}`")]
    Dimension(String),
    /// A map row of another width than the header's.
    #[error("row has {got} cells, the header says width {width}")]
    RowWidth {
        /// Cells on the row.
        got: usize,
        /// The header's width.
        width: usize,
    },
    /// A terrain character MovingAI does not define.
    #[error("unknown terrain `{terrain}` in column {column} (expected one of . G S @ O T W)")]
    Terrain {
        /// The character, escaped.
        terrain: String,
        /// 1-based column.
        column: usize,
    },
    /// A scenario line without its 9 fields.
    #[error(
        "expected 9 fields (bucket map width height start_x start_y goal_x goal_y \
         optimal_length), got {0}"
    )]
    Fields(usize),
    /// A field that must be a whole number.
    #[error("`{name}` must be a whole number ≥ 0, got `{word}`")]
    Whole {
        /// The field.
        name: &'static str,
        /// Its text.
        word: String,
    },
    /// An optimal length that is not a number ≥ 0.
    #[error("`optimal_length` must be a number ≥ 0, got `{0}`")]
    Length(String),
    /// A scenario's start or goal off its map.
    #[error("start {start:?} or goal {goal:?} lies outside the {width}×{height} map")]
    Outside {
        /// The start cell.
        start: [usize; 2],
        /// The goal cell.
        goal: [usize; 2],
        /// The map's width.
        width: usize,
        /// The map's height.
        height: usize,
    },
}

fn parse_dimension(word: &str) -> Result<usize, LineError> {
    match word.parse::<usize>() {
        Ok(n) if n > 0 => Ok(n),
        _ => Err(LineError::Dimension(word.to_string())),
    }
}

/// The passability of one map row.
fn parse_row(text: &str, width: usize) -> Result<Vec<bool>, LineError> {
    let cells: Vec<char> = text.chars().collect();
    if cells.len() != width {
        return Err(LineError::RowWidth {
            got: cells.len(),
            width,
        });
    }
    cells
        .iter()
        .enumerate()
        .map(|(column, &c)| match c {
            '.' | 'G' | 'S' => Ok(true),
            '@' | 'O' | 'T' | 'W' => Ok(false),
            other => Err(LineError::Terrain {
                terrain: other.escape_debug().to_string(),
                column: column + 1,
            }),
        })
        .collect()
}

/// Reads a `.scen` file.
pub fn read_scenarios(path: &Path) -> Result<Vec<Scenario>, MovingAiError> {
    parse_scenarios(&read_text(path)?, path)
}

/// Parses the text of a `.scen` file; `path` names it in errors.
pub fn parse_scenarios(text: &str, path: &Path) -> Result<Vec<Scenario>, MovingAiError> {
    let syntax = |line: usize, message: String| MovingAiError::Syntax {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut lines = text.lines().map(|l| l.trim_end_matches('\r')).enumerate();
    match lines.next() {
        Some((_, first)) if first.split_whitespace().collect::<Vec<_>>() == ["version", "1"] => {}
        Some((_, first)) => return Err(syntax(1, format!("expected `version 1`, got `{first}`"))),
        None => return Err(syntax(1, "empty file, expected `version 1`".into())),
    }
    lines
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(k, l)| parse_scenario(l).map_err(|m| syntax(k + 1, m.to_string())))
        .collect()
}

fn parse_scenario(line: &str) -> Result<Scenario, LineError> {
    let fields: Vec<&str> = line.split('\t').map(str::trim).collect();
    let fields: Vec<&str> = if fields.len() == 9 {
        fields
    } else {
        line.split_whitespace().collect()
    };
    let [bucket, map, width, height, sx, sy, gx, gy, length] = fields.as_slice() else {
        return Err(LineError::Fields(fields.len()));
    };
    let whole = |name: &'static str, word: &str| {
        word.parse::<usize>().map_err(|_| LineError::Whole {
            name,
            word: word.to_string(),
        })
    };
    let scenario = Scenario {
        bucket: whole("bucket", bucket)? as u32,
        map: map.to_string(),
        width: whole("width", width)?,
        height: whole("height", height)?,
        start: [whole("start_x", sx)?, whole("start_y", sy)?],
        goal: [whole("goal_x", gx)?, whole("goal_y", gy)?],
        optimal_length: length
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && *v >= 0.0)
            .ok_or_else(|| LineError::Length(length.to_string()))?,
    };
    let inside = |[x, y]: [usize; 2]| x < scenario.width && y < scenario.height;
    if !(inside(scenario.start) && inside(scenario.goal)) {
        return Err(LineError::Outside {
            start: scenario.start,
            goal: scenario.goal,
            width: scenario.width,
            height: scenario.height,
        });
    }
    Ok(scenario)
}

fn read_text(path: &Path) -> Result<String, MovingAiError> {
    std::fs::read_to_string(path).map_err(|source| MovingAiError::Read {
        path: path.to_path_buf(),
        source,
    })
}

/// Fails unless `resolution` is a finite number > 0; `path` names the input in errors.
fn check_resolution(resolution: f64, path: &Path) -> Result<(), MovingAiError> {
    if resolution.is_finite() && resolution > 0.0 {
        Ok(())
    } else {
        Err(MovingAiError::Invalid {
            path: path.to_path_buf(),
            message: format!("resolution must be a finite number > 0, got {resolution}"),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MAP: &str = "type octile\nheight 2\nwidth 3\nmap\n.@T\nGS.\n";

    #[test]
    fn parses_maps_with_top_row_first() {
        let map = parse_map(MAP, Path::new("m.map")).unwrap();
        assert_eq!((map.width, map.height), (3, 2));
        assert!(map.is_passable(0, 0) && !map.is_passable(1, 0) && !map.is_passable(2, 0));
        assert!(map.is_passable(1, 1) && !map.is_passable(3, 1));
        let crlf = MAP.replace('\n', "\r\n");
        assert_eq!(parse_map(&crlf, Path::new("m.map")).unwrap(), map);
    }

    #[test]
    fn map_errors_name_file_and_line() {
        let cases = [
            (
                MAP.replace(".@T", ".x."),
                "m.map:5: unknown terrain `x` in column 2",
            ),
            (MAP.replace(".@T", ".@"), "m.map:5: row has 2 cells"),
            (MAP.replace("GS.\n", ""), "m.map:6: missing row 1 of 2"),
            (
                MAP.replace("octile", "tile"),
                "m.map:1: expected `type octile`",
            ),
            (
                MAP.replace("width 3", "width -3"),
                "m.map:3: expected a positive",
            ),
            (format!("{MAP}...\n"), "m.map:7: extra line"),
            (
                MAP.replace("height 2", "height 4000000000"),
                "m.map:7: missing row 2 of 4000000000",
            ),
        ];
        for (text, needle) in cases {
            let err = parse_map(&text, Path::new("m.map"))
                .unwrap_err()
                .to_string();
            assert!(err.starts_with(needle), "{err}");
        }
    }

    #[test]
    fn parses_scenarios() {
        let text = "version 1\n3\tm.map\t3\t2\t0\t1\t2\t1\t2.5\n\n";
        let s = parse_scenarios(text, Path::new("m.scen")).unwrap();
        assert_eq!(s.len(), 1);
        assert_eq!(
            (s[0].start, s[0].goal, s[0].optimal_length),
            ([0, 1], [2, 1], 2.5)
        );
        let err = parse_scenarios(
            "version 1\n3\tm.map\t3\t2\t0\t5\t2\t1\t2.5\n",
            Path::new("m.scen"),
        )
        .unwrap_err()
        .to_string();
        assert!(err.starts_with("m.scen:2: start [0, 5]"), "{err}");
        assert!(parse_scenarios("version 2\n", Path::new("m.scen")).is_err());
    }

    #[test]
    fn scenario_cells_map_to_world_centres_and_back() {
        assert_eq!(scenario_to_world([0, 0], 4, 0.5), [0.25, 1.75]);
        assert_eq!(scenario_to_world([2, 3], 4, 0.5), [1.25, 0.25]);
        for cell in [[0, 0], [2, 3], [1, 2]] {
            let p = scenario_to_world(cell, 4, 0.5);
            assert_eq!(world_to_scenario(p, 3, 4, 0.5), Some(cell));
        }
        assert_eq!(world_to_scenario([-0.1, 0.0], 3, 4, 0.5), None);
    }
}
