//! A TSPLIB95 reader (Reinelt 1991; see TSPLIB95's `DOC.PS`).
//!
//! Supported: `TYPE` TSP and ATSP; `EDGE_WEIGHT_TYPE` EUC_2D, CEIL_2D, MAN_2D, MAX_2D,
//! GEO, ATT and EXPLICIT with `EDGE_WEIGHT_FORMAT` FULL_MATRIX, UPPER_ROW, LOWER_ROW,
//! UPPER_DIAG_ROW, LOWER_DIAG_ROW and their column-wise twins. Numbers of a section may
//! wrap across lines arbitrarily. Distances are rounded exactly as TSPLIB defines them, so
//! tour costs are the integers the published optima refer to.
//!
//! Tolerated quirks: diagonal placeholders (9999, 100000000, …) are ignored — the diagonal
//! is always 0; `DIMENSION` wins over the number in the name (ftv33 has 34 nodes); a
//! missing `EOF`; blank lines; `KEY: value`, `KEY : value` and `KEY value`-less sections.

mod cursor;
mod distance;
mod error;
mod tour;

pub(crate) use cursor::Cursor;
pub use cursor::MAX_DIMENSION;
use cursor::{parse_dimension, Located};
use distance::{coordinate_matrix, WeightType};
pub use error::TsplibError;
use smug_core::CostMatrix;
use std::path::Path;
pub use tour::parse_tour;

/// Problem types the reader accepts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProblemType {
    /// Symmetric TSP.
    Tsp,
    /// Asymmetric TSP.
    Atsp,
}

/// A TSPLIB instance: its name and the cost matrix (node `k` of the file is index
/// `k − 1`).
#[derive(Clone, Debug, PartialEq)]
pub struct TsplibInstance {
    /// `NAME` (the file stem if absent).
    pub name: String,
    /// `TYPE`.
    pub problem: ProblemType,
    /// `COMMENT` lines, joined.
    pub comment: String,
    /// How the weights were given, e.g. `EUC_2D` or `EXPLICIT/FULL_MATRIX`.
    pub weights: String,
    /// Costs between nodes, diagonal 0.
    pub costs: CostMatrix,
    /// The `NODE_COORD_SECTION` coordinates, when the file has them (for distances other
    /// than TSPLIB's rounded ones, e.g. the unrounded Euclidean of the mTSP literature).
    pub coords: Option<Vec<(f64, f64)>>,
}

/// Reads a `.tsp` / `.atsp` file.
pub fn read_tsplib(path: impl AsRef<Path>) -> Result<TsplibInstance, TsplibError> {
    let path = path.as_ref();
    let text = read_text(path)?;
    let mut instance = parse_tsplib(&text, &path.display().to_string())?;
    if instance.name.is_empty() {
        instance.name = file_stem(path);
    }
    Ok(instance)
}

/// The file's name without its extension: the name of an instance whose file has no
/// `NAME`.
pub(crate) fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Reads a `.tour` file: the order as 0-based node indices.
pub fn read_tour(path: impl AsRef<Path>) -> Result<Vec<usize>, TsplibError> {
    let path = path.as_ref();
    parse_tour(&read_text(path)?, &path.display().to_string())
}

/// The file's text (bytes that are not UTF-8 replaced).
pub(crate) fn read_text(path: &Path) -> Result<String, TsplibError> {
    let bytes = std::fs::read(path).map_err(|error| TsplibError::Io {
        path: path.display().to_string(),
        error,
    })?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// Layout of an `EDGE_WEIGHT_SECTION` (column-wise formats are read as their row-wise
/// twins: for a symmetric matrix the number sequences coincide).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum WeightFormat {
    FullMatrix,
    UpperRow,
    LowerRow,
    UpperDiagRow,
    LowerDiagRow,
    Function,
}

impl WeightFormat {
    fn value_count(self, n: usize) -> usize {
        match self {
            WeightFormat::FullMatrix => n * n,
            WeightFormat::UpperRow | WeightFormat::LowerRow => n * n.saturating_sub(1) / 2,
            WeightFormat::UpperDiagRow | WeightFormat::LowerDiagRow => n * (n + 1) / 2,
            WeightFormat::Function => 0,
        }
    }

