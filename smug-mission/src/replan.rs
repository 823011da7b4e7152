//! Replanning during the mission: the remaining targets from the robot's pose to the
//! mission's end pose (the start for closed missions), without the visited targets and
//! the failed PoIs, on the world with the newly seen obstacles, through the config's
//! pipeline ([`assemble_replan`] then [`replan_mission`]).

use crate::oracle::KnownAnswers;
use crate::run::{plan_mission_keeping_reporting, MissionFailed};
use smug_core::config::{LoadedConfig, RobotConfig};
use smug_core::error::{Error, Result};
use smug_core::mission::MissionState;
use smug_core::mission::{add_obstacles, MaskedEstimator};
use smug_core::mission::{Mission, PlanOptions, Target};
use smug_core::pipeline::{BuildContext, DroppedPoi, Pipeline};
use smug_core::plan::Plan;
pub use smug_core::plan::{ReplanInfo, SkippedTarget};
use smug_core::registry::{ObjectiveStage, SpaceStage, Stage, TraversabilityStage, WorldStage};
use smug_core::stages::{ChangedDisc, Fingerprint};
use smug_core::world::World;

/// The state leaves nothing to visit: every target is visited or skipped.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("the mission state leaves no reachable target to visit{}", describe(.skipped))]
pub struct NoTargetLeft {
    /// The targets left out, with the reason.
    pub skipped: Vec<SkippedTarget>,
}

fn describe(skipped: &[SkippedTarget]) -> String {
    if skipped.is_empty() {
        return " (every target is visited)".into();
    }
    let parts: Vec<String> = skipped
        .iter()
        .map(|s| format!("`{}`: {}", s.target, s.reason))
        .collect();
    format!(" (skipped {})", parts.join("; "))
}

/// The config's world (built from its `[world]` section) with `obstacles` added, its
/// mission, and the context it was built in.
fn updated_world(
    loaded: &LoadedConfig,
    state: &MissionState,
    path: &str,
) -> Result<(World, Mission, BuildContext, Fingerprint)> {
    let mut world_only = loaded.clone();
    let world_stages = [WorldStage::NAME, SpaceStage::NAME, ObjectiveStage::NAME];
    world_only.config.keep_sections(&world_stages);
    let pipeline = Pipeline::assemble(&world_only)?;
    let mut world = pipeline
        .world
        .as_deref()
        .cloned()
        .ok_or(Error::MissingStage {
            stage: "replan".into(),
            needed: "world",
        })?;
    let mission = pipeline.given_mission.clone().ok_or(Error::MissingStage {
        stage: "replan".into(),
        needed: "world",
    })?;
    state
        .check(&mission, &world.bounds(), path)
        .map_err(|e| Error::stage("replan", e))?;
    let fingerprint = crate::fingerprint::fingerprint(loaded, &world);
    add_obstacles(&mut world, &state.obstacles);
    Ok((world, mission, pipeline.context(), fingerprint))
}

/// Assembles the config's pipeline on its world updated with the state's obstacles
/// (checked against the mission and the map first; `path` names the state in errors).
/// The pipeline's world keeps the original mission; [`replan_mission`] plans the rest.
pub fn assemble_replan(
    loaded: &LoadedConfig,
    state: &MissionState,
    path: &str,
) -> Result<Pipeline> {
    Ok(assemble_replan_fingerprinted(loaded, state, path)?.0)
}

/// The regions a mission state's obstacles changed, each widened by the robot's
/// extent (half the diagonal of its base box): a warm roadmap checks again what
/// reaches into them.
pub fn changed_discs(state: &MissionState, robot: &RobotConfig) -> Vec<ChangedDisc> {
    let extent = 0.5 * robot.length.hypot(robot.width);
    state
        .obstacles
        .iter()
        .map(|o| ChangedDisc {
            center: o.center,
            radius: o.radius + extent,
        })
        .collect()
}

/// [`assemble_replan`], with the [`Fingerprint`] of the config's world before the
/// state's obstacles (what a saved roadmap must have been built for).
pub fn assemble_replan_fingerprinted(
    loaded: &LoadedConfig,
    state: &MissionState,
    path: &str,
) -> Result<(Pipeline, Fingerprint)> {
    let (world, original, ctx, fingerprint) = updated_world(loaded, state, path)?;
    // No mission while assembling: the replan prunes the PoIs itself (a visited
    // target whose poses are now blocked is no error).
    let build_world = Some((world, None));
    let mut pipeline = match (&loaded.config.traversability, state.obstacles.is_empty()) {
        (Some(section), false) => {
            let inner = ctx.build::<TraversabilityStage>(section)?.object;
            let masked = MaskedEstimator {
                inner,
                obstacles: state.obstacles.clone(),
            };
            Pipeline::assemble_with(
                loaded,
                build_world,
                Some((section.kind.as_str(), Box::new(masked))),
            )?
        }
        _ => Pipeline::assemble_with(loaded, build_world, None)?,
    };
    let endpoints = replan_mission_of(&original, state, vec![]);
    check_endpoints(&pipeline, &endpoints, path)?;
    pipeline.given_mission = Some(original.clone());
    pipeline.mission = Some(original);
    Ok((pipeline, fingerprint))
}

