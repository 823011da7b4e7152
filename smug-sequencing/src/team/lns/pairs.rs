//! Pair re-optimisation for the total: the targets of two near routes solved again as a
//! two-robot problem of their own (the same search on a problem a fraction of the
//! size, from the two routes as they are) and kept when the pair costs less. It reaches
//! what moves of one to three targets cannot: on rat99 with 7 robots (route sizes 9 to
//! 22), searches end in a basin (2174.45) where two routes of 18 and 22 targets, the
//! longer at its bound, share their 40 targets worse than they could; as a problem of
//! its own the pair is solved (897.82 → 893.60, the best-known 2170.22) in a thousand
//! iterations.

use super::search::better;
use super::state::{Setting, State};
use rand::Rng;
use smug_core::{Deadline, TeamObjective, TeamProblem, TeamRobot, TeamSolution, TeamTarget, Visit};
use std::time::Instant;

/// Neighbours of a target looked at to find the routes near its own.
const NEAR: usize = 5;
/// Passes over the near pairs at most (each ends when no pair improved).
const MAX_PASSES: usize = 3;

/// What pair re-optimisation may spend: per pair, iterations (with no time budget) or
/// seconds, and in all.
#[derive(Clone, Copy, Debug)]
pub(super) struct PairBudget {
    /// Iterations of each pair's search when there is no time budget.
    pub iterations: u64,
    /// Iterations of all the pairs together at most (0 = no limit): no more than the
    /// search itself had, however many pairs.
    pub total_iterations: u64,
    /// Seconds for all the pairs together (0 = iterations only).
    pub time_s: f64,
}

/// How a pair's problem is solved: from the warm start, with `(seconds, iterations)`
/// (seconds 0: iterations only) and a seed; the solution and the iterations spent
/// (`None`: not solved). `team-lns` passes itself, without pair re-optimisation.
pub(super) type PairSolver<'a> =
    dyn FnMut(&TeamProblem, &TeamSolution, (f64, u64), u64) -> Option<(TeamSolution, u64)> + 'a;

/// `state` with every near pair of routes re-optimised by `solve` where that lowers
/// the total (where it [`applies`]), and the iterations spent.
pub(super) fn reoptimise_pairs(
    setting: &Setting,
    mut state: State,
    budget: PairBudget,
    deadline: &Deadline,
    rng: &mut impl Rng,
    solve: &mut PairSolver,
) -> (State, u64) {
    if !applies(setting) {
        return (state, 0);
    }
    let started = Instant::now();
    let mut iterations = 0;
    for _pass in 0..MAX_PASSES {
        let pairs = near_pairs(setting, &state);
        let mut improved = false;
        for (k, &(a, b)) in pairs.iter().enumerate() {
            let time_s = if budget.time_s > 0.0 {
                let left = budget.time_s - started.elapsed().as_secs_f64();
                if left <= 0.0 {
                    return (state, iterations);
                }
                left / (pairs.len() - k) as f64
            } else {
                0.0
            };
            let spent = budget.total_iterations > 0 && iterations >= budget.total_iterations;
            if spent || deadline.passed() {
                return (state, iterations);
            }
            let seed: u64 = rng.random();
            let Some((found, done)) = solve_pair(
                setting,
                &state,
                (a, b),
                (time_s, budget.iterations),
                seed,
                solve,
            ) else {
                continue;
            };
            iterations += done;
            if better(setting, &found, &state) {
                state = found;
                improved = true;
            }
        }
        if !improved {
            break;
        }
    }
    (state, iterations)
}

/// Whether pairs are re-optimised: for the total, on three robots or more (a pair of
/// two is the whole problem).
pub(super) fn applies(setting: &Setting) -> bool {
    let problem = setting.problem;
    problem.objective() == TeamObjective::Sum && problem.robots().len() >= 3
}