    /// The `(row, column)` cells in the order the section lists them.
    fn cells(self, n: usize) -> Box<dyn Iterator<Item = (usize, usize)>> {
        match self {
            WeightFormat::FullMatrix => {
                Box::new((0..n).flat_map(move |i| (0..n).map(move |j| (i, j))))
            }
            WeightFormat::UpperRow => {
                Box::new((0..n).flat_map(move |i| (i + 1..n).map(move |j| (i, j))))
            }
            WeightFormat::LowerRow => Box::new((0..n).flat_map(|i| (0..i).map(move |j| (i, j)))),
            WeightFormat::UpperDiagRow => {
                Box::new((0..n).flat_map(move |i| (i..n).map(move |j| (i, j))))
            }
            WeightFormat::LowerDiagRow => {
                Box::new((0..n).flat_map(|i| (0..=i).map(move |j| (i, j))))
            }
            WeightFormat::Function => Box::new(std::iter::empty()),
        }
    }
}

/// Keys read before the data sections.
#[derive(Default)]
struct Header {
    name: String,
    problem: Option<ProblemType>,
    comment: Vec<String>,
    dimension: Option<usize>,
    weight_type: Option<WeightType>,
    weight_format: Option<WeightFormat>,
}

/// Parses the text of a `.tsp` / `.atsp` file; `path` is only used in errors.
pub fn parse_tsplib(text: &str, path: &str) -> Result<TsplibInstance, TsplibError> {
    parse_with(text, path, &mut |_, _, _, _| Ok(false))
}

/// A handler of the keys a format adds to TSPLIB (GTSP-LIB's sets): it gets the cursor
/// (positioned after the key's line), the line number, the upper-case key and its value,
/// and returns whether it consumed the key.
pub(crate) type ExtraKeys<'h> =
    dyn FnMut(&mut Cursor, usize, &str, &str) -> Result<bool, TsplibError> + 'h;

/// [`parse_tsplib`] with `extra` offered every key first.
pub(crate) fn parse_with(
    text: &str,
    path: &str,
    extra: &mut ExtraKeys,
) -> Result<TsplibInstance, TsplibError> {
    let mut cursor = Cursor::new(text, path);
    let mut header = Header::default();
    let mut coords: Option<Vec<(f64, f64)>> = None;
    let mut explicit: Option<Vec<Located>> = None;
    while let Some((line, key, value)) = cursor.next_entry() {
        if extra(&mut cursor, line, &key, value)? {
            continue;
        }
        match key.as_str() {
            "EOF" => break,
            "NAME" => header.name = value.to_string(),
            "COMMENT" => header.comment.push(value.to_string()),
            "TYPE" => header.problem = Some(parse_problem(&cursor, line, value)?),
            "DIMENSION" => header.dimension = Some(parse_dimension(&cursor, line, value)?),
            "EDGE_WEIGHT_TYPE" => {
                header.weight_type = Some(parse_weight_type(&cursor, line, value)?)
            }
            "EDGE_WEIGHT_FORMAT" => {
                header.weight_format = Some(parse_weight_format(&cursor, line, value)?)
            }
            "NODE_COORD_TYPE" if value.eq_ignore_ascii_case("TWOD_COORDS") => {}
            "NODE_COORD_TYPE" if value.eq_ignore_ascii_case("NO_COORDS") => {}
            "NODE_COORD_TYPE" => {
                return Err(cursor.syntax(line, format!("NODE_COORD_TYPE {value} is not supported")))
            }
            "DISPLAY_DATA_TYPE" | "CAPACITY" => {}
            "NODE_COORD_SECTION" => {
                let n = dimension_before(&cursor, &header, line, &key)?;
                coords = Some(read_coords(&mut cursor, n)?);
            }
            "EDGE_WEIGHT_SECTION" => {
                let n = dimension_before(&cursor, &header, line, &key)?;
                let format = header.weight_format.ok_or_else(|| {
                    cursor.syntax(line, "EDGE_WEIGHT_SECTION before EDGE_WEIGHT_FORMAT")
                })?;
                explicit = Some(cursor.numbers(format.value_count(n), "EDGE_WEIGHT_SECTION")?);
            }
            "DISPLAY_DATA_SECTION" => {
                let n = dimension_before(&cursor, &header, line, &key)?;
                cursor.numbers(3 * n, "DISPLAY_DATA_SECTION")?;
            }
            _ => return Err(cursor.syntax(line, format!("unknown or unsupported keyword `{key}`"))),
        }
    }
    build_instance(&cursor, header, coords, explicit)
}

