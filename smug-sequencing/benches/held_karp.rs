//! Held-Karp on seeded random symmetric (Euclidean) cost matrices over the lunar
//! bounds (30 × 29 m), at the sizes of the paper's mission (13 ToIs):
//!
//! - `closed/13`: a closed tour over 13 nodes;
//! - `closed/14`: start + 13 ToIs, returning to the start;
//! - `open/15`: start + 13 ToIs + a distinct end node (`TourKind::OpenTo(14)`).

mod common;

use common::random_matrix;
use criterion::{criterion_group, criterion_main, Criterion};
use smug_core::{Sequencer, TourKind};
use smug_sequencing::{HeldKarp, HeldKarpParams};
use std::hint::black_box;
use std::time::Duration;

fn held_karp(c: &mut Criterion) {
    let solver = HeldKarp::new(HeldKarpParams::default()).expect("default parameters");
    let cases = [
        ("closed/13", 13, TourKind::Closed),
        ("closed/14", 14, TourKind::Closed),
        ("open/15", 15, TourKind::OpenTo(14)),
    ];
    let mut group = c.benchmark_group("held_karp");
    for (name, n, kind) in cases {
        let costs = random_matrix(n, n as u64, [30.0, 29.0]);
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
