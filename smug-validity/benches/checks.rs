//! State and edge checks on the procedural lunar world of `configs/lunar.toml`
//! (geometric traversability, ANYmal box), the pipeline assembled once:
//!
//! - `state_check`: `hierarchical` (t_low/t_high = 0.3/0.3 and 0.3/0.8), `volumetric`
//!   and `exact` state validity checkers on fixed, seeded states drawn uniformly over
//!   the world (1 000 per iteration; 100 for the slow `exact`);
//! - `edge_check`: the config's `discrete` motion validator (resolution 0.5,
//!   inclination limit, over hierarchical 0.3/0.3) on 256 fixed, seeded straight edges
//!   of 1–3 m whose endpoints are valid states (as LazyPRM*'s edges are).
//!
//! - `traversability`: the `geometric` estimator's layer of the lunar world (ANYmal
//!   window), on one thread.
//!
//! Throughputs are per state, per edge or per cell.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smug_core::registry::ValidityStage;
use smug_core::{Bounds2, LoadedConfig, Pipeline, PluginSection, Pose2, StateValidityChecker};
use std::f64::consts::PI;
use std::hint::black_box;
use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

// The plugins the pipeline builds register themselves when their crates are linked.
use smug_validity as _;
use smug_worlds as _;

const CONFIG: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../configs/lunar.toml");

/// The lunar pipeline up to the motion validator (later stages are not needed here).
fn lunar_pipeline() -> Pipeline {
    let mut loaded = LoadedConfig::from_file(Path::new(CONFIG), &[]).expect("configs/lunar.toml");
    loaded.config.keep_sections(&[
        "world",
        "traversability",
        "space",
        "objective",
        "validity",
        "motion",
    ]);
    Pipeline::assemble(&loaded).expect("lunar pipeline assembles")
}

fn checker(pipeline: &Pipeline, kind: &str, params: &str) -> Arc<dyn StateValidityChecker> {
    let mut section = PluginSection::new("validity", kind);
    section.params = params
        .parse::<smug_core::toml::Table>()
        .expect("valid TOML");
    pipeline
        .context()
        .build::<ValidityStage>(&section)
        .expect("checker builds")
        .object
        .into()
}

fn random_pose(rng: &mut ChaCha8Rng, b: &Bounds2) -> Pose2 {
    Pose2::new(
        rng.random_range(b.min[0]..b.max[0]),
        rng.random_range(b.min[1]..b.max[1]),
        rng.random_range(-PI..PI),
    )
}

fn state_checks(c: &mut Criterion, pipeline: &Pipeline) {
    let bounds = pipeline.world.as_ref().expect("a world").bounds();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let states: Vec<Pose2> = (0..1_000).map(|_| random_pose(&mut rng, &bounds)).collect();
    let checkers = [
        (
            "hierarchical/0.3-0.3",
            "hierarchical",
            "t_low = 0.3\nt_high = 0.3",
            1_000,
        ),
        (
            "hierarchical/0.3-0.8",
            "hierarchical",
            "t_low = 0.3\nt_high = 0.8",
            1_000,
        ),
        ("volumetric", "volumetric", "", 1_000),
        ("exact", "exact", "", 100),
    ];
    let mut group = c.benchmark_group("state_check");
    for (name, kind, params, count) in checkers {
        let checker = checker(pipeline, kind, params);
        let states = &states[..count];
        group.throughput(Throughput::Elements(count as u64));
        group.bench_function(name, |b| {
            b.iter(|| {
                for s in states {
                    black_box(checker.is_valid(s));
                }
            })
        });
    }
    group.finish();
}

fn edge_checks(c: &mut Criterion, pipeline: &Pipeline) {
    const EDGES: usize = 256;
    let bounds = pipeline.world.as_ref().expect("a world").bounds();
    let states = pipeline
        .state_validity
        .as_ref()
        .expect("a validity checker");
    let motions = pipeline
        .motion_validator
        .as_ref()
        .expect("a motion validator");
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let mut edges = Vec::with_capacity(EDGES);
    while edges.len() < EDGES {
        let a = random_pose(&mut rng, &bounds);
        let (length, heading) = (rng.random_range(1.0..3.0), rng.random_range(-PI..PI));
        let b = Pose2::new(
            a.x + length * heading.cos(),
            a.y + length * heading.sin(),
            a.yaw + rng.random_range(-PI / 2.0..PI / 2.0),
        );
        if bounds.contains(b.x, b.y) && states.is_valid(&a) && states.is_valid(&b) {
            edges.push((a, b));
        }
    }
    let valid = edges
        .iter()
        .filter(|(a, b)| motions.is_valid_motion(a, b))
        .count();
    eprintln!("edge_check: {valid} of {EDGES} edges valid");
    let mut group = c.benchmark_group("edge_check");
    group.throughput(Throughput::Elements(EDGES as u64));
    group.bench_function("discrete/1-3m", |b| {
        b.iter(|| {
            for (a, b) in &edges {
                black_box(motions.is_valid_motion(a, b));
            }
        })
    });
    group.finish();
}

/// The geometric traversability layer of the lunar world, estimated on one thread.
fn traversability(c: &mut Criterion, pipeline: &Pipeline) {
    use smug_core::TraversabilityEstimator;
    use smug_validity::geometric::GeometricParams;
    let world = &*pipeline.context().world().expect("world");
    let radius = 0.5 * 1.07f64.hypot(0.55); // the ANYmal window
    let estimator = smug_validity::GeometricEstimator::new(GeometricParams::default(), radius)
        .expect("estimator");
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let mut group = c.benchmark_group("traversability");
    group.throughput(Throughput::Elements(world.elevation.data.len() as u64));
    group.bench_function("geometric/lunar", |b| {
        b.iter(|| one_thread.install(|| black_box(estimator.estimate(world).expect("layer"))))
    });
    group.finish();
}

fn checks(c: &mut Criterion) {
    let pipeline = lunar_pipeline();
    traversability(c, &pipeline);
    state_checks(c, &pipeline);
    edge_checks(c, &pipeline);
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = checks
}
criterion_main!(benches);