/// The problem type: the value's first word (GTSP-LIB files append an author, as in
/// `GTSP (M.~Hofmeister)`); GTSP and AGTSP read as their TSP twins, the sets being a
/// separate section.
fn parse_problem(cursor: &Cursor, line: usize, value: &str) -> Result<ProblemType, TsplibError> {
    let word = value.split_whitespace().next().unwrap_or_default();
    match word.to_ascii_uppercase().as_str() {
        "TSP" | "GTSP" => Ok(ProblemType::Tsp),
        "ATSP" | "AGTSP" => Ok(ProblemType::Atsp),
        other => Err(cursor.syntax(line, format!("TYPE {other} is not supported (TSP or ATSP)"))),
    }
}

fn parse_weight_type(cursor: &Cursor, line: usize, value: &str) -> Result<WeightType, TsplibError> {
    Ok(match value.to_ascii_uppercase().as_str() {
        "EXPLICIT" => WeightType::Explicit,
        "EUC_2D" => WeightType::Euc2d,
        "CEIL_2D" => WeightType::Ceil2d,
        "MAN_2D" => WeightType::Man2d,
        "MAX_2D" => WeightType::Max2d,
        "GEO" => WeightType::Geo,
        "ATT" => WeightType::Att,
        other => {
            return Err(cursor.syntax(line, format!("EDGE_WEIGHT_TYPE {other} is not supported")))
        }
    })
}

fn parse_weight_format(
    cursor: &Cursor,
    line: usize,
    value: &str,
) -> Result<WeightFormat, TsplibError> {
    Ok(match value.to_ascii_uppercase().as_str() {
        "FULL_MATRIX" => WeightFormat::FullMatrix,
        "UPPER_ROW" | "LOWER_COL" => WeightFormat::UpperRow,
        "LOWER_ROW" | "UPPER_COL" => WeightFormat::LowerRow,
        "UPPER_DIAG_ROW" | "LOWER_DIAG_COL" => WeightFormat::UpperDiagRow,
        "LOWER_DIAG_ROW" | "UPPER_DIAG_COL" => WeightFormat::LowerDiagRow,
        "FUNCTION" => WeightFormat::Function,
        other => {
            return Err(cursor.syntax(line, format!("EDGE_WEIGHT_FORMAT {other} is not supported")))
        }
    })
}

fn dimension_before(
    cursor: &Cursor,
    header: &Header,
    line: usize,
    section: &str,
) -> Result<usize, TsplibError> {
    header
        .dimension
        .ok_or_else(|| cursor.syntax(line, format!("{section} before DIMENSION")))
}

/// `n` records `id x y` (ids 1..=n, any order, each once).
fn read_coords(cursor: &mut Cursor, n: usize) -> Result<Vec<(f64, f64)>, TsplibError> {
    let numbers = cursor.numbers(3 * n, "NODE_COORD_SECTION")?;
    let mut coords: Vec<Option<(f64, f64)>> = vec![None; n];
    for record in numbers.chunks_exact(3) {
        let (id, line) = record[0];
        let index = (id.fract() == 0.0 && id >= 1.0 && id <= n as f64)
            .then(|| id as usize - 1)
            .ok_or_else(|| cursor.syntax(line, format!("node id {id} is not in 1..={n}")))?;
        if coords[index].replace((record[1].0, record[2].0)).is_some() {
            return Err(cursor.syntax(line, format!("node {id} appears twice")));
        }
    }
    // n records with distinct ids in 1..=n cover every node.
    Ok(coords.into_iter().map(|c| c.unwrap_or_default()).collect())
}

