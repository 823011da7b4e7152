//! The ruin-and-recreate loop with simulated-annealing acceptance (SISR-style: accept a
//! candidate below `current − T·ln U`), the temperature cooling geometrically with the
//! budget's progress (for the total, in `sum_cycles` cycles, each restarting hot from the
//! best state seen).

use super::cross::cross_routes;
use super::exchange::exchange_routes;
use super::improve::improve_route;
use super::params::TeamLnsParams;
use super::ruin::{recreate, ruin, RuinSize};
use super::state::{Setting, State};
use rand::Rng;
use smug_core::{Deadline, TeamObjective};
use std::time::Instant;

/// The budget of one search: time, iterations, the run's deadline.
pub(super) struct Budget<'a> {
    pub time_limit_s: f64,
    pub max_iterations: u64,
    pub deadline: &'a Deadline,
}

impl Budget<'_> {
    /// Fraction of the budget used (≥ 1: done).
    fn progress(&self, started: Instant, iterations: u64) -> f64 {
        let mut used: f64 = 0.0;
        if self.time_limit_s > 0.0 {
            used = used.max(started.elapsed().as_secs_f64() / self.time_limit_s);
        }
        if self.max_iterations > 0 {
            used = used.max(iterations as f64 / self.max_iterations as f64);
        }
        if self.deadline.passed() {
            used = 1.0;
        }
        used
    }
}

/// Whether `a` is better than `b`: fewer size violations, then the objective.
pub(super) fn better(setting: &Setting, a: &State, b: &State) -> bool {
    let (ka, kb) = (a.key(setting), b.key(setting));
    ka.0 < kb.0 || (ka.0 == kb.0 && smug_core::lex_less((ka.1, ka.2), (kb.1, kb.2)))
}

/// The first state: every target at its cheapest place, in a random order, routes
/// improved (for the total, exchanges between routes too).
pub(super) fn construct(setting: &Setting, rng: &mut impl Rng) -> State {
    let mut state = State::empty(setting);
    let m = state.routes.len();
    let mut dirty = vec![false; m];
    let all: Vec<usize> = (0..setting.problem.targets().len()).collect();
    recreate(setting, &mut state, all, 0.0, rng, &mut dirty);
    for r in 0..m {
        improve_route(setting, &mut state, r);
    }
    if m > 1 && setting.problem.objective() == TeamObjective::Sum {
        exchange_and_improve(setting, &mut state, &mut dirty);
    }
    state
}

/// Searches from `start`; returns the best state seen and the iterations done. With
/// `stall > 0` the search ends early once its best has not improved for `stall`
/// iterations and for as many as it took to reach that best.
pub(super) fn search(
    setting: &Setting,
    start: State,
    params: &TeamLnsParams,
    budget: &Budget,
    stall: u64,
    rng: &mut impl Rng,
) -> (State, u64) {
    let started = Instant::now();
    let k = setting.problem.targets().len();
    if k == 0 {
        return (start, 0);
    }
    let size = RuinSize {
        mean_removed: mean_removed(setting, params),
        max_string: params.max_string,
    };
    let unit = mean_leg(setting, &start);
    let (hot, cold) = (params.temp_start * unit, params.temp_end * unit);
    let mut current = start;
    let mut current_scalar = current.scalar(setting);
    let mut best = current.clone();
    let mut best_scalar = current_scalar;
    let mut iterations = 0u64;
    let m = current.routes.len();
    let cycles = match setting.problem.objective() {
        TeamObjective::Sum => params.sum_cycles.max(1),
        TeamObjective::Makespan => 1,
    };
    let mut cycle = 0u64;
    let mut improved_at = 0u64;
    loop {
        let progress = budget.progress(started, iterations);
        if progress >= 1.0 || stalled(stall, improved_at, iterations) {
            break;
        }
        iterations += 1;
        let scaled = progress * cycles as f64;
        if scaled.floor() as u64 > cycle {
            // A new cycle: hot again, from the best state seen.
            cycle = scaled.floor() as u64;
            current = best.clone();
            current_scalar = current.scalar(setting);
        }
        let temperature = hot * (cold / hot).powf(scaled - scaled.floor());
        let mut candidate = current.clone();
        let mut dirty = vec![false; m];
        let removed = ruin(setting, &mut candidate, size, rng, &mut dirty);
        recreate(
            setting,
            &mut candidate,
            removed,
            params.blink_rate,
            rng,
            &mut dirty,
        );
        let mut scalar = candidate.scalar(setting);
        if scalar < best_scalar * (1.0 + params.improve_within) + temperature {
            if m > 1 {
                cross_routes(setting, &mut candidate, &mut dirty);
            }
            for r in (0..m).filter(|&r| dirty[r]) {
                improve_route(setting, &mut candidate, r);
            }
            scalar = candidate.scalar(setting);
            let close = best_scalar * (1.0 + params.improve_within * EXCHANGE_WITHIN);
            if m > 1 && setting.problem.objective() == TeamObjective::Sum && scalar < close {
                exchange_and_improve(setting, &mut candidate, &mut dirty);
                scalar = candidate.scalar(setting);
            }
        }
        if better(setting, &candidate, &best) {
            best = candidate.clone();
            best_scalar = best_scalar.min(scalar);
            improved_at = iterations;
        }
        let threshold = current_scalar - temperature * rng.random::<f64>().max(1e-300).ln();
        if scalar < threshold {
            current = candidate;
            current_scalar = scalar;
        }
    }
    (best, iterations)
}

