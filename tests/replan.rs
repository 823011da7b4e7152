//! Replanning from a mission state: the replan never visits a visited target or a
//! failed pose, starts at the state's pose, ends at the mission's end pose, and every
//! motion is valid on the world with the new obstacles; an empty state reproduces the
//! original plan bit-identically.

#[path = "replan_checks.rs"]
mod replan_checks;

use proptest::prelude::*;
use replan_checks::{check_replan, state_strategy};
use smug_core::mission::{DiscObstacle, MissionState};
use smug_core::{Error, LoadedConfig, Pipeline, Plan};
use smug_mission::plan_mission;
use smug_mission::{assemble_replan, replan_mission, CutOff, NoTargetLeft, Unreachable};

use smug_app as _;

mod support;
use support::shipped_config as config;

fn original(loaded: &LoadedConfig) -> (Plan, Pipeline) {
    let mut pipeline = Pipeline::assemble(loaded).unwrap();
    let plan = plan_mission(&mut pipeline, loaded.config.plan).unwrap();
    (plan, pipeline)
}

fn replan(loaded: &LoadedConfig, state: &MissionState) -> (Result<Plan, Error>, Pipeline) {
    let mut pipeline = assemble_replan(loaded, state, "state.toml").unwrap();
    let options = pipeline.config.plan;
    (replan_mission(&mut pipeline, options, state), pipeline)
}

/// Everything but the timings and counters.
fn same_route(a: &Plan, b: &Plan) {
    assert_eq!(a.sequence, b.sequence);
    assert_eq!(a.pois, b.pois);
    assert_eq!(a.segments, b.segments);
    assert_eq!(a.waypoints, b.waypoints);
    assert_eq!(a.cost.to_bits(), b.cost.to_bits());
    assert_eq!(a.metrics, b.metrics);
}

