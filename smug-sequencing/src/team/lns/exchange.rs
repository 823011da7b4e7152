//! Granular inter-route moves for the total objective: relocate (a target moved beside
//! one of its nearest targets on another route), swap (two near targets of two routes
//! trade places) and SWAP* (Vidal's HGS: the two trade routes, each inserted at its
//! best place in the other route, not in the other's slot). Only pairs of near targets
//! (the setting's neighbour lists) are tried, so a pass is O(k·G·len). Every move keeps
//! the route-size bounds (never a route below its minimum or above its maximum when it
//! was within them), the robots' restrictions, and is checked on the recomputed route
//! costs before it is kept, so asymmetric and per-robot costs are exact.

use super::state::{leg_delta, Setting, State};
use smug_core::{CostMatrix, Visit};

/// Improvements smaller than this are ignored (floating-point noise).
const EPSILON: f64 = 1e-9;
/// Nearest targets a target's moves pair it with.
const GRANULAR: usize = 20;
/// Passes over every target at most (each pass ends when none moved).
const MAX_PASSES: usize = 50;

/// Whether a change of the total is an improvement (not noise, not NaN).
fn improves(delta: f64) -> bool {
    delta < -EPSILON
}

/// A move between two routes: the routes' new visit lists.
struct Move {
    /// Route of the target moved or swapped first, its new visits.
    a: (usize, Vec<Visit>),
    /// The other route, its new visits.
    b: (usize, Vec<Visit>),
    /// The move's estimated change of the total.
    delta: f64,
}

/// Relocate, swap and SWAP* between routes until none lowers the total (first
/// improvement, near pairs only), moving the targets of the routes marked in `active`
/// or in `changed`; marks the routes it changes in `changed` and returns whether
/// anything moved.
pub(super) fn exchange_routes(
    setting: &Setting,
    state: &mut State,
    active: &[bool],
    changed: &mut [bool],
) -> bool {
    let k = setting.problem.targets().len();
    let mut moved_any = false;
    for _pass in 0..MAX_PASSES {
        let mut moved = false;
        let mut at = state.positions(k);
        for u in 0..k {
            let ru = at[u].0;
            if ru == usize::MAX || !(active[ru] || changed[ru]) {
                continue;
            }
            if let Some(best) = best_move_for(setting, state, &at, u) {
                if apply(setting, state, best, changed) {
                    moved = true;
                    at = state.positions(k);
                }
            }
        }
        moved_any |= moved;
        if !moved {
            break;
        }
    }
    moved_any
}

/// The best improving move of target `u` with one of its near targets on another route.
fn best_move_for(
    setting: &Setting,
    state: &State,
    at: &[(usize, usize)],
    u: usize,
) -> Option<Move> {
    let (ru, iu) = at[u];
    let mut best: Option<Move> = None;
    let mut keep = |candidate: Option<Move>| {
        if let Some(m) = candidate {
            if m.delta < -EPSILON && best.as_ref().is_none_or(|b| m.delta < b.delta) {
                best = Some(m);
            }
        }
    };
    for &v in setting.neighbours[u].iter().take(GRANULAR) {
        let (rv, iv) = at[v];
        if rv == usize::MAX || rv == ru {
            continue;
        }
        keep(relocate(setting, state, (ru, iu), (rv, iv)));
        keep(relocate(setting, state, (rv, iv), (ru, iu)));
        keep(swap(setting, state, (ru, iu), (rv, iv)));
        keep(swap_star(setting, state, (ru, iu), (rv, iv)));
    }
    best
}

/// Keeps `m` if the recomputed total is lower; returns whether it was kept.
fn apply(setting: &Setting, state: &mut State, m: Move, dirty: &mut [bool]) -> bool {
    let (a, b) = (m.a.0, m.b.0);
    let before = state.costs[a] + state.costs[b];
    let new_a = setting.problem.route_cost(a, &m.a.1);
    let new_b = setting.problem.route_cost(b, &m.b.1);
    if !improves(new_a + new_b - before) {
        return false;
    }
    state.routes[a] = m.a.1;
    state.routes[b] = m.b.1;
    state.costs[a] = new_a;
    state.costs[b] = new_b;
    dirty[a] = true;
    dirty[b] = true;
    true
}

/// The node at sequence position `i` of `route` (0 = the robot's start, `len + 1` = end).
fn node_at(setting: &Setting, r: usize, route: &[Visit], i: usize) -> usize {
    let robot = &setting.problem.robots()[r];
    if i == 0 {
        robot.start
    } else if i > route.len() {
        robot.end
    } else {
        route[i - 1].node
    }
}