/// Whether a search whose best last improved at iteration `improved_at` has stalled at
/// iteration `iterations` (never with `stall == 0`).
fn stalled(stall: u64, improved_at: u64, iterations: u64) -> bool {
    let idle = iterations - improved_at;
    stall > 0 && idle >= stall && idle >= improved_at
}

/// Mean number of targets a ruin removes: `mean_removed`, at most half the targets, for
/// the total at most `sum_removed_per_route` of a mean route; at least one.
fn mean_removed(setting: &Setting, params: &TeamLnsParams) -> f64 {
    let k = setting.problem.targets().len() as f64;
    let mut mean = params.mean_removed.min(k / 2.0);
    if setting.problem.objective() == TeamObjective::Sum && params.sum_removed_per_route > 0.0 {
        let per_route = k / setting.problem.robots().len() as f64;
        mean = mean.min(params.sum_removed_per_route * per_route);
    }
    mean.max(1.0)
}

/// Inter-route exchanges and route improvement in turn until the exchanges find nothing
/// (a few rounds at most).
pub(super) fn exchange_and_improve(setting: &Setting, state: &mut State, dirty: &mut [bool]) {
    let mut active = dirty.to_vec();
    for _round in 0..EXCHANGE_ROUNDS {
        let mut changed = vec![false; active.len()];
        if !exchange_routes(setting, state, &active, &mut changed) {
            break;
        }
        for r in (0..changed.len()).filter(|&r| changed[r]) {
            improve_route(setting, state, r);
            dirty[r] = true;
        }
        active = changed;
    }
}

/// Candidates within this fraction of `improve_within` of the best get the exchanges
/// between routes too (for the total).
const EXCHANGE_WITHIN: f64 = 0.25;

/// Rounds of exchanges and route improvement per candidate at most.
const EXCHANGE_ROUNDS: usize = 4;

/// The mean finite leg of a state (the temperature's unit): its total over its legs.
fn mean_leg(setting: &Setting, state: &State) -> f64 {
    let legs = setting.problem.targets().len() + state.routes.len();
    let total: f64 = state.costs.iter().filter(|c| c.is_finite()).sum();
    let unit = total / legs.max(1) as f64;
    if unit > 0.0 && unit.is_finite() {
        unit
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::stalled;

    #[test]
    fn a_search_stalls_after_the_stall_and_as_long_as_its_best_took() {
        assert!(!stalled(0, 0, 1_000_000), "no stall given: never");
        assert!(!stalled(100, 0, 99));
        assert!(stalled(100, 0, 100));
        // Best found at 300: idle for 100 is not enough, idle for 300 is.
        assert!(!stalled(100, 300, 400));
        assert!(stalled(100, 300, 600));
    }
}