#[test]
fn an_empty_state_reproduces_the_original_plan_bit_identically() {
    for name in [
        "flat-demo.toml",
        "flat-dubins.toml",
        "lunar.toml",
        "lunar-irba.toml",
        "lunar-wheeled.toml",
        "indoor.toml",
        "indoor-disc.toml",
    ] {
        let loaded = config(name, &[]);
        let (plan, pipeline) = original(&loaded);
        let state = MissionState::at_start(pipeline.given_mission.as_ref().unwrap());
        let (again, _) = replan(&loaded, &state);
        let again = again.unwrap();
        same_route(&plan, &again);
        assert_eq!(
            again.replan.unwrap().state,
            state,
            "{name}: marked as a replan"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn a_replan_respects_the_state_and_the_updated_world(state in state_strategy()) {
        let loaded = config("flat-demo.toml", &[]);
        let (outcome, pipeline) = replan(&loaded, &state);
        match outcome {
            Ok(plan) => check_replan(&plan, &pipeline, &state),
            Err(Error::Stage { source, .. }) if source.is::<NoTargetLeft>() => {
                // Only when every target not visited has all its PoIs failed or blocked.
                let mission = &pipeline.given_mission.as_ref().unwrap();
                let checker = pipeline.state_validity.clone().unwrap();
                for t in mission.targets.iter().filter(|t| !state.visited.contains(&t.id)) {
                    let open = t.pois.iter().enumerate()
                        .any(|(k, p)| !state.failed(&t.id, k) && checker.is_valid(p));
                    prop_assert!(!open, "target {} still had a PoI", t.id);
                }
            }
            Err(Error::Stage { source, .. }) if source.is::<Unreachable>() => {
                prop_assert!(!state.obstacles.is_empty(), "only a new obstacle can cut a target off");
            }
            // A new rock may leave the way home only through a passage barely wider
            // than the robot: "no path into the end pose", named with the budget that
            // ran out (or the proof). The regression test below holds the planner to
            // a passage it must find.
            Err(Error::Stage { source, .. }) if source.is::<CutOff>() => {
                prop_assert!(!state.obstacles.is_empty(), "only a new obstacle can cut the end off");
            }
            Err(other) => prop_assert!(false, "unexpected error {other}"),
        }
    }
}

/// A rock dropped beside the top of flat-demo's first wall leaves the way home only
/// through a gap 1.04 m wide (the robot is 0.55 m wide, 1.07 m long): uniform samples
/// seldom land in it (20 000 did not, once a proptest case), bridge samples do.
#[test]
fn a_replan_finds_the_narrow_passage_a_new_rock_leaves_beside_a_wall() {
    let loaded = config("flat-demo.toml", &[]);
    let state = MissionState {
        pose: [6.5, 3.0, -1.5],
        visited: vec!["gauge-a".to_string()],
        failed_pois: vec![],
        obstacles: vec![DiscObstacle {
            center: [4.794035907759088, 6.626256428046025],
            radius: 0.5877672149905271,
            height: 1.0,
        }],
    };
    let (outcome, pipeline) = replan(&loaded, &state);
    let plan = outcome.unwrap_or_else(|e| panic!("the passage exists: {e}"));
    check_replan(&plan, &pipeline, &state);
    let through_the_gap = plan
        .segments
        .iter()
        .flat_map(|s| &s.path.states)
        .any(|p| (3.9..=5.8).contains(&p.x) && (5.0..=6.04).contains(&p.y));
    assert!(
        through_the_gap,
        "the way home crosses the wall's top beside the rock"
    );
}

/// The robot halfway through the mission, the next target's chosen PoI failed, a new
/// obstacle across the next leg: on lunar (hierarchical validity, IDP and IRBA), the
/// wheeled robot's lunar (its own objective and motion model), a Dubins car and a disc
/// robot indoors.
#[test]
fn a_replan_after_the_three_events_is_valid_for_every_kind_of_pipeline() {
    for name in [
        "lunar.toml",
        "lunar-irba.toml",
        "lunar-wheeled.toml",
        "flat-dubins.toml",
        "indoor-disc.toml",
    ] {
        let loaded = config(name, &[]);
        let (plan, _) = original(&loaded);
        let half = plan.sequence.len() / 2;
        let here = plan.pois[half - 1].pose;
        let next = &plan.pois[half];
        let leg = &plan.segments[half].path.states;
        let mid = leg[leg.len() / 2];
        let state = MissionState {
            pose: [here.x, here.y, here.yaw],
            visited: plan.sequence[..half].to_vec(),
            failed_pois: vec![(next.target.clone(), next.index)],
            obstacles: vec![DiscObstacle {
                center: [mid.x, mid.y],
                radius: 0.4,
                height: 1.0,
            }],
        };
        let (replanned, pipeline) = replan(&loaded, &state);
        let replanned = replanned.unwrap_or_else(|e| panic!("{name}: {e}"));
        check_replan(&replanned, &pipeline, &state);
        let left = replanned.sequence.len() + replanned.skipped.len();
        assert_eq!(left, plan.sequence.len() - half, "{name}");
    }
}

/// The three events replanned on the roadmap the original plan saved (through its
/// planner-independent snapshot): the replan is valid on the updated world, the
/// obstacle's neighbourhood was checked again, and the rest of the roadmap reused.
#[test]
fn a_replan_on_the_warm_roadmap_after_the_three_events_is_valid() {
    use smug_mission::changed_discs;
    for name in ["lunar.toml", "lunar-wheeled.toml", "flat-dubins.toml"] {
        let loaded = config(name, &[]);
        let (plan, pipeline) = original(&loaded);
        let saved = pipeline.planner.as_ref().unwrap().save_roadmap().unwrap();
        let snapshot = smug_planners::RoadmapSnapshot::from_bytes(&saved).unwrap();
        let half = plan.sequence.len() / 2;
        let here = plan.pois[half - 1].pose;
        let next = &plan.pois[half];
        let leg = &plan.segments[half].path.states;
        let mid = leg[leg.len() / 2];
        let state = MissionState {
            pose: [here.x, here.y, here.yaw],
            visited: plan.sequence[..half].to_vec(),
            failed_pois: vec![(next.target.clone(), next.index)],
            obstacles: vec![DiscObstacle {
                center: [mid.x, mid.y],
                radius: 0.4,
                height: 1.0,
            }],
        };
        let mut pipeline = assemble_replan(&loaded, &state, "state.toml").unwrap();
        let changed = changed_discs(&state, &loaded.config.robot);
        let planner = pipeline.planner.as_mut().unwrap();
        planner.load_roadmap(&saved, &changed).unwrap();
        let options = pipeline.config.plan;
        let replanned = replan_mission(&mut pipeline, options, &state)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        check_replan(&replanned, &pipeline, &state);
        let counters = &replanned.stats.counters;
        assert_eq!(counters["warm_vertices"], snapshot.vertices.len() as u64);
        assert!(
            counters["warm_vertices_rechecked"] > 0,
            "{name}: {counters:?}"
        );
        assert!(counters["warm_answers_dropped"] > 0, "{name}: {counters:?}");
        assert!(
            counters["warm_vertices_rechecked"] < counters["warm_vertices"] / 2,
            "{name}: only the obstacle's neighbourhood is checked again"
        );
    }
}
