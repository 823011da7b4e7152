//! One run of a sweep: its config loaded, its mission planned, its row made; a run
//! that fails is a row saying why, never an error of the sweep.

use super::row::{RunStatus, SweepRow};
use super::spec::RunSpec;
use crate::outcome::{one_line, Outcome};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

/// Plans `spec` and makes its row. `threads`: the run plans on a pool of its own with
/// that many threads (a sweep runs on one thread per run: runs side by side use the
/// cores better than one run's parallel loops); `None`: on rayon's current pool. A
/// config, input or planning error, and a panic, are a row with status `error`.
pub fn run_one(spec: &RunSpec, threads: Option<usize>) -> SweepRow {
    let started = Instant::now();
    let planned = catch_unwind(AssertUnwindSafe(|| on_threads(threads, || plan_row(spec))));
    let seconds = started.elapsed().as_secs_f64();
    let mut row = match planned {
        Ok(Ok(row)) => row,
        Ok(Err(why)) => SweepRow::failed(spec, RunStatus::Error, why, seconds),
        Err(panic) => SweepRow::failed(
            spec,
            RunStatus::Error,
            format!("the run panicked: {}", panic_text(panic.as_ref())),
            seconds,
        ),
    };
    row.total_time_s = seconds;
    row
}

/// The row of `spec` planned, or the error's line.
fn plan_row(spec: &RunSpec) -> Result<SweepRow, String> {
    let loaded = spec.load().map_err(|err| one_line(&err))?;
    let row = match crate::plan::plan(&loaded, None, None).map_err(|err| one_line(&err))? {
        Outcome::Solved(planned) => SweepRow::planned(spec, &planned.plan, 0.0),
        Outcome::NoSolution { why } => SweepRow::no_solution(spec, &why, 0.0),
    };
    Ok(row)
}

/// `work` run on a pool of `threads` threads, or on the current pool.
fn on_threads<T: Send>(
    threads: Option<usize>,
    work: impl FnOnce() -> Result<T, String> + Send,
) -> Result<T, String> {
    let Some(threads) = threads else {
        return work();
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|err| format!("cannot start a pool of {threads} threads: {err}"))?;
    pool.install(work)
}

/// A panic's message, when it is text.
fn panic_text(panic: &(dyn std::any::Any + Send)) -> &str {
    panic
        .downcast_ref::<&str>()
        .copied()
        .or_else(|| panic.downcast_ref::<String>().map(String::as_str))
        .unwrap_or("(no message)")
}
