//! The GTSP-LIB benchmark suite: instances with optimal or best-known values, and gap
//! measurement.
//!
//! A suite directory holds `values.csv` with the columns `instance`, `file` (a path
//! relative to the folder; anything after its first space is ignored), `n` and
//! `value`. The project ships no suite: see [`GTSP_SUITE_DESCRIPTION`].

use crate::tsp::suite::{csv_rows, gap_percent};
use serde::Serialize;
use smug_core::{Sequencer, TourKind};
use smug_sequencing::gtsplib::GtspInstance;
use smug_sequencing::tsplib::TsplibError;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What a GTSP suite folder holds (for messages).
pub const GTSP_SUITE_DESCRIPTION: &str = "the suite is GTSP-LIB (Fischetti, Salazar-González \
and Toth 1997: clustered TSPLIB instances; best-known values as published with GLNS, Smith \
and Imeson 2017), laid out as DIR/values.csv with the columns instance, file (relative to \
DIR), n and value";

/// An instance of the suite and its optimal or best-known tour length.
#[derive(Clone, Debug, PartialEq)]
pub struct GtspBenchInstance {
    /// Instance name.
    pub name: String,
    /// The instance file.
    pub path: PathBuf,
    /// Number of nodes.
    pub n: usize,
    /// Optimal or best-known tour length.
    pub value: f64,
}

/// One solver run on one instance.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GtspBenchResult {
    /// Instance name.
    pub instance: String,
    /// Number of nodes.
    pub n: usize,
    /// Number of clusters.
    pub m: usize,
    /// Optimal or best-known value.
    pub value: f64,
    /// The time budget in seconds.
    pub budget_s: f64,
    /// Cost of the tour found.
    pub cost: f64,
    /// `100 · (cost − value) / value`.
    pub gap_percent: f64,
    /// Wall time of the solve, in seconds.
    pub time_s: f64,
    /// The tour: one node per cluster, 0-based, starting in cluster 0.
    pub tour: Vec<usize>,
}

/// The instances listed in `dir/values.csv`, in its order.
pub fn load_gtsp_suite(dir: &Path) -> Result<Vec<GtspBenchInstance>, TsplibError> {
    let csv = dir.join("values.csv");
    let path = csv.display().to_string();
    let text = std::fs::read_to_string(&csv).map_err(|error| TsplibError::Io {
        path: path.clone(),
        error,
    })?;
    csv_rows(&text, &path, &["instance", "file", "n", "value"])?
        .into_iter()
        .map(|(line, fields)| {
            let file = fields[1].split_whitespace().next().unwrap_or_default();
            match (fields[2].parse::<usize>(), fields[3].parse::<f64>()) {
                (Ok(n), Ok(value)) if !fields[0].is_empty() && !file.is_empty() => {
                    Ok(GtspBenchInstance {
                        name: fields[0].clone(),
                        path: dir.join(file),
                        n,
                        value,
                    })
                }
                _ => Err(TsplibError::Syntax {
                    path: path.clone(),
                    line,
                    message: "expected an instance name, a file, an integer n and a numeric \
                              value"
                        .into(),
                }),
            }
        })
        .collect()
}

/// Solves `instance` (read as `gtsp`) as a closed tour with `solver` and measures it.
pub fn run_gtsp_instance(
    instance: &GtspBenchInstance,
    gtsp: &GtspInstance,
    solver: &dyn Sequencer,
    budget_s: f64,
) -> smug_core::Result<GtspBenchResult> {
    let started = Instant::now();
    let tour = solver.solve_clusters(&gtsp.costs, &gtsp.clusters, TourKind::Closed)?;
    let time_s = started.elapsed().as_secs_f64();
    Ok(GtspBenchResult {
        instance: instance.name.clone(),
        n: gtsp.costs.len(),
        m: gtsp.clusters.len(),
        value: instance.value,
        budget_s,
        cost: tour.cost,
        gap_percent: gap_percent(tour.cost, instance.value),
        time_s,
        tour: tour.order,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_values_table() {
        let dir = std::env::temp_dir().join(format!("smug-gtsp-suite-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("values.csv"),
            "instance,file,n,m,value\n3a6,sub/3a6.gtsp (copy),6,3,42\n",
        )
        .unwrap();
        let suite = load_gtsp_suite(&dir).unwrap();
        assert_eq!(suite[0].name, "3a6");
        assert_eq!(suite[0].path, dir.join("sub/3a6.gtsp"));
        assert_eq!((suite[0].n, suite[0].value), (6, 42.0));
        std::fs::write(dir.join("values.csv"), "instance,file,n,value\nx,f,6,big\n").unwrap();
        let err = load_gtsp_suite(&dir).unwrap_err().to_string();
        assert!(
            err.ends_with(
                "values.csv:2: expected an instance name, a file, an integer n and a numeric value"
            ),
            "{err}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