/// Change of route `r`'s cost when its visit at index `i` leaves.
fn removal_delta(setting: &Setting, r: usize, route: &[Visit], i: usize) -> f64 {
    let c = &setting.problem.robots()[r].costs;
    let (p, x, n) = (
        node_at(setting, r, route, i),
        route[i].node,
        node_at(setting, r, route, i + 2),
    );
    leg_delta(c.get(p, n), c.get(p, x) + c.get(x, n))
}

/// Whether the two routes' sizes after a move stay as bounded as before.
fn sizes_ok(setting: &Setting, old: (usize, usize), new: (usize, usize)) -> bool {
    setting.size_violation(new.0) + setting.size_violation(new.1)
        <= setting.size_violation(old.0) + setting.size_violation(old.1)
}

/// Target `from` (route, index) moved next to `to` (route, index): just before or just
/// after it, whichever is cheaper, at the best of its nodes.
fn relocate(
    setting: &Setting,
    state: &State,
    from: (usize, usize),
    to: (usize, usize),
) -> Option<Move> {
    let ((ra, ia), (rb, ib)) = (from, to);
    let (route_a, route_b) = (&state.routes[ra], &state.routes[rb]);
    let target = route_a[ia].target;
    if !setting.problem.allows(target, rb)
        || !sizes_ok(
            setting,
            (route_a.len(), route_b.len()),
            (route_a.len() - 1, route_b.len() + 1),
        )
    {
        return None;
    }
    let removed = removal_delta(setting, ra, route_a, ia);
    let c = &setting.problem.robots()[rb].costs;
    let mut best: Option<(f64, usize, usize)> = None;
    // Sequence gaps (k, k+1) beside `to` (sequence position ib + 1).
    for k in [ib, ib + 1] {
        let (x, y) = (
            node_at(setting, rb, route_b, k),
            node_at(setting, rb, route_b, k + 1),
        );
        for &node in &setting.problem.targets()[target].nodes {
            let added = leg_delta(c.get(x, node) + c.get(node, y), c.get(x, y));
            if best.is_none_or(|b| added < b.0) {
                best = Some((added, k, node));
            }
        }
    }
    let (added, k, node) = best?;
    if !improves(removed + added) {
        return None;
    }
    let mut new_a = route_a.clone();
    new_a.remove(ia);
    let mut new_b = route_b.clone();
    new_b.insert(k, Visit { target, node });
    Some(Move {
        a: (ra, new_a),
        b: (rb, new_b),
        delta: removed + added,
    })
}

/// The nodes robot `r` drives through with `route`'s visit at index `skip` taken out:
/// start, the other visits, end (a view, no copy).
struct Without<'a> {
    route: &'a [Visit],
    skip: usize,
    start: usize,
    end: usize,
}

impl<'a> Without<'a> {
    fn new(setting: &Setting, r: usize, route: &'a [Visit], skip: usize) -> Self {
        let robot = &setting.problem.robots()[r];
        Self {
            route,
            skip,
            start: robot.start,
            end: robot.end,
        }
    }

    /// Number of nodes (start and end included).
    fn len(&self) -> usize {
        self.route.len() + 1
    }

    /// The `k`-th node.
    fn node(&self, k: usize) -> usize {
        if k == 0 {
            self.start
        } else if k >= self.route.len() {
            self.end
        } else if k <= self.skip {
            self.route[k - 1].node
        } else {
            self.route[k].node
        }
    }

    /// Cost change of putting `node` between the `k`-th and the next node.
    fn gap_delta(&self, c: &CostMatrix, k: usize, node: usize) -> f64 {
        let (x, y) = (self.node(k), self.node(k + 1));
        leg_delta(c.get(x, node) + c.get(node, y), c.get(x, y))
    }
}

/// Two visits in two routes about to trade targets: each route with its visit taken
/// out, the robots' costs, and the cost change of taking both out.
struct Trade<'a> {
    a: Side<'a>,
    b: Side<'a>,
    /// The cost change of taking both visits out.
    removal: f64,
}

/// One route of a [`Trade`].
struct Side<'a> {
    /// The route's robot, and the index of its visit.
    robot: usize,
    index: usize,
    /// The route as it is, and without the visit.
    route: &'a [Visit],
    without: Without<'a>,
    /// The visit's target.
    target: usize,
    /// The robot's costs.
    costs: &'a CostMatrix,
}

