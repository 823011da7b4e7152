//! LazyPRM* on a real MovingAI map (random-32-32-10) with a disc robot of radius
//! 0.25 cell and yaw weight 0, configured by `configs/p2p-grid.toml` (as `smug bench
//! p2p`, which runs the bigger maps): 50 scenarios spread over the file, every one
//! solved, no path entering a blocked cell, mean length within 5% of the optimal
//! octile length.

use smug_core::{LoadedConfig, Mission, Pipeline, PlannerOutcome, Pose2};
use smug_worlds::map_file::load_map;
use smug_worlds::movingai::{convert_movingai, read_map, read_scenarios, scenario_to_world};
use std::path::{Path, PathBuf};

use smug_objectives as _;
use smug_planners as _;
use smug_samplers as _;
use smug_validity as _;

/// The documented grid config of `smug p2p` and `smug bench p2p`.
const CONFIG: &str = include_str!("../configs/p2p-grid.toml");
/// What `smug bench p2p` adds: the SE(2) metric without its yaw term, a 0.25-cell disc.
const SET: [&str; 3] = [
    "cost.type=se2",
    "cost.params.rotation_weight=0",
    "validity.params.radius=0.25",
];

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data/movingai/mapf")
}

#[test]
fn random_32_32_10_scenarios_are_solved_safely_and_near_optimally() {
    let map_path = data().join("random-32-32-10.map");
    let grid = read_map(&map_path).unwrap();
    let scenarios = read_scenarios(&data().join("random-32-32-10-random-1.scen")).unwrap();
    let dir = std::env::temp_dir().join(format!("smug-movingai-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let yaml = dir.join("r10.yaml");
    convert_movingai(&map_path, &yaml, 1.0).unwrap();
    let layers = load_map(&yaml, 2.0).unwrap();
    let to_pose = |cell: [usize; 2]| {
        let [x, y] = scenario_to_world(cell, grid.height, 1.0);
        Pose2::new(x, y, 0.0)
    };
    let picked: Vec<_> = (0..50)
        .map(|i| &scenarios[i * scenarios.len() / 50])
        .collect();
    let mission = Mission {
        start: to_pose(picked[0].start),
        end: None,
        targets: vec![],
    };
    let world = layers.into_world("r10", mission, &yaml).unwrap();
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
    println!("random-32-32-10: mean planned / optimal octile length = {ratio:.4}");
    assert!(
        ratio <= 1.05,
        "planned paths are {:.1}% longer than optimal",
        100.0 * (ratio - 1.0)
    );
    std::fs::remove_dir_all(&dir).ok();
}
