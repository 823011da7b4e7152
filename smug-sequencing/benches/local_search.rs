//! The local search on a seeded random Euclidean matrix of 1 000 nodes (a thousand
//! targets, as `lunar` 1000×10 sequences):
//!
//! - `warm/1000`: one warm start (`solve_from`, 4 rounds: one after the quarter) from
//!   a tour found before: what each round of the lazy loop costs besides its rounds —
//!   the working copy of the matrix, the candidate lists and the first descent;
//! - `cold/1000`: a solve from scratch with 100 rounds.

mod common;

use common::random_matrix;
use criterion::{criterion_group, criterion_main, Criterion};
use smug_core::{Sequencer, TourKind};
use smug_sequencing::{LocalSearch, LocalSearchParams};
use std::hint::black_box;
use std::time::Duration;

fn solver(rounds: u64) -> LocalSearch {
    let params = LocalSearchParams {
        time_limit_s: 0.0,
        max_iterations: rounds,
        ..LocalSearchParams::default()
    };
    LocalSearch::with_seed(params, 1).expect("parameters")
}

fn local_search(c: &mut Criterion) {
    let costs = random_matrix(1000, 1, [200.0, 200.0]);
    let kind = TourKind::Closed;
    let initial = solver(100).solve(&costs, kind).expect("solves");
    let mut group = c.benchmark_group("local_search");
    let warm = solver(4);
    group.bench_function("warm/1000", |b| {
        b.iter(|| black_box(warm.solve_from(&costs, kind, &initial).expect("solves")))
    });
    let cold = solver(100);
    group.bench_function("cold/1000", |b| {
        b.iter(|| black_box(cold.solve(&costs, kind).expect("solves")))
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = local_search
}
criterion_main!(benches);