impl<'a> Side<'a> {
    fn new(setting: &'a Setting, state: &'a State, (robot, index): (usize, usize)) -> Self {
        let route = &state.routes[robot];
        Self {
            robot,
            index,
            route,
            without: Without::new(setting, robot, route, index),
            target: route[index].target,
            costs: &setting.problem.robots()[robot].costs,
        }
    }
}

impl<'a> Trade<'a> {
    /// Visit `a` (route, index) and visit `b` about to trade targets; `None` when a
    /// target may not be served by the other route's robot.
    fn new(
        setting: &'a Setting,
        state: &'a State,
        a: (usize, usize),
        b: (usize, usize),
    ) -> Option<Self> {
        let (a, b) = (Side::new(setting, state, a), Side::new(setting, state, b));
        if !setting.problem.allows(a.target, b.robot) || !setting.problem.allows(b.target, a.robot)
        {
            return None;
        }
        let removal = removal_delta(setting, a.robot, a.route, a.index)
            + removal_delta(setting, b.robot, b.route, b.index);
        Some(Self { a, b, removal })
    }

    /// The move that puts `b`'s target into route `a` at `(gap, node)` and `a`'s into
    /// route `b` at theirs (`None` as the gap: in the taken-out visit's slot).
    fn into_move(
        self,
        into_a: (Option<usize>, usize),
        into_b: (Option<usize>, usize),
        delta: f64,
    ) -> Move {
        let place = |side: &Side, (gap, node): (Option<usize>, usize), target: usize| {
            let mut route = side.route.to_vec();
            let visit = Visit { target, node };
            match gap {
                None => route[side.index] = visit,
                Some(gap) => {
                    route.remove(side.index);
                    route.insert(gap, visit);
                }
            }
            (side.robot, route)
        };
        Move {
            a: place(&self.a, into_a, self.b.target),
            b: place(&self.b, into_b, self.a.target),
            delta,
        }
    }
}

/// The two targets trade slots (each at the best of its nodes).
fn swap(setting: &Setting, state: &State, a: (usize, usize), b: (usize, usize)) -> Option<Move> {
    let trade = Trade::new(setting, state, a, b)?;
    let (ta, tb) = (&trade.a, &trade.b);
    let (into_a, node_b) = cheapest_node(setting, ta.costs, &ta.without, ta.index, tb.target);
    let (into_b, node_a) = cheapest_node(setting, tb.costs, &tb.without, tb.index, ta.target);
    let delta = trade.removal + into_a + into_b;
    if !improves(delta) {
        return None;
    }
    Some(trade.into_move((None, node_b), (None, node_a), delta))
}

/// The cheapest of `target`'s nodes in gap `k` of `nodes` (after its `k`-th node): its cost change and node.
fn cheapest_node(
    setting: &Setting,
    c: &CostMatrix,
    nodes: &Without,
    k: usize,
    target: usize,
) -> (f64, usize) {
    setting.problem.targets()[target]
        .nodes
        .iter()
        .map(|&node| (nodes.gap_delta(c, k, node), node))
        .min_by(|x, y| x.0.total_cmp(&y.0))
        .expect("a target has a node")
}

/// The cheapest gap of `nodes` for `target`: its cost change, gap and node.
fn cheapest_gap(
    setting: &Setting,
    c: &CostMatrix,
    nodes: &Without,
    target: usize,
) -> (f64, usize, usize) {
    let mut best = (f64::INFINITY, 0, setting.problem.targets()[target].nodes[0]);
    for k in 0..nodes.len() - 1 {
        let (delta, node) = cheapest_node(setting, c, nodes, k, target);
        if delta < best.0 {
            best = (delta, k, node);
        }
    }
    best
}

