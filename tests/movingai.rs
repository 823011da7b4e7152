//! LazyPRM* on a generated MovingAI-format map (32×32, 10% random obstacles, seed 1)
//! with a disc robot of radius 0.25 cell and yaw weight 0, configured by
//! `configs/p2p-grid.toml` (as `smug bench p2p`, which runs bigger maps): 50 scenarios
//! drawn by our octile Dijkstra, every one solved, no path entering a blocked cell, mean
//! length within RATIO_BOUND of the optimal octile length.

use smug_core::{LoadedConfig, Pipeline, PlannerOutcome, Pose2};
use smug_worlds::grid_gen::{generate, GridFamily, GridParams};
use smug_worlds::map_file::load_map;
use smug_worlds::movingai::{generate_scenarios, grid_to_map_yaml, scenario_to_world};
use std::path::Path;

use smug_app as _;

/// The documented grid config of `smug p2p` and `smug bench p2p`.
const CONFIG: &str = include_str!("../configs/p2p-grid.toml");
/// What `smug bench p2p` adds: the SE(2) metric without its yaw term, a 0.25-cell disc.
const SET: [&str; 5] = [
    "space.type=se2",
    "space.params.rotation_weight=0",
    "objective.type=path-length",
    "objective.params.rotation_weight=0",
    "validity.params.radius=0.25",
];

/// Upper bound on Σ planned length / Σ optimal octile length. Measured 0.9452 (any-angle
/// paths beat the 8-connected optimum); the bound leaves 1.5% for planner changes.
const RATIO_BOUND: f64 = 0.96;

#[test]
fn random_32x32_10_percent_scenarios_are_solved_safely_and_near_optimally() {
    let grid = generate(&GridParams::new(GridFamily::Random, 32, 32, 1)).unwrap();
    let scenarios = generate_scenarios(&grid, "r10.map", 50, 1).unwrap();
    let dir = std::env::temp_dir().join(format!("smug-movingai-{}", std::process::id()));
    let yaml = dir.join("r10.yaml");
    grid_to_map_yaml(&grid, &yaml, 1.0, "generated").unwrap();
    let layers = load_map(&yaml, 2.0).unwrap();
    let to_pose = |cell: [usize; 2]| {
        let [x, y] = scenario_to_world(cell, grid.height, 1.0);
        Pose2::new(x, y, 0.0)
    };
    let picked: Vec<_> = scenarios.iter().collect();
    assert_eq!(picked.len(), 50);
    let world = layers.into_world("r10");
    let set: Vec<String> = SET.iter().map(|s| s.to_string()).collect();
    let loaded = LoadedConfig::from_text(CONFIG, "p2p-grid.toml", Path::new("."), &set).unwrap();
    let mut pipeline = Pipeline::assemble_with_world(&loaded, world).unwrap();
    let planner = pipeline.planner.as_mut().unwrap();

    let blocked = |x: f64, y: f64| {
        let (col, row_from_bottom) = (x.floor() as usize, y.floor() as usize);
        !grid.is_passable(col, grid.height - 1 - row_from_bottom)
    };
    let (mut planned, mut optimal) = (0.0, 0.0);
    for s in &picked {
        let (start, goal) = (to_pose(s.start), to_pose(s.goal));
        let outcome = planner.plan(&start, &goal).unwrap();
        let PlannerOutcome::Exact(path) = outcome else {
            panic!("scenario {s:?} not solved: {outcome:?}")
        };
        for w in path.states.windows(2) {
            let steps = (w[0].xy_distance(&w[1]) / 0.005).ceil().max(1.0) as usize;
            for k in 0..=steps {
                let t = k as f64 / steps as f64;
                let (x, y) = (
                    w[0].x + t * (w[1].x - w[0].x),
                    w[0].y + t * (w[1].y - w[0].y),
                );
                assert!(
                    !blocked(x, y),
                    "the path of {s:?} enters a blocked cell at ({x}, {y})"
                );
            }
        }
        planned += path.cost;
        optimal += s.optimal_length;
    }
    let ratio = planned / optimal;
    println!("random 32×32 10%: mean planned / optimal octile length = {ratio:.4}");
    assert!(
        ratio <= RATIO_BOUND,
        "planned paths are {:.1}% longer than optimal",
        100.0 * (ratio - 1.0)
    );
    std::fs::remove_dir_all(&dir).ok();
}
