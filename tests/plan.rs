//! The end-to-end plan is valid: every waypoint passes the validity checker, every
//! segment the motion validator, one PoI per ToI, from the start back to the start.

use smug_core::{LoadedConfig, Pipeline, PlanOptions};
use smug_mission::plan_mission;
use std::path::Path;

mod support;

use smug_app as _;

fn demo() -> Pipeline {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../configs/flat-demo.toml");
    Pipeline::assemble(&LoadedConfig::from_file(&path, &[]).unwrap()).unwrap()
}

#[test]
fn the_demo_plan_is_valid_and_complete() {
    let mut pipeline = demo();
    let plan = plan_mission(&mut pipeline, PlanOptions::default()).unwrap();
    let mission = pipeline.given_mission.clone().unwrap();
    let states = pipeline.state_validity.clone().unwrap();
    let motions = pipeline.motion_validator.clone().unwrap();

    let mut ids = plan.sequence.clone();
    ids.sort();
    let mut expected: Vec<String> = mission.targets.iter().map(|t| t.id.clone()).collect();
    expected.sort();
    assert_eq!(ids, expected, "every target exactly once");
    assert_eq!(plan.pois.len(), mission.targets.len());
    for chosen in &plan.pois {
        let target = mission
            .targets
            .iter()
            .find(|t| t.id == chosen.target)
            .unwrap();
        assert_eq!(target.pois[chosen.index], chosen.pose);
    }
    let first = plan.waypoints.first().unwrap();
    let last = plan.waypoints.last().unwrap();
    assert_eq!(
        (first.x, first.y, first.yaw),
        (mission.start.x, mission.start.y, mission.start.yaw)
    );
    assert_eq!((last.x, last.y), (mission.start.x, mission.start.y));
    for w in &plan.waypoints {
        assert!(states.is_valid(&w.pose()), "invalid waypoint {w:?}");
        assert!(w.z.is_finite());
    }
    for segment in &plan.segments {
        for pair in segment.path.states.windows(2) {
            assert!(
                motions.check_motion(&pair[0], &pair[1]).is_valid(),
                "invalid motion in {} → {}",
                segment.from,
                segment.to
            );
        }
    }
    for pair in plan.waypoints.windows(2) {
        assert!(
            motions
                .check_motion(&pair[0].pose(), &pair[1].pose())
                .is_valid(),
            "invalid waypoint motion {pair:?}"
        );
    }
    let segment_sum: f64 = plan.segments.iter().map(|s| s.path.cost).sum();
    assert!(
        (plan.cost - segment_sum).abs() < 1e-6,
        "cost {} vs segments {segment_sum}",
        plan.cost
    );
    assert!(plan.stats.paths_planned > 0 && plan.stats.validity_queries > 0);
}

#[test]
fn plans_are_reproducible_for_a_seed() {
    let a = plan_mission(&mut demo(), PlanOptions::default()).unwrap();
    let b = plan_mission(&mut demo(), PlanOptions::default()).unwrap();
    assert_eq!(a.waypoints, b.waypoints);
    assert_eq!(a.cost, b.cost);
}

/// On the lunar mission (IDP on one shared roadmap), repairing the previous search
/// (incremental attempts) gives the same plan, from the same checks, as searching again.
#[test]
fn incremental_attempts_change_no_lunar_plan() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../configs/lunar.toml");
    let plan = |set: &[&str]| {
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        let mut pipeline =
            Pipeline::assemble(&LoadedConfig::from_file(&path, &set).unwrap()).unwrap();
        plan_mission(&mut pipeline, PlanOptions::default()).unwrap()
    };
    let repairing = plan(&[]);
    let searching = plan(&["planner.params.incremental_attempts=false"]);
    assert_eq!(repairing.waypoints, searching.waypoints);
    assert_eq!(repairing.cost, searching.cost);
    let counter = |p: &smug_core::Plan, key: &str| p.stats.counters[key];
    for key in [
        "edge_checks",
        "vertex_checks",
        "roadmap_edges",
        "roadmap_vertices",
    ] {
        assert_eq!(counter(&repairing, key), counter(&searching, key), "{key}");
    }
    assert!(counter(&repairing, "astar_repairs") > 0);
    assert!(counter(&repairing, "astar_expansions") < counter(&searching, "astar_expansions"));
}

/// Refining the route's legs (`plan.refine_legs`) happens after the choice: the same
/// targets in the same order from the same PoIs, no leg dearer than before, every
/// refined motion valid; and it does lower some plan's cost (else it would be idle).
/// (With `"lazy"` sequencing costs `refine_legs` also settles the order, planning legs
/// again before the choice: `"lazy-unsettled"` here.)
#[test]
fn refining_the_legs_keeps_the_route_and_never_makes_a_leg_dearer() {
    let mut lowered = 0;
    for (config, mode, costs) in [
        ("indoor.toml", "sequential", "full"),
        ("indoor.toml", "joint", "full"),
        ("lunar.toml", "joint", "full"),
        ("flat-demo.toml", "sequential", "lazy-unsettled"),
    ] {
        for seed in 1..=3 {
            let plan = |refine: bool| {
                let set = [
                    format!("seed={seed}"),
                    format!("plan.mode={mode}"),
                    format!("plan.refine_legs={refine}"),
                    format!("plan.sequencing_costs={costs}"),
                    "sequencer.type=auto".to_string(),
                ];
                let set: Vec<&str> = set.iter().map(String::as_str).collect();
                let loaded = support::shipped_config(config, &set);
                let mut pipeline = Pipeline::assemble(&loaded).unwrap();
                let plan = plan_mission(&mut pipeline, loaded.config.plan).unwrap();
                (plan, pipeline)
            };
            let (kept, _) = plan(false);
            let (refined, pipeline) = plan(true);
            let case = format!("{config} {mode} seed {seed}");
            assert_eq!(kept.sequence, refined.sequence, "{case}");
            assert_eq!(kept.pois, refined.pois, "{case}");
            let motions = pipeline.motion_validator.clone().unwrap();
            for (a, b) in kept.segments.iter().zip(&refined.segments) {
                assert!(b.path.cost <= a.path.cost, "{case}: {} → {}", a.from, a.to);
                for pair in b.path.states.windows(2) {
                    assert!(
                        motions.check_motion(&pair[0], &pair[1]).is_valid(),
                        "{case}"
                    );
                }
            }
            let sum: f64 = refined.segments.iter().map(|s| s.path.cost).sum();
            assert!((refined.cost - sum).abs() < 1e-6, "{case}");
            if refined.cost < kept.cost - 1e-9 {
                lowered += 1;
            }
        }
    }
    assert!(lowered > 0, "no plan got cheaper by refining its legs");
}

#[test]
fn a_car_on_an_occupancy_map_keeps_its_disc_clear_all_along_its_curves() {
    // A disc robot (`clearance-2d`) driving Reeds–Shepp curves: the motion checks follow
    // the curves themselves (they once followed the chords, and plans crossed walls).
    let loaded = support::shipped_config("imported-map.toml", &["space.type=reeds-shepp"]);
    let mut pipeline = Pipeline::assemble(&loaded).unwrap();
    let plan = plan_mission(&mut pipeline, PlanOptions::default()).unwrap();
    let states = pipeline.state_validity.clone().unwrap();
    // A car's plan is its curves sampled densely (about every 0.1 m): every sample
    // keeps the disc clear.
    assert!(plan.waypoints.len() > 100);
    for w in &plan.waypoints {
        assert!(states.is_valid(&w.pose()), "{w:?} inside an obstacle");
    }
}
