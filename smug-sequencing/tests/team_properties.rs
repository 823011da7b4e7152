//! Properties of the team sequencers on random team problems (asymmetric per-robot
//! matrices with missing legs, several PoIs per target, restricted targets, both
//! objectives, open routes, size bounds): `team-exact` equals brute force, `team-lns`
//! is valid, reproducible, never worse than its warm start and optimal on small ones.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smug_core::{
    CostMatrix, RouteSize, Sequencer, TeamError, TeamObjective, TeamProblem, TeamRobot,
    TeamSequencer, TeamSolution, TeamTarget, TourKind,
};
use smug_sequencing::team::{
    brute_force_team, mtsp_problem, TeamExact, TeamExactParams, TeamLns, TeamLnsParams,
};
use smug_sequencing::{LocalSearch, LocalSearchParams};
use std::sync::Arc;

/// A random team problem with `m` robots and `k` targets, or `None` when the draw is
/// unservable (a target with no finite PoI for any allowed robot).
fn random_problem(rng: &mut ChaCha8Rng, m: usize, k: usize) -> Option<TeamProblem> {
    let starts = m + 1; // node m: a shared end some robots use
    let mut targets = Vec::new();
    let mut next = starts;
    for _ in 0..k {
        let count = rng.random_range(1..=2);
        let robots = rng.random_bool(0.3).then(|| {
            let mut allowed: Vec<usize> = (0..m).filter(|_| rng.random_bool(0.5)).collect();
            if allowed.is_empty() {
                allowed.push(rng.random_range(0..m));
            }
            allowed
        });
        targets.push(TeamTarget {
            nodes: (next..next + count).collect(),
            robots,
        });
        next += count;
    }
    let n = next;
    let robots = (0..m)
        .map(|r| {
            let costs = CostMatrix::from_fn(n, |i, j| {
                if i == j {
                    0.0
                } else if rng.random_bool(0.08) {
                    f64::INFINITY
                } else {
                    rng.random_range(1..30) as f64 + rng.random_range(0..4) as f64 * 0.25
                }
            })
            .unwrap();
            let end = if rng.random_bool(0.25) { m } else { r };
            TeamRobot {
                costs: Arc::new(costs),
                start: r,
                end,
            }
        })
        .collect();
    let objective = if rng.random_bool(0.5) {
        TeamObjective::Sum
    } else {
        TeamObjective::Makespan
    };
    let route_size = (rng.random_bool(0.15) && k > 0).then(|| {
        let min = rng.random_range(0..=k / m);
        let max = rng.random_range(k.div_ceil(m).max(min)..=k);
        RouteSize { min, max }
    });
    TeamProblem::new(robots, targets, objective, route_size).ok()
}

fn close(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
}

fn same_score(problem: &TeamProblem, a: &TeamSolution, b: &TeamSolution) -> bool {
    let (x, y) = (problem.score(a), problem.score(b));
    close(x.0, y.0) && close(x.1, y.1)
}

#[test]
fn exact_equals_brute_force_on_400_random_problems() {
    let mut rng = ChaCha8Rng::seed_from_u64(32);
    let exact = TeamExact::new(TeamExactParams::default()).unwrap();
    let (mut checked, mut makespan, mut infinite) = (0, 0, 0);
    while checked < 400 {
        let m = rng.random_range(1..=3);
        let k = rng.random_range(0..=if m == 3 { 5 } else { 6 });
        let Some(problem) = random_problem(&mut rng, m, k) else {
            continue;
        };
        let brute = brute_force_team(&problem).expect("small enough");
        let found = exact.solve(&problem).unwrap();
        problem.validate(&found).unwrap();
        assert!(
            same_score(&problem, &found, &brute),
            "problem {checked}: exact {:?} vs brute force {:?}",
            problem.score(&found),
            problem.score(&brute)
        );
        checked += 1;
        makespan += usize::from(problem.objective() == TeamObjective::Makespan);
        infinite += usize::from(!brute.total.is_finite());
    }
    // Both objectives and some problems with no finite solution were drawn.
    assert!(makespan > 100 && makespan < 300, "{makespan}");
    assert!(infinite > 0 && infinite < 100, "{infinite}");
}

fn lns(iterations: u64, seed: u64) -> TeamLns {
    let params = TeamLnsParams {
        max_iterations: iterations,
        ..TeamLnsParams::default()
    };
    TeamLns::with_seed(params, seed).unwrap()
}

#[test]
fn lns_is_valid_reproducible_and_finds_the_optimum_of_small_problems() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let exact = TeamExact::new(TeamExactParams::default()).unwrap();
    let (mut checked, mut optimal) = (0, 0);
    while checked < 60 {
        let m = rng.random_range(1..=3);
        let Some(problem) = random_problem(&mut rng, m, 8) else {
            continue;
        };
        let best = exact.solve(&problem).unwrap();
        if !best.total.is_finite() {
            continue;
        }
        let found = lns(4000, checked).solve(&problem).unwrap();
        problem.validate(&found).unwrap();
        assert_eq!(found, lns(4000, checked).solve(&problem).unwrap());
        let (f, b) = (problem.score(&found), problem.score(&best));
        assert!(f.0 >= b.0 - 1e-9, "below the optimum: {f:?} < {b:?}");
        optimal += usize::from(same_score(&problem, &found, &best));

        checked += 1;
    }
    // Random non-metric matrices are hard for insertion: 55 of 60 measured.
    assert!(optimal >= 54, "optimal on only {optimal} of 60");
}

