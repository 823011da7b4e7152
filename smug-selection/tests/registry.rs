//! The selectors as a pipeline builds them: registered names, typed parameters, errors.

use smug_core::registry::{SelectorStage, Stage};
use smug_core::{
    BuildContext, Path, PathLength, PlannerOutcome, PlannerStats, PluginSection, PoiSelector,
    PointToPointPlanner, Pose2, Result, RobotConfig, SelectionProblem,
};
use smug_mission::PathOracle;
use std::sync::Arc;
// Link the crate so that its `inventory` registrations are collected.
use smug_selection as _;

fn section(kind: &str, params: &str) -> PluginSection {
    let mut section = PluginSection::new("selector", kind);
    section.params = smug_core::toml::from_str(params).expect("test parameters are valid TOML");
    section
}

fn build(kind: &str, params: &str) -> Result<Box<dyn PoiSelector>> {
    let ctx = BuildContext::new(42, RobotConfig::default());
    Ok(ctx.build::<SelectorStage>(&section(kind, params))?.object)
}

struct StraightLine;

impl PointToPointPlanner for StraightLine {
    fn plan(&mut self, a: &Pose2, b: &Pose2) -> Result<PlannerOutcome> {
        let metric = PathLength::new(1.0, 0.0).expect("valid weights");
        Ok(PlannerOutcome::Exact(Path::new(vec![*a, *b], &metric)))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

#[test]
fn all_four_selectors_are_registered() {
    let names = SelectorStage::registry().unwrap().names();
    for name in ["brute-force", "dp", "idp", "irba"] {
        assert!(names.contains(&name), "{name} missing from {names:?}");
    }
}

#[test]
fn selectors_build_from_parameters_and_select() {
    let metric = PathLength::new(1.0, 0.0).unwrap();
    for (kind, params) in [
        ("dp", ""),
        ("idp", ""),
        ("irba", "max_sweeps = 3"),
        ("brute-force", "max_combinations = 10"),
    ] {
        let selector = build(kind, params).unwrap_or_else(|e| panic!("{kind}: {e}"));
        let mut oracle = PathOracle::new(Arc::new(metric.clone()), Box::new(StraightLine));
        for (x, y) in [(0.0, 0.0), (4.0, 3.0), (1.0, 1.0), (2.0, 0.0), (5.0, 5.0)] {
            oracle.add_pose(Pose2::new(x, y, 0.0));
        }
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 2], vec![3, 4]],
            end: 0,
        };
        let s = selector.select(&mut oracle, &problem).unwrap();
        assert_eq!(s.chosen, vec![2, 3], "{kind}");
        assert!((s.cost - (2.0 * 2f64.sqrt() + 2.0)).abs() < 1e-12, "{kind}");
    }
}

#[test]
fn bad_parameters_are_rejected_with_their_name() {
    for (kind, params, needle) in [
        ("dp", "lazy = true", "lazy"),
        ("idp", "max_iterations = 3", "max_iterations"),
        ("irba", "max_sweep = 3", "max_sweep"),
        ("irba", "max_sweeps = 0", "max_sweeps"),
    ] {
        let message = build(kind, params)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(message.contains(needle), "{kind} {params}: `{message}`");
    }
}
