//! Sweeps: configs × seeds × a grid of `--set` overrides, one run each, one row per
//! run; shared by `smug sweep` (local processes) and Python's `smug.sweep` (any
//! executor: processes, Ray, Dask).
//!
//! - [`spec`]: the seeds (`1..10`, `1,4,9`), the grid (`KEY=V1,V2`), the runs they
//!   expand to, each with its [`RunSpec::run_id`] (a hash of the config file's content,
//!   the overrides, the seed and SMUG's version);
//! - [`row`]: what one run reports ([`SweepRow`]: status, error, cost, length, times,
//!   paths planned, the plan's metrics), the same from every front end;
//! - [`run`]: [`run_one`], one run to its row, on a pool of the threads it is given;
//! - [`jsonl`]: rows as JSON lines, and the run ids a file already holds (resume).

pub mod jsonl;
pub mod row;
pub mod run;
pub mod spec;

pub use row::{RunStatus, SweepRow};
pub use run::run_one;
pub use spec::{parse_grid, parse_seeds, GridAxis, RunSpec, Sweep, SweepError};
