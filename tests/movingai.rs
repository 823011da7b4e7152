//! LazyPRM* on a real MovingAI map (random-32-32-10) with a disc robot of radius
//! 0.25 cell and yaw weight 0: 50 scenarios spread over the file, every one solved,
//! no path entering a blocked cell, mean length within 5% of the optimal octile length.

use smug_core::{LoadedConfig, Mission, Pipeline, PlannerOutcome, Pose2};
use smug_worlds::map_file::load_map;
use smug_worlds::movingai::{convert_movingai, read_map, read_scenarios, scenario_to_world};
use std::path::{Path, PathBuf};

use smug_planners as _;
use smug_samplers as _;
use smug_validity as _;

const CONFIG: &str = r#"
seed = 1
[cost]
type = "se2"
params = { rotation_weight = 0.0 }
[validity]
type = "clearance-2d"
params = { radius = 0.25 }
[motion]
type = "discrete"
params = { resolution = 0.05, max_inclination = 1e9 }
[sampler]
type = "informed"
[planner]
type = "lazy-prm-star"
"#;

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
    let loaded = LoadedConfig::from_text(CONFIG, "movingai.toml", Path::new("."), &[]).unwrap();
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
