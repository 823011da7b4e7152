//! The reader on the small TSPLIB files of `tests/data` (written for these tests):
//! every distance type and matrix layout it supports, the quirks of real files, and
//! `.tour` files. Expected weights are worked out by hand in the comments.

use smug_core::{CostMatrix, TourKind};
use smug_sequencing::tsplib::ProblemType;
use smug_sequencing::{read_tour, read_tsplib, TsplibInstance};
use std::path::PathBuf;

fn sample(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(file)
}

fn read(file: &str) -> TsplibInstance {
    read_tsplib(sample(file)).unwrap_or_else(|e| panic!("{e}"))
}

/// Asserts the upper triangle given row by row (`upper[i][k]` is the cost from node
/// `i` to node `i + 1 + k`, 0-based) and that the matrix is symmetric.
fn assert_symmetric(costs: &CostMatrix, upper: &[&[f64]]) {
    assert_eq!(costs.len(), upper.len() + 1);
    for (i, row) in upper.iter().enumerate() {
        for (k, &expected) in row.iter().enumerate() {
            let j = i + 1 + k;
            assert_eq!(costs.get(i, j), expected, "({i}, {j})");
            assert_eq!(costs.get(j, i), expected, "({j}, {i})");
        }
    }
    assert!((0..costs.len()).all(|i| costs.get(i, i) == 0.0));
}

#[test]
fn euc_2d_uses_nint_rounding_and_needs_no_eof() {
    let text = std::fs::read_to_string(sample("rounding5.tsp")).unwrap();
    let has_eof = text.lines().any(|line| line.trim() == "EOF");
    assert!(!has_eof, "the sample must lack its EOF line");
    let tsp = read("rounding5.tsp");
    assert_eq!(
        (tsp.name.as_str(), tsp.weights.as_str()),
        ("rounding5", "EUC2D")
    );
    // (0,0) (3,4) (0,2.5) (1.5,0) (12,3): 5; 2.5 → 3 and 1.5 → 2 (halves round up);
    // √153 = 12.37 → 12; √11.25 = 3.35 → 3; √18.25 = 4.27 → 4; √82 = 9.06 → 9;
    // √8.5 = 2.92 → 3; √144.25 = 12.01 → 12; √119.25 = 10.92 → 11.
    assert_symmetric(
        &tsp.costs,
        &[
            &[5.0, 3.0, 2.0, 12.0],
            &[3.0, 4.0, 9.0],
            &[3.0, 12.0],
            &[11.0],
        ],
    );
}

#[test]
fn ceil_2d_rounds_up() {
    // (0,0) (1,1) (3,4): √2 → 2, 5 stays 5, √13 = 3.61 → 4.
    let tsp = read("ceil3.tsp");
    assert_eq!(tsp.weights, "CEIL2D");
    assert_symmetric(&tsp.costs, &[&[2.0, 5.0], &[4.0]]);
}

#[test]
fn att_is_pseudo_euclidean_with_its_rounding() {
    // r = √((dx² + dy²) / 10), t = nint(r), t + 1 if t < r else t:
    // (0,0)-(6,8): r = √10 = 3.16, t = 3 < r → 4; (0,0)-(30,10): r = 10 → 10;
    // (6,8)-(30,10): r = √58 = 7.62, t = 8 ≥ r → 8.
    let tsp = read("att3.tsp");
    assert_eq!(tsp.weights, "ATT");
    assert_symmetric(&tsp.costs, &[&[4.0, 10.0], &[8.0]]);
}

#[test]
fn geo_reads_degrees_and_minutes_on_the_tsplib_sphere() {
    // Along the equator or a meridian the distance is the arc RRR · PI · Δ / 180 with
    // PI = 3.141592, RRR = 6378.388, Δ in degrees, plus 1, truncated:
    // 30' of longitude (0.30 is 0° 30', not 0.3°): 55.66 + 1 → 56;
    // 0.00 to -0.30 (30' south, the degrees truncated towards 0): 56;
    // 0.00 to 10.50 (10° 50' = 10.833°): 1206.01 + 1 → 1207;
    // -0.30 to 10.50 (11.333°): 1261.67 + 1 → 1262.
    let costs = read("geo4.tsp").costs;
    assert_eq!(costs.get(0, 1), 56.0);
    assert_eq!(costs.get(0, 2), 56.0);
    assert_eq!(costs.get(0, 3), 1207.0);
    assert_eq!(costs.get(2, 3), 1262.0);
    assert!(costs.is_symmetric(0.0));
    assert_eq!(costs.get(3, 3), 0.0);
}

