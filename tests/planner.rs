//! LazyPRM* end to end on real worlds: valid paths, lower bounds, determinism,
//! unreachable goals.

use smug_core::{LoadedConfig, NoPathReason, Pipeline, PlannerOutcome, Pose2, Proof};
use std::path::Path;

use smug_app as _;

/// A 12 × 8 m flat world with two walls (a zig-zag corridor) and a closed box around
/// (10.5, 1.5); a disc robot of radius 0.3.
const CONFIG: &str = r#"
seed = 4
[world]
type = "flat"
[world.params]
size = [12.0, 8.0]
obstacles = [
    { min = [3.0, 0.0], max = [3.4, 5.5] },
    { min = [7.0, 2.5], max = [7.4, 8.0] },
    { min = [9.5, 0.5], max = [11.5, 0.7] },
    { min = [9.5, 2.3], max = [11.5, 2.5] },
    { min = [9.5, 0.5], max = [9.7, 2.5] },
    { min = [11.3, 0.5], max = [11.5, 2.5] },
]
mission = { start = { x = 1.0, y = 1.0 } }
[validity]
type = "clearance-2d"
params = { radius = 0.3 }
[motion]
type = "discrete"
params = { resolution = 0.05 }
[sampler]
type = "informed"
[planner]
type = "lazy-prm-star"
params = { max_samples = 4000 }
"#;

fn pipeline(overrides: &[&str]) -> Pipeline {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let loaded =
        LoadedConfig::from_text(CONFIG, "planner.toml", Path::new("."), &overrides).unwrap();
    Pipeline::assemble(&loaded).unwrap()
}

fn queries() -> Vec<(Pose2, Pose2)> {
    vec![
        (Pose2::new(1.0, 1.0, 0.0), Pose2::new(11.0, 7.0, 1.0)),
        (Pose2::new(1.0, 7.0, -1.0), Pose2::new(5.0, 1.0, 0.0)),
        (Pose2::new(5.0, 7.0, 2.0), Pose2::new(8.5, 1.0, -2.0)),
        (Pose2::new(11.0, 7.0, 1.0), Pose2::new(1.0, 1.0, 0.0)),
    ]
}

/// The settings of `configs/p2p-grid.toml` beyond the planner defaults.
const GRID_SETTINGS: [&str; 5] = [
    "sampler.type=bridge",
    "planner.params.focus=0.5",
    "planner.params.attempt_share=0.1",
    "planner.params.smooth=true",
    "planner.params.shortcut=true",
];

#[test]
fn paths_are_valid_and_no_cheaper_than_the_straight_line() {
    check_paths(&[]);
}

#[test]
fn with_the_grid_settings_paths_are_valid_and_no_cheaper_than_the_straight_line() {
    check_paths(&GRID_SETTINGS);
}

#[test]
fn with_the_grid_settings_runs_are_reproducible_for_a_seed() {
    let run = |seed: &str| {
        let mut settings = GRID_SETTINGS.to_vec();
        settings.push(seed);
        let mut p = pipeline(&settings);
        let planner = p.planner.as_mut().unwrap();
        queries()
            .into_iter()
            .map(|(s, g)| planner.plan(&s, &g).unwrap().exact_path().unwrap().clone())
            .collect::<Vec<_>>()
    };
    assert_eq!(run("seed=4"), run("seed=4"));
}

#[test]
fn with_the_grid_settings_unreachable_goals_and_invalid_endpoints_are_outcomes() {
    check_outcomes(&GRID_SETTINGS);
}

fn check_paths(settings: &[&str]) {
    let mut p = pipeline(settings);
    let motions = p.motion_validator.clone().unwrap();
    let objective = p.objective.clone();
    let planner = p.planner.as_mut().unwrap();
    for (start, goal) in queries() {
        let outcome = planner.plan(&start, &goal).unwrap();
        let PlannerOutcome::Exact(path) = outcome else {
            panic!("{start:?} → {goal:?}: {outcome:?}")
        };
        assert_eq!(path.states.first(), Some(&start));
        assert_eq!(path.states.last(), Some(&goal));
        for w in path.states.windows(2) {
            assert!(
                motions.check_motion(&w[0], &w[1]).is_valid(),
                "invalid segment {:?} → {:?}",
                w[0],
                w[1]
            );
        }
        assert!(path.cost >= objective.cost_bound(&start, &goal) - 1e-9);
    }
    let stats = planner.stats();
    assert_eq!(stats.queries, 4);
    assert!(stats.vertices > 50 && stats.counters["edge_checks"] > 0);
    assert!(stats.breakdown.astar_s > 0.0 && stats.breakdown.edge_checking_s > 0.0);
}

#[test]
fn runs_are_reproducible_for_a_seed() {
    let run = |seed: &str| {
        let mut p = pipeline(&[seed]);
        let planner = p.planner.as_mut().unwrap();
        queries()
            .into_iter()
            .map(|(s, g)| planner.plan(&s, &g).unwrap().exact_path().unwrap().cost)
            .collect::<Vec<f64>>()
    };
    assert_eq!(run("seed=4"), run("seed=4"));
    assert_ne!(run("seed=4"), run("seed=5"));
}

#[test]
fn unreachable_goals_and_invalid_endpoints_are_outcomes() {
    check_outcomes(&[]);
}

