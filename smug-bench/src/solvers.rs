//! TSP / GTSP solvers by plugin name, built through the sequencer registry with a
//! budget and a seed (for `smug tsp` and `smug bench tsp`).

use smug_core::registry::{SequencerStage, Stage};
use smug_core::{BuildContext, PluginSection, RobotConfig, Sequencer};

/// The registry's TSP solvers that `smug tsp` and `smug bench tsp` offer, in the order
/// their `--help` lists them.
pub const TSP_SOLVERS: [&str; 4] = ["auto", "held-karp", "local-search", "brute-force"];

/// The registry's GTSP solvers that `smug gtsp` offers, in the order its `--help` lists
/// them.
pub const GTSP_SOLVERS: [&str; 2] = ["gtsp-lns", "gtsp-exact"];

/// Budget and seed for [`sequencer`]; solvers without a budget ignore it.
#[derive(Clone, Debug, PartialEq)]
pub struct SolverOptions {
    /// Wall-time budget in seconds (0 = none).
    pub time_limit_s: f64,
    /// Budget of search rounds (`None`: no limit).
    pub max_iterations: Option<u64>,
    /// Seed (the solver's generator is derived from it as a pipeline would).
    pub seed: u64,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            time_limit_s: 1.0,
            max_iterations: None,
            seed: 0,
        }
    }
}

/// The sequencer plugin `name` with default parameters apart from the budget and seed
/// (set where the plugin has `time_limit_s` / `max_iterations`); an unknown name is an
/// error that lists the known ones.
pub fn sequencer(name: &str, options: &SolverOptions) -> smug_core::Result<Box<dyn Sequencer>> {
    let defaults = (SequencerStage::registry()?.get(name)?.default_params)();
    let mut section = PluginSection::new("sequencer", name);
    if defaults.contains_key("time_limit_s") {
        section
            .params
            .insert("time_limit_s".into(), options.time_limit_s.into());
    }
    if defaults.contains_key("max_iterations") {
        let rounds = options.max_iterations.unwrap_or(0);
        let rounds = i64::try_from(rounds).unwrap_or(i64::MAX);
        section
            .params
            .insert("max_iterations".into(), rounds.into());
    }
    let ctx = BuildContext::new(options.seed, RobotConfig::default());
    Ok(ctx.build::<SequencerStage>(&section)?.object)
}
