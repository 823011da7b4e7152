//! The parameters of `team-lns` and their checks.

use crate::local_search::check_search_budget;
use crate::ParamError;
use serde::{Deserialize, Serialize};
use smug_core::TeamObjective;

/// Parameters of [`TeamLns`](super::TeamLns).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TeamLnsParams {
    /// Wall-time budget in seconds (0 = none: then `max_iterations` alone, reproducible).
    pub time_limit_s: f64,
    /// Budget of ruin-and-recreate iterations (0 = none).
    pub max_iterations: u64,
    /// Mean number of targets a ruin removes.
    pub mean_removed: f64,
    /// Longest string a ruin removes from one route.
    pub max_string: usize,
    /// Probability of skipping an insertion position (SISR's blinks).
    pub blink_rate: f64,
    /// Start temperature, in mean legs of the first solution.
    pub temp_start: f64,
    /// End temperature, in mean legs of the first solution.
    pub temp_end: f64,
    /// Makespan objective: weight of the mean route cost (the total over the robots) in
    /// the annealed value.
    pub sum_weight: f64,
    /// Candidates within this fraction of the best get their routes improved.
    pub improve_within: f64,
    /// Fraction of the time budget left for reordering the best routes with the TSP
    /// local search (iteration budgets: 200 rounds per route).
    pub polish_fraction: f64,
    /// Fraction of the time budget for the route-first construction's TSP tour through
    /// every target (iteration budgets: `max_iterations / 20` rounds, at most 1000); the
    /// search starts from its best cut or from insertion, whichever is better
    /// (0 = insertion only).
    pub split_fraction: f64,
    /// The route-first construction is tried only when the robots average more than
    /// this many targets (on shorter routes insertion and the search do as well: measured
    /// on He & Hao's Set I, `docs/bench-mtsp.md`).
    pub split_above: usize,
    /// Routes longer than this are improved with moves between near targets only
    /// (Or-opt and 2-opt in O(len·K) instead of O(len²)), and so are pairs of routes
    /// holding more together (2-opt*).
    pub near_moves_above: usize,
    /// Total objective: a ruin removes on average at most this fraction of a mean
    /// route's targets (`mean_removed` caps it too).
    pub sum_removed_per_route: f64,
    /// Total objective: the annealing cools this many times over the budget, each
    /// cycle starting hot again from the best state seen (1 = one cooling).
    pub sum_cycles: u64,
    /// Total objective: members of the elite pool (0 = no pool: one search). With a
    /// pool, that many independent searches fill it, then `sum_offspring` children of
    /// two members (order crossover and split) are searched in turn.
    pub sum_elite: usize,
    /// Total objective, with a pool: children searched after the pool is filled (at
    /// least; more when searches stall and leave budget).
    pub sum_offspring: usize,
    /// Total objective, with a pool: a child's search ends once its best has not
    /// improved for this many iterations per target and for as many as it took to reach
    /// it; what it leaves of its share goes to further children (0 = every search runs
    /// its share; the pool's first members always do).
    pub sum_stall_per_target: f64,
    /// Makespan objective: members of the elite pool (0 = no pool: one search), as
    /// `sum_elite` is for the total.
    pub makespan_elite: usize,
    /// Makespan objective, with a pool: children searched after the pool is filled (at
    /// least), as `sum_offspring` is for the total (16: on mTSPLib min-max at 1 s, idle,
    /// every proven optimum on every seed where 8 missed eil76 m=2; docs/bench-mtsp.md).
    pub makespan_offspring: usize,
    /// Makespan objective, with a pool: a child's search stall, iterations per target,
    /// as `sum_stall_per_target` is for the total.
    pub makespan_stall_per_target: f64,
    /// Makespan objective: the pool is kept only on problems of at most this many
    /// targets; larger ones get one search with the whole budget (measured on He & Hao's
    /// Set I at 10 s: the pool wins on 75 targets, is mixed on 150–200 and loses from 318
    /// on, where one search needs all the time it can get).
    pub makespan_pool_max_targets: usize,
    /// Total objective, three robots or more: after the search, each pair of near
    /// routes is solved again as a two-robot problem from its routes, with this many
    /// iterations per pair (iteration budgets; all pairs together at most
    /// `max_iterations`; 0 = no pair re-optimisation).
    pub pair_iterations: u64,
    /// With a time budget: the fraction of it left for pair re-optimisation (shared
    /// by the pairs; 0 = none).
    pub pair_fraction: f64,
}

