//! Ruin: remove some targets from a state (strings of related targets as in SISR,
//! random ones, the costliest, a whole route) and put them back at their cheapest
//! places (recreate), in an order drawn from random / farthest / nearest first.

use super::state::{leg_delta, Setting, State};
use rand::seq::SliceRandom;
use rand::Rng;
use smug_core::TeamObjective;

/// How much a ruin removes.
#[derive(Clone, Copy, Debug)]
pub(super) struct RuinSize {
    /// Mean number of targets removed.
    pub mean_removed: f64,
    /// Longest string removed from one route.
    pub max_string: usize,
}

/// Removes targets from `state` (marking the routes it changed in `dirty`); returns them.
pub(super) fn ruin(
    setting: &Setting,
    state: &mut State,
    size: RuinSize,
    rng: &mut impl Rng,
    dirty: &mut [bool],
) -> Vec<usize> {
    let k = setting.problem.targets().len();
    if k == 0 {
        return Vec::new();
    }
    let removed = match rng.random_range(0..20) {
        0..=13 => strings(setting, state, size, rng),
        14..=15 => random(state, size, rng, k),
        16..=17 => worst(setting, state, size, rng),
        _ => route(setting, state, size, rng),
    };
    let mut removed_flags = vec![false; k];
    for &t in &removed {
        removed_flags[t] = true;
    }
    for (r, route) in state.routes.iter_mut().enumerate() {
        let before = route.len();
        route.retain(|v| !removed_flags[v.target]);
        if route.len() != before {
            dirty[r] = true;
        }
    }
    for (r, is_dirty) in dirty.iter().enumerate() {
        if *is_dirty {
            state.refresh(setting, r);
        }
    }
    removed
}

/// A robot to start a ruin from: for the makespan, the longest route half the time.
fn focus_robot(setting: &Setting, state: &State, rng: &mut impl Rng) -> Option<usize> {
    let busy: Vec<usize> = (0..state.routes.len())
        .filter(|&r| !state.routes[r].is_empty())
        .collect();
    if busy.is_empty() {
        return None;
    }
    if setting.problem.objective() == TeamObjective::Makespan && rng.random_bool(0.5) {
        let longest = busy
            .iter()
            .copied()
            .max_by(|&a, &b| state.costs[a].total_cmp(&state.costs[b]))?;
        return Some(longest);
    }
    Some(busy[rng.random_range(0..busy.len())])
}

/// SISR's string removal: strings around the targets nearest a seed, one per route.
fn strings(setting: &Setting, state: &State, size: RuinSize, rng: &mut impl Rng) -> Vec<usize> {
    let Some(robot) = focus_robot(setting, state, rng) else {
        return Vec::new();
    };
    let seed = state.routes[robot][rng.random_range(0..state.routes[robot].len())].target;
    let busy = state.routes.iter().filter(|r| !r.is_empty()).count().max(1);
    let mean_len = state.routes.iter().map(Vec::len).sum::<usize>() as f64 / busy as f64;
    let longest = (size.max_string as f64).min(mean_len).max(1.0);
    let most_strings = (4.0 * size.mean_removed / (1.0 + longest) - 1.0).max(1.0);
    let strings = rng.random_range(1.0..most_strings + 1.0).floor() as usize;
    let at = state.positions(setting.problem.targets().len());
    let mut ruined = vec![false; state.routes.len()];
    let mut removed = Vec::new();
    for t in std::iter::once(seed).chain(setting.neighbours[seed].iter().copied()) {
        if ruined.iter().filter(|r| **r).count() >= strings {
            break;
        }
        let (r, i) = at[t];
        if r == usize::MAX || ruined[r] {
            continue;
        }
        let route = &state.routes[r];
        let most = (longest as usize).min(route.len()).max(1);
        let len = rng.random_range(1..=most);
        let first = i + 1 - rng.random_range(1..=len.min(i + 1));
        let last = (first + len).min(route.len());
        removed.extend(route[first..last].iter().map(|v| v.target));
        ruined[r] = true;
    }
    removed
}

/// Number of targets to remove: uniform in `1..=2·mean`, at most all.
fn count(size: RuinSize, rng: &mut impl Rng, k: usize) -> usize {
    let most = ((2.0 * size.mean_removed).round() as usize).clamp(1, k);
    rng.random_range(1..=most)
}

fn random(state: &State, size: RuinSize, rng: &mut impl Rng, k: usize) -> Vec<usize> {
    let mut all: Vec<usize> = state.routes.iter().flatten().map(|v| v.target).collect();
    all.shuffle(rng);
    all.truncate(count(size, rng, k));
    all
}

/// The targets whose removal saves most, drawn with a bias to the top.
fn worst(setting: &Setting, state: &State, size: RuinSize, rng: &mut impl Rng) -> Vec<usize> {
    let mut savings: Vec<(f64, usize)> = Vec::new();
    for (r, route) in state.routes.iter().enumerate() {
        let robot = &setting.problem.robots()[r];
        let c = &robot.costs;
        for (i, v) in route.iter().enumerate() {
            let prev = if i == 0 {
                robot.start
            } else {
                route[i - 1].node
            };
            let next = route.get(i + 1).map_or(robot.end, |w| w.node);
            let saving = -leg_delta(c.get(prev, next), c.get(prev, v.node) + c.get(v.node, next));
            savings.push((saving, v.target));
        }
    }
    savings.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let want = count(size, rng, savings.len().max(1));
    let mut removed = Vec::new();
    while removed.len() < want && !savings.is_empty() {
        let pick = (rng.random::<f64>().powi(4) * savings.len() as f64) as usize;
        removed.push(savings.remove(pick.min(savings.len() - 1)).1);
    }
    removed
}

/// A whole route (or, for a long one, a random stretch of it of the usual size).
fn route(setting: &Setting, state: &State, size: RuinSize, rng: &mut impl Rng) -> Vec<usize> {
    let Some(r) = focus_robot(setting, state, rng) else {
        return Vec::new();
    };
    let route = &state.routes[r];
    let most = (3.0 * size.mean_removed).ceil() as usize;
    if route.len() <= most {
        return route.iter().map(|v| v.target).collect();
    }
    let len = rng.random_range(1..=most);
    let first = rng.random_range(0..=route.len() - len);
    route[first..first + len].iter().map(|v| v.target).collect()
}

/// Puts `removed` back, each at its cheapest place, in a random, farthest-first or
/// nearest-first order (by robot 0's cost from its start).
pub(super) fn recreate(
    setting: &Setting,
    state: &mut State,
    mut removed: Vec<usize>,
    blink: f64,
    rng: &mut impl Rng,
    dirty: &mut [bool],
) {
    removed.shuffle(rng);
    let depot_cost = |t: usize| {
        let robot = &setting.problem.robots()[0];
        let node = setting.problem.targets()[t].nodes[0];
        robot.costs.get(robot.start, node)
    };
    match rng.random_range(0..7) {
        0..=3 => {}
        4..=5 => removed.sort_by(|&a, &b| depot_cost(b).total_cmp(&depot_cost(a))),
        _ => removed.sort_by(|&a, &b| depot_cost(a).total_cmp(&depot_cost(b))),
    }
    let count = removed.len();
    for (i, t) in removed.into_iter().enumerate() {
        let place = state.best_insertion(setting, t, count - i, blink, rng);
        dirty[place.robot] = true;
        state.insert(setting, t, place);
    }
}