/// The pairs of routes `(a, b)`, `a < b`, where a target of one has one of its
/// [`NEAR`] nearest targets on the other, in increasing order.
fn near_pairs(setting: &Setting, state: &State) -> Vec<(usize, usize)> {
    let at = state.positions(setting.problem.targets().len());
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for (t, &(r, _)) in at.iter().enumerate() {
        for &u in setting.neighbours[t].iter().take(NEAR) {
            let s = at[u].0;
            if r != usize::MAX && s != usize::MAX && r != s {
                pairs.push((r.min(s), r.max(s)));
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

/// Routes `a` and `b` of `state` solved by `solve` as a two-robot problem from their
/// present routes, with `time_s` seconds (0: `iterations`); the state with the pair's
/// new routes and the iterations spent, or `None` when the pair is not a problem of its
/// own (too few targets, or one the checks refuse).
fn solve_pair(
    setting: &Setting,
    state: &State,
    (a, b): (usize, usize),
    (time_s, iterations): (f64, u64),
    seed: u64,
    solve: &mut PairSolver,
) -> Option<(State, u64)> {
    let problem = setting.problem;
    let targets: Vec<usize> = [a, b]
        .iter()
        .flat_map(|&r| state.routes[r].iter().map(|v| v.target))
        .collect();
    if targets.len() < 3 {
        return None;
    }
    let sub = sub_problem(problem, &targets, [a, b])?;
    // `targets` lists route `a`'s targets, then route `b`'s: the sub-problem's target
    // `k` is the `k`-th of them.
    let first = state.routes[a].len();
    let warm_routes: Vec<Vec<Visit>> = [(a, 0), (b, first)]
        .iter()
        .map(|&(r, offset)| {
            state.routes[r]
                .iter()
                .enumerate()
                .map(|(k, v)| Visit {
                    target: offset + k,
                    node: v.node,
                })
                .collect()
        })
        .collect();
    let warm: TeamSolution = sub.solution(warm_routes);
    let (solution, done) = solve(&sub, &warm, (time_s, iterations), seed)?;
    let mut found = state.clone();
    for (k, &r) in [a, b].iter().enumerate() {
        found.routes[r] = solution.routes[k]
            .iter()
            .map(|v| Visit {
                target: targets[v.target],
                node: v.node,
            })
            .collect();
        found.refresh(setting, r);
    }
    Some((found, done))
}

/// The problem of `targets` (indices in `problem`) served by `robots` alone, robot
/// restrictions renumbered; `None` when its checks refuse it.
fn sub_problem(
    problem: &TeamProblem,
    targets: &[usize],
    robots: [usize; 2],
) -> Option<TeamProblem> {
    let team: Vec<TeamRobot> = robots
        .iter()
        .map(|&r| problem.robots()[r].clone())
        .collect();
    let sub_targets: Vec<TeamTarget> = targets
        .iter()
        .map(|&t| {
            let target = &problem.targets()[t];
            TeamTarget {
                nodes: target.nodes.clone(),
                robots: target
                    .robots
                    .as_ref()
                    .map(|allowed| (0..2).filter(|&k| allowed.contains(&robots[k])).collect()),
            }
        })
        .collect();
    TeamProblem::new(team, sub_targets, problem.objective(), problem.route_size()).ok()
}

#[cfg(test)]
mod tests {
    use super::super::params::TeamLnsParams;
    use super::super::search::{search, Budget};
    use super::*;
    use proptest::prelude::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use smug_core::{CostMatrix, RouteSize};
    use std::sync::Arc;

    /// A depot (node 0) and one node per target at `xy`, Euclidean; `m` robots, the
    /// total, `bounds`, target `t` restricted to the robots `only[t]` where given.
    fn problem(
        xy: &[(f64, f64)],
        m: usize,
        bounds: Option<RouteSize>,
        only: &[Option<Vec<usize>>],
    ) -> TeamProblem {
        let n = xy.len() + 1;
        let at = |i: usize| if i == 0 { (50.0, 50.0) } else { xy[i - 1] };
        let costs = Arc::new(
            CostMatrix::from_fn(n, |i, j| (at(i).0 - at(j).0).hypot(at(i).1 - at(j).1)).unwrap(),
        );
        let robots = (0..m)
            .map(|_| TeamRobot {
                costs: costs.clone(),
                start: 0,
                end: 0,
            })
            .collect();
        let targets = (0..xy.len())
            .map(|t| TeamTarget {
                nodes: vec![t + 1],
                robots: only.get(t).cloned().flatten(),
            })
            .collect();
        TeamProblem::new(robots, targets, TeamObjective::Sum, bounds).unwrap()
    }

    fn reoptimised(problem: &TeamProblem, routes: Vec<Vec<usize>>) -> (State, State) {
        let setting = Setting::new(problem, 0.02, 100);
        let visits = routes
            .into_iter()
            .map(|r| {
                r.into_iter()
                    .map(|t| Visit {
                        target: t,
                        node: t + 1,
                    })
                    .collect()
            })
            .collect();
        let start = State::of(&setting, &problem.solution(visits));
        let budget = PairBudget {
            iterations: 300,
            total_iterations: 0,
            time_s: 0.0,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (found, _) = reoptimise_pairs(
            &setting,
            start.clone(),
            budget,
            &Deadline::new(),
            &mut rng,
            &mut |sub, warm, (_, iterations), seed| {
                // The search alone (no pool, no polish): enough for these pairs.
                let setting = Setting::new(sub, 0.02, 100);
                let budget = Budget {
                    time_limit_s: 0.0,
                    max_iterations: iterations,
                    deadline: &Deadline::new(),
                };
                let params = TeamLnsParams::default();
                let mut rng = ChaCha8Rng::seed_from_u64(seed);
                let start = State::of(&setting, warm);
                let (found, done) = search(&setting, start, &params, &budget, 0, &mut rng);
                Some((found.solution(&setting), done))
            },
        );
        (start, found)
    }

    /// Two clusters of targets east and west of the depot, each served half by one robot
    /// and half by the other (a third robot elsewhere): the pair, solved on its own,
    /// gives each robot one cluster.
    #[test]
    fn two_routes_sharing_two_clusters_crosswise_are_untangled() {
        let mut xy = Vec::new();
        for k in 0..6 {
            xy.push((90.0, 40.0 + 4.0 * k as f64)); // east: 0..6
        }
        for k in 0..6 {
            xy.push((10.0, 40.0 + 4.0 * k as f64)); // west: 6..12
        }
        xy.extend([(50.0, 95.0), (55.0, 95.0), (45.0, 95.0)]); // north: 12..15
        let p = problem(&xy, 3, Some(RouteSize { min: 3, max: 6 }), &[]);
        let (start, found) = reoptimised(
            &p,
            vec![
                vec![0, 1, 2, 6, 7, 8],
                vec![3, 4, 5, 9, 10, 11],
                vec![12, 13, 14],
            ],
        );
        let setting = Setting::new(&p, 0.02, 100);
        assert!(found.scalar(&setting) < 0.8 * start.scalar(&setting));
        let mut east_west: Vec<Vec<usize>> = found.routes[..2]
            .iter()
            .map(|r| {
                let mut t: Vec<usize> = r.iter().map(|v| v.target).collect();
                t.sort_unstable();
                t
            })
            .collect();
        east_west.sort();
        assert_eq!(
            east_west,
            vec![(0..6).collect::<Vec<_>>(), (6..12).collect()]
        );
        let mut north: Vec<usize> = found.routes[2].iter().map(|v| v.target).collect();
        north.sort_unstable();
        assert_eq!(north, vec![12, 13, 14]);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(40))]

        /// On random problems (size bounds, robot restrictions) the result is a valid
        /// solution never worse than the start.
        #[test]
        fn pairs_never_worsen_nor_break_a_solution(
            xy in proptest::collection::vec((0.0f64..100.0, 0.0f64..100.0), 6..24),
            m in 3usize..5,
            restricted in proptest::collection::vec(proptest::option::of(0usize..5), 24),
            seed in 0u64..1000,
        ) {
            let k = xy.len();
            let only: Vec<Option<Vec<usize>>> =
                (0..k).map(|t| restricted[t].map(|r| vec![r % m])).collect();
            let p = problem(&xy, m, None, &only);
            // A start that respects the restrictions: each target on its robot, or
            // spread round the robots.
            let mut routes = vec![Vec::new(); m];
            for t in 0..k {
                routes[only[t].as_ref().map_or(t % m, |r| r[0])].push(t);
            }
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            for r in routes.iter_mut() {
                use rand::seq::SliceRandom;
                r.shuffle(&mut rng);
            }
            let (start, found) = reoptimised(&p, routes);
            let setting = Setting::new(&p, 0.02, 100);
            let solution = found.solution(&setting);
            prop_assert!(p.validate(&solution).is_ok(), "{:?}", p.validate(&solution));
            prop_assert!(!better(&setting, &start, &found));
        }
    }
}
