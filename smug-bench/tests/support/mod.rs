//! Instances the tests make themselves, with optima known by construction, and a writer
//! of TSPLIB files and suite folders for them. No third-party data is read.
//!
//! - `lattice`: a `cols × rows` grid (rows even) of spacing `s`. Every leg joins two
//!   distinct lattice points, so it costs at least `s` (also after TSPLIB rounding):
//!   a serpentine cycle of `n` unit steps is optimal at `n · s`, and the cycle without
//!   its last leg is an optimal open path (`(n − 1) · s`).
//! - `convex`: points on an ellipse, Euclidean (unrounded) costs. The hull order is the
//!   optimal tour; the hull minus one side is an optimal open path between its ends.
//! - `with_potentials`: `c'(i, j) = c(i, j) + a_i + b_j` makes any instance asymmetric
//!   and shifts every closed tour by `Σa + Σb` (every open path between fixed ends by
//!   the same amount less `a_end + b_start`), so the optimal order is unchanged.
//! - `planted`: an asymmetric matrix whose hidden cycle has legs of 1–9 and every
//!   other leg (its reverse included) 1000 or more: the cycle is optimal while it
//!   costs below 1000.

#![allow(dead_code)]

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smug_core::{CostMatrix, TourKind};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// An instance and an optimal tour (closed unless `kind` says otherwise).
#[derive(Clone, Debug)]
pub struct Known {
    /// Our name for it (also the file stem when written).
    pub name: String,
    /// Node coordinates, when the costs come from them (EUC_2D when written).
    pub coords: Option<Vec<(f64, f64)>>,
    /// The costs.
    pub costs: CostMatrix,
    /// An optimal order, starting at node 0.
    pub tour: Vec<usize>,
    /// Closed tour or open path.
    pub kind: TourKind,
    /// The optimal cost.
    pub optimum: f64,
}

impl Known {
    /// Recomputes the optimum from the tour, so a wrong construction cannot hide.
    pub fn new(
        name: &str,
        coords: Option<Vec<(f64, f64)>>,
        costs: CostMatrix,
        tour: Vec<usize>,
    ) -> Self {
        let optimum = costs.tour_cost(&tour, TourKind::Closed);
        Self {
            name: name.to_string(),
            coords,
            costs,
            tour,
            kind: TourKind::Closed,
            optimum,
        }
    }

    /// The optimal open path from node 0 to the last node of the optimal tour: that tour
    /// without its closing leg. (Any path from 0 to that node plus the same closing leg
    /// is a tour, so no path can be cheaper.)
    pub fn open(mut self) -> Self {
        let end = *self.tour.last().expect("a non-empty tour");
        self.kind = TourKind::OpenTo(end);
        self.optimum = self.costs.tour_cost(&self.tour, self.kind);
        self.name.push_str("-open");
        self
    }

    /// Number of nodes.
    pub fn n(&self) -> usize {
        self.costs.len()
    }
}

/// TSPLIB's `nint` (round half up) of the Euclidean distance.
pub fn euc_2d(a: (f64, f64), b: (f64, f64)) -> f64 {
    ((a.0 - b.0).hypot(a.1 - b.1) + 0.5).floor()
}

fn matrix_from_coords(
    coords: &[(f64, f64)],
    metric: fn((f64, f64), (f64, f64)) -> f64,
) -> CostMatrix {
    CostMatrix::from_fn(coords.len(), |i, j| {
        if i == j {
            0.0
        } else {
            metric(coords[i], coords[j])
        }
    })
    .unwrap()
}

/// The serpentine cycle of a `cols × rows` lattice (node `r · cols + c`): along row 0
/// from column 0, back and forth over columns 1.. of each row, home down column 0.
fn serpentine(cols: usize, rows: usize) -> Vec<usize> {
    assert!(
        cols >= 2 && rows >= 2 && rows.is_multiple_of(2),
        "{cols} × {rows}"
    );
    let mut tour = vec![0];
    for r in 0..rows {
        let columns: Vec<usize> = if r % 2 == 0 {
            (1..cols).collect()
        } else {
            (1..cols).rev().collect()
        };
        tour.extend(columns.into_iter().map(|c| r * cols + c));
    }
    tour.extend((1..rows).rev().map(|r| r * cols));
    tour
}

