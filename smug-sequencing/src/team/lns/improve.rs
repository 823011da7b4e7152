//! Route-internal improvement: Or-opt (segments of 1–3 targets moved, reversed too on
//! symmetric costs), 2-opt (symmetric costs only: a reversal's cost on asymmetric ones
//! is a recomputation, which this search skips) and the PoI choice re-optimised for the
//! route's order (a layered shortest path, as the joint GTSP mode does). Routes longer
//! than the setting's `near_above` try only moves that join a target to one of its
//! nearest targets (O(len·K) per pass instead of O(len²)).

use super::state::{leg_delta, Setting, State};
use smug_core::{CostMatrix, Visit};

/// Improvements smaller than this are ignored (floating-point noise).
const EPSILON: f64 = 1e-9;
/// Nearest targets a long route's moves join a target to.
const NEAR: usize = 10;

/// Improves route `r` of `state` in place until no move helps.
pub(super) fn improve_route(setting: &Setting, state: &mut State, r: usize) {
    let robot = &setting.problem.robots()[r];
    let c: &CostMatrix = &robot.costs;
    let route = &mut state.routes[r];
    let near = (route.len() > setting.near_above).then_some(setting);
    if route.len() >= 2 {
        loop {
            let mut moved = false;
            if setting.symmetric {
                moved |= match near {
                    Some(setting) => near_two_opt(setting, c, robot.start, robot.end, route),
                    None => two_opt(c, robot.start, robot.end, route),
                };
            }
            moved |= or_opt(c, robot.start, robot.end, route, setting.symmetric, near);
            if !moved {
                break;
            }
        }
    }
    if !setting.single_nodes && !route.is_empty() {
        choose_nodes(setting, r, route);
    }
    state.refresh(setting, r);
}

fn node_at(route: &[Visit], start: usize, end: usize, i: usize) -> usize {
    if i == 0 {
        start
    } else if i > route.len() {
        end
    } else {
        route[i - 1].node
    }
}

/// The change of replacing edges `i` and `j` (sequence positions `i, i+1` and `j, j+1`)
/// by `i, j` and `i+1, j+1`, reversing the stretch between.
fn two_opt_delta(
    c: &CostMatrix,
    start: usize,
    end: usize,
    route: &[Visit],
    i: usize,
    j: usize,
) -> f64 {
    let a = node_at(route, start, end, i);
    let b = node_at(route, start, end, i + 1);
    let x = node_at(route, start, end, j);
    let y = node_at(route, start, end, j + 1);
    leg_delta(c.get(a, x) + c.get(b, y), c.get(a, b) + c.get(x, y))
}

/// One pass of first-improvement 2-opt; true if it moved.
fn two_opt(c: &CostMatrix, start: usize, end: usize, route: &mut [Visit]) -> bool {
    let len = route.len();
    let mut moved = false;
    // Positions 0..=len+1 in the sequence start, route…, end; edge i joins i and i+1.
    for i in 0..len {
        for j in i + 2..=len {
            if two_opt_delta(c, start, end, route, i, j) < -EPSILON {
                route[i..j].reverse();
                moved = true;
            }
        }
    }
    moved
}

/// Per target, its index in `route` (`usize::MAX` when elsewhere).
fn indices(setting: &Setting, route: &[Visit]) -> Vec<usize> {
    let mut at = vec![usize::MAX; setting.problem.targets().len()];
    for (i, v) in route.iter().enumerate() {
        at[v.target] = i;
    }
    at
}

/// One pass of first-improvement 2-opt over the moves that join a target to one of its
/// nearest targets on the route (either side); true if it moved.
fn near_two_opt(
    setting: &Setting,
    c: &CostMatrix,
    start: usize,
    end: usize,
    route: &mut [Visit],
) -> bool {
    let len = route.len();
    let mut at = indices(setting, route);
    let mut moved = false;
    for idx in 0..len {
        let target = route[idx].target;
        for &u in setting.neighbours[target].iter().take(NEAR) {
            let q = at[u];
            if q == usize::MAX {
                continue;
            }
            // Sequence positions (0 = start): the target at idx + 1, u at q + 1. Joining
            // them after each (edges p,p+1 and q,q+1) or before each (edges p-1,p and q-1,q).
            let (p, q) = (idx + 1, q + 1);
            let (lo, hi) = (p.min(q), p.max(q));
            let mut done = false;
            for (i, j) in [(lo, hi), (lo - 1, hi - 1)] {
                if j < i + 2 {
                    continue;
                }
                if two_opt_delta(c, start, end, route, i, j) < -EPSILON {
                    route[i..j].reverse();
                    for (k, v) in route[i..j].iter().enumerate() {
                        at[v.target] = i + k;
                    }
                    done = true;
                    break;
                }
            }
            if done {
                moved = true;
                break;
            }
        }
    }
    moved
}

