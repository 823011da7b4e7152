//! 2-opt* between two routes: route `a` keeps its head up to a cut and takes `b`'s tail
//! after a cut, and the other way round. Heads and tails keep their direction, so
//! asymmetric and per-robot costs are exact: prefix costs for the heads, each tail's
//! cost under both robots' matrices for the tails, O(1) per pair of cuts. Every pair of
//! cuts is tried when the two routes hold at most the setting's `near_above` targets
//! together, else only the cuts joining near targets.

use super::state::{Setting, State};
use smug_core::Visit;

/// Improvements smaller than this are ignored (floating-point noise).
const EPSILON: f64 = 1e-9;

/// Per cut `i` (0..=len): the cost of robot `r` from its start through `route[..i]`.
fn heads(setting: &Setting, r: usize, route: &[Visit]) -> Vec<f64> {
    let robot = &setting.problem.robots()[r];
    let mut costs = Vec::with_capacity(route.len() + 1);
    let (mut at, mut sum) = (robot.start, 0.0);
    costs.push(0.0);
    for v in route {
        sum += robot.costs.get(at, v.node);
        at = v.node;
        costs.push(sum);
    }
    costs
}

/// Per cut `i`: robot `r`'s cost of `route[i..]` to its end, entering from the node
/// before the cut excluded (the joining leg is added by the caller), and whether `r`
/// may serve every target of that tail.
fn tails(setting: &Setting, r: usize, route: &[Visit]) -> (Vec<f64>, Vec<bool>) {
    let robot = &setting.problem.robots()[r];
    let len = route.len();
    let mut costs = vec![0.0; len + 1];
    let mut allowed = vec![true; len + 1];
    let mut next = robot.end;
    for i in (0..len).rev() {
        costs[i] = costs[i + 1] + robot.costs.get(route[i].node, next);
        allowed[i] = allowed[i + 1] && setting.problem.allows(route[i].target, r);
        next = route[i].node;
    }
    (costs, allowed)
}

/// The first node of the tail at cut `i`, or the robot's end for an empty tail.
fn joined(setting: &Setting, r: usize, route: &[Visit], i: usize) -> usize {
    route
        .get(i)
        .map_or(setting.problem.robots()[r].end, |v| v.node)
}

/// The last node of the head at cut `i`, or the robot's start.
fn head_end(setting: &Setting, r: usize, route: &[Visit], i: usize) -> usize {
    if i == 0 {
        setting.problem.robots()[r].start
    } else {
        route[i - 1].node
    }
}

/// The best 2-opt* between routes `a` and `b` by the annealed value; applies it and
/// returns true if it improves that value.
pub(super) fn two_opt_star(setting: &Setting, state: &mut State, a: usize, b: usize) -> bool {
    let (ra, rb) = (&state.routes[a], &state.routes[b]);
    let (ha, hb) = (heads(setting, a, ra), heads(setting, b, rb));
    // Tails of b driven by a, tails of a driven by b.
    let (tb_a, ok_b_for_a) = tails(setting, a, rb);
    let (ta_b, ok_a_for_b) = tails(setting, b, ra);
    let (ca, cb) = (
        &setting.problem.robots()[a].costs,
        &setting.problem.robots()[b].costs,
    );
    let others = other_routes(state, a, b);
    let before = pair_value(setting, state.costs[a], state.costs[b], others);
    let mut best: Option<(f64, usize, usize)> = None;
    let mut consider = |i: usize, j: usize| {
        if !ok_a_for_b[i] || !ok_b_for_a[j] || (i == ra.len() && j == rb.len()) {
            return;
        }
        let (len_a, len_b) = (i + rb.len() - j, j + ra.len() - i);
        if setting.size_violation(len_a) + setting.size_violation(len_b)
            > setting.size_violation(ra.len()) + setting.size_violation(rb.len())
        {
            return;
        }
        let new_a =
            ha[i] + ca.get(head_end(setting, a, ra, i), joined(setting, a, rb, j)) + tb_a[j];
        let new_b =
            hb[j] + cb.get(head_end(setting, b, rb, j), joined(setting, b, ra, i)) + ta_b[i];
        let value = pair_value(setting, new_a, new_b, others);
        if value < before - EPSILON && best.is_none_or(|x| value < x.0) {
            best = Some((value, i, j));
        }
    };
    if ra.len() + rb.len() > setting.near_above {
        for (i, j) in near_cuts(setting, ra, rb) {
            consider(i, j);
        }
    } else {
        for i in 0..=ra.len() {
            for j in 0..=rb.len() {
                consider(i, j);
            }
        }
    }
    let Some((_, i, j)) = best else {
        return false;
    };
    let tail_a: Vec<Visit> = state.routes[a].drain(i..).collect();
    let tail_b: Vec<Visit> = state.routes[b].drain(j..).collect();
    state.routes[a].extend(tail_b);
    state.routes[b].extend(tail_a);
    state.refresh(setting, a);
    state.refresh(setting, b);
    true
}

