//! The solvers, the reader and the suite loader on instances the tests make, with
//! optima known by construction (see `support`) or computed here by brute force or
//! Held-Karp. No third-party data is read.

mod support;

use smug_bench::tsp::suite::{load_suite, BenchInstance};
use smug_core::{CostMatrix, Sequencer, TourKind};
use smug_sequencing::tsplib::ProblemType;
use smug_sequencing::{
    read_tour, read_tsplib, BruteForce, HeldKarp, HeldKarpParams, LocalSearch, LocalSearchParams,
};
use std::time::Instant;
use support::{convex, lattice, planted, random_matrix, random_points, with_potentials, Known};

/// A small instance with integer EUC_2D costs whose optimum brute force finds.
fn brute_forced(name: &str, coords: Option<Vec<(f64, f64)>>, costs: CostMatrix) -> Known {
    let tour = BruteForce.solve(&costs, TourKind::Closed).unwrap();
    Known::new(name, coords, costs, tour.order)
}

/// The generated suite: three symmetric (EUC_2D) and three asymmetric (FULL_MATRIX)
/// instances with integer costs.
fn suite_instances() -> Vec<Known> {
    let (coords, costs) = random_points(9, 1);
    let grid = lattice("grid4x4", 4, 4, 10.0);
    vec![
        grid.clone(),
        lattice("grid5x6", 5, 6, 7.0),
        brute_forced("random9", Some(coords), costs),
        planted("planted17", 17, 2),
        with_potentials(&grid, "grid4x4-skewed", 20, 3),
        brute_forced("random8-asym", None, random_matrix(8, false, 4)),
    ]
}

/// Writes the generated suite to a fresh temporary folder and loads it.
fn suite(label: &str) -> (Vec<Known>, Vec<BenchInstance>) {
    let dir = support::temp_dir(label);
    let known = suite_instances();
    support::write_suite(&dir, &known);
    let loaded = load_suite(&dir).unwrap_or_else(|e| panic!("{e}"));
    (known, loaded)
}

