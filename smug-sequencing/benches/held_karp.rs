//! Held-Karp on seeded random symmetric (Euclidean) cost matrices over the lunar
//! bounds (30 × 29 m), at the sizes of the paper's mission (13 ToIs):
//!
//! - `closed/13`: a closed tour over 13 nodes;
//! - `closed/14`: start + 13 ToIs, returning to the start;
//! - `open/15`: start + 13 ToIs + a distinct end node (`TourKind::OpenTo(14)`).

use criterion::{criterion_group, criterion_main, Criterion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smug_core::{CostMatrix, Sequencer, TourKind};
use smug_sequencing::{HeldKarp, HeldKarpParams};
use std::hint::black_box;
use std::time::Duration;

/// Euclidean distances between `n` seeded random points in 30 × 29 m.
fn random_matrix(n: usize, seed: u64) -> CostMatrix {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let points: Vec<(f64, f64)> = (0..n)
        .map(|_| (rng.random_range(0.0..30.0), rng.random_range(0.0..29.0)))
        .collect();
    CostMatrix::from_fn(n, |i, j| {
        (points[i].0 - points[j].0).hypot(points[i].1 - points[j].1)
    })
    .expect("finite costs")
}

fn held_karp(c: &mut Criterion) {
    let solver = HeldKarp::new(HeldKarpParams::default()).expect("default parameters");
    let cases = [
        ("closed/13", 13, TourKind::Closed),
        ("closed/14", 14, TourKind::Closed),
        ("open/15", 15, TourKind::OpenTo(14)),
    ];
    let mut group = c.benchmark_group("held_karp");
    for (name, n, kind) in cases {
        let costs = random_matrix(n, n as u64);
        group.bench_function(name, |b| {
            b.iter(|| black_box(solver.solve(&costs, kind).expect("solves")))
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = held_karp
}
criterion_main!(benches);
