//! A small population (HGS-style, with the LNS as the education): a few
//! independent searches fill an elite pool, then children of two members — the order
//! crossover (OX) of their giant tours, cut by the size-bounded split, routes improved
//! and exchanged — are searched in turn, each result replacing the pool's worst member
//! when it is better and new. Every search gets an equal share of what is left of the
//! budget, so the wall time is kept and iteration budgets stay reproducible. A child's
//! search whose best has stalled (`sum_stall_per_target`, `makespan_stall_per_target`)
//! ends early and leaves the rest of its share to the next ones; children are searched
//! until the budget is spent. The pool's first members search their whole shares (on
//! rat99 m=7 they improve until late in their cooling).

use super::improve::improve_route;
use super::params::Pool;
use super::search::{better, construct, exchange_and_improve, search, Budget};
use super::split::best_cuts;
use super::state::{Setting, State};
use super::TeamLnsParams;
use rand::Rng;
use std::time::Instant;

/// Two totals closer than this (relative) count as the same solution in the pool.
const SAME: f64 = 1e-9;

/// Searches with a pool of `pool.elite` members and at least `pool.offspring`
/// children (more while stalled searches leave budget); returns the best state and the
/// iterations of every search together (`start` itself, after no iteration, when the
/// deadline has already passed).
pub(super) fn evolve(
    setting: &Setting,
    start: State,
    params: &TeamLnsParams,
    pool_size: Pool,
    budget: &Budget,
    rng: &mut impl Rng,
) -> (State, u64) {
    let started = Instant::now();
    let elite = pool_size.elite.max(1);
    let planned = elite + pool_size.offspring;
    let mut pool: Vec<State> = Vec::with_capacity(elite);
    let mut iterations = 0u64;
    let mut first = Some(start);
    let stall = (pool_size.stall_per_target * setting.problem.targets().len() as f64).ceil() as u64;
    for run in 0.. {
        let out_of_iterations = budget.max_iterations > 0 && iterations >= budget.max_iterations;
        let share = share(budget, started, iterations, planned.saturating_sub(run));
        if out_of_iterations || share.time_limit_s < 0.0 || budget.deadline.passed() {
            break;
        }
        let from = if let Some(state) = first.take() {
            state
        } else if run < elite {
            construct(setting, rng)
        } else {
            child(setting, &pool, rng)
        };
        // The first members run their whole shares; children may stall.
        let stall = if run < elite { 0 } else { stall };
        let (found, done) = search(setting, from, params, &share, stall, rng);
        iterations += done;
        admit(setting, &mut pool, found, elite);
        if done == 0 {
            // Nothing to search (no target): one search says it all.
            break;
        }
    }
    // No search ran (the deadline had passed): the start is the answer.
    let best = match best_member(setting, &pool) {
        Some(k) => pool.swap_remove(k),
        None => first.expect("the start is kept when no search runs"),
    };
    (best, iterations)
}

/// The index of the pool's best member (the first of equals); `None` for an empty pool.
fn best_member(setting: &Setting, pool: &[State]) -> Option<usize> {
    (0..pool.len()).reduce(|a, b| {
        if better(setting, &pool[b], &pool[a]) {
            b
        } else {
            a
        }
    })
}

/// An equal share of what is left of `budget` for one of `left` searches (a negative
/// time when nothing is left).
fn share<'a>(budget: &Budget<'a>, started: Instant, iterations: u64, left: usize) -> Budget<'a> {
    let left = left.max(1) as f64;
    let time_limit_s = if budget.time_limit_s > 0.0 {
        let rest = budget.time_limit_s - started.elapsed().as_secs_f64();
        if rest <= 0.0 {
            -1.0
        } else {
            rest / left
        }
    } else {
        0.0
    };
    let max_iterations = if budget.max_iterations > 0 {
        let rest = budget.max_iterations.saturating_sub(iterations);
        ((rest as f64 / left).ceil() as u64).max(1)
    } else {
        0
    };
    Budget {
        time_limit_s,
        max_iterations,
        deadline: budget.deadline,
    }
}

