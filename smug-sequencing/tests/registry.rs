//! The plugins as a pipeline builds them: registered names, typed parameters, errors.

use smug_core::registry::{SequencerStage, Stage};
use smug_core::{BuildContext, CostMatrix, PluginSection, RobotConfig, TourKind};
// Link the crate so that its `inventory` registrations are collected.
use smug_sequencing as _;

fn section(kind: &str, params: &str) -> PluginSection {
    let mut section = PluginSection::new("sequencer", kind);
    section.params = toml::from_str(params).expect("test parameters are valid TOML");
    section
}

fn build(kind: &str, params: &str) -> smug_core::Result<Box<dyn smug_core::Sequencer>> {
    let ctx = BuildContext::new(42, RobotConfig::default());
    Ok(ctx.build::<SequencerStage>(&section(kind, params))?.object)
}

#[test]
fn all_four_plugins_are_registered() {
    let names = SequencerStage::registry().unwrap().names();
    for name in ["auto", "brute-force", "held-karp", "local-search"] {
        assert!(names.contains(&name), "{name} missing from {names:?}");
    }
}

#[test]
fn plugins_build_from_parameters_and_solve() {
    let costs = CostMatrix::from_fn(16, |i, j| (i as f64 - j as f64).abs()).unwrap();
    let plugins = [
        ("held-karp", "max_nodes = 16"),
        ("local-search", "time_limit_s = 0.0\nmax_iterations = 50\nneighbours = 6"),
        ("auto", "threshold = 10\ntime_limit_s = 0.0\nmax_iterations = 50\nconstruction = \"nearest-neighbour\""),
    ];
    for (kind, params) in plugins {
        let solver = build(kind, params).unwrap_or_else(|e| panic!("{kind}: {e}"));
        let tour = solver.solve(&costs, TourKind::Closed).unwrap();
        assert_eq!(tour.cost, 30.0, "{kind}");
        let path = solver.solve(&costs, TourKind::OpenTo(15)).unwrap();
        assert_eq!(path.cost, 15.0, "{kind}");
    }
    assert!(build("brute-force", "").is_ok());
}

#[test]
fn bad_parameters_are_rejected_with_their_name() {
    let cases = [
        ("held-karp", "max_node = 5", "max_node"),
        ("held-karp", "max_nodes = 40", "max_nodes"),
        (
            "local-search",
            "time_limit_s = 0.0\nmax_iterations = 0",
            "max_iterations",
        ),
        ("local-search", "neighbours = 1", "neighbours"),
        ("local-search", "construction = \"random\"", "random"),
        ("auto", "threshold = 25", "threshold"),
    ];
    for (kind, params, needle) in cases {
        let message = build(kind, params)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(message.contains(needle), "{kind} {params}: `{message}`");
    }
}

#[test]
fn gtsp_plugins_build_and_solve_clustered_problems() {
    // Clusters {0}, {1, 2}, {3, 4} on a line; the cheap nodes are 2 and 4.
    let x = [0.0, 10.0, 1.0, 11.0, 2.0_f64];
    let costs = CostMatrix::from_fn(5, |i, j| (x[i] - x[j]).abs()).unwrap();
    let clusters = smug_core::Clusters::new(5, vec![vec![0], vec![1, 2], vec![3, 4]]).unwrap();
    let plugins = [
        ("gtsp-exact", "max_clusters = 10"),
        ("gtsp-lns", "max_iterations = 20\nnoise = 0.2"),
    ];
    for (kind, params) in plugins {
        let solver = build(kind, params).unwrap_or_else(|e| panic!("{kind}: {e}"));
        let tour = solver
            .solve_clusters(&costs, &clusters, TourKind::Closed)
            .unwrap();
        assert_eq!(tour.cost, 4.0, "{kind}");
        assert_eq!(solver.solve(&costs, TourKind::Closed).unwrap().cost, 22.0);
    }
    let err = build("gtsp-lns", "time_limit_s = 0.0\nmax_iterations = 0")
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("would never stop"), "{err}");
    for bad in ["0", "65"] {
        let err = build("gtsp-lns", &format!("neighbours_per_iteration = {bad}"))
            .err()
            .unwrap()
            .to_string();
        assert!(
            err.contains(&format!(
                "neighbours_per_iteration = {bad} must be in [1, 64]"
            )),
            "{err}"
        );
    }
    let tsp_only = build("held-karp", "").unwrap();
    let err = tsp_only
        .solve_clusters(&costs, &clusters, TourKind::Closed)
        .unwrap_err()
        .to_string();
    assert!(err.contains("gtsp-lns"), "{err}");
}
