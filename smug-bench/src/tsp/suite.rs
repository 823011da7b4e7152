//! The TSPLIB benchmark suite: instances with proven optima, and gap measurement.
//!
//! A suite directory holds `tsp/` and `atsp/`, each with instance files and an
//! `optima.csv` whose columns include `name` and `optimal_tour_length`. The project
//! ships no suite: see [`SUITE_DESCRIPTION`] for where TSPLIB95 is published, and
//! [`suite_dir`] for how a folder is found.

use serde::Serialize;
use smug_core::{CostMatrix, Sequencer, TourKind};
use smug_sequencing::tsplib::{ProblemType, TsplibError};
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The environment variable naming a data folder; the TSPLIB suite is its `tsplib/`.
pub const DATA_ENV: &str = "SMUG_DATA";

/// What a suite folder holds and where the instances are published (for messages).
pub const SUITE_DESCRIPTION: &str = "the suite is TSPLIB95 (G. Reinelt, Universität Heidelberg; \
published at http://comopt.ifi.uni-heidelberg.de/software/TSPLIB95/), laid out as \
DIR/tsp/NAME.tsp and DIR/atsp/NAME.atsp, each folder with an optima.csv whose columns \
include name and optimal_tour_length (the optima TSPLIB95 lists)";

/// The suite folder: `given` (a `--data DIR` option) if any, else `tsplib/` inside the
/// folder that `data_env` (the value of [`DATA_ENV`]) names; `None` when neither is set.
pub fn suite_dir(given: Option<&Path>, data_env: Option<&OsStr>) -> Option<PathBuf> {
    given.map(Path::to_path_buf).or_else(|| {
        data_env
            .filter(|value| !value.is_empty())
            .map(|value| Path::new(value).join("tsplib"))
    })
}

/// An instance of the suite and its optimal tour length.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchInstance {
    /// Instance name (file stem).
    pub name: String,
    /// The instance file.
    pub path: PathBuf,
    /// Symmetric or asymmetric.
    pub problem: ProblemType,
    /// Proven optimal tour length.
    pub optimum: f64,
}

/// One solver run on one instance.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BenchResult {
    /// Instance name.
    pub instance: String,
    /// The solver's name.
    pub solver: String,
    /// True for ATSP instances.
    pub asymmetric: bool,
    /// Number of nodes.
    pub n: usize,
    /// Proven optimum.
    pub optimum: f64,
    /// The time budget the solver was given, in seconds.
    pub budget_s: f64,
    /// Cost of the tour found.
    pub cost: f64,
    /// `100 · (cost − optimum) / optimum`.
    pub gap_percent: f64,
    /// Wall time of the solve, in seconds.
    pub time_s: f64,
    /// The tour, 0-based, starting at node 0.
    pub tour: Vec<usize>,
}

/// The instances of the suite in `dir` (`tsp/` first, then `atsp/`), in the order of
/// their `optima.csv` files. A missing sub-directory is skipped.
pub fn load_suite(dir: &Path) -> Result<Vec<BenchInstance>, TsplibError> {
    let mut instances = Vec::new();
    for (sub, extension, problem) in [
        ("tsp", "tsp", ProblemType::Tsp),
        ("atsp", "atsp", ProblemType::Atsp),
    ] {
        let folder = dir.join(sub);
        let csv = folder.join("optima.csv");
        if !csv.exists() {
            continue;
        }
        let text = std::fs::read_to_string(&csv).map_err(|error| TsplibError::Io {
            path: csv.display().to_string(),
            error,
        })?;
        for (name, optimum) in parse_optima(&text, &csv.display().to_string())? {
            instances.push(BenchInstance {
                path: folder.join(format!("{name}.{extension}")),
                name,
                problem,
                optimum,
            });
        }
    }
    if instances.is_empty() {
        return Err(TsplibError::Invalid {
            path: dir.display().to_string(),
            message: "no tsp/optima.csv or atsp/optima.csv here".into(),
        });
    }
    Ok(instances)
}

/// `(name, optimal_tour_length)` rows of an optima CSV (simple CSV: no quoted commas).
fn parse_optima(text: &str, path: &str) -> Result<Vec<(String, f64)>, TsplibError> {
    csv_rows(text, path, &["name", "optimal_tour_length"])?
        .into_iter()
        .map(|(line, fields)| match fields[1].parse::<f64>() {
            Ok(value) if !fields[0].is_empty() => Ok((fields[0].clone(), value)),
            _ => Err(TsplibError::Syntax {
                path: path.to_string(),
                line,
                message: "expected a name and a numeric optimal_tour_length".into(),
            }),
        })
        .collect()
}

