//! The exact `visibility` planner on generated maps of every family (random obstacles,
//! rooms with one-cell doors, a maze of one-cell corridors) through the p2p pipeline
//! (`configs/p2p-grid.toml`, a disc of 0.25 cell, yaw weight 0): it solves every
//! scenario our octile Dijkstra draws, its paths are valid for the disc at every
//! millimetre under the pipeline's own checker, never longer than LazyPRM*'s and never
//! above the octile optimum; LazyPRM* never beats it, solves every scenario too, and
//! comes within 2% of it on average (10% on the worst). And the planner refuses,
//! naming the key, the pipelines it cannot serve.

use smug_core::{LoadedConfig, Pipeline, PlannerOutcome, Pose2, StateValidityChecker};
use smug_worlds::grid_gen::{generate, GridFamily, GridParams};
use smug_worlds::map_file::load_map;
use smug_worlds::movingai::{generate_scenarios, grid_to_map_yaml, scenario_to_world};
use std::path::Path;

use smug_app as _;

const CONFIG: &str = include_str!("../configs/p2p-grid.toml");
const SET: [&str; 5] = [
    "space.type=se2",
    "space.params.rotation_weight=0",
    "objective.type=path-length",
    "objective.params.rotation_weight=0",
    "validity.params.radius=0.25",
];

/// A generated map as a world, with `n` scenarios (start, goal, octile optimum).
fn generated(params: &GridParams, n: usize) -> (smug_core::World, Vec<(Pose2, Pose2, f64)>) {
    let grid = generate(params).unwrap();
    let scenarios = generate_scenarios(&grid, "g.map", n, params.seed).unwrap();
    let dir = std::env::temp_dir().join(format!(
        "smug-visibility-{}-{}",
        params.family,
        std::process::id()
    ));
    let yaml = dir.join("g.yaml");
    grid_to_map_yaml(&grid, &yaml, 1.0, "generated").unwrap();
    let to_pose = |cell: [usize; 2]| {
        let [x, y] = scenario_to_world(cell, grid.height, 1.0);
        Pose2::new(x, y, 0.0)
    };
    let queries: Vec<_> = scenarios
        .iter()
        .map(|s| (to_pose(s.start), to_pose(s.goal), s.optimal_length))
        .collect();
    let world = load_map(&yaml, 2.0).unwrap().into_world("g");
    std::fs::remove_dir_all(&dir).ok();
    (world, queries)
}

fn pipeline(world: smug_core::World, planner: &str) -> Pipeline {
    let mut set: Vec<String> = SET.iter().map(|s| s.to_string()).collect();
    set.push(format!("planner.type={planner}"));
    if planner != "lazy-prm-star" {
        set.push("planner.params={}".to_string());
    }
    let loaded = LoadedConfig::from_text(CONFIG, "p2p-grid.toml", Path::new("."), &set).unwrap();
    Pipeline::assemble_with_world(&loaded, world).unwrap()
}

/// True when the disc is valid at every millimetre of the path.
fn valid_everywhere(checker: &dyn StateValidityChecker, states: &[Pose2]) -> bool {
    states.windows(2).all(|w| {
        let n = (w[0].xy_distance(&w[1]) / 1e-3).ceil().max(1.0) as usize;
        (0..=n).all(|k| {
            let t = k as f64 / n as f64;
            checker.is_valid(&Pose2::new(
                w[0].x + t * (w[1].x - w[0].x),
                w[0].y + t * (w[1].y - w[0].y),
                0.0,
            ))
        })
    })
}

fn families() -> Vec<GridParams> {
    let dense = GridParams {
        density: 0.2,
        ..GridParams::new(GridFamily::Random, 32, 32, 2)
    };
    vec![
        GridParams::new(GridFamily::Random, 32, 32, 1),
        dense,
        GridParams::new(GridFamily::Rooms, 48, 48, 1),
        GridParams::new(GridFamily::Maze, 25, 25, 1),
    ]
}

