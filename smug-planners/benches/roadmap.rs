//! Roadmap hot paths of LazyPRM* on the lunar bounds (30 × 29 m), default SE(2) metric:
//!
//! - `knn`: [`XyGrid::k_nearest`] among 20 000 seeded random poses, with LazyPRM*'s
//!   `k = ⌈e(1 + 1/3) ln n⌉` (36), for 128 fixed random queries per iteration;
//! - `roadmap/build`: adding 5 000 vertices to a [`Roadmap`] (k-NN, edges, components);
//! - `astar`: [`AStar::search`] and [`AStar::search_lazy`] on a fixed 5 000-vertex
//!   roadmap between 32 fixed random vertex pairs per iteration. The lazy evaluator
//!   hides 10% of the edges as invalid but records nothing, so the roadmap stays the
//!   same from one iteration to the next.
//!
//! Throughputs are per query (k-NN queries, searches) or per vertex (build).

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode, Throughput};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smug_core::{Bounds2, PathLength, Pose2, Se2Space, StateSpace};
use smug_planners::nn::XyGrid;
use smug_planners::roadmap::{AStar, Evaluator, Roadmap, Validity};
use std::f64::consts::PI;
use std::hint::black_box;
use std::time::Duration;

/// The lunar world's bounds (`LunarParams::default().size`).
const BOUNDS: Bounds2 = Bounds2 {
    min: [0.0, 0.0],
    max: [30.0, 29.0],
};

/// LazyPRM*'s connection count `k = ⌈e(1 + 1/d) ln n⌉` with `d = 3`, at least 1.
fn connection_k(n: usize) -> usize {
    let k = (std::f64::consts::E * (1.0 + 1.0 / 3.0) * (n.max(1) as f64).ln()).ceil();
    (k as usize).max(1)
}

fn random_poses(n: usize, seed: u64) -> Vec<Pose2> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            Pose2::new(
                rng.random_range(BOUNDS.min[0]..BOUNDS.max[0]),
                rng.random_range(BOUNDS.min[1]..BOUNDS.max[1]),
                rng.random_range(-PI..PI),
            )
        })
        .collect()
}

/// A roadmap of `n` valid vertices, each connected to its k nearest as LazyPRM* does.
fn build_roadmap(poses: &[Pose2], metric: &Se2Space) -> Roadmap {
    let (w_t, _) = metric.lower_bound_weights();
    let objective = PathLength::default();
    let mut map = Roadmap::new(BOUNDS);
    for pose in poses {
        let k = connection_k(map.live_vertex_count() + 1);
        map.add_vertex(*pose, Validity::Valid, k, (metric, w_t), &objective);
    }
    map
}

fn knn(c: &mut Criterion) {
    const N: usize = 20_000;
    const QUERIES: usize = 128;
    let metric = Se2Space::default();
    let (w_t, _) = metric.lower_bound_weights();
    let poses = random_poses(N, 1);
    // Built as the roadmap builds it: coarse cells, refined as points arrive.
    let [w, h] = BOUNDS.extent();
    let mut grid = XyGrid::new(BOUNDS, (w.max(h) / 8.0).max(1e-3));
    for (id, p) in poses.iter().enumerate() {
        grid.insert(id as u32, p, &poses);
    }
    let queries = random_poses(QUERIES, 2);
    let k = connection_k(N);

    let mut group = c.benchmark_group("knn");
    group.sampling_mode(SamplingMode::Flat);
    group.throughput(Throughput::Elements(QUERIES as u64));
    group.bench_function(format!("k_nearest/n={N}/k={k}"), |b| {
        b.iter(|| {
            for q in &queries {
                black_box(grid.k_nearest(q, k, &poses, &metric, w_t, f64::INFINITY, None));
            }
        })
    });
    group.finish();
}

fn build(c: &mut Criterion) {
    const N: usize = 5_000;
    let metric = Se2Space::default();
    let poses = random_poses(N, 3);
    let mut group = c.benchmark_group("roadmap");
    // Long iterations: the same number in every sample.
    group.sampling_mode(SamplingMode::Flat).sample_size(10);
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function(format!("build/n={N}"), |b| {
        b.iter_with_large_drop(|| build_roadmap(&poses, &metric))
    });
    group.finish();
}

/// Every vertex valid; a fixed, seeded 10% of the edges invalid. Records nothing.
struct HiddenEdges(Vec<bool>);

impl Evaluator for HiddenEdges {
    fn vertex(&mut self, _: &mut Roadmap, _: u32) -> bool {
        true
    }

    fn edge(&mut self, _: &mut Roadmap, e: u32) -> bool {
        self.0[e as usize]
    }
}

fn astar(c: &mut Criterion) {
    const N: usize = 5_000;
    const PAIRS: usize = 32;
    let metric = Se2Space::default();
    let mut map = build_roadmap(&random_poses(N, 3), &metric);
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let pairs: Vec<(u32, u32)> = (0..PAIRS)
        .map(|_| {
            let a = rng.random_range(0..N as u32);
            let mut b = rng.random_range(0..N as u32);
            while b == a {
                b = rng.random_range(0..N as u32);
            }
            (a, b)
        })
        .collect();
    // No edge was removed: edge ids are 0..live_edge_count.
    let edge_count = map.live_edge_count();
    let mut hidden = HiddenEdges((0..edge_count).map(|_| rng.random_bool(0.9)).collect());
    let mut search = AStar::default();

    let mut group = c.benchmark_group("astar");
    group.sampling_mode(SamplingMode::Flat);
    group.throughput(Throughput::Elements(PAIRS as u64));
    group.bench_function(format!("search/n={N}"), |b| {
        b.iter(|| {
            for &(s, g) in &pairs {
                black_box(search.search(&map, s, g, &PathLength::default(), f64::INFINITY));
            }
        })
    });
    group.bench_function(format!("search_lazy/n={N}/10%-invalid-edges"), |b| {
        b.iter(|| {
            for &(s, g) in &pairs {
                black_box(search.search_lazy(
                    &mut map,
                    s,
                    g,
                    &PathLength::default(),
                    &mut hidden,
                    f64::INFINITY,
                ));
            }
        })
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = knn, build, astar
}
criterion_main!(benches);
