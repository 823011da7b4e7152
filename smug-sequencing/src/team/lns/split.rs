//! Route-first, cluster-second construction: one TSP tour through every target (the TSP
//! local search over robot 0's costs from its start, each target at its first node),
//! cut into one consecutive stretch per robot by dynamic programming — the cuts that
//! minimise the makespan or the total, within the route-size bounds and the targets'
//! robot restrictions. With few robots and hundreds of targets per route this starts
//! the search from TSP-quality routes, which insertion alone does not reach.

use super::improve::improve_route;
use super::state::{Setting, State};
use crate::local_search::{LocalSearch, LocalSearchParams};
use smug_core::{CostMatrix, Deadline, Sequencer, TeamObjective, TourKind, Visit};

/// The budget of the TSP tour's search.
pub(super) struct TourBudget {
    /// Seconds (0: none, then `max_iterations` alone).
    pub time_limit_s: f64,
    /// Perturbation rounds (0: none).
    pub max_iterations: u64,
}

/// The routes of the best cut of a TSP tour, improved; `None` when no cut respects the
/// bounds and restrictions (or the tour search fails).
pub(super) fn split_tour(
    setting: &Setting,
    budget: &TourBudget,
    seed: u64,
    deadline: &Deadline,
) -> Option<State> {
    let order = giant_tour(setting, budget, seed, deadline)?;
    let routes = best_cuts(setting, &order)?;
    let mut state = State::empty(setting);
    for (r, route) in routes.into_iter().enumerate() {
        state.routes[r] = route;
        state.refresh(setting, r);
        improve_route(setting, &mut state, r);
    }
    Some(state)
}

/// The targets in the order of a closed TSP tour from robot 0's start.
fn giant_tour(
    setting: &Setting,
    budget: &TourBudget,
    seed: u64,
    deadline: &Deadline,
) -> Option<Vec<usize>> {
    let problem = setting.problem;
    let robot = &problem.robots()[0];
    let k = problem.targets().len();
    let node = |i: usize| {
        if i == 0 {
            robot.start
        } else {
            problem.targets()[i - 1].nodes[0]
        }
    };
    let costs = CostMatrix::from_fn(k + 1, |i, j| robot.costs.get(node(i), node(j))).ok()?;
    let params = LocalSearchParams {
        time_limit_s: budget.time_limit_s,
        max_iterations: budget.max_iterations,
        ..LocalSearchParams::default()
    };
    let solver = LocalSearch::with_seed(params, seed)
        .ok()?
        .with_deadline(deadline.clone());
    let tour = solver.solve(&costs, TourKind::Closed).ok()?.order;
    let at = tour.iter().position(|&i| i == 0)?;
    Some(
        tour[at + 1..]
            .iter()
            .chain(&tour[..at])
            .map(|&i| i - 1)
            .collect(),
    )
}

/// Per robot, its costs along `order`: the legs' prefix sums and the count of targets
/// it may not serve before each position.
struct Along {
    prefix: Vec<f64>,
    forbidden: Vec<usize>,
}

fn along(setting: &Setting, r: usize, order: &[usize]) -> Along {
    let c = &setting.problem.robots()[r].costs;
    let targets = setting.problem.targets();
    let mut prefix = vec![0.0; order.len()];
    for i in 1..order.len() {
        let leg = c.get(targets[order[i - 1]].nodes[0], targets[order[i]].nodes[0]);
        prefix[i] = prefix[i - 1] + leg;
    }
    let mut forbidden = vec![0; order.len() + 1];
    for (i, &t) in order.iter().enumerate() {
        forbidden[i + 1] = forbidden[i] + usize::from(!setting.problem.allows(t, r));
    }
    Along { prefix, forbidden }
}

/// Robot `r`'s cost of serving `order[i..j]` (infinite when it may not serve one).
fn stretch_cost(
    setting: &Setting,
    r: usize,
    order: &[usize],
    a: &Along,
    i: usize,
    j: usize,
) -> f64 {
    let robot = &setting.problem.robots()[r];
    if j == i {
        return robot.costs.get(robot.start, robot.end);
    }
    if a.forbidden[j] != a.forbidden[i] {
        return f64::INFINITY;
    }
    let targets = setting.problem.targets();
    let (first, last) = (targets[order[i]].nodes[0], targets[order[j - 1]].nodes[0]);
    robot.costs.get(robot.start, first) + a.prefix[j - 1] - a.prefix[i]
        + robot.costs.get(last, robot.end)
}