#[test]
fn exact_paths_are_valid_and_never_longer_than_lazy_prm_star_on_every_family() {
    for params in families() {
        let (world, queries) = generated(&params, 12);
        let mut exact = pipeline(world.clone(), "visibility");
        let checker = exact.state_validity.clone().unwrap();
        let mut lazy = pipeline(world, "lazy-prm-star");
        let (e, l) = (
            exact.planner.as_mut().unwrap(),
            lazy.planner.as_mut().unwrap(),
        );
        let mut ratios = Vec::new();
        for (k, (s, g, octile)) in queries.iter().enumerate() {
            let PlannerOutcome::Exact(path) = e.plan(s, g).unwrap() else {
                panic!("{}: scenario {k} not solved by visibility", params.family);
            };
            assert!(
                valid_everywhere(checker.as_ref(), &path.states),
                "{}: scenario {k}: exact path invalid",
                params.family
            );
            // Any-angle never exceeds the 8-connected optimum (which a 0.25-cell disc
            // can follow: no corner cutting).
            assert!(
                path.cost <= octile + 1e-6,
                "{} > octile {octile}",
                path.cost
            );
            let PlannerOutcome::Exact(lazy_path) = l.plan(s, g).unwrap() else {
                panic!("{}: scenario {k} not solved by LazyPRM*", params.family);
            };
            assert!(
                path.cost <= lazy_path.cost + 1e-9,
                "{}: scenario {k}: exact {} longer than LazyPRM* {}",
                params.family,
                path.cost,
                lazy_path.cost
            );
            if path.cost > 0.0 {
                ratios.push(lazy_path.cost / path.cost);
            }
        }
        // LazyPRM* with the shipped config converges on every family (issue 21's
        // goals: within 2% of the optimum on average, 10% on the worst query).
        let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
        let worst = ratios.iter().copied().fold(1.0, f64::max);
        assert!(
            mean <= 1.02 && worst <= 1.10,
            "{}: LazyPRM* / exact: mean {mean:.4}, worst {worst:.4}",
            params.family
        );
    }
}

#[test]
fn one_to_many_equals_one_to_one_on_a_maze() {
    let (world, queries) = generated(&GridParams::new(GridFamily::Maze, 25, 25, 3), 10);
    let mut many = pipeline(world.clone(), "visibility");
    let mut one = pipeline(world, "visibility");
    let start = queries[0].0;
    let goals: Vec<Pose2> = queries.iter().map(|q| q.1).collect();
    let all = many
        .planner
        .as_mut()
        .unwrap()
        .plan_many(&start, &goals)
        .unwrap();
    for (goal, outcome) in goals.iter().zip(&all) {
        let single = one.planner.as_mut().unwrap().plan(&start, goal).unwrap();
        let (a, b) = (
            outcome.exact_path().unwrap().cost,
            single.exact_path().unwrap().cost,
        );
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
}

/// The error of assembling `config` with `planner.type=visibility` and `set`.
fn refusal(config: &str, set: &[&str]) -> String {
    let mut set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    set.push("planner.type=visibility".into());
    set.push("planner.params={}".into());
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(config);
    let loaded = LoadedConfig::from_file(&path, &set).unwrap();
    match Pipeline::assemble(&loaded) {
        Ok(_) => panic!("{config} {set:?}: visibility accepted"),
        Err(err) => err.to_string(),
    }
}

#[test]
fn refuses_what_it_cannot_plan_naming_the_key() {
    // A box robot (volumetric checker), a car, another objective, a terrain world.
    let err = refusal("configs/flat-demo.toml", &[]);
    assert!(
        err.contains("validity.type") && err.contains("not a disc"),
        "{err}"
    );
    let err = refusal("configs/imported-map.toml", &["space.type=dubins"]);
    assert!(
        err.contains("space.type") && err.contains("curved"),
        "{err}"
    );
    let err = refusal("configs/imported-map.toml", &["objective.type=energy"]);
    assert!(
        err.contains("objective.type") && err.contains("path length"),
        "{err}"
    );
    let err = refusal("configs/lunar.toml", &[]);
    assert!(
        err.contains("traversability.type") && err.contains("terrain"),
        "{err}"
    );
}