/// SWAP*: the two targets trade routes, each at its best place in the other's route
/// (the other target taken out).
fn swap_star(
    setting: &Setting,
    state: &State,
    a: (usize, usize),
    b: (usize, usize),
) -> Option<Move> {
    let trade = Trade::new(setting, state, a, b)?;
    let (ta, tb) = (&trade.a, &trade.b);
    let (into_a, ka, node_b) = cheapest_gap(setting, ta.costs, &ta.without, tb.target);
    let (into_b, kb, node_a) = cheapest_gap(setting, tb.costs, &tb.without, ta.target);
    let delta = trade.removal + into_a + into_b;
    if !improves(delta) {
        return None;
    }
    Some(trade.into_move((Some(ka), node_b), (Some(kb), node_a), delta))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use smug_core::{RouteSize, TeamObjective, TeamProblem, TeamRobot, TeamTarget};
    use std::sync::Arc;

    /// Random asymmetric per-robot costs, 1–2 nodes per target, some restricted
    /// targets, size bounds `min..=max`; a random state within them.
    fn random_case(rng: &mut ChaCha8Rng, m: usize, k: usize) -> (TeamProblem, Vec<Vec<Visit>>) {
        let mut targets = Vec::new();
        let mut next = m;
        for t in 0..k {
            let count = rng.random_range(1..=2);
            // Restricted targets keep robot t % m so that the state below can serve them.
            let robots = rng
                .random_bool(0.2)
                .then(|| vec![t % m, rng.random_range(0..m)]);
            targets.push(TeamTarget {
                nodes: (next..next + count).collect(),
                robots,
            });
            next += count;
        }
        let robots = (0..m)
            .map(|r| TeamRobot {
                costs: Arc::new(
                    CostMatrix::from_fn(next, |i, j| {
                        if i == j {
                            0.0
                        } else {
                            rng.random_range(1.0..30.0)
                        }
                    })
                    .unwrap(),
                ),
                start: r,
                end: r,
            })
            .collect();
        let (min, max) = (k / m - 1, k / m + 2);
        let problem = TeamProblem::new(
            robots,
            targets,
            TeamObjective::Sum,
            Some(RouteSize { min, max }),
        )
        .unwrap();
        let mut routes = vec![Vec::new(); m];
        for t in 0..k {
            let node = problem.targets()[t].nodes[0];
            routes[t % m].push(Visit { target: t, node });
        }
        (problem, routes)
    }

    fn check_routes(problem: &TeamProblem, routes: &[Vec<Visit>]) {
        let mut seen: Vec<usize> = routes.iter().flatten().map(|v| v.target).collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..problem.targets().len()).collect::<Vec<_>>());
        let bounds = problem.route_size().unwrap();
        for (r, route) in routes.iter().enumerate() {
            assert!(
                (bounds.min..=bounds.max).contains(&route.len()),
                "{r}: {}",
                route.len()
            );
            for v in route {
                assert!(problem.allows(v.target, r));
                assert!(problem.targets()[v.target].nodes.contains(&v.node));
            }
        }
    }

    #[test]
    fn every_move_keeps_a_permutation_and_the_bounds_and_its_delta_is_exact() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut moves = 0;
        for _case in 0..40 {
            let m = rng.random_range(2..=4);
            let k = rng.random_range(3 * m..=6 * m);
            let (problem, routes) = random_case(&mut rng, m, k);
            let setting = Setting::new(&problem, 0.02, 100);
            let state = State::of(&setting, &problem.solution(routes));
            let at = state.positions(k);
            for u in 0..k {
                for v in (0..k).filter(|&v| at[v].0 != at[u].0) {
                    let candidates = [
                        relocate(&setting, &state, at[u], at[v]),
                        swap(&setting, &state, at[u], at[v]),
                        swap_star(&setting, &state, at[u], at[v]),
                    ];
                    for found in candidates.into_iter().flatten() {
                        let mut routes = state.routes.clone();
                        routes[found.a.0] = found.a.1.clone();
                        routes[found.b.0] = found.b.1.clone();
                        check_routes(&problem, &routes);
                        let before = state.costs[found.a.0] + state.costs[found.b.0];
                        let after = problem.route_cost(found.a.0, &found.a.1)
                            + problem.route_cost(found.b.0, &found.b.1);
                        assert!((after - before - found.delta).abs() < 1e-9);
                        assert!(found.delta < 0.0);
                        moves += 1;
                    }
                }
            }
        }
        assert!(moves > 100, "{moves}");
    }

    #[test]
    fn exchanges_never_raise_the_total_and_keep_the_bounds() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for _case in 0..40 {
            let m = rng.random_range(2..=4);
            let k = rng.random_range(3 * m..=6 * m);
            let (problem, routes) = random_case(&mut rng, m, k);
            let setting = Setting::new(&problem, 0.02, 100);
            let mut state = State::of(&setting, &problem.solution(routes));
            let before = state.total();
            let mut dirty = vec![false; m];
            let moved = exchange_routes(&setting, &mut state, &vec![true; m], &mut dirty);
            check_routes(&problem, &state.routes);
            let recomputed = problem.solution(state.routes.clone()).total;
            assert!((recomputed - state.total()).abs() < 1e-9);
            assert!(recomputed <= before);
            assert_eq!(moved, recomputed < before);
            assert_eq!(moved, dirty.iter().any(|&d| d));
        }
    }
}