/// Nearest targets a cut of long routes joins.
const NEAR: usize = 10;

/// The cuts `(i, j)` of long routes `ra`, `rb` worth trying: those whose new legs join a
/// target to one of its nearest targets, and those that hand over a whole route or
/// nothing (a cut at either end of one of them).
fn near_cuts(setting: &Setting, ra: &[Visit], rb: &[Visit]) -> Vec<(usize, usize)> {
    let mut in_b = vec![usize::MAX; setting.problem.targets().len()];
    for (q, v) in rb.iter().enumerate() {
        in_b[v.target] = q;
    }
    let mut cuts = Vec::new();
    for (p, v) in ra.iter().enumerate() {
        for &u in setting.neighbours[v.target].iter().take(NEAR) {
            let q = in_b[u];
            if q != usize::MAX {
                // a's head ending at v joins b's tail from u; b's head ending at u joins
                // a's tail from v.
                cuts.push((p + 1, q));
                cuts.push((p, q + 1));
            }
        }
    }
    for j in 0..=rb.len() {
        cuts.push((0, j));
        cuts.push((ra.len(), j));
    }
    for i in 0..=ra.len() {
        cuts.push((i, 0));
        cuts.push((i, rb.len()));
    }
    cuts
}

/// `(largest, sum)` of the routes other than `a` and `b`.
fn other_routes(state: &State, a: usize, b: usize) -> (f64, f64) {
    state
        .costs
        .iter()
        .enumerate()
        .filter(|(r, _)| *r != a && *r != b)
        .fold((0.0, 0.0), |(m, s), (_, &c)| (f64::max(m, c), s + c))
}

/// The annealed value (without size penalties) with routes `a`, `b` costing `x`, `y`.
fn pair_value(setting: &Setting, x: f64, y: f64, others: (f64, f64)) -> f64 {
    let total = others.1 + x + y;
    match setting.problem.objective() {
        smug_core::TeamObjective::Sum => total,
        smug_core::TeamObjective::Makespan => others.0.max(x).max(y) + setting.sum_weight * total,
    }
}

/// 2-opt* until no pair helps: for the makespan between the longest route and each
/// other, for the sum between each changed route and each other; marks what it changes.
pub(super) fn cross_routes(setting: &Setting, state: &mut State, dirty: &mut [bool]) {
    let m = state.routes.len();
    for _round in 0..m.max(2) {
        let firsts: Vec<usize> = match setting.problem.objective() {
            smug_core::TeamObjective::Makespan => vec![longest(state)],
            smug_core::TeamObjective::Sum => (0..m).filter(|&r| dirty[r]).collect(),
        };
        let mut moved = false;
        for &a in &firsts {
            for b in (0..m).filter(|&b| b != a) {
                if two_opt_star(setting, state, a, b) {
                    dirty[a] = true;
                    dirty[b] = true;
                    moved = true;
                }
            }
        }
        if !moved {
            break;
        }
    }
}

fn longest(state: &State) -> usize {
    (0..state.costs.len())
        .max_by(|&x, &y| state.costs[x].total_cmp(&state.costs[y]))
        .unwrap_or(0)
}