/// The fields `columns` (named in the header line) of every non-blank row of a simple
/// CSV (no quoted commas), with each row's 1-based line number; a missing field is
/// empty.
pub(crate) fn csv_rows(
    text: &str,
    path: &str,
    columns: &[&str],
) -> Result<Vec<(usize, Vec<String>)>, TsplibError> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let header: Vec<&str> = lines
        .next()
        .map(|(_, l)| l.split(',').map(str::trim).collect())
        .unwrap_or_default();
    let positions = columns
        .iter()
        .map(|name| {
            header
                .iter()
                .position(|h| h == name)
                .ok_or_else(|| TsplibError::Invalid {
                    path: path.to_string(),
                    message: format!("no `{name}` column in the header"),
                })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(lines
        .map(|(index, line)| {
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            let picked = positions
                .iter()
                .map(|&k| fields.get(k).copied().unwrap_or_default().to_string())
                .collect();
            (index + 1, picked)
        })
        .collect())
}

/// Relative excess over the optimum, in percent.
pub fn gap_percent(cost: f64, optimum: f64) -> f64 {
    if optimum == 0.0 {
        if cost == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    } else {
        100.0 * (cost - optimum) / optimum
    }
}

impl BenchResult {
    /// The record of the closed tour `order` that `solver` found on `instance` (whose
    /// matrix is `costs`) in `time_s` seconds with a budget of `budget_s`.
    pub fn new(
        instance: &BenchInstance,
        costs: &CostMatrix,
        solver: &str,
        budget_s: f64,
        order: Vec<usize>,
        time_s: f64,
    ) -> Self {
        let cost = costs.tour_cost(&order, TourKind::Closed);
        Self {
            instance: instance.name.clone(),
            solver: solver.to_string(),
            asymmetric: instance.problem == ProblemType::Atsp,
            n: costs.len(),
            optimum: instance.optimum,
            budget_s,
            cost,
            gap_percent: gap_percent(cost, instance.optimum),
            time_s,
            tour: order,
        }
    }
}

/// Solves `costs` (the instance's matrix) as a closed tour with `solver` (called
/// `solver_name` in the record) and measures it.
pub fn run_instance(
    instance: &BenchInstance,
    costs: &CostMatrix,
    solver: &dyn Sequencer,
    solver_name: &str,
    budget_s: f64,
) -> smug_core::Result<BenchResult> {
    let started = Instant::now();
    let tour = solver.solve(costs, TourKind::Closed)?;
    let time_s = started.elapsed().as_secs_f64();
    Ok(BenchResult::new(
        instance,
        costs,
        solver_name,
        budget_s,
        tour.order,
        time_s,
    ))
}

/// The suite folder from `--data DIR`, else `$SMUG_DATA/tsplib`; neither is an error
/// that says where the suite comes from.
pub fn require_suite_dir(data: Option<&Path>) -> crate::Result<PathBuf> {
    suite_dir(data, std::env::var_os(DATA_ENV).as_deref()).ok_or_else(|| {
        crate::error::invalid!(
            "no TSPLIB suite given: pass --data DIR or set {DATA_ENV} (the suite is then \
             ${DATA_ENV}/tsplib); {SUITE_DESCRIPTION}"
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_optima_columns_by_name() {
        let text = "name,dimension,optimal_tour_length,note\nring5,6,21,x\n\ngrid4x4,16,160,\n";
        let rows = parse_optima(text, "optima.csv").unwrap();
        assert_eq!(
            rows,
            vec![("ring5".to_string(), 21.0), ("grid4x4".to_string(), 160.0)]
        );
        let err = parse_optima("name,optimal_tour_length\nx,y\n", "o.csv").unwrap_err();
        assert!(err.to_string().starts_with("o.csv:2:"), "{err}");
        assert!(parse_optima("name\n", "o.csv").is_err());
    }

    #[test]
    fn the_option_wins_over_the_environment() {
        let env = Some(OsStr::new("/data"));
        assert_eq!(
            suite_dir(Some(Path::new("suite")), env),
            Some(PathBuf::from("suite"))
        );
        assert_eq!(suite_dir(None, env), Some(PathBuf::from("/data/tsplib")));
        assert_eq!(suite_dir(None, Some(OsStr::new(""))), None);
        assert_eq!(suite_dir(None, None), None);
    }

    #[test]
    fn gaps() {
        assert_eq!(gap_percent(110.0, 100.0), 10.0);
        assert_eq!(gap_percent(0.0, 0.0), 0.0);
    }
}