impl Default for TeamLnsParams {
    fn default() -> Self {
        Self {
            time_limit_s: 0.0,
            max_iterations: 20_000,
            mean_removed: 20.0,
            max_string: 10,
            blink_rate: 0.01,
            temp_start: 1.0,
            temp_end: 0.03,
            sum_weight: 0.02,
            improve_within: 0.02,
            polish_fraction: 0.05,
            split_fraction: 0.1,
            split_above: 200,
            near_moves_above: 100,
            sum_removed_per_route: 0.5,
            sum_cycles: 1,
            sum_elite: 4,
            sum_offspring: 8,
            sum_stall_per_target: 80.0,
            makespan_elite: 4,
            makespan_offspring: 16,
            makespan_stall_per_target: 80.0,
            makespan_pool_max_targets: 100,
            pair_iterations: 1000,
            pair_fraction: 0.1,
        }
    }
}

impl TeamLnsParams {
    /// The population settings for `objective` on `targets` targets (`elite == 0`: one
    /// search, no pool).
    pub(super) fn pool(&self, objective: TeamObjective, targets: usize) -> Pool {
        match objective {
            TeamObjective::Sum => Pool {
                elite: self.sum_elite,
                offspring: self.sum_offspring,
                stall_per_target: self.sum_stall_per_target,
            },
            TeamObjective::Makespan => Pool {
                elite: if targets <= self.makespan_pool_max_targets {
                    self.makespan_elite
                } else {
                    0
                },
                offspring: self.makespan_offspring,
                stall_per_target: self.makespan_stall_per_target,
            },
        }
    }

    /// Checks the values; the message names the offending parameter.
    pub fn validate(&self) -> Result<(), ParamError> {
        check_search_budget(self.time_limit_s, self.max_iterations)?;
        for (name, value, most) in [
            ("blink_rate", self.blink_rate, 1.0),
            ("sum_weight", self.sum_weight, 1.0),
            ("improve_within", self.improve_within, 10.0),
            ("polish_fraction", self.polish_fraction, 0.9),
            (
                "pair_fraction",
                self.pair_fraction,
                0.9 - self.polish_fraction,
            ),
            ("split_fraction", self.split_fraction, 0.5),
            ("sum_removed_per_route", self.sum_removed_per_route, 10.0),
            ("sum_stall_per_target", self.sum_stall_per_target, 1e9),
            (
                "makespan_stall_per_target",
                self.makespan_stall_per_target,
                1e9,
            ),
            ("temp_start", self.temp_start, 1e6),
            ("temp_end", self.temp_end, self.temp_start.max(0.0)),
        ] {
            if !(value >= 0.0 && value <= most) {
                return Err(ParamError::OutOfRange { name, value, most });
            }
        }
        if !(self.mean_removed >= 1.0 && self.mean_removed.is_finite()) || self.max_string == 0 {
            return Err(ParamError::OutOfRange {
                name: "mean_removed / max_string",
                value: self.mean_removed.min(self.max_string as f64),
                most: f64::INFINITY,
            });
        }
        if self.temp_end <= 0.0 {
            return Err(ParamError::OutOfRange {
                name: "temp_end (must be > 0)",
                value: self.temp_end,
                most: self.temp_start,
            });
        }
        Ok(())
    }
}

/// A population's settings for one objective (see `population`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Pool {
    /// Members of the elite pool; 0 = no pool.
    pub elite: usize,
    /// Children searched after the pool is filled (at least).
    pub offspring: usize,
    /// A child's search ends once stalled this many iterations per target.
    pub stall_per_target: f64,
}