/// One pass of first-improvement Or-opt; true if it moved. With `near`, a segment
/// goes only beside one of its ends' nearest targets or at the route's ends.
fn or_opt(
    c: &CostMatrix,
    start: usize,
    end: usize,
    route: &mut Vec<Visit>,
    reverse: bool,
    near: Option<&Setting>,
) -> bool {
    let mut moved = false;
    let mut at = near.map(|setting| indices(setting, route));
    for seg in 1..=3usize {
        let mut i = 1;
        while i + seg <= route.len() + 1 && route.len() > seg {
            let places = match (near, &at) {
                (Some(setting), Some(at)) => near_places(setting, route, at, i, seg),
                _ => (0..=route.len()).collect(),
            };
            if let Some((to, reversed)) = best_move(c, start, end, route, i, seg, reverse, &places)
            {
                let mut piece: Vec<Visit> = route.drain(i - 1..i - 1 + seg).collect();
                if reversed {
                    piece.reverse();
                }
                let to = if to > i - 1 { to - seg } else { to };
                route.splice(to..to, piece);
                moved = true;
                if let Some(setting) = near {
                    at = Some(indices(setting, route));
                }
            }
            i += 1;
        }
    }
    moved
}

/// The places (sequence positions `k`: between `k` and `k + 1`) beside the nearest
/// targets of the segment at sequence positions `i..i+seg`, and the route's two ends.
fn near_places(
    setting: &Setting,
    route: &[Visit],
    at: &[usize],
    i: usize,
    seg: usize,
) -> Vec<usize> {
    let mut places = vec![0, route.len()];
    for end in [route[i - 1].target, route[i + seg - 2].target] {
        for &u in setting.neighbours[end].iter().take(NEAR) {
            if at[u] != usize::MAX {
                // u sits at sequence position at[u] + 1: before it and after it.
                places.push(at[u]);
                places.push(at[u] + 1);
            }
        }
    }
    places
}

/// A route's cost change by a move: the infinite legs (no path) it adds, negative when
/// it removes them, and the change of its finite legs. One infinite leg outweighs any
/// finite sum, so every accepted move lowers the pair lexicographically and the
/// improvement loop ends (a single `added − removed` number cannot order moves between
/// infinite legs).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Change {
    infinite: i32,
    finite: f64,
}

impl Change {
    /// Two legs `added` in place of the leg `removed`.
    fn of(added: [f64; 2], removed: f64) -> Self {
        let infinite = added.iter().filter(|c| !c.is_finite()).count() as i32
            - i32::from(!removed.is_finite());
        let added: f64 = added.iter().filter(|c| c.is_finite()).sum();
        let removed = if removed.is_finite() { removed } else { 0.0 };
        Self {
            infinite,
            finite: added - removed,
        }
    }

    /// This change less `other`: `self − other`, part by part.
    fn minus(self, other: Self) -> Self {
        Self {
            infinite: self.infinite - other.infinite,
            finite: self.finite - other.finite,
        }
    }

    /// Whether the move lowers the route's cost (beyond floating-point noise).
    fn improves(self) -> bool {
        self.infinite < 0 || (self.infinite == 0 && self.finite < -EPSILON)
    }

    /// Whether the move lowers the cost more than `other` does.
    fn beats(self, other: Self) -> bool {
        self.infinite < other.infinite
            || (self.infinite == other.infinite && self.finite < other.finite)
    }
}