#[test]
fn lns_never_returns_worse_than_its_warm_start() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let exact = TeamExact::new(TeamExactParams::default()).unwrap();
    let mut checked = 0;
    while checked < 40 {
        let m = rng.random_range(2..=3);
        let Some(problem) = random_problem(&mut rng, m, 9) else {
            continue;
        };
        // The optimum as a warm start: a search of 5 iterations must keep it.
        let best = exact.solve(&problem).unwrap();
        let found = lns(5, checked).solve_from(&problem, &best).unwrap();
        problem.validate(&found).unwrap();
        assert!(same_score(&problem, &found, &best));
        checked += 1;
    }
}

#[test]
fn a_warm_start_that_does_not_fit_is_refused() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let problem = loop {
        if let Some(p) = random_problem(&mut rng, 2, 4) {
            break p;
        }
    };
    let mut bad = TeamExact::new(TeamExactParams::default())
        .unwrap()
        .solve(&problem)
        .unwrap();
    let moved = bad.routes[0].pop().or_else(|| bad.routes[1].pop());
    assert!(moved.is_some());
    let err = lns(5, 1).solve_from(&problem, &bad).unwrap_err();
    assert!(err.to_string().contains("not served"), "{err}");
}

/// Unit-square cities, Euclidean costs scaled by 1000.
fn euclidean(rng: &mut ChaCha8Rng, n: usize) -> CostMatrix {
    let points: Vec<(f64, f64)> = (0..n).map(|_| (rng.random(), rng.random())).collect();
    CostMatrix::from_fn(n, |i, j| {
        1000.0 * ((points[i].0 - points[j].0).powi(2) + (points[i].1 - points[j].1).powi(2)).sqrt()
    })
    .unwrap()
}

fn mtsp(costs: CostMatrix, m: usize, objective: TeamObjective) -> TeamProblem {
    mtsp_problem(costs, m, objective, None).unwrap()
}

#[test]
fn one_robot_matches_the_tsp_local_search() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let costs = euclidean(&mut rng, 150);
    let tsp = LocalSearch::with_seed(LocalSearchParams::default(), 1)
        .unwrap()
        .solve(&costs, TourKind::Closed)
        .unwrap();
    let problem = mtsp(costs, 1, TeamObjective::Sum);
    let found = lns(1000, 1).solve(&problem).unwrap();
    problem.validate(&found).unwrap();
    assert!(
        found.total <= tsp.cost * 1.005,
        "team-lns {} vs local-search {}",
        found.total,
        tsp.cost
    );
}

#[test]
fn makespan_leaves_no_robot_idle_and_beats_the_sum_objective_on_it() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let costs = euclidean(&mut rng, 60);
    let minmax = mtsp(costs.clone(), 4, TeamObjective::Makespan);
    let minsum = mtsp(costs, 4, TeamObjective::Sum);
    let a = lns(2000, 1).solve(&minmax).unwrap();
    let b = lns(2000, 1).solve(&minsum).unwrap();
    assert!(a.routes.iter().all(|r| !r.is_empty()), "{:?}", a.costs);
    assert!(a.makespan < b.makespan, "{} vs {}", a.makespan, b.makespan);
    assert!(b.total <= a.total, "{} vs {}", b.total, a.total);
}

#[test]
fn unservable_targets_and_empty_teams_are_named() {
    let costs = Arc::new(
        CostMatrix::from_fn(3, |i, j| if j == 2 && i != 2 { f64::INFINITY } else { 1.0 }).unwrap(),
    );
    let robot = TeamRobot {
        costs,
        start: 0,
        end: 0,
    };
    let targets = vec![
        TeamTarget {
            nodes: vec![1],
            robots: None,
        },
        TeamTarget {
            nodes: vec![2],
            robots: None,
        },
    ];
    let err = TeamProblem::new(
        vec![robot.clone()],
        targets.clone(),
        TeamObjective::Sum,
        None,
    )
    .unwrap_err();
    assert!(
        matches!(err, TeamError::Unservable { target: 1, .. }),
        "{err}"
    );
    let err = TeamProblem::new(vec![], targets.clone(), TeamObjective::Sum, None).unwrap_err();
    assert_eq!(err, TeamError::NoRobots);
    let restricted = vec![TeamTarget {
        nodes: vec![1],
        robots: Some(vec![3]),
    }];
    let err = TeamProblem::new(vec![robot], restricted, TeamObjective::Sum, None).unwrap_err();
    assert!(err.to_string().contains("robot 3"), "{err}");
}

/// A depot at the centre of `k` targets evenly spaced on a circle of radius 10.
fn circle(k: usize) -> CostMatrix {
    let point = |i: usize| {
        if i == 0 {
            (0.0, 0.0)
        } else {
            let a = std::f64::consts::TAU * (i - 1) as f64 / k as f64;
            (10.0 * a.cos(), 10.0 * a.sin())
        }
    };
    CostMatrix::from_fn(k + 1, |i, j| {
        let (a, b) = (point(i), point(j));
        (a.0 - b.0).hypot(a.1 - b.1)
    })
    .unwrap()
}

#[test]
fn long_routes_start_from_a_cut_tsp_tour_reproducibly() {
    // 2 salesmen, 450 targets on a circle: the routes average above `split_above`, so the
    // search starts from the better of insertion and the best cut of a TSP tour; the
    // optimum is two half circles, each with two radii (≈ 10π + 20).
    let problem = mtsp(circle(450), 2, TeamObjective::Makespan);
    let solve = || lns(40, 3).solve(&problem).unwrap();
    let (a, b) = (solve(), solve());
    assert_eq!(a.routes, b.routes);
    problem.validate(&a).unwrap();
    let makespan = problem.score(&a).0;
    let optimum = 10.0 * std::f64::consts::PI + 20.0;
    assert!(makespan < optimum * 1.01, "{makespan} vs ≈ {optimum}");
}
