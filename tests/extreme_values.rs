//! Numeric hygiene at the public entry points: random and extreme values (±1e308, the
//! largest finite, subnormals, −0.0, NaN, ∞, huge counts) give an answer or a typed
//! error, never a panic or an endless loop (each case runs under a step budget or an
//! iteration budget; a hang fails the suite's time limit).

use proptest::prelude::*;
use smug_core::rng::stage_rng;
use smug_core::stages::Clusters;
use smug_core::{
    CostMatrix, GridGeometry, LoadedConfig, Pipeline, Pose2, Se2Space, Sequencer, StateSpace,
    TourKind,
};
use smug_sequencing::{
    GtspLns, GtspLnsParams, HeldKarp, HeldKarpParams, LocalSearch, LocalSearchParams,
};
use smug_spaces::{DubinsSpace, ReedsSheppSpace};
use std::path::Path;

use smug_app as _;

/// Values that break arithmetic: extremes, specials, and ordinary ones between them.
fn extreme() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(1e308),
        Just(-1e308),
        Just(f64::MAX),
        Just(5e-324),
        Just(-0.0),
        Just(0.0),
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        -1e3..1e3f64,
    ]
}

/// Non-negative costs, `INFINITY` (no path) and the largest finite ones included.
fn extreme_cost() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(1e308),
        Just(f64::MAX),
        Just(5e-324),
        Just(0.0),
        Just(f64::INFINITY),
        0.0..1e3f64,
    ]
}

fn is_permutation(order: &[usize], n: usize) -> bool {
    let mut sorted = order.to_vec();
    sorted.sort_unstable();
    sorted.iter().copied().eq(0..n)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Every state space measures and interpolates poses at extreme coordinates.
    #[test]
    fn state_spaces_answer_extreme_poses(
        a in (extreme(), extreme(), extreme()),
        b in (extreme(), extreme(), extreme()),
        bound in extreme(),
        t in extreme(),
    ) {
        let spaces: [Box<dyn StateSpace>; 3] = [
            Box::new(Se2Space::default()),
            Box::new(DubinsSpace::new(1.0).unwrap()),
            Box::new(ReedsSheppSpace::new(1.0).unwrap()),
        ];
        let (a, b) = (Pose2::new(a.0, a.1, a.2), Pose2::new(b.0, b.1, b.2));
        for space in &spaces {
            let d = space.distance(&a, &b);
            prop_assert!(d.is_nan() || d >= 0.0, "distance {d}");
            let _ = space.distance_within(&a, &b, bound);
            let _ = space.interpolate(&a, &b, t);
        }
    }

    /// The TSP and GTSP solvers give a tour or a typed error on extreme costs.
    #[test]
    fn solvers_answer_extreme_cost_matrices(
        costs in (2usize..8).prop_flat_map(|n| (Just(n), prop::collection::vec(extreme_cost(), n * n))),
        open in any::<bool>(),
    ) {
        let (n, mut data) = costs;
        (0..n).for_each(|i| data[i * n + i] = 0.0);
        let Ok(matrix) = CostMatrix::from_rows(n, data) else {
            return Ok(());
        };
        let kind = if open { TourKind::OpenTo(n - 1) } else { TourKind::Closed };
        let held_karp = HeldKarp::new(HeldKarpParams::default()).unwrap();
        let search = LocalSearch::new(
            LocalSearchParams { time_limit_s: 0.0, max_iterations: 50, ..LocalSearchParams::default() },
            stage_rng(1, "sequencer"),
        ).unwrap();
        for solver in [&held_karp as &dyn Sequencer, &search] {
            if let Ok(tour) = solver.solve(&matrix, kind) {
                prop_assert!(is_permutation(&tour.order, n), "{:?}", tour.order);
                prop_assert!(!tour.cost.is_nan());
            }
        }
        let members: Vec<Vec<usize>> = (0..n).step_by(2).map(|i| (i..(i + 2).min(n)).collect()).collect();
        let clusters = Clusters::new(n, members.clone()).unwrap();
        let lns = GtspLns::new(GtspLnsParams { max_iterations: 30, ..GtspLnsParams::default() }, stage_rng(1, "sequencer")).unwrap();
        let kind = if open { TourKind::OpenTo(members.len() - 1) } else { TourKind::Closed };
        if let Ok(tour) = lns.solve_clusters(&matrix, &clusters, kind) {
            prop_assert_eq!(tour.order.len(), members.len());
        }
    }

    /// Grid geometries refuse non-finite or oversized inputs and locate extreme points.
    #[test]
    fn grid_geometries_refuse_or_answer_extremes(
        origin in (extreme(), extreme()),
        resolution in extreme(),
        size in (prop_oneof![Just(usize::MAX), Just(1usize << 40), 0usize..100], 0usize..100),
        point in (extreme(), extreme()),
    ) {
        if let Ok(grid) = GridGeometry::new([origin.0, origin.1], resolution, [size.0, size.1]) {
            prop_assert!((size.0 as u128) * (size.1 as u128) <= 2_000_000_000);
            if let Some([i, j]) = grid.cell_of(point.0, point.1) {
                prop_assert!(i < size.0 && j < size.1);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Extreme values in any numeric key of a config assemble a pipeline or give an
    /// error naming the key (world building bounded by a small memory limit).
    #[test]
    fn configs_with_extreme_values_assemble_or_name_the_key(
        key in prop::sample::select(vec![
            "robot.length", "robot.width", "robot.height", "robot.base_height",
            "world.params.resolution", "world.params.size", "space.params.rotation_weight",
            "objective.params.translation_weight", "planner.params.max_samples",
            "planner.params.improvement", "plan.deadline", "limits.memory_gb", "seed",
        ]),
        value in prop_oneof![
            Just("1e308".to_string()), Just("-1e308".to_string()), Just("5e-324".to_string()),
            Just("-0.0".to_string()), Just("nan".to_string()), Just("inf".to_string()),
            Just("18446744073709551615".to_string()), Just("[1e308, 1e308]".to_string()),
            Just("[1e6, 1e6]".to_string()), Just("0".to_string()),
        ],
    ) {
        let configs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../configs");
        let text = std::fs::read_to_string(configs.join("flat-demo.toml")).unwrap();
        let set = [format!("{key}={value}"), "limits.memory_gb=0.2".to_string()];
        let set = if key == "limits.memory_gb" { vec![set[0].clone()] } else { set.to_vec() };
        match LoadedConfig::from_text(&text, "flat-demo.toml", &configs, &set) {
            Err(err) => {
                let message = err.to_string();
                prop_assert!(message.contains(key) || message.contains(&value), "{message}");
            }
            Ok(loaded) => {
                let _ = Pipeline::assemble(&loaded);
            }
        }
    }
}