/// The best place among `places` (sequence positions `k`: between `k` and `k + 1`) to
/// move the segment at sequence positions `i..i+seg` (position 0 is the start): the
/// route index it goes before (numbered before its removal) and whether reversed, if
/// that helps.
#[allow(clippy::too_many_arguments)]
fn best_move(
    c: &CostMatrix,
    start: usize,
    end: usize,
    route: &[Visit],
    i: usize,
    seg: usize,
    reverse: bool,
    places: &[usize],
) -> Option<(usize, bool)> {
    let at = |k: usize| node_at(route, start, end, k);
    let (p, s0, s1, n) = (at(i - 1), at(i), at(i + seg - 1), at(i + seg));
    // What taking the segment out saves.
    let gain = Change::of([c.get(p, s0), c.get(s1, n)], c.get(p, n));
    let mut best: Option<(Change, usize, bool)> = None;
    // Insert between sequence positions k and k+1, outside the segment.
    for &k in places {
        if k + 1 >= i && k < i + seg {
            continue;
        }
        let (u, v) = (at(k), at(k + 1));
        let old = c.get(u, v);
        let forward = Change::of([c.get(u, s0), c.get(s1, v)], old).minus(gain);
        if forward.improves() && best.is_none_or(|b| forward.beats(b.0)) {
            best = Some((forward, k, false));
        }
        if reverse && seg > 1 {
            let backward = Change::of([c.get(u, s1), c.get(s0, v)], old).minus(gain);
            if backward.improves() && best.is_none_or(|b| backward.beats(b.0)) {
                best = Some((backward, k, true));
            }
        }
    }
    // `k` is the route index before which the segment goes, counted before its removal;
    // the segment occupies route indices i-1..i-1+seg.
    best.map(|(_, to, reversed)| (to, reversed))
}

/// Re-picks every visit's node for the route's order: a shortest path through the layers.
fn choose_nodes(setting: &Setting, r: usize, route: &mut [Visit]) {
    let robot = &setting.problem.robots()[r];
    let c = &robot.costs;
    let targets = setting.problem.targets();
    let mut layers: Vec<Vec<(f64, usize)>> = Vec::with_capacity(route.len());
    let mut prev: Vec<(usize, f64)> = vec![(robot.start, 0.0)];
    for visit in route.iter() {
        let options = &targets[visit.target].nodes;
        let mut layer = Vec::with_capacity(options.len());
        let mut here = Vec::with_capacity(options.len());
        for &node in options {
            let (cost, from) = prev
                .iter()
                .enumerate()
                .map(|(k, &(p, cost))| (cost + c.get(p, node), k))
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .expect("a layer has a node");
            layer.push((cost, from));
            here.push((node, cost));
        }
        layers.push(layer);
        prev = here;
    }
    let (mut pick, _) = prev
        .iter()
        .enumerate()
        .map(|(k, &(node, cost))| (k, cost + c.get(node, robot.end)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("a route has a visit");
    for i in (0..route.len()).rev() {
        route[i].node = targets[route[i].target].nodes[pick];
        pick = layers[i][pick].1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The route's legs without a path and the sum of the others.
    fn route_cost(c: &CostMatrix, start: usize, end: usize, route: &[Visit]) -> (usize, f64) {
        let nodes: Vec<usize> = std::iter::once(start)
            .chain(route.iter().map(|v| v.node))
            .chain(std::iter::once(end))
            .collect();
        let legs: Vec<f64> = nodes.windows(2).map(|w| c.get(w[0], w[1])).collect();
        let infinite = legs.iter().filter(|l| !l.is_finite()).count();
        (infinite, legs.iter().filter(|l| l.is_finite()).sum())
    }

    #[test]
    fn or_opt_ends_on_routes_with_legs_that_have_no_path() {
        // Many pairs without a path: a single `added − removed` number let moves between
        // infinite legs count as improvements and Or-opt cycled forever.
        for seed in 0..300 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let n = 9;
            let mut cost = vec![0.0; n * n];
            for i in 0..n {
                for j in i + 1..n {
                    let value = if rng.random_bool(0.4) {
                        f64::INFINITY
                    } else {
                        rng.random_range(1.0..10.0)
                    };
                    cost[i * n + j] = value;
                    cost[j * n + i] = value;
                }
            }
            let c = CostMatrix::from_fn(n, |i, j| cost[i * n + j]).unwrap();
            let mut route: Vec<Visit> = (1..n).map(|k| Visit { target: k, node: k }).collect();
            let before = route_cost(&c, 0, 0, &route);
            let mut passes = 0;
            while or_opt(&c, 0, 0, &mut route, true, None) {
                passes += 1;
                assert!(passes < 200, "seed {seed}: Or-opt did not end");
            }
            let after = route_cost(&c, 0, 0, &route);
            assert!(
                after.0 < before.0 || (after.0 == before.0 && after.1 <= before.1 + 1e-9),
                "seed {seed}: {before:?} -> {after:?}"
            );
            let mut targets: Vec<usize> = route.iter().map(|v| v.target).collect();
            targets.sort_unstable();
            assert_eq!(targets, (1..n).collect::<Vec<_>>(), "seed {seed}");
        }
    }
}
