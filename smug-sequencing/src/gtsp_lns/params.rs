//! The parameters of the GTSP large-neighbourhood search and their checks.

use crate::error::ParamError;
use crate::local_search::{check_search_budget, search_termination};
use serde::{Deserialize, Serialize};
use smug_core::Termination;

/// The most neighbours an iteration may build (each is a copy of the tour).
const MOST_NEIGHBOURS_PER_ITERATION: usize = 64;

/// Parameters of [`GtspLns`](super::GtspLns).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GtspLnsParams {
    /// Wall-time budget in seconds; 0 = none (then the result depends only on the seed).
    pub time_limit_s: f64,
    /// Budget of removal/insertion iterations; 0 = no limit.
    pub max_iterations: u64,
    /// Most clusters one iteration removes, as a fraction of all clusters (at least 10).
    pub max_removal_fraction: f64,
    /// Insertion costs are raised by random amounts up to a level drawn in `[0, noise)`
    /// average legs per iteration.
    pub noise: f64,
    /// Initial annealing temperature as a fraction of an average leg.
    pub temperature: f64,
    /// Iterations per epoch (then a restart from the best tour); 0 = `max(200, 10 m)`.
    pub epoch_iterations: u64,
    /// Move-opt runs on tours within this fraction above the best cost.
    pub move_opt_within: f64,
    /// Perturbation rounds of the TSP local search that reorders the chosen nodes.
    pub reorder_iterations: u64,
    /// Iteration budget of a warm-started solve (from the previous round's tour in the
    /// joint mode's lazy loop, whose matrix differs only where paths were planned
    /// since); 0 = `max_iterations`. The time budget applies as it is.
    pub warm_iterations: u64,
    /// Neighbours built per iteration, side by side on the rayon pool, the cheapest
    /// one judged by the annealing (1: one, as GLNS does). The plan does not depend on
    /// the number of threads, only on this count.
    pub neighbours_per_iteration: usize,
}

impl Default for GtspLnsParams {
    /// An iteration budget and no time limit, so that a seed fixes the result. Two
    /// neighbours per iteration over 700 iterations (250 warm) against one over 2000
    /// (500), measured in `smug bench modes --modes joint`, 10 seeds: lunar 200 × 10
    /// 1125.05 / 5.90 s → 1124.32 / 4.00 s (cheaper on 8 of 10 seeds), lunar 48 × 6
    /// 157.55 / 0.283 s → 157.51 / 0.214 s, lunar 13 × 10 95.81 / 0.146 s → 95.82 /
    /// 0.101 s; GTSP-LIB at 1 s (seeds 1–8) within noise, 0.078% → 0.089% mean gap.
    fn default() -> Self {
        Self {
            time_limit_s: 0.0,
            max_iterations: 700,
            max_removal_fraction: 0.3,
            noise: 0.5,
            temperature: 1.0,
            epoch_iterations: 0,
            move_opt_within: 0.02,
            reorder_iterations: 50,
            warm_iterations: 250,
            neighbours_per_iteration: 2,
        }
    }
}

impl GtspLnsParams {
    /// The stopping rule: the time budget, the iteration budget, or both.
    pub fn termination(&self) -> Termination {
        search_termination(self.time_limit_s, self.max_iterations)
    }

    /// Checks the values; the message names the offending parameter.
    pub fn validate(&self) -> Result<(), ParamError> {
        check_search_budget(self.time_limit_s, self.max_iterations)?;
        let fractions = [
            ("max_removal_fraction", self.max_removal_fraction, 1.0),
            ("noise", self.noise, f64::MAX),
            ("temperature", self.temperature, f64::MAX),
            ("move_opt_within", self.move_opt_within, f64::MAX),
        ];
        for (name, value, most) in fractions {
            if !(value >= 0.0 && value <= most) {
                return Err(ParamError::OutOfRange { name, value, most });
            }
        }
        let neighbours = self.neighbours_per_iteration;
        if !(1..=MOST_NEIGHBOURS_PER_ITERATION).contains(&neighbours) {
            return Err(ParamError::CountOutOfRange {
                name: "neighbours_per_iteration",
                value: neighbours,
                least: 1,
                most: MOST_NEIGHBOURS_PER_ITERATION,
            });
        }
        Ok(())
    }
}