fn build_instance(
    cursor: &Cursor,
    header: Header,
    coords: Option<Vec<(f64, f64)>>,
    explicit: Option<Vec<Located>>,
) -> Result<TsplibInstance, TsplibError> {
    let problem = header
        .problem
        .ok_or_else(|| cursor.invalid("TYPE is missing"))?;
    let n = header
        .dimension
        .ok_or_else(|| cursor.invalid("DIMENSION is missing"))?;
    let weight_type = header
        .weight_type
        .ok_or_else(|| cursor.invalid("EDGE_WEIGHT_TYPE is missing"))?;
    let (data, weights) = match weight_type {
        WeightType::Explicit => {
            let format = header
                .weight_format
                .filter(|f| *f != WeightFormat::Function)
                .ok_or_else(|| {
                    cursor
                        .invalid("EXPLICIT weights need an EDGE_WEIGHT_FORMAT other than FUNCTION")
                })?;
            let values =
                explicit.ok_or_else(|| cursor.invalid("EDGE_WEIGHT_SECTION is missing"))?;
            (
                fill_explicit(cursor, n, format, &values)?,
                format!("EXPLICIT/{format:?}"),
            )
        }
        kind => {
            let coords = coords
                .as_ref()
                .ok_or_else(|| cursor.invalid("NODE_COORD_SECTION is missing"))?;
            let data = coordinate_matrix(kind, coords);
            if let Some(k) = data.iter().position(|d| !d.is_finite()) {
                return Err(cursor.invalid(format!(
                    "the {kind:?} distance between nodes {} and {} is {}: coordinates this \
                     large overflow",
                    k / n + 1,
                    k % n + 1,
                    data[k]
                )));
            }
            (data, format!("{kind:?}"))
        }
    };
    check_tour_costs_finite(cursor, n, &data)?;
    let costs = CostMatrix::from_rows(n, data).map_err(|e| cursor.invalid(e.to_string()))?;
    Ok(TsplibInstance {
        name: header.name,
        problem,
        comment: header.comment.join(" "),
        weights: weights.to_ascii_uppercase(),
        costs,
        coords,
    })
}

fn fill_explicit(
    cursor: &Cursor,
    n: usize,
    format: WeightFormat,
    values: &[Located],
) -> Result<Vec<f64>, TsplibError> {
    let mut data = vec![0.0; n * n];
    for ((i, j), &(value, line)) in format.cells(n).zip(values) {
        if i == j {
            continue; // diagonal placeholders (9999, 100000000, …) mean nothing
        }
        if value < 0.0 {
            return Err(cursor.syntax(
                line,
                format!(
                    "weight {value} from node {} to {} is negative",
                    i + 1,
                    j + 1
                ),
            ));
        }
        data[i * n + j] = value;
        if format != WeightFormat::FullMatrix {
            data[j * n + i] = value;
        }
    }
    Ok(data)
}