/// The cut of `order` into one stretch per robot (in robot order) with the least
/// makespan or total, every stretch within the size bounds; `None` if none is finite.
pub(super) fn best_cuts(setting: &Setting, order: &[usize]) -> Option<Vec<Vec<Visit>>> {
    let k = order.len();
    let m = setting.problem.robots().len();
    let (least, most) = setting
        .problem
        .route_size()
        .map_or((0, k), |b| (b.min, b.max.min(k)));
    let combine = |a: f64, b: f64| match setting.problem.objective() {
        TeamObjective::Sum => a + b,
        TeamObjective::Makespan => a.max(b),
    };
    // value[j]: the best over the robots so far serving order[..j]; cut[r][j]: where
    // robot r's stretch starts in that best.
    let mut value = vec![f64::INFINITY; k + 1];
    value[0] = 0.0;
    let mut cut = vec![vec![usize::MAX; k + 1]; m];
    for (r, cuts) in cut.iter_mut().enumerate() {
        let a = along(setting, r, order);
        let mut next = vec![f64::INFINITY; k + 1];
        for (j, best) in next.iter_mut().enumerate() {
            let first = j.saturating_sub(most);
            for (i, &before) in value.iter().enumerate().take(j + 1).skip(first) {
                if j - i < least || !before.is_finite() {
                    continue;
                }
                let v = combine(before, stretch_cost(setting, r, order, &a, i, j));
                if v < *best {
                    *best = v;
                    cuts[j] = i;
                }
            }
        }
        value = next;
    }
    if !value[k].is_finite() {
        return None;
    }
    let targets = setting.problem.targets();
    let mut routes = vec![Vec::new(); m];
    let mut j = k;
    for r in (0..m).rev() {
        let i = cut[r][j];
        routes[r] = order[i..j]
            .iter()
            .map(|&t| Visit {
                target: t,
                node: targets[t].nodes[0],
            })
            .collect();
        j = i;
    }
    Some(routes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::team::mtsp::mtsp_problem;
    use smug_core::{RouteSize, TeamProblem};

    /// A depot at the centre of `k` targets evenly spaced on a circle, `m` salesmen.
    fn circle(
        k: usize,
        m: usize,
        objective: TeamObjective,
        size: Option<RouteSize>,
    ) -> TeamProblem {
        let xy: Vec<(f64, f64)> = std::iter::once((0.0, 0.0))
            .chain((0..k).map(|i| {
                let a = std::f64::consts::TAU * i as f64 / k as f64;
                (10.0 * a.cos(), 10.0 * a.sin())
            }))
            .collect();
        let costs = CostMatrix::from_fn(k + 1, |i, j| (xy[i].0 - xy[j].0).hypot(xy[i].1 - xy[j].1))
            .unwrap();
        mtsp_problem(costs, m, objective, size).unwrap()
    }

    fn split(problem: &TeamProblem) -> Option<State> {
        let setting = Setting::new(problem, 0.02, 100);
        let budget = TourBudget {
            time_limit_s: 0.0,
            max_iterations: 20,
        };
        split_tour(&setting, &budget, 1, &Deadline::new())
    }

    #[test]
    fn a_circle_is_cut_into_equal_arcs_for_the_makespan() {
        let problem = circle(60, 3, TeamObjective::Makespan, None);
        let state = split(&problem).expect("a cut");
        let sizes: Vec<usize> = state.routes.iter().map(Vec::len).collect();
        assert_eq!(sizes, vec![20, 20, 20]);
        problem.validate(&problem.solution(state.routes)).unwrap();
    }

    #[test]
    fn cuts_keep_the_size_bounds() {
        // For the total, one salesman would take every target; the bounds forbid it.
        for (min, max) in [(12, 18), (15, 15), (1, 29)] {
            let bounds = RouteSize { min, max };
            let problem = circle(30, 2, TeamObjective::Sum, Some(bounds));
            let state = split(&problem).expect("a cut");
            assert!(state.routes.iter().all(|r| (min..=max).contains(&r.len())));
            problem.validate(&problem.solution(state.routes)).unwrap();
        }
    }
}
