//! Sweeps from Python: the runs a sweep expands to and one run's row, as `smug sweep`
//! makes them (the package's `smug.sweep` hands the runs to an executor).

use crate::{ConfigError, InputError};
use pyo3::prelude::*;
use smug_app::sweep::{
    parse_seeds, run_one, GridAxis, RunSpec, RunStatus, Sweep, SweepError, SweepRow,
};
use std::path::PathBuf;

/// The Python exception for a sweep that cannot start: `ConfigError` for seeds, grid
/// and configs, `InputError` for the rows file.
fn sweep_to_py(err: SweepError) -> PyErr {
    match err {
        err @ SweepError::Rows { .. } => InputError::new_err(smug_app::one_line(&err)),
        err => ConfigError::new_err(smug_app::one_line(&err)),
    }
}

/// A run as `(run_id, config, overrides, seed)`.
type RunTuple = (String, String, Vec<String>, u64);

/// Every run of configs × the grid's combinations × seeds, in order, checked as
/// `smug sweep` checks them (a config that does not load with a combination is a
/// `ConfigError` naming the config and the override).
#[pyfunction]
pub fn sweep_runs(
    py: Python<'_>,
    configs: Vec<PathBuf>,
    seeds: Vec<u64>,
    grid: Vec<(String, Vec<String>)>,
) -> PyResult<Vec<RunTuple>> {
    let grid = grid
        .into_iter()
        .map(|(key, values)| GridAxis::new(&key, values))
        .collect::<Result<Vec<_>, _>>()
        .map_err(sweep_to_py)?;
    let sweep = Sweep {
        configs,
        seeds,
        grid,
    };
    let runs = py.detach(|| sweep.runs()).map_err(sweep_to_py)?;
    Ok(runs
        .into_iter()
        .map(|run| {
            let config = run.config.display().to_string();
            (run.run_id, config, run.overrides, run.seed)
        })
        .collect())
}

/// Seeds written as `smug sweep --seeds` takes them: `1..10`, `1,4,9`, `7`.
#[pyfunction]
pub fn sweep_seeds(text: &str) -> PyResult<Vec<u64>> {
    parse_seeds(text).map_err(sweep_to_py)
}

/// One run of a sweep planned on `threads` threads (a pool of its own); its row as
/// JSON, the line `smug sweep` writes for it. A run that fails is a row saying why.
#[pyfunction]
#[pyo3(signature = (config, seed, overrides, threads=1))]
pub fn sweep_task(
    py: Python<'_>,
    config: PathBuf,
    seed: u64,
    overrides: Vec<String>,
    threads: Option<usize>,
) -> PyResult<String> {
    let spec = RunSpec::new(&config, &overrides, seed).map_err(sweep_to_py)?;
    Ok(py.detach(|| run_one(&spec, threads)).to_json_line())
}

/// The row of a run whose task failed outside SMUG (a worker that died, an executor's
/// error), as JSON: status `error` and `message`.
#[pyfunction]
pub fn sweep_failed_row(
    config: PathBuf,
    seed: u64,
    overrides: Vec<String>,
    message: String,
) -> PyResult<String> {
    let spec = RunSpec::new(&config, &overrides, seed).map_err(sweep_to_py)?;
    Ok(SweepRow::failed(&spec, RunStatus::Error, message, 0.0).to_json_line())
}
