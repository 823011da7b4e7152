//! `bench`: a generated suite folder loads, every instance runs and its gap is measured
//! against the optimum written in `optima.csv`.

mod support;

use smug_bench::solvers::{sequencer, SolverOptions};
use smug_bench::tsp::suite::{gap_percent, load_suite, run_instance, BenchResult};
use smug_core::TourKind;
use smug_sequencing::read_tsplib;
use smug_sequencing::tsplib::ProblemType;
use support::{lattice, planted, with_potentials, Known};

fn generated() -> Vec<Known> {
    let grid = lattice("grid6x4", 6, 4, 5.0);
    vec![
        grid.clone(),
        lattice("grid10x8", 10, 8, 3.0),
        planted("planted30", 30, 21),
        with_potentials(&grid, "grid6x4-skewed", 9, 22),
    ]
}

#[test]
fn a_generated_suite_runs_at_zero_gap() {
    let dir = support::temp_dir("bench");
    support::write_suite(&dir, &generated());
    let suite = load_suite(&dir).unwrap();
    assert_eq!(suite.len(), 4);
    let options = SolverOptions {
        time_limit_s: 0.0,
        max_iterations: Some(300),
        seed: 1,
    };
    let solver = sequencer("auto", &options).unwrap();
    for instance in &suite {
        let costs = read_tsplib(&instance.path).unwrap().costs;
        let result = run_instance(instance, &costs, solver.as_ref(), "auto", 0.0).unwrap();
        assert_eq!(result.asymmetric, instance.problem == ProblemType::Atsp);
        assert_eq!(result.n, costs.len());
        assert_eq!(result.cost, costs.tour_cost(&result.tour, TourKind::Closed));
        assert_eq!(
            (result.cost, result.gap_percent),
            (instance.optimum, 0.0),
            "{}",
            instance.name
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_worse_tour_reports_its_gap() {
    let dir = support::temp_dir("bench-gap");
    support::write_suite(&dir, &generated()[..1]);
    let instance = &load_suite(&dir).unwrap()[0];
    let costs = read_tsplib(&instance.path).unwrap().costs;
    assert_eq!(instance.optimum, 120.0, "24 steps of 5");
    // Row by row, 0 … 23: five steps of 5 in each of the 4 rows, three jumps from a
    // row's end to the next row's start, (25, r) → (0, r + 5): √650 = 25.50 → 25, and
    // home from 23 = (25, 15): √850 = 29.15 → 29. 100 + 75 + 29 = 204, 70% above 120.
    let order: Vec<usize> = (0..24).collect();
    let result = BenchResult::new(instance, &costs, "rows", 1.0, order, 0.5);
    assert_eq!(result.cost, 204.0);
    assert_eq!(result.gap_percent, 70.0);
    assert_eq!(
        (result.solver.as_str(), result.budget_s, result.time_s),
        ("rows", 1.0, 0.5)
    );
    assert_eq!(gap_percent(126.0, 120.0), 5.0);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_folder_without_optima_is_an_error() {
    let dir = support::temp_dir("bench-empty");
    let err = load_suite(&dir).unwrap_err().to_string();
    assert!(
        err.contains("no tsp/optima.csv or atsp/optima.csv"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
