//! What `smug bench paper` runs and measures: its experiments and runs (read by the
//! harness and by its report).

use serde::Serialize;
use smug_core::TimeBreakdown;
use std::collections::BTreeMap;

/// One experiment: a config, overrides, and where it goes in the report.
#[derive(Clone, Debug, Serialize)]
pub struct Experiment {
    /// Stable key, e.g. `lunar/idp` or `scalability/48/dp`.
    pub key: String,
    /// The config file, relative to `--configs`.
    pub config: String,
    /// `--set` overrides.
    pub set: Vec<String>,
}

/// One planning run's numbers.
#[derive(Clone, Debug, Serialize)]
pub struct Run {
    /// The experiment's key.
    pub experiment: String,
    /// The config seed.
    pub seed: u64,
    /// Why the run failed, if it did (then the numbers are zero).
    pub error: Option<String>,
    /// Plan cost.
    pub cost: f64,
    /// Planning time: sequencing + selection + post-processing (what the paper times).
    pub planning_s: f64,
    /// End to end, with building the world, traversability and distance field.
    pub total_s: f64,
    /// Point-to-point paths planned.
    pub paths_planned: u64,
    /// State validity queries.
    pub validity_queries: u64,
    /// The planner's time breakdown.
    pub breakdown: TimeBreakdown,
    /// Every stage time and counter of the plan.
    pub stage_times_s: BTreeMap<String, f64>,
    /// The planner's and checkers' counters.
    pub counters: BTreeMap<String, u64>,
}

/// The whole benchmark: settings and raw runs (written as JSON).
#[derive(Debug, Serialize)]
pub struct PaperBench {
    /// Runs per experiment.
    pub runs: u64,
    /// Whether every seed had its own world.
    pub vary_world: bool,
    /// Whether this was the `--quick` smoke version.
    pub quick: bool,
    /// The experiments, in report order.
    pub experiments: Vec<Experiment>,
    /// Every run.
    pub raw: Vec<Run>,
}

impl PaperBench {
    /// The successful runs of one experiment.
    pub fn runs_of<'a>(&'a self, key: &'a str) -> impl Iterator<Item = &'a Run> + 'a {
        self.raw
            .iter()
            .filter(move |r| r.experiment == key && r.error.is_none())
    }
}

/// The selectors of Tables I and IV, in the paper's column order.
pub const SELECTORS: [&str; 3] = ["dp", "idp", "irba"];
/// The scalability sizes of Table IV (ToIs, 6 PoIs each).
pub const SCALABILITY: [usize; 4] = [6, 12, 24, 48];
/// The validity settings of Table II: (key, label, config, overrides).
pub const VALIDITY: [(&str, &str, &str, &str); 3] = [
    (
        "validity/0.3-0.3",
        "hierarchical 0.3 / 0.3",
        "lunar.toml",
        "",
    ),
    (
        "validity/0.3-0.8",
        "hierarchical 0.3 / 0.8",
        "lunar.toml",
        "validity.params.t_high=0.8",
    ),
    (
        "validity/full",
        "full collision",
        "lunar-full-collision.toml",
        "",
    ),
];
