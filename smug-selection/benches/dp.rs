//! PoI selection with `dp` and `idp` on a lunar-sized mission: 13 targets × 10 PoIs
//! (on a 1.3 m circle around each seeded random stone in 30 × 29 m, facing it), a
//! closed tour from a start pose, targets in greedy nearest-neighbour order.
//!
//! No planner runs: the oracle's planner is a stub that answers from a fixed,
//! precomputed, symmetric cost table (the SE(2) straight-line cost times a seeded
//! detour factor in [1, 1.5], and in [1.5, 3] for one leg in five), so the benches
//! measure the selectors and the oracle's cache, not path planning.
//!
//! - `fresh-oracle`: every iteration starts from an empty oracle cache, so each leg
//!   the selector asks for goes through the stub (DP asks for all `M²(N−1) + 2M`);
//! - `cached-oracle`: every leg is already cached (the DP layers alone).

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smug_core::{
    Objective, Path, PathLength, PlannerOutcome, PlannerStats, PoiSelector, PointToPointPlanner,
    Pose2, Result, SelectionProblem,
};
use smug_mission::PathOracle;
use smug_selection::{DpSelector, IdpSelector};
use std::collections::HashMap;
use std::f64::consts::PI;
use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;

const TARGETS: usize = 13;
const POIS: usize = 10;

/// Answers every query from the table (poses are found by their exact xy).
struct TablePlanner {
    index: Arc<HashMap<[u64; 2], usize>>,
    costs: Arc<Vec<f64>>,
    n: usize,
}

impl TablePlanner {
    fn id(&self, p: &Pose2) -> usize {
        self.index[&[p.x.to_bits(), p.y.to_bits()]]
    }
}

impl PointToPointPlanner for TablePlanner {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        let cost = self.costs[self.id(start) * self.n + self.id(goal)];
        Ok(PlannerOutcome::Exact(Path {
            states: vec![*start, *goal],
            cost,
        }))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

/// The mission's poses (start first), the selection problem over them, and the table.
struct Fixture {
    poses: Vec<Pose2>,
    problem: SelectionProblem,
    index: Arc<HashMap<[u64; 2], usize>>,
    costs: Arc<Vec<f64>>,
}

impl Fixture {
    fn new(seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let metric = PathLength::default();
        let start = Pose2::new(1.0, 1.0, 0.0);
        let stones: Vec<(f64, f64)> = (0..TARGETS)
            .map(|_| (rng.random_range(2.0..28.0), rng.random_range(2.0..27.0)))
            .collect();
        // Visit the stones in greedy nearest-neighbour order from the start.
        let mut order = Vec::with_capacity(TARGETS);
        let mut at = (start.x, start.y);
        let mut left: Vec<usize> = (0..TARGETS).collect();
        while !left.is_empty() {
            let dist = |k: usize| (stones[k].0 - at.0).hypot(stones[k].1 - at.1);
            let (pos, _) = left
                .iter()
                .enumerate()
                .min_by(|a, b| dist(*a.1).total_cmp(&dist(*b.1)))
                .expect("stones left");
            let k = left.swap_remove(pos);
            order.push(k);
            at = stones[k];
        }
        let mut poses = vec![start];
        let mut groups = Vec::with_capacity(TARGETS);
        for k in order {
            let (sx, sy) = stones[k];
            let group = (0..POIS)
                .map(|p| {
                    let angle = 2.0 * PI * p as f64 / POIS as f64;
                    // On the circle, facing the stone.
                    poses.push(Pose2::new(
                        sx + 1.3 * angle.cos(),
                        sy + 1.3 * angle.sin(),
                        angle - PI,
                    ));
                    poses.len() - 1
                })
                .collect();
            groups.push(group);
        }
        let n = poses.len();
        let mut costs = vec![0.0; n * n];
        for i in 0..n {
            for j in i + 1..n {
                let detour = if rng.random_bool(0.2) {
                    rng.random_range(1.5..3.0)
                } else {
                    rng.random_range(1.0..1.5)
                };
                let cost = metric.motion_cost(&poses[i], &poses[j]) * detour;
                costs[i * n + j] = cost;
                costs[j * n + i] = cost;
            }
        }
        let index = poses
            .iter()
            .enumerate()
            .map(|(i, p)| ([p.x.to_bits(), p.y.to_bits()], i))
            .collect::<HashMap<_, _>>();
        assert_eq!(index.len(), n, "poses have distinct xy");
        Self {
            poses,
            problem: SelectionProblem {
                start: 0,
                groups,
                end: 0,
            },
            index: Arc::new(index),
            costs: Arc::new(costs),
        }
    }

    /// An oracle with every pose registered and nothing planned.
    fn oracle(&self) -> PathOracle {
        let planner = TablePlanner {
            index: self.index.clone(),
            costs: self.costs.clone(),
            n: self.poses.len(),
        };
        let mut oracle = PathOracle::new(Arc::new(PathLength::default()), Box::new(planner));
        for p in &self.poses {
            oracle.add_pose(*p);
        }
        oracle
    }
}

fn selection(c: &mut Criterion) {
    let fixture = Fixture::new(7);
    let selectors: [(&str, &dyn PoiSelector); 2] = [
        ("dp", &DpSelector::default()),
        ("idp", &IdpSelector::default()),
    ];
    let mut group = c.benchmark_group("selection");
    for (name, selector) in selectors {
        let mut probe = fixture.oracle();
        let s = selector
            .select(&mut probe, &fixture.problem)
            .expect("selects");
        eprintln!(
            "{name}: cost {:.3}, {} paths planned",
            s.cost,
            probe.stats().paths_planned
        );
        group.bench_function(format!("{name}/{TARGETS}x{POIS}/fresh-oracle"), |b| {
            b.iter_batched(
                || fixture.oracle(),
                |mut oracle| {
                    let s = selector.select(&mut oracle, &fixture.problem);
                    black_box(s.expect("selects"));
                    oracle
                },
                BatchSize::SmallInput,
            )
        });
    }
    // Every leg DP needs is cached by the first run.
    let mut warm = fixture.oracle();
    DpSelector::default()
        .select(&mut warm, &fixture.problem)
        .expect("selects");
    group.bench_function(format!("dp/{TARGETS}x{POIS}/cached-oracle"), |b| {
        b.iter(|| black_box(DpSelector::default().select(&mut warm, &fixture.problem)))
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = selection
}
criterion_main!(benches);
