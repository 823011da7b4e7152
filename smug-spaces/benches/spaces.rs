//! Distances of the curvature-limited spaces (turning radius 1.5 m, the rover's), on
//! 1 024 seeded random pose pairs per iteration:
//!
//! - `distance/<space>`: the full shortest-curve length;
//! - `distance_within/<space>`: the length only where it is at most 2 m (the k-NN
//!   case: most candidates are farther than the k-th nearest found so far).
//!
//! Pairs lie within a 6 × 6 m square with any headings, as k-NN candidates do.
//! Throughput is per distance.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smug_core::{Pose2, StateSpace};
use smug_spaces::{DubinsSpace, ReedsSheppSpace};
use std::f64::consts::PI;
use std::hint::black_box;

/// Seeded random pose pairs within a 6 × 6 m square.
fn pairs(n: usize) -> Vec<(Pose2, Pose2)> {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut pose = || {
        Pose2::new(
            rng.random_range(0.0..6.0),
            rng.random_range(0.0..6.0),
            rng.random_range(-PI..PI),
        )
    };
    (0..n).map(|_| (pose(), pose())).collect()
}

fn bench_space(c: &mut Criterion, name: &str, space: &dyn StateSpace) {
    let pairs = pairs(1024);
    let mut group = c.benchmark_group("spaces");
    group.throughput(Throughput::Elements(pairs.len() as u64));
    group.bench_function(format!("distance/{name}"), |b| {
        b.iter(|| {
            pairs
                .iter()
                .map(|(a, g)| space.distance(black_box(a), black_box(g)))
                .sum::<f64>()
        })
    });
    group.bench_function(format!("distance_within/{name}"), |b| {
        b.iter(|| {
            pairs
                .iter()
                .filter_map(|(a, g)| space.distance_within(black_box(a), black_box(g), 2.0))
                .sum::<f64>()
        })
    });
    group.finish();
}

fn spaces(c: &mut Criterion) {
    bench_space(c, "reeds-shepp", &ReedsSheppSpace::new(1.5).unwrap());
    bench_space(c, "dubins", &DubinsSpace::new(1.5).unwrap());
}

criterion_group!(benches, spaces);
criterion_main!(benches);