/// A `cols × rows` lattice of spacing `spacing` with TSPLIB EUC_2D costs.
pub fn lattice(name: &str, cols: usize, rows: usize, spacing: f64) -> Known {
    let coords: Vec<(f64, f64)> = (0..rows * cols)
        .map(|k| ((k % cols) as f64 * spacing, (k / cols) as f64 * spacing))
        .collect();
    let costs = matrix_from_coords(&coords, euc_2d);
    let known = Known::new(name, Some(coords), costs, serpentine(cols, rows));
    assert_eq!(known.optimum, (rows * cols) as f64 * spacing);
    known
}

/// `n` points on an ellipse at random angles, unrounded Euclidean costs.
pub fn convex(name: &str, n: usize, seed: u64) -> Known {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut angles: Vec<f64> = (0..n)
        .map(|k| (k as f64 + rng.random_range(0.1..0.9)) * std::f64::consts::TAU / n as f64)
        .collect();
    angles.sort_by(f64::total_cmp);
    // Shuffle the node numbering so that the identity is not the answer.
    let mut ids: Vec<usize> = (0..n).collect();
    for k in (2..n).rev() {
        ids.swap(k, rng.random_range(1..=k));
    }
    let mut coords = vec![(0.0, 0.0); n];
    for (position, &id) in ids.iter().enumerate() {
        let a = angles[position];
        coords[id] = (1000.0 * a.cos(), 600.0 * a.sin());
    }
    let costs = matrix_from_coords(&coords, |a, b| (a.0 - b.0).hypot(a.1 - b.1));
    Known::new(name, Some(coords), costs, ids)
}

/// `known` with a random potential per row and per column (integers in 0..`max`).
pub fn with_potentials(known: &Known, name: &str, max: u32, seed: u64) -> Known {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = known.n();
    let a: Vec<f64> = (0..n)
        .map(|_| f64::from(rng.random_range(0..max)))
        .collect();
    let b: Vec<f64> = (0..n)
        .map(|_| f64::from(rng.random_range(0..max)))
        .collect();
    let costs = CostMatrix::from_fn(n, |i, j| {
        if i == j {
            0.0
        } else {
            known.costs.get(i, j) + a[i] + b[j]
        }
    })
    .unwrap();
    let shifted = Known::new(name, None, costs, known.tour.clone());
    let shift: f64 = a.iter().sum::<f64>() + b.iter().sum::<f64>();
    assert!((shifted.optimum - known.optimum - shift).abs() < 1e-6);
    shifted
}

/// An `n`-node asymmetric matrix with a planted optimal cycle (see the module doc).
pub fn planted(name: &str, n: usize, seed: u64) -> Known {
    assert!(
        9 * n < 1000,
        "the planted cycle must cost less than any other leg"
    );
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut tour: Vec<usize> = (0..n).collect();
    for k in (2..n).rev() {
        tour.swap(k, rng.random_range(1..=k));
    }
    let mut next = vec![0; n];
    for k in 0..n {
        next[tour[k]] = tour[(k + 1) % n];
    }
    let cells: Vec<f64> = (0..n * n)
        .map(|k| {
            let (i, j) = (k / n, k % n);
            if i == j {
                0.0
            } else if next[i] == j {
                f64::from(rng.random_range(1..=9u32))
            } else {
                f64::from(rng.random_range(1000..2000u32))
            }
        })
        .collect();
    let costs = CostMatrix::from_rows(n, cells).unwrap();
    Known::new(name, None, costs, tour)
}

