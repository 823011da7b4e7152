//! The mTSP suite folder: `instances/` (TSPLIB files, depot = node 1) and
//! `best_known.csv` (columns read by name: `instance, m, objective, best_known, source,
//! distance, set, n, min_size, max_size`, optionally `lkh_claimed` and `verified`), and,
//! when present, `mtsplib_minmax.csv` (the 16 mTSPLib min-max cells with a `status`
//! column marking proven optima; read as the set [`MTSPLIB_MINMAX16`]).

use serde::{Deserialize, Serialize};
use smug_core::{RouteSize, TeamObjective};
use smug_sequencing::team::MtspDistance;
use std::path::{Path, PathBuf};

/// The set name given to the rows of `mtsplib_minmax.csv`.
pub const MTSPLIB_MINMAX16: &str = "mTSPLib-MinMax16";

/// One row of the suite: an instance, a team size and an objective with its best-known
/// value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MtspRow {
    /// The set (column `set`).
    pub set: String,
    /// Instance name (file stem).
    pub instance: String,
    /// Number of salesmen.
    pub m: usize,
    /// `minmax` or `minsum`.
    pub objective: String,
    /// Best-known value.
    pub best_known: f64,
    /// Where the best-known value comes from.
    pub source: String,
    /// `euclid` or `tsplib`.
    pub distance: String,
    /// Route-size bounds, if the row has them.
    pub route_size: Option<RouteSize>,
    /// LKH-3's value from Helsgaun's runAll script, if the row has it.
    pub lkh_claimed: Option<f64>,
    /// `yes` when the best-known value was re-measured from a stored LKH-3 tour.
    pub verified: String,
    /// `optimal …` when the value is proven optimal (mtsplib_minmax.csv only).
    pub status: String,
}

impl MtspRow {
    /// The team objective.
    pub fn team_objective(&self) -> TeamObjective {
        if self.objective == "minsum" {
            TeamObjective::Sum
        } else {
            TeamObjective::Makespan
        }
    }

    /// The distance convention.
    pub fn mtsp_distance(&self) -> MtspDistance {
        if self.distance == "tsplib" {
            MtspDistance::Tsplib
        } else {
            MtspDistance::Euclid
        }
    }
}

#[derive(Deserialize)]
struct CsvRow {
    instance: String,
    m: usize,
    objective: String,
    best_known: f64,
    #[serde(default)]
    source: String,
    #[serde(default)]
    distance: Option<String>,
    #[serde(default)]
    set: Option<String>,
    #[serde(default)]
    min_size: Option<usize>,
    #[serde(default)]
    max_size: Option<usize>,
    #[serde(default)]
    lkh_claimed: Option<f64>,
    #[serde(default)]
    verified: Option<String>,
    #[serde(default)]
    status: Option<String>,
}

/// Every row of `best_known.csv` in `dir`, then those of `mtsplib_minmax.csv` if present.
pub fn load_rows(dir: &Path) -> crate::Result<Vec<MtspRow>> {
    let main = dir.join("best_known.csv");
    crate::error::ensure!(
        main.is_file(),
        "{}: no best_known.csv here (an mTSP suite folder holds instances/ and best_known.csv)",
        dir.display()
    );
    let mut rows = read_csv(&main, None)?;
    let extra = dir.join("mtsplib_minmax.csv");
    if extra.is_file() {
        rows.extend(read_csv(&extra, Some(MTSPLIB_MINMAX16))?);
    }
    Ok(rows)
}

fn read_csv(path: &Path, set: Option<&str>) -> crate::Result<Vec<MtspRow>> {
    let mut reader = csv::Reader::from_path(path)
        .map_err(|e| crate::error::invalid!("{}: {e}", path.display()))?;
    let mut rows = Vec::new();
    for record in reader.deserialize::<CsvRow>() {
        let row = record.map_err(|e| crate::error::invalid!("{}: {e}", path.display()))?;
        crate::error::ensure!(
            row.objective == "minmax" || row.objective == "minsum",
            "{}: instance {} has objective `{}`; expected minmax or minsum",
            path.display(),
            row.instance,
            row.objective
        );
        let route_size = match (row.min_size, row.max_size) {
            (None, None) => None,
            (min, max) => Some(RouteSize {
                min: min.unwrap_or(0),
                max: max.unwrap_or(usize::MAX),
            }),
        };
        rows.push(MtspRow {
            set: set.map(str::to_string).or(row.set).unwrap_or_default(),
            instance: row.instance,
            m: row.m,
            objective: row.objective,
            best_known: row.best_known,
            source: row.source,
            distance: row.distance.unwrap_or_else(|| "euclid".into()),
            route_size,
            lkh_claimed: row.lkh_claimed,
            verified: row.verified.unwrap_or_default(),
            status: row.status.unwrap_or_default(),
        });
    }
    Ok(rows)
}

/// The instance file of `name` in `dir/instances`: `NAME.tsp` or `NAME.atsp`, else a
/// file whose stem matches ignoring case.
pub fn instance_path(dir: &Path, name: &str) -> Option<PathBuf> {
    let folder = dir.join("instances");
    for extension in ["tsp", "atsp"] {
        let path = folder.join(format!("{name}.{extension}"));
        if path.is_file() {
            return Some(path);
        }
    }
    let entries = std::fs::read_dir(&folder).ok()?;
    let mut matches: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let ext_ok = p.extension().is_some_and(|e| e == "tsp" || e == "atsp");
            let stem_ok = p
                .file_stem()
                .is_some_and(|s| s.to_string_lossy().eq_ignore_ascii_case(name));
            ext_ok && stem_ok
        })
        .collect();
    matches.sort();
    matches.into_iter().next()
}

/// `100 · (value − best) / best`.
pub fn gap_percent(value: f64, best: f64) -> f64 {
    100.0 * (value - best) / best
}
