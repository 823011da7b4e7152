//! The solvers and the reader on the TSPLIB instances in `shared/data/tsplib`.

use smug_core::{Sequencer, TourKind};
use smug_sequencing::bench::{load_suite, BenchInstance};
use smug_sequencing::tsplib::ProblemType;
use smug_sequencing::{
    read_tour, read_tsplib, HeldKarp, HeldKarpParams, LocalSearch, LocalSearchParams,
};
use std::path::PathBuf;
use std::time::Instant;

fn data_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/data/tsplib")
}

fn suite() -> Vec<BenchInstance> {
    load_suite(&data_dir()).expect("the TSPLIB suite in shared/data/tsplib")
}

fn instance(name: &str) -> BenchInstance {
    suite()
        .into_iter()
        .find(|i| i.name == name)
        .unwrap_or_else(|| panic!("{name} is not in the suite"))
}

#[test]
fn every_instance_reads_with_its_listed_dimension() {
    let suite = suite();
    assert_eq!(suite.len(), 23);
    for entry in suite {
        let tsp = read_tsplib(&entry.path).unwrap_or_else(|e| panic!("{e}"));
        let n = tsp.costs.len();
        assert_eq!(tsp.name, entry.name);
        assert_eq!(tsp.problem, entry.problem);
        assert!(
            (0..n).all(|i| tsp.costs.get(i, i) == 0.0),
            "{}: diagonal",
            entry.name
        );
        let integral = (0..n * n).all(|k| tsp.costs.get(k / n, k % n).fract() == 0.0);
        assert!(integral, "{}: TSPLIB weights are integers", entry.name);
        match entry.problem {
            ProblemType::Tsp => {
                assert_eq!(tsp.weights, "EUC2D");
                assert!(tsp.costs.is_symmetric(0.0));
            }
            ProblemType::Atsp => assert_eq!(tsp.weights, "EXPLICIT/FULLMATRIX"),
        }
    }
}

#[test]
fn full_matrix_quirks_are_handled() {
    // ftv33 has 34 nodes (DIMENSION wins over the name); br17's diagonal holds 9999.
    let ftv33 = read_tsplib(instance("ftv33").path).unwrap();
    assert_eq!(ftv33.costs.len(), 34);
    let br17 = read_tsplib(instance("br17").path).unwrap();
    assert_eq!(
        (
            br17.costs.get(0, 0),
            br17.costs.get(0, 1),
            br17.costs.get(16, 15)
        ),
        (0.0, 3.0, 8.0)
    );
    assert!(!read_tsplib(instance("ry48p").path)
        .unwrap()
        .costs
        .is_symmetric(0.0));
}

#[test]
fn euc_2d_uses_nint_rounding() {
    let eil51 = read_tsplib(instance("eil51").path).unwrap();
    // Nodes 1 (37, 52) and 2 (49, 49): √153 = 12.37 → 12.
    assert_eq!(eil51.costs.get(0, 1), 12.0);
    // pr1002 has no EOF line.
    assert_eq!(
        read_tsplib(instance("pr1002").path).unwrap().costs.len(),
        1002
    );
}

#[test]
fn shipped_optimal_tours_cost_the_listed_optimum() {
    let mut checked = 0;
    for entry in suite() {
        let tour_file = entry.path.with_extension("opt.tour");
        if !tour_file.exists() {
            continue;
        }
        let costs = read_tsplib(&entry.path).unwrap().costs;
        let order = read_tour(&tour_file).unwrap();
        assert_eq!(
            costs.tour_cost(&order, TourKind::Closed),
            entry.optimum,
            "{}",
            entry.name
        );
        checked += 1;
    }
    assert_eq!(checked, 10);
}

#[test]
fn held_karp_solves_br17_exactly() {
    let costs = read_tsplib(instance("br17").path).unwrap().costs;
    let started = Instant::now();
    let tour = HeldKarp::new(HeldKarpParams::default())
        .unwrap()
        .solve(&costs, TourKind::Closed)
        .unwrap();
    assert!(tour.is_valid_for(17, TourKind::Closed));
    assert_eq!(tour.cost, 39.0);
    assert!(started.elapsed().as_secs_f64() < 5.0);
}

/// Deterministic budget: a fixed number of perturbation rounds, no time limit.
fn deterministic(iterations: u64) -> LocalSearchParams {
    LocalSearchParams {
        time_limit_s: 0.0,
        max_iterations: iterations,
        ..LocalSearchParams::default()
    }
}

#[test]
fn local_search_is_within_two_percent_on_small_euclidean_instances() {
    for name in ["eil51", "berlin52", "kroA100"] {
        let entry = instance(name);
        let costs = read_tsplib(&entry.path).unwrap().costs;
        let solver = LocalSearch::with_seed(deterministic(1000), 7).unwrap();
        let started = Instant::now();
        let tour = solver.solve(&costs, TourKind::Closed).unwrap();
        let elapsed = started.elapsed().as_secs_f64();
        assert!(tour.is_valid_for(costs.len(), TourKind::Closed));
        let gap = 100.0 * (tour.cost - entry.optimum) / entry.optimum;
        assert!(
            gap <= 2.0,
            "{name}: {} is {gap:.2}% above {}",
            tour.cost,
            entry.optimum
        );
        if !cfg!(debug_assertions) {
            assert!(elapsed < 1.0, "{name}: {elapsed:.2} s");
        }
    }
}

#[test]
fn local_search_handles_asymmetric_instances() {
    for name in ["ftv33", "ry48p"] {
        let entry = instance(name);
        let costs = read_tsplib(&entry.path).unwrap().costs;
        let tour = LocalSearch::with_seed(deterministic(2000), 7)
            .unwrap()
            .solve(&costs, TourKind::Closed)
            .unwrap();
        let gap = 100.0 * (tour.cost - entry.optimum) / entry.optimum;
        assert!(
            gap <= 3.0,
            "{name}: {} is {gap:.2}% above {}",
            tour.cost,
            entry.optimum
        );
    }
}

#[test]
fn an_iteration_budget_gives_bit_identical_tours() {
    let costs = read_tsplib(instance("kroA100").path).unwrap().costs;
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
    // kroA100 with a third of its legs removed (symmetrically, by a fixed pattern).
    let full = read_tsplib(instance("kroA100").path).unwrap().costs;
    let holes = |i: usize, j: usize| (i.min(j) * 7 + i.max(j) * 13) % 3 == 0;
    let costs = smug_core::CostMatrix::from_fn(100, |i, j| {
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
fn the_time_limit_is_respected_on_pr1002() {
    let costs = read_tsplib(instance("pr1002").path).unwrap().costs;
    let params = LocalSearchParams {
        time_limit_s: 0.3,
        ..LocalSearchParams::default()
    };
    let started = Instant::now();
    let tour = LocalSearch::with_seed(params, 0)
        .unwrap()
        .solve(&costs, TourKind::OpenTo(500))
        .unwrap();
    let elapsed = started.elapsed().as_secs_f64();
    assert!(tour.is_valid_for(1002, TourKind::OpenTo(500)));
    if !cfg!(debug_assertions) {
        assert!(elapsed < 0.6, "{elapsed:.2} s");
        // An open path is a tour minus one leg: within 5% of the optimal tour.
        assert!(tour.cost < 1.05 * 259045.0, "{}", tour.cost);
    }
}