/// The pentagon of `tests/data`: sides 10–14, diagonals 20–24.
const PENTAGON: [&[f64]; 4] = [
    &[10.0, 20.0, 21.0, 14.0],
    &[11.0, 22.0, 23.0],
    &[12.0, 24.0],
    &[13.0],
];

#[test]
fn every_explicit_layout_reads_the_same_matrix() {
    for (layout, weights) in [
        ("full", "EXPLICIT/FULLMATRIX"),
        ("upper-row", "EXPLICIT/UPPERROW"),
        ("lower-row", "EXPLICIT/LOWERROW"),
        ("upper-diag-row", "EXPLICIT/UPPERDIAGROW"),
        ("lower-diag-row", "EXPLICIT/LOWERDIAGROW"),
    ] {
        let tsp = read(&format!("pentagon-{layout}.tsp"));
        assert_eq!(tsp.weights, weights);
        assert_eq!(tsp.problem, ProblemType::Tsp);
        assert_symmetric(&tsp.costs, &PENTAGON);
    }
}

#[test]
fn full_matrix_quirks_are_handled() {
    // ring5 has 6 nodes (DIMENSION wins over the name), 9999 on its diagonal, rows
    // wrapped anywhere with tabs and trailing blanks, two COMMENT lines and a blank
    // line before EOF.
    let ring = read("ring5-full.atsp");
    assert_eq!(ring.name, "ring5");
    assert_eq!(ring.problem, ProblemType::Atsp);
    assert_eq!(ring.weights, "EXPLICIT/FULLMATRIX");
    let costs = &ring.costs;
    assert_eq!(costs.len(), 6);
    assert!(
        (0..6).all(|i| costs.get(i, i) == 0.0),
        "the 9999s are dropped"
    );
    // Leg i → i + 1 costs i + 1 (1-based: 1 → 2 costs 1); any other leg 30 + 10i + j.
    assert_eq!((costs.get(0, 1), costs.get(1, 0)), (1.0, 40.0));
    assert_eq!((costs.get(5, 0), costs.get(0, 5)), (6.0, 35.0));
    assert_eq!((costs.get(3, 2), costs.get(4, 3)), (62.0, 73.0));
    assert!(!costs.is_symmetric(0.0));
    assert!(ring.comment.contains("9999") && ring.comment.contains("costs 21"));
}

#[test]
fn optimal_tours_cost_the_known_optimum() {
    for (instance, tour, optimum) in [
        ("grid4x4.tsp", "grid4x4.opt.tour", 160.0),
        ("pentagon-upper-row.tsp", "pentagon.opt.tour", 60.0),
        ("ring5-full.atsp", "ring5-full.opt.tour", 21.0),
    ] {
        let costs = read(instance).costs;
        let order = read_tour(sample(tour)).unwrap();
        assert_eq!(order.len(), costs.len(), "{tour}");
        assert_eq!(order[0], 0, "{tour}: tours start at node 1");
        assert_eq!(costs.tour_cost(&order, TourKind::Closed), optimum, "{tour}");
    }
    // The grid's tour is 16 unit steps of 10, so it is 160 whichever way it is read.
    let grid = read("grid4x4.tsp").costs;
    assert_eq!(
        (grid.get(0, 1), grid.get(0, 5), grid.get(0, 15)),
        (10.0, 14.0, 42.0)
    );
}

#[test]
fn the_exact_solvers_find_the_samples_optima() {
    use smug_core::Sequencer;
    use smug_sequencing::{BruteForce, HeldKarp, HeldKarpParams};
    let held_karp = HeldKarp::new(HeldKarpParams::default()).unwrap();
    for (file, optimum) in [("pentagon-full.tsp", 60.0), ("ring5-full.atsp", 21.0)] {
        let costs = read(file).costs;
        assert_eq!(
            BruteForce.solve(&costs, TourKind::Closed).unwrap().cost,
            optimum
        );
        assert_eq!(
            held_karp.solve(&costs, TourKind::Closed).unwrap().cost,
            optimum
        );
    }
    let grid = read("grid4x4.tsp").costs;
    assert_eq!(
        held_karp.solve(&grid, TourKind::Closed).unwrap().cost,
        160.0
    );
}