/// A goal in a closed box ends with no path, proved (the disc checker's free cells
/// do not join the box's inside to the rest: no sample is spent); endpoints in a
/// wall or off the map are reported as such.
fn check_outcomes(settings: &[&str]) {
    let mut settings = settings.to_vec();
    settings.push("planner.params.max_samples=1500");
    let mut p = pipeline(&settings);
    let planner = p.planner.as_mut().unwrap();
    let inside_box = Pose2::new(10.5, 1.5, 0.0);
    assert_eq!(
        planner
            .plan(&Pose2::new(1.0, 1.0, 0.0), &inside_box)
            .unwrap(),
        PlannerOutcome::NoPath(NoPathReason::Proved(Proof::Disconnected))
    );
    let in_wall = Pose2::new(3.2, 1.0, 0.0);
    assert_eq!(
        planner.plan(&in_wall, &inside_box).unwrap(),
        PlannerOutcome::InvalidStart
    );
    assert_eq!(
        planner.plan(&Pose2::new(1.0, 1.0, 0.0), &in_wall).unwrap(),
        PlannerOutcome::InvalidGoal
    );
    let off_map = Pose2::new(-5.0, 1.0, 0.0);
    assert_eq!(
        planner.plan(&off_map, &inside_box).unwrap(),
        PlannerOutcome::InvalidStart
    );
}

#[test]
fn shortcutting_never_raises_cost_nor_breaks_validity() {
    let mut plain = pipeline(&[]);
    let mut short = pipeline(&["planner.params.shortcut=true"]);
    let motions = short.motion_validator.clone().unwrap();
    for (s, g) in queries() {
        let a = plain.planner.as_mut().unwrap().plan(&s, &g).unwrap();
        let b = short.planner.as_mut().unwrap().plan(&s, &g).unwrap();
        let (a, b) = (a.exact_path().unwrap(), b.exact_path().unwrap());
        assert!(
            b.cost <= a.cost + 1e-9,
            "shortcut raised the cost: {} > {}",
            b.cost,
            a.cost
        );
        assert!(b
            .states
            .windows(2)
            .all(|w| motions.check_motion(&w[0], &w[1]).is_valid()));
    }
}

/// Repairing the previous search (incremental attempts) changes no path, only the work.
#[test]
fn incremental_attempts_change_no_path() {
    compare_incremental_attempts(&[]);
}

/// The same with the grid settings (the focus spaces attempts differently).
#[test]
fn with_the_grid_settings_incremental_attempts_change_no_path() {
    compare_incremental_attempts(&GRID_SETTINGS);
}

fn compare_incremental_attempts(settings: &[&str]) {
    let mut repairing = pipeline(settings);
    let mut off = settings.to_vec();
    off.push("planner.params.incremental_attempts=false");
    let mut searching = pipeline(&off);
    let mut queries = queries();
    queries.extend(queries.clone().iter().map(|&(s, g)| (g, s)));
    for (s, g) in queries {
        let a = repairing.planner.as_mut().unwrap().plan(&s, &g).unwrap();
        let b = searching.planner.as_mut().unwrap().plan(&s, &g).unwrap();
        assert_eq!(a, b, "from {s:?} to {g:?}");
    }
    let stats = |p: &Pipeline| p.planner.as_ref().unwrap().stats().counters;
    let (a, b) = (stats(&repairing), stats(&searching));
    assert!(a["astar_repairs"] > 0, "{a:?}");
    assert_eq!(b["astar_repairs"], 0);
    assert!(a["astar_searches"] < b["astar_searches"], "{a:?} vs {b:?}");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(12))]

    /// Random queries on one shared roadmap, with the grid settings and a random seed:
    /// every exact path joins its endpoints by valid motions and costs at least the
    /// straight line.
    #[test]
    fn with_the_grid_settings_random_queries_give_valid_paths_above_the_lower_bound(
        seed in 1u64..1000,
        ends in proptest::collection::vec(
            (0.2..11.8f64, 0.2..7.8f64, -3.0..3.0f64, 0.2..11.8f64, 0.2..7.8f64, -3.0..3.0f64),
            1..6,
        ),
    ) {
        let seed = format!("seed={seed}");
        let mut settings = GRID_SETTINGS.to_vec();
        settings.extend([seed.as_str(), "planner.params.max_samples=1500"]);
        let mut p = pipeline(&settings);
        let motions = p.motion_validator.clone().unwrap();
        let objective = p.objective.clone();
        let planner = p.planner.as_mut().unwrap();
        for (sx, sy, syaw, gx, gy, gyaw) in ends {
            let (start, goal) = (Pose2::new(sx, sy, syaw), Pose2::new(gx, gy, gyaw));
            if let PlannerOutcome::Exact(path) = planner.plan(&start, &goal).unwrap() {
                proptest::prop_assert_eq!(path.states.first(), Some(&start));
                proptest::prop_assert_eq!(path.states.last(), Some(&goal));
                proptest::prop_assert!(path
                    .states
                    .windows(2)
                    .all(|w| motions.check_motion(&w[0], &w[1]).is_valid()));
                proptest::prop_assert!(path.cost >= objective.cost_bound(&start, &goal) - 1e-9);
            }
        }
    }
}