/// Puts `found` into the pool: added while it has room, else in place of the worst
/// member when better than it; a total already in the pool is not added twice.
fn admit(setting: &Setting, pool: &mut Vec<State>, found: State, elite: usize) {
    let total = found.scalar(setting);
    if pool
        .iter()
        .any(|s| (s.scalar(setting) - total).abs() <= SAME * total.abs().max(1.0))
    {
        return;
    }
    if pool.len() < elite {
        pool.push(found);
        return;
    }
    let worst = (0..pool.len())
        .reduce(|a, b| {
            if better(setting, &pool[a], &pool[b]) {
                b
            } else {
                a
            }
        })
        .expect("a full pool is not empty");
    if better(setting, &found, &pool[worst]) {
        pool[worst] = found;
    }
}

/// A child of the pool's best member and another one drawn at random: OX of their
/// giant tours, cut by the split, improved; the best member itself when the cut fails.
fn child(setting: &Setting, pool: &[State], rng: &mut impl Rng) -> State {
    let best = best_member(setting, pool).expect("the pool is not empty");
    if pool.len() < 2 {
        return pool[best].clone();
    }
    let mut other = rng.random_range(0..pool.len() - 1);
    if other >= best {
        other += 1;
    }
    let a = giant_tour(setting, &pool[best], rng);
    let b = giant_tour(setting, &pool[other], rng);
    let order = order_crossover(&a, &b, rng);
    let Some(routes) = best_cuts(setting, &order) else {
        return pool[best].clone();
    };
    let mut state = State::empty(setting);
    for (r, route) in routes.into_iter().enumerate() {
        state.routes[r] = route;
        state.refresh(setting, r);
        improve_route(setting, &mut state, r);
    }
    let mut dirty = vec![true; state.routes.len()];
    exchange_and_improve(setting, &mut state, &mut dirty);
    state
}

/// The targets of `state`'s routes one after the other: a random route first, then
/// each time the route whose first target is nearest (robot 0's costs) to the last
/// target so far.
fn giant_tour(setting: &Setting, state: &State, rng: &mut impl Rng) -> Vec<usize> {
    let costs = &setting.problem.robots()[0].costs;
    let mut left: Vec<usize> = (0..state.routes.len())
        .filter(|&r| !state.routes[r].is_empty())
        .collect();
    let mut order = Vec::with_capacity(setting.problem.targets().len());
    if left.is_empty() {
        return order;
    }
    let mut r = left.swap_remove(rng.random_range(0..left.len()));
    loop {
        order.extend(state.routes[r].iter().map(|v| v.target));
        let last = state.routes[r].last().expect("not empty").node;
        let Some(next) = (0..left.len()).min_by(|&x, &y| {
            let cx = costs.get(last, state.routes[left[x]][0].node);
            let cy = costs.get(last, state.routes[left[y]][0].node);
            cx.total_cmp(&cy)
        }) else {
            return order;
        };
        r = left.remove(next);
    }
}