/// `n` random integer points in a 100 × 100 square, TSPLIB EUC_2D costs; the optimum is
/// left to the caller (brute force or Held-Karp).
pub fn random_points(n: usize, seed: u64) -> (Vec<(f64, f64)>, CostMatrix) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let coords: Vec<(f64, f64)> = (0..n)
        .map(|_| {
            (
                f64::from(rng.random_range(0..100u32)),
                f64::from(rng.random_range(0..100u32)),
            )
        })
        .collect();
    let costs = matrix_from_coords(&coords, euc_2d);
    (coords, costs)
}

/// `n × n` random integers in 1..100, symmetric or not.
pub fn random_matrix(n: usize, symmetric: bool, seed: u64) -> CostMatrix {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let cells: Vec<f64> = (0..n * n)
        .map(|_| f64::from(rng.random_range(1..100u32)))
        .collect();
    CostMatrix::from_fn(n, |i, j| {
        if i == j {
            0.0
        } else if symmetric {
            cells[i.min(j) * n + i.max(j)]
        } else {
            cells[i * n + j]
        }
    })
    .unwrap()
}

/// The TSPLIB text of `known`: EUC_2D coordinates when it has them (and its costs are
/// the rounded ones), else an EXPLICIT FULL_MATRIX of integers (TYPE ATSP unless
/// symmetric).
pub fn tsplib_text(known: &Known) -> String {
    let n = known.n();
    let symmetric = known.costs.is_symmetric(0.0);
    let mut text = format!(
        "NAME: {}\nTYPE: {}\nCOMMENT: generated by the smug-sequencing tests\nDIMENSION: {n}\n",
        known.name,
        if symmetric { "TSP" } else { "ATSP" }
    );
    match &known.coords {
        Some(coords) => {
            text.push_str("EDGE_WEIGHT_TYPE: EUC_2D\nNODE_COORD_SECTION\n");
            for (k, (x, y)) in coords.iter().enumerate() {
                let _ = writeln!(text, "{} {x} {y}", k + 1);
            }
        }
        None => {
            text.push_str("EDGE_WEIGHT_TYPE: EXPLICIT\nEDGE_WEIGHT_FORMAT: FULL_MATRIX\n");
            text.push_str("EDGE_WEIGHT_SECTION\n");
            for i in 0..n {
                let row: Vec<String> = (0..n).map(|j| known.costs.get(i, j).to_string()).collect();
                let _ = writeln!(text, "{}", row.join(" "));
            }
        }
    }
    text.push_str("EOF\n");
    text
}

/// The `.tour` text of `known`'s optimal tour (1-based ids ended by -1).
pub fn tour_text(known: &Known) -> String {
    let ids: Vec<String> = known.tour.iter().map(|v| (v + 1).to_string()).collect();
    format!(
        "NAME: {}.opt.tour\nTYPE: TOUR\nDIMENSION: {}\nTOUR_SECTION\n{}\n-1\nEOF\n",
        known.name,
        known.n(),
        ids.join("\n")
    )
}

/// A fresh, empty temporary directory for `label`.
pub fn temp_dir(label: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("smug-seq-{label}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes a suite as `bench::load_suite` reads it: `tsp/` for the symmetric instances,
/// `atsp/` for the others, each with its files, `NAME.opt.tour` and `optima.csv`.
pub fn write_suite(dir: &Path, instances: &[Known]) {
    for (sub, symmetric) in [("tsp", true), ("atsp", false)] {
        let folder = dir.join(sub);
        std::fs::create_dir_all(&folder).unwrap();
        let mut csv = "name,dimension,optimal_tour_length,note\n".to_string();
        for known in instances
            .iter()
            .filter(|k| k.costs.is_symmetric(0.0) == symmetric)
        {
            assert_eq!(known.kind, TourKind::Closed, "suites hold closed tours");
            let file = folder.join(format!("{}.{sub}", known.name));
            std::fs::write(file, tsplib_text(known)).unwrap();
            let tour = folder.join(format!("{}.opt.tour", known.name));
            std::fs::write(tour, tour_text(known)).unwrap();
            let _ = writeln!(
                csv,
                "{},{},{},generated",
                known.name,
                known.n(),
                known.optimum
            );
        }
        std::fs::write(folder.join("optima.csv"), csv).unwrap();
    }
}