#[test]
fn every_instance_reads_with_its_listed_dimension() {
    let (known, suite) = suite("read");
    let names: Vec<&str> = suite.iter().map(|i| i.name.as_str()).collect();
    let expected = [
        "grid4x4",
        "grid5x6",
        "random9",
        "planted17",
        "grid4x4-skewed",
    ];
    assert_eq!(
        names[..5],
        expected,
        "tsp/ first, each in its optima.csv order"
    );
    assert_eq!(suite.len(), 6);
    for entry in suite {
        let made = known.iter().find(|k| k.name == entry.name).unwrap();
        let tsp = read_tsplib(&entry.path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(tsp.name, entry.name);
        assert_eq!(tsp.problem, entry.problem);
        assert_eq!(tsp.costs, made.costs, "{}: read back exactly", entry.name);
        assert_eq!(entry.optimum, made.optimum);
        let n = tsp.costs.len();
        assert!((0..n).all(|i| tsp.costs.get(i, i) == 0.0), "{}", entry.name);
        let integral = (0..n * n).all(|k| tsp.costs.get(k / n, k % n).fract() == 0.0);
        assert!(integral, "{}: TSPLIB weights are integers", entry.name);
        match entry.problem {
            ProblemType::Tsp => {
                assert_eq!(tsp.weights, "EUC2D");
                assert!(tsp.costs.is_symmetric(0.0));
            }
            ProblemType::Atsp => {
                assert_eq!(tsp.weights, "EXPLICIT/FULLMATRIX");
                assert!(!tsp.costs.is_symmetric(0.0));
            }
        }
    }
}

#[test]
fn shipped_optimal_tours_cost_the_listed_optimum() {
    let (_, suite) = suite("tours");
    let mut checked = 0;
    for entry in suite {
        let costs = read_tsplib(&entry.path).unwrap().costs;
        let order = read_tour(entry.path.with_extension("opt.tour")).unwrap();
        assert_eq!(
            costs.tour_cost(&order, TourKind::Closed),
            entry.optimum,
            "{}",
            entry.name
        );
        checked += 1;
    }
    assert_eq!(checked, 6);
}

fn held_karp() -> HeldKarp {
    HeldKarp::new(HeldKarpParams::default()).unwrap()
}

#[test]
fn held_karp_solves_17_node_asymmetric_instances_exactly() {
    let started = Instant::now();
    for known in [
        planted("planted17", 17, 5),
        with_potentials(&lattice("grid4x4", 4, 4, 10.0), "skewed", 50, 6),
    ] {
        let tour = held_karp().solve(&known.costs, TourKind::Closed).unwrap();
        assert!(tour.is_valid_for(known.n(), TourKind::Closed));
        assert_eq!(tour.cost, known.optimum, "{}", known.name);
    }
    assert!(started.elapsed().as_secs_f64() < 5.0);
}

#[test]
fn exact_solvers_agree_with_brute_force_on_random_instances() {
    for seed in 0..6 {
        let symmetric = seed % 2 == 0;
        let costs = random_matrix(9, symmetric, 100 + seed);
        for kind in [TourKind::Closed, TourKind::OpenTo(1 + seed as usize)] {
            let reference = BruteForce.solve(&costs, kind).unwrap();
            let exact = held_karp().solve(&costs, kind).unwrap();
            assert!(exact.is_valid_for(9, kind));
            assert_eq!(exact.cost, reference.cost, "seed {seed}, {kind:?}");
        }
    }
}

#[test]
fn every_solver_reaches_constructed_optima_closed_and_open() {
    let auto = smug_sequencing::Auto::new(
        smug_sequencing::AutoParams::default(),
        smug_core::rng::stage_rng(1, "sequencer"),
    )
    .unwrap();
    let square = lattice("grid4x4", 4, 4, 10.0);
    let ring = convex("ellipse14", 14, 8);
    let skewed = with_potentials(&ring, "ellipse14-skewed", 30, 9);
    for known in [square, ring, skewed, planted("planted15", 15, 10)] {
        for case in [known.clone(), known.open()] {
            let solvers: [(&str, &dyn Sequencer); 3] = [
                ("held-karp", &held_karp()),
                ("auto", &auto),
                (
                    "local-search",
                    &LocalSearch::with_seed(deterministic(200), 3).unwrap(),
                ),
            ];
            for (solver, sequencer) in solvers {
                let tour = sequencer.solve(&case.costs, case.kind).unwrap();
                assert!(tour.is_valid_for(case.n(), case.kind));
                let gap = tour.cost - case.optimum;
                assert!(
                    gap.abs() < 1e-6,
                    "{solver} on {}: {} vs {}",
                    case.name,
                    tour.cost,
                    case.optimum
                );
            }
        }
    }
}

/// Deterministic budget: a fixed number of perturbation rounds, no time limit.
fn deterministic(iterations: u64) -> LocalSearchParams {
    LocalSearchParams {
        time_limit_s: 0.0,
        max_iterations: iterations,
        ..LocalSearchParams::default()
    }
}

/// Local search's gap on `known` in percent, with `iterations` rounds (seed 7).
fn local_search_gap(known: &Known, iterations: u64) -> (f64, f64) {
    let solver = LocalSearch::with_seed(deterministic(iterations), 7).unwrap();
    let started = Instant::now();
    let tour = solver.solve(&known.costs, known.kind).unwrap();
    let elapsed = started.elapsed().as_secs_f64();
    assert!(tour.is_valid_for(known.n(), known.kind), "{}", known.name);
    assert!(
        tour.cost >= known.optimum - 1e-6,
        "{}: below the optimum",
        known.name
    );
    (100.0 * (tour.cost - known.optimum) / known.optimum, elapsed)
}

#[test]
fn local_search_is_within_two_percent_on_small_euclidean_instances() {
    for known in [
        convex("ellipse51", 51, 11),
        lattice("grid9x6", 9, 6, 10.0),
        lattice("grid10x10", 10, 10, 10.0),
    ] {
        let (gap, elapsed) = local_search_gap(&known, 1000);
        assert!(
            gap <= 2.0,
            "{}: {gap:.2}% above {}",
            known.name,
            known.optimum
        );
        if !cfg!(debug_assertions) {
            assert!(elapsed < 1.0, "{}: {elapsed:.2} s", known.name);
        }
    }
}

#[test]
fn local_search_handles_asymmetric_instances() {
    let ellipse = convex("ellipse48", 48, 12);
    for known in [
        with_potentials(&lattice("grid6x6", 6, 6, 10.0), "grid6x6-skewed", 40, 13),
        with_potentials(&ellipse, "ellipse48-skewed", 500, 14),
        planted("planted48", 48, 15),
    ] {
        let (gap, _) = local_search_gap(&known, 2000);
        assert!(
            gap <= 3.0,
            "{}: {gap:.2}% above {}",
            known.name,
            known.optimum
        );
    }
}

#[test]
fn local_search_finds_near_optimal_open_paths() {
    let ellipse = convex("ellipse60", 60, 16);
    for known in [
        lattice("grid8x8", 8, 8, 10.0).open(),
        ellipse.clone().open(),
        with_potentials(&ellipse, "ellipse60-skewed", 500, 17).open(),
    ] {
        let (gap, _) = local_search_gap(&known, 1000);
        assert!(
            gap <= 2.0,
            "{}: {gap:.2}% above {}",
            known.name,
            known.optimum
        );
    }
}

#[test]
fn an_iteration_budget_gives_bit_identical_tours() {
    let (_, costs) = random_points(100, 18);
    let solve = |seed| {
        LocalSearch::with_seed(deterministic(300), seed)
            .unwrap()
            .solve(&costs, TourKind::Closed)
            .unwrap()
    };
    let first = solve(3);
    assert_eq!(first, solve(3));
    let open = LocalSearch::with_seed(deterministic(300), 3).unwrap();
    let a = open.solve(&costs, TourKind::OpenTo(42)).unwrap();
    assert_eq!(a, open.solve(&costs, TourKind::OpenTo(42)).unwrap());
    assert!(a.is_valid_for(100, TourKind::OpenTo(42)));
}

#[test]
fn missing_legs_are_avoided_when_a_finite_tour_exists() {
    // 100 random points with a third of their legs removed (symmetrically, by a fixed
    // pattern); the lattice order 0, 1, …, 99 is kept finite so a finite tour exists.
    let (_, full) = random_points(100, 19);
    let kept = |i: usize, j: usize| i.abs_diff(j) == 1 || i.abs_diff(j) == 99;
    let holes =
        |i: usize, j: usize| !kept(i, j) && (i.min(j) * 7 + i.max(j) * 13).is_multiple_of(3);
    let costs = CostMatrix::from_fn(100, |i, j| {
        if i != j && holes(i, j) {
            f64::INFINITY
        } else {
            full.get(i, j)
        }
    })
    .unwrap();
    for kind in [TourKind::Closed, TourKind::OpenTo(99)] {
        let tour = LocalSearch::with_seed(deterministic(500), 1)
            .unwrap()
            .solve(&costs, kind)
            .unwrap();
        assert!(tour.is_valid_for(100, kind));
        assert!(tour.cost.is_finite(), "{kind:?}: {}", tour.cost);
    }
}

#[test]
fn the_time_limit_is_respected_on_a_thousand_nodes() {
    let known = lattice("grid25x40", 25, 40, 10.0);
    let params = LocalSearchParams {
        time_limit_s: 0.3,
        ..LocalSearchParams::default()
    };
    let started = Instant::now();
    let tour = LocalSearch::with_seed(params, 0)
        .unwrap()
        .solve(&known.costs, TourKind::OpenTo(500))
        .unwrap();
    let elapsed = started.elapsed().as_secs_f64();
    assert!(tour.is_valid_for(known.n(), TourKind::OpenTo(500)));
    if !cfg!(debug_assertions) {
        assert!(elapsed < 0.6, "{elapsed:.2} s");
        // An open path is a tour minus one leg: within 5% of the optimal tour.
        assert!(tour.cost < 1.05 * known.optimum, "{}", tour.cost);
    }
}