/// Refuses weights so large that a tour's cost (a sum of `n` of them) could overflow.
fn check_tour_costs_finite(cursor: &Cursor, n: usize, data: &[f64]) -> Result<(), TsplibError> {
    let largest = data
        .iter()
        .copied()
        .filter(|w| w.is_finite())
        .fold(0.0, f64::max);
    if (largest * n as f64).is_finite() {
        return Ok(());
    }
    Err(cursor.invalid(format!(
        "a weight of {largest} times {n} nodes overflows: a tour's cost must stay finite"
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinates_whose_distances_or_tours_overflow_are_refused() {
        let instance = |coords: &str| {
            format!(
                "NAME: big\nTYPE: TSP\nDIMENSION: 3\nEDGE_WEIGHT_TYPE: EUC_2D\n\
                 NODE_COORD_SECTION\n{coords}EOF\n"
            )
        };
        let infinite = instance("1 1e308 0\n2 -1e308 0\n3 0 0\n");
        let err = parse_tsplib(&infinite, "big.tsp").unwrap_err().to_string();
        assert!(
            err.contains("big.tsp") && err.contains("nodes 1 and 2"),
            "{err}"
        );
        let tour_overflow = instance("1 4e307 0\n2 -4e307 0\n3 0 0\n");
        let err = parse_tsplib(&tour_overflow, "big.tsp")
            .unwrap_err()
            .to_string();
        assert!(err.contains("overflows"), "{err}");
        assert!(parse_tsplib(&instance("1 1e300 0\n2 -1e300 0\n3 0 0\n"), "ok.tsp").is_ok());
    }

    /// A symmetric 4-node matrix in every explicit layout.
    const MATRIX: [[f64; 4]; 4] = [
        [0.0, 1.0, 2.0, 3.0],
        [1.0, 0.0, 4.0, 5.0],
        [2.0, 4.0, 0.0, 6.0],
        [3.0, 5.0, 6.0, 0.0],
    ];

    fn explicit(format: &str, numbers: &str) -> String {
        format!(
            "NAME: t\nTYPE: TSP\nDIMENSION: 4\nEDGE_WEIGHT_TYPE: EXPLICIT\n\
             EDGE_WEIGHT_FORMAT: {format}\nEDGE_WEIGHT_SECTION\n{numbers}\nEOF\n"
        )
    }

    fn assert_matrix(costs: &CostMatrix) {
        for (i, row) in MATRIX.iter().enumerate() {
            for (j, &value) in row.iter().enumerate() {
                assert_eq!(costs.get(i, j), value, "({i}, {j})");
            }
        }
    }

    #[test]
    fn every_explicit_layout_gives_the_same_matrix() {
        let layouts = [
            (
                "FULL_MATRIX",
                "9999 1 2 3\n1 9999 4\n5 2 4 9999 6 3 5 6 9999",
            ),
            ("UPPER_ROW", "1 2 3\n4 5\n6"),
            ("LOWER_COL", "1 2 3 4 5 6"),
            ("LOWER_ROW", "1\n2 4\n3 5 6"),
            ("UPPER_COL", "1 2\n 4 3 5 6"),
            ("UPPER_DIAG_ROW", "0 1 2 3 0 4 5 0 6 0"),
            ("LOWER_DIAG_COL", "0 1 2 3\n0 4 5\n0 6\n0"),
            ("LOWER_DIAG_ROW", "100000000\n1 0\n2 4 0\n3 5 6 0"),
            ("UPPER_DIAG_COL", "0 1 0 2 4 0 3 5 6 0"),
        ];
        for (format, numbers) in layouts {
            let instance = parse_tsplib(&explicit(format, numbers), format)
                .unwrap_or_else(|e| panic!("{format}: {e}"));
            assert_matrix(&instance.costs);
            assert_eq!(instance.name, "t");
        }
    }

    #[test]
    fn asymmetric_full_matrix_keeps_direction() {
        let text = "NAME:a\nTYPE: ATSP\nDIMENSION: 3\nEDGE_WEIGHT_TYPE: EXPLICIT\n\
                    EDGE_WEIGHT_FORMAT: FULL_MATRIX\nEDGE_WEIGHT_SECTION\n0 1 2\n3 0 4\n5 6 0\n";
        let instance = parse_tsplib(text, "a").unwrap();
        assert_eq!(instance.problem, ProblemType::Atsp);
        assert_eq!(
            (instance.costs.get(0, 1), instance.costs.get(1, 0)),
            (1.0, 3.0)
        );
        assert_eq!(instance.weights, "EXPLICIT/FULLMATRIX");
    }

    fn coordinates(kind: &str, nodes: &str) -> CostMatrix {
        let n = nodes.lines().filter(|l| !l.trim().is_empty()).count();
        let text = format!(
            "NAME : c\nTYPE : TSP\nDIMENSION : {n}\nEDGE_WEIGHT_TYPE : {kind}\nNODE_COORD_SECTION\n{nodes}\n"
        );
        parse_tsplib(&text, kind).unwrap().costs
    }

    #[test]
    fn euclidean_distances_round_as_tsplib_does() {
        let costs = coordinates("EUC_2D", "1 0 0\n2 3 4\n3 0 1.5\n4 0 2.5");
        assert_eq!(costs.get(0, 1), 5.0);
        assert_eq!(costs.get(0, 2), 2.0); // nint(1.5) = 2
        assert_eq!(costs.get(0, 3), 3.0); // nint(2.5) = 3 (half up)
        let costs = coordinates("CEIL_2D", "1 0 0\n2 1 1");
        assert_eq!(costs.get(0, 1), 2.0);
        let costs = coordinates("MAN_2D", "1 0 0\n2 1 2");
        assert_eq!(costs.get(1, 0), 3.0);
        let costs = coordinates("MAX_2D", "1 0 0\n2 1 2");
        assert_eq!(costs.get(1, 0), 2.0);
    }

    #[test]
    fn att_distance_is_the_pseudo_euclidean_one() {
        // r = sqrt(100 / 10) = 3.162…, nint = 3 < r → 4.
        let costs = coordinates("ATT", "1 0 0\n2 6 8");
        assert_eq!(costs.get(0, 1), 4.0);
        // r = sqrt(1000 / 10) = 10 exactly → 10.
        let costs = coordinates("ATT", "1 0 0\n2 30 10");
        assert_eq!(costs.get(0, 1), 10.0);
    }

    #[test]
    fn geo_distances_use_degrees_and_minutes() {
        // On a meridian or the equator: RRR · PI · Δ° / 180 + 1, truncated. 1.00 is 1°
        // (111.32 + 1 → 112); -45.30 is 45° 30' = 45.5° (5065.24 + 1 → 5066), not 45.3°;
        // 0.50 is 50' = 0.833° (92.77 + 1 → 93): its degrees are truncated, not rounded.
        let nodes = "1 0.00 0.00\n2 1.00 0.00\n3 0.00 -45.30\n4 0.50 0.00";
        let costs = coordinates("GEO", nodes);
        assert_eq!(costs.get(0, 3), 93.0);
        assert_eq!(costs.get(0, 1), 112.0);
        assert_eq!(costs.get(0, 2), 5066.0);
        assert_eq!(costs.get(2, 0), 5066.0);
    }

    fn error_of(text: &str) -> String {
        parse_tsplib(text, "f.tsp").unwrap_err().to_string()
    }

    #[test]
    fn malformed_files_name_the_line() {
        let header =
            "NAME: x\nTYPE: TSP\nDIMENSION: 3\nEDGE_WEIGHT_TYPE: EUC_2D\nNODE_COORD_SECTION\n";
        assert_eq!(
            error_of(&format!("{header}1 0 0\n2 zero 1\n3 1 1\n")),
            "f.tsp:7: NODE_COORD_SECTION: `zero` is not a number (found 4 of 9)"
        );
        assert!(error_of(&format!("{header}1 0 0\n2 1 1\n"))
            .starts_with("f.tsp:7: NODE_COORD_SECTION: the file ends"));
        assert!(
            error_of(&format!("{header}1 0 0\n2 1 1\n7 1 1\n")).starts_with("f.tsp:8: node id 7")
        );
        assert!(error_of(&format!("{header}1 0 0\n1 1 1\n3 1 1\n"))
            .starts_with("f.tsp:7: node 1 appears twice"));
        assert!(error_of("NAME: x\nTYPE: CVRP\n").starts_with("f.tsp:2: TYPE CVRP"));
        assert!(error_of("NAME: x\nFOO: 3\n")
            .starts_with("f.tsp:2: unknown or unsupported keyword `FOO`"));
        assert!(error_of("TYPE: TSP\nDIMENSION: -3\n").starts_with("f.tsp:2: DIMENSION"));
        assert!(error_of("DIMENSION: 99999999999\n").contains("above the 20000 nodes"));
        assert!(error_of("TYPE: TSP\nNODE_COORD_SECTION\n")
            .starts_with("f.tsp:2: NODE_COORD_SECTION before DIMENSION"));
        assert_eq!(
            error_of("TYPE: TSP\nDIMENSION: 2\n"),
            "f.tsp: EDGE_WEIGHT_TYPE is missing"
        );
        let negative = explicit("UPPER_ROW", "1 2 3\n4 -5\n6");
        assert!(parse_tsplib(&negative, "n")
            .unwrap_err()
            .to_string()
            .starts_with("n:8: weight -5"));
        let extra = explicit("UPPER_ROW", "1 2 3 4 5 6 7");
        assert!(parse_tsplib(&extra, "e")
            .unwrap_err()
            .to_string()
            .contains("unexpected `7`"));
    }

    #[test]
    fn tours_are_read_zero_based() {
        let text = "NAME : t.tour\nTYPE : TOUR\nDIMENSION : 3\nTOUR_SECTION\n1\n3 2\n-1\nEOF\n";
        assert_eq!(parse_tour(text, "t").unwrap(), vec![0, 2, 1]);
        assert!(parse_tour("DIMENSION : 3\nTOUR_SECTION\n1 1 2 -1\n", "t").is_err());
        assert!(parse_tour("DIMENSION : 3\nTOUR_SECTION\n1 2 3\n", "t").is_err());
    }
}