/// OX: a random stretch of `a` kept in place, the other positions filled after it
/// (wrapping) with the rest of the targets in `b`'s order from the same point.
fn order_crossover(a: &[usize], b: &[usize], rng: &mut impl Rng) -> Vec<usize> {
    let k = a.len();
    if k < 2 {
        return a.to_vec();
    }
    let i = rng.random_range(0..k);
    let j = rng.random_range(0..k);
    let (from, to) = (i.min(j), i.max(j));
    let size = a.iter().chain(b).copied().max().map_or(0, |t| t + 1);
    let mut taken = vec![false; size];
    let mut child = vec![usize::MAX; k];
    for p in from..=to {
        child[p] = a[p];
        taken[a[p]] = true;
    }
    let mut write = (to + 1) % k;
    for step in 0..k {
        let t = b[(to + 1 + step) % k];
        if taken[t] {
            continue;
        }
        taken[t] = true;
        child[write] = t;
        write = (write + 1) % k;
    }
    child
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::team::mtsp::mtsp_problem;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use smug_core::{CostMatrix, Deadline, RouteSize, TeamObjective, TeamProblem};

    /// A depot and `k` targets drawn in a square, `m` salesmen, the total, bounds 3..=9.
    fn problem(k: usize, m: usize) -> TeamProblem {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let xy: Vec<(f64, f64)> = (0..=k)
            .map(|_| (rng.random_range(0.0..100.0), rng.random_range(0.0..100.0)))
            .collect();
        let costs = CostMatrix::from_fn(k + 1, |i, j| (xy[i].0 - xy[j].0).hypot(xy[i].1 - xy[j].1))
            .unwrap();
        let bounds = RouteSize { min: 3, max: 9 };
        mtsp_problem(costs, m, TeamObjective::Sum, Some(bounds)).unwrap()
    }

    fn evolved(problem: &TeamProblem, seed: u64) -> (State, u64) {
        evolved_with(problem, seed, TeamLnsParams::default().sum_stall_per_target)
    }

    fn evolved_with(problem: &TeamProblem, seed: u64, stall_per_target: f64) -> (State, u64) {
        let setting = Setting::new(problem, 0.02, 100);
        let params = TeamLnsParams {
            max_iterations: 600,
            sum_elite: 3,
            sum_offspring: 3,
            sum_stall_per_target: stall_per_target,
            ..TeamLnsParams::default()
        };
        seeded_evolution(&setting, &params, params.pool(TeamObjective::Sum, 30), seed).1
    }

    /// A constructed start and its evolution with `params`' iteration budget.
    fn seeded_evolution(
        setting: &Setting,
        params: &TeamLnsParams,
        pool: Pool,
        seed: u64,
    ) -> (State, (State, u64)) {
        let deadline = Deadline::new();
        let budget = Budget {
            time_limit_s: 0.0,
            max_iterations: params.max_iterations,
            deadline: &deadline,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let start = construct(setting, &mut rng);
        let evolved = evolve(setting, start.clone(), params, pool, &budget, &mut rng);
        (start, evolved)
    }

    #[test]
    fn evolution_is_reproducible_feasible_and_keeps_the_iteration_budget() {
        let problem = problem(30, 4);
        let setting = Setting::new(&problem, 0.02, 100);
        let (state, iterations) = evolved(&problem, 3);
        assert_eq!(state.violation(&setting), 0, "{:?}", state.routes);
        problem.validate(&state.solution(&setting)).unwrap();
        // Six searches share the 600 iterations (each rounded up).
        assert!((600..=606).contains(&iterations), "{iterations}");
        assert_eq!(evolved(&problem, 3), (state, iterations));
    }

    #[test]
    fn the_makespan_keeps_a_pool_on_small_problems_only() {
        let params = TeamLnsParams::default();
        let small = params.pool(TeamObjective::Makespan, params.makespan_pool_max_targets);
        assert_eq!(small.elite, params.makespan_elite);
        assert!(small.elite > 0);
        let large = params.pool(
            TeamObjective::Makespan,
            params.makespan_pool_max_targets + 1,
        );
        assert_eq!(large.elite, 0, "one search with the whole budget");
        // The total keeps its pool at any size.
        assert_eq!(
            params.pool(TeamObjective::Sum, 10_000).elite,
            params.sum_elite
        );
    }

    #[test]
    fn a_makespan_population_is_reproducible_and_feasible() {
        let mut rng = ChaCha8Rng::seed_from_u64(8);
        let xy: Vec<(f64, f64)> = (0..=40)
            .map(|_| (rng.random_range(0.0..100.0), rng.random_range(0.0..100.0)))
            .collect();
        let costs =
            CostMatrix::from_fn(41, |i, j| (xy[i].0 - xy[j].0).hypot(xy[i].1 - xy[j].1)).unwrap();
        let problem = mtsp_problem(costs, 3, TeamObjective::Makespan, None).unwrap();
        let setting = Setting::new(&problem, 0.02, 100);
        let params = TeamLnsParams {
            max_iterations: 900,
            ..TeamLnsParams::default()
        };
        let pool = params.pool(TeamObjective::Makespan, 40);
        let run = |seed: u64| seeded_evolution(&setting, &params, pool, seed);
        let (start, (state, iterations)) = run(4);
        problem.validate(&state.solution(&setting)).unwrap();
        assert!(
            !better(&setting, &start, &state),
            "never worse than its start"
        );
        // Twelve searches share the 900 iterations (each rounded up).
        assert!((900..=912).contains(&iterations), "{iterations}");
        assert_eq!(run(4).1, (state, iterations));
    }

    #[test]
    fn stalled_searches_leave_their_iterations_to_more_children() {
        let problem = problem(30, 4);
        let setting = Setting::new(&problem, 0.02, 100);
        // A stall of one iteration per target (30): searches end early, more of them run,
        // and together they still spend the whole budget, reproducibly.
        let (state, iterations) = evolved_with(&problem, 3, 1.0);
        assert_eq!(state.violation(&setting), 0, "{:?}", state.routes);
        problem.validate(&state.solution(&setting)).unwrap();
        assert!((600..=700).contains(&iterations), "{iterations}");
        assert_eq!(evolved_with(&problem, 3, 1.0), (state, iterations));
    }

    #[test]
    fn a_passed_deadline_returns_the_start_untouched() {
        let problem = problem(12, 2);
        let setting = Setting::new(&problem, 0.02, 100);
        let deadline = Deadline::after(0.0);
        let budget = Budget {
            time_limit_s: 10.0,
            max_iterations: 0,
            deadline: &deadline,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let start = construct(&setting, &mut rng);
        let (state, iterations) = evolve(
            &setting,
            start.clone(),
            &TeamLnsParams::default(),
            TeamLnsParams::default().pool(TeamObjective::Sum, 12),
            &budget,
            &mut rng,
        );
        assert_eq!((state, iterations), (start, 0));
    }

    #[test]
    fn the_pool_keeps_distinct_members_and_replaces_its_worst() {
        let problem = problem(12, 2);
        let setting = Setting::new(&problem, 0.02, 100);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let a = construct(&setting, &mut rng);
        let mut pool = vec![a.clone()];
        admit(&setting, &mut pool, a.clone(), 2);
        assert_eq!(
            pool.len(),
            1,
            "a total already in the pool is not added again"
        );
        // A worse copy (a 2-opt move undone on a route) joins while there is room…
        let mut worse = a.clone();
        worse.routes[0].swap(0, 2);
        worse.refresh(&setting, 0);
        assert!(better(&setting, &a, &worse));
        admit(&setting, &mut pool, worse.clone(), 2);
        assert_eq!(pool.len(), 2);
        // …and a better one then takes the worst member's place.
        let mut best = a.clone();
        best.costs[0] -= 1.0;
        admit(&setting, &mut pool, best.clone(), 2);
        assert_eq!(pool.len(), 2);
        assert!(pool.contains(&best) && pool.contains(&a) && !pool.contains(&worse));
    }

    #[test]
    fn a_giant_tour_holds_every_target_of_the_routes_once() {
        let problem = problem(20, 3);
        let setting = Setting::new(&problem, 0.02, 100);
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let state = construct(&setting, &mut rng);
        let mut tour = giant_tour(&setting, &state, &mut rng);
        tour.sort_unstable();
        assert_eq!(tour, (0..20).collect::<Vec<_>>());
    }

    #[test]
    fn order_crossover_keeps_every_target_once_and_a_stretch_of_the_first_parent() {
        let a: Vec<usize> = (0..12).collect();
        let b: Vec<usize> = (0..12).rev().collect();
        for seed in 0..20 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let child = order_crossover(&a, &b, &mut rng);
            let mut sorted = child.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, a, "{child:?}");
            let kept = child
                .iter()
                .enumerate()
                .filter(|&(p, &t)| a[p] == t)
                .count();
            assert!(kept >= 1, "{child:?}");
        }
    }
}
