//! The team sequencers as a pipeline builds them: registered names, typed parameters,
//! errors naming the parameter.

use smug_core::registry::{Stage, TeamSequencerStage};
use smug_core::{
    BuildContext, CostMatrix, PluginSection, RobotConfig, TeamObjective, TeamProblem, TeamRobot,
    TeamTarget,
};
use std::sync::Arc;
// Link the crate so that its `inventory` registrations are collected.
use smug_sequencing as _;

fn build(kind: &str, params: &str) -> smug_core::Result<Box<dyn smug_core::TeamSequencer>> {
    let mut section = PluginSection::new("team_sequencer", kind);
    section.params = toml::from_str(params).expect("test parameters are valid TOML");
    let ctx = BuildContext::new(42, RobotConfig::default());
    Ok(ctx.build::<TeamSequencerStage>(&section)?.object)
}

/// Two robots on a line (nodes 0 and 5 their depots), targets at 1..=4: robot 0 serves
/// 1, 2 and robot 1 serves 3, 4 (makespan 4, total 8).
fn line() -> TeamProblem {
    let costs = Arc::new(CostMatrix::from_fn(6, |i, j| (i as f64 - j as f64).abs()).unwrap());
    let robots = [0, 5]
        .into_iter()
        .map(|depot| TeamRobot {
            costs: costs.clone(),
            start: depot,
            end: depot,
        })
        .collect();
    let targets = (1..=4)
        .map(|node| TeamTarget {
            nodes: vec![node],
            robots: None,
        })
        .collect();
    TeamProblem::new(robots, targets, TeamObjective::Makespan, None).unwrap()
}

#[test]
fn the_three_team_plugins_build_and_solve() {
    let names = TeamSequencerStage::registry().unwrap().names();
    for (kind, params) in [
        ("team-exact", ""),
        ("team-lns", "max_iterations = 100"),
        (
            "team-auto",
            "exact_targets = 2\n[lns]\nmax_iterations = 100",
        ),
    ] {
        assert!(names.contains(&kind), "{kind} missing from {names:?}");
        let solver = build(kind, params).unwrap_or_else(|e| panic!("{kind}: {e}"));
        let solution = solver.solve(&line()).unwrap();
        assert_eq!((solution.makespan, solution.total), (4.0, 8.0), "{kind}");
    }
}

#[test]
fn bad_team_parameters_are_named() {
    for (kind, params, needle) in [
        ("team-exact", "max_targets = 40", "max_targets"),
        ("team-lns", "blink_rate = 2.0", "blink_rate"),
        ("team-lns", "max_iterations = 0", "max_iterations"),
        ("team-auto", "exact_target = 3", "exact_target"),
    ] {
        let message = build(kind, params)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(message.contains(needle), "{kind} {params}: {message}");
    }
}