/// The targets still to visit (PoIs that failed or are invalid on the updated world
/// left out) and the ones skipped, with the reason.
fn remaining_targets(
    pipeline: &Pipeline,
    original: &Mission,
    state: &MissionState,
) -> (Vec<Target>, Vec<SkippedTarget>, Vec<DroppedPoi>) {
    let (mut targets, mut skipped, mut dropped) = (Vec::new(), Vec::new(), Vec::new());
    for target in &original.targets {
        if state.visited.contains(&target.id) {
            continue;
        }
        let mut pois = Vec::new();
        let mut failed = 0;
        for (k, pose) in target.pois.iter().enumerate() {
            if state.failed(&target.id, k) {
                failed += 1;
            } else if pipeline
                .state_validity
                .as_ref()
                .is_some_and(|c| !c.is_valid(pose))
            {
                dropped.push(DroppedPoi {
                    target: target.id.clone(),
                    index: k,
                    pose: *pose,
                });
            } else {
                pois.push(*pose);
            }
        }
        if pois.is_empty() {
            let reason = if failed == target.pois.len() {
                "every PoI failed".to_string()
            } else {
                format!(
                    "no PoI left: {failed} failed, {} not valid for the robot on the updated world",
                    target.pois.len() - failed
                )
            };
            skipped.push(SkippedTarget {
                target: target.id.clone(),
                reason,
            });
        } else {
            targets.push(Target {
                pois,
                ..target.clone()
            });
        }
    }
    (targets, skipped, dropped)
}

/// The mission the replan plans: from the state's pose to the original end pose (a
/// closed mission stays closed when the robot is still at its start).
fn replan_mission_of(original: &Mission, state: &MissionState, targets: Vec<Target>) -> Mission {
    let pose = state.pose();
    let end = if original.end.is_none() && pose == original.start {
        None
    } else {
        Some(original.end_pose())
    };
    Mission {
        start: pose,
        end,
        targets,
    }
}

/// Checks the robot's pose and the end pose against the pipeline's validity checker;
/// `path` names the state in errors.
fn check_endpoints(pipeline: &Pipeline, mission: &Mission, path: &str) -> Result<()> {
    let Some(checker) = pipeline.state_validity.as_ref() else {
        return Ok(());
    };
    let p = mission.start;
    if !checker.is_valid(&p) {
        return Err(Error::InvalidInput(format!(
            "{path}: `pose`: [{}, {}, {}] is not valid for the robot (in collision, \
             untraversable or off the map)",
            p.x, p.y, p.yaw
        )));
    }
    let e = mission.end_pose();
    if !checker.is_valid(&e) {
        return Err(Error::InvalidInput(format!(
            "the mission's end pose ({}, {}, yaw {}) is not valid for the robot on the updated \
             world (check the state's `obstacles`)",
            e.x, e.y, e.yaw
        )));
    }
    Ok(())
}

/// Plans the remaining targets of the pipeline's world mission from the state's pose
/// to the mission's end pose; the pipeline comes from [`assemble_replan`] (or, for a
/// state without obstacles, [`Pipeline::assemble`]). The plan is marked with the state
/// (`plan.replan`); targets left without a PoI are listed in `skipped`.
pub fn replan_mission(
    pipeline: &mut Pipeline,
    options: PlanOptions,
    state: &MissionState,
) -> Result<Plan> {
    replan_mission_reporting(pipeline, options, state).map_err(|failed| failed.error)
}

/// [`replan_mission`] that, when it fails, also says what the run did up to then (as
/// [`plan_mission_reporting`](crate::plan_mission_reporting)).
pub fn replan_mission_reporting(
    pipeline: &mut Pipeline,
    options: PlanOptions,
    state: &MissionState,
) -> std::result::Result<Plan, MissionFailed> {
    replan_mission_keeping_reporting(pipeline, options, state, None)
}

/// [`replan_mission`] with paths kept between missions (as
/// [`plan_mission_keeping`](crate::run::plan_mission_keeping)).
pub(crate) fn replan_mission_keeping(
    pipeline: &mut Pipeline,
    options: PlanOptions,
    state: &MissionState,
    answers: Option<&mut KnownAnswers>,
) -> Result<Plan> {
    replan_mission_keeping_reporting(pipeline, options, state, answers)
        .map_err(|failed| failed.error)
}

/// [`replan_mission_keeping`] that, when it fails, also says what the run did up to then.
fn replan_mission_keeping_reporting(
    pipeline: &mut Pipeline,
    options: PlanOptions,
    state: &MissionState,
    answers: Option<&mut KnownAnswers>,
) -> std::result::Result<Plan, MissionFailed> {
    let before_planning = |error| MissionFailed {
        error,
        stats: Box::default(),
    };
    let original = pipeline
        .given_mission
        .clone()
        .ok_or(Error::MissingStage {
            stage: "replan".into(),
            needed: "world",
        })
        .map_err(before_planning)?;
    let (targets, skipped, dropped) = remaining_targets(pipeline, &original, state);
    if targets.is_empty() {
        return Err(before_planning(Error::stage(
            "replan",
            NoTargetLeft { skipped },
        )));
    }
    let mission = replan_mission_of(&original, state, targets);
    check_endpoints(pipeline, &mission, "mission state").map_err(before_planning)?;
    pipeline.mission = Some(mission);
    pipeline.dropped_pois = dropped;
    let mut plan = plan_mission_keeping_reporting(pipeline, options, answers)?;
    let mut skipped_all = skipped.clone();
    skipped_all.extend(plan.skipped.iter().map(|id| SkippedTarget {
        target: id.clone(),
        reason: "unreachable".into(),
    }));
    if plan.sequence.is_empty() {
        return Err(MissionFailed {
            error: Error::stage(
                "replan",
                NoTargetLeft {
                    skipped: skipped_all,
                },
            ),
            stats: Box::new(plan.stats),
        });
    }
    let mut ids: Vec<String> = skipped.into_iter().map(|s| s.target).collect();
    ids.append(&mut plan.skipped);
    plan.skipped = ids;
    plan.replan = Some(ReplanInfo {
        state_file: None,
        state: state.clone(),
        skipped: skipped_all,
    });
    Ok(plan)
}
