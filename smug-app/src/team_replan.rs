//! Team replans (`smug replan` and `smug.replan` on a team config): the targets the
//! team has not visited, shared again among the robots that are not lost, each from
//! its pose in the [`TeamState`] to its end, on the world with the obstacles seen.

use crate::no_plan::NoPlan;
use crate::team::Deployment;
use crate::team::{assemble_on, no_team_plan, plan_assembled, restrictions, team_config};
use crate::team::{Team, TeamPlanned};
use crate::{AppError, Outcome, Result};
use smug_core::config::TeamConfig;
use smug_core::mission::{add_obstacles, MaskedEstimator, Target, TeamState};
use smug_core::plan::SkippedTarget;
use smug_core::registry::{Stage, TraversabilityStage, WorldStage};
use smug_core::{LoadedConfig, Mission, Pipeline, Pose2, TeamReplanInfo, World};
use smug_mission::NoTargetLeft;
use std::sync::Arc;

/// The targets a team replan plans and what it leaves out.
pub(crate) struct Remaining {
    /// The targets not visited, without their failed PoIs.
    pub(crate) mission: Mission,
    /// Per remaining target, the config's robots allowed to serve it.
    pub(crate) allowed: Vec<Option<Vec<usize>>>,
    /// Targets left out, with the reason.
    pub(crate) skipped: Vec<SkippedTarget>,
}

/// Replans the team of `loaded` from `state` (`state_file` names it in errors and in the
/// plan): the robots not lost share the targets not visited, for the config's team
/// objective. The plan's `replan` holds the state, the lost robots and the skipped
/// targets.
pub fn replan_team(
    loaded: &LoadedConfig,
    state: &TeamState,
    state_file: Option<&str>,
) -> Result<Outcome<TeamPlanned, NoPlan>> {
    let started = std::time::Instant::now();
    let team = assemble_replan(loaded, state, state_file)?;
    let (mut team, skipped) = match team {
        Ok(assembled) => assembled,
        Err(none_left) => {
            let error = smug_core::Error::stage("replan", none_left);
            return no_team_plan(error, started.elapsed().as_secs_f64());
        }
    };
    team.spend(started.elapsed().as_secs_f64());
    let objective = team.objective;
    let mut planned = match plan_assembled(team, &[objective])? {
        Outcome::Solved(planned) => planned,
        Outcome::NoSolution { why } => return Ok(Outcome::NoSolution { why }),
    };
    let info = replan_info(team_config(loaded)?, state, state_file, skipped);
    planned.plans[0].replan = Some(info);
    Ok(Outcome::Solved(planned))
}

/// What a team replan from `state` records in its plan: the state, the robots lost,
/// the targets `skipped`.
pub(crate) fn replan_info(
    config: &TeamConfig,
    state: &TeamState,
    state_file: Option<&str>,
    skipped: Vec<SkippedTarget>,
) -> TeamReplanInfo {
    let lost = config
        .robots
        .iter()
        .filter(|r| state.robot(&r.name).is_some_and(|s| s.lost))
        .map(|r| r.name.clone())
        .collect();
    TeamReplanInfo {
        state_file: state_file.map(str::to_string),
        state: state.clone(),
        lost,
        skipped,
    }
}

/// The team for `state`: its robots not lost, each from its pose, on the world with the
/// state's obstacles, for the targets left (or why none is left).
pub(crate) fn assemble_replan(
    loaded: &LoadedConfig,
    state: &TeamState,
    state_file: Option<&str>,
) -> Result<std::result::Result<(Team, Vec<SkippedTarget>), NoTargetLeft>> {
    let config = team_config(loaded)?;
    let path = state_file.unwrap_or("team state");
    let (world, original) = updated_world(loaded, config, state, path)?;
    let allowed = restrictions(loaded, config, &original)?;
    let remaining = remaining_targets(config, &original, &allowed, state);
    if remaining.mission.targets.is_empty() {
        return Ok(Err(NoTargetLeft {
            skipped: remaining.skipped,
        }));
    }
    let deployed = deployments(config, state);
    let team = assemble_on(
        loaded,
        world,
        remaining.mission,
        &remaining.allowed,
        &deployed,
    )?;
    Ok(Ok((team, remaining.skipped)))
}

/// The config's world with the state's obstacles (the traversability layer estimated
/// with them masked in) and its mission as given; the state is checked against both.
pub(crate) fn updated_world(
    loaded: &LoadedConfig,
    config: &TeamConfig,
    state: &TeamState,
    path: &str,
) -> Result<(Arc<World>, Mission)> {
    let mut world_only = loaded.clone();
    world_only.config.keep_sections(&[WorldStage::NAME]);
    world_only.config.team = None;
    let built = Pipeline::assemble(&world_only)?;
    let mut world = built.world.as_deref().cloned().ok_or(AppError::NoWorld)?;
    let mission = built.given_mission.clone().ok_or(AppError::NoWorld)?;
    let names: Vec<String> = config.robots.iter().map(|r| r.name.clone()).collect();
    state.check(&names, &mission, &world.bounds(), path)?;
    add_obstacles(&mut world, &state.obstacles);
    let estimator = match (&loaded.config.traversability, state.obstacles.is_empty()) {
        (Some(section), false) => {
            let inner = built
                .context()
                .build::<TraversabilityStage>(section)?
                .object;
            let masked: Box<dyn smug_core::TraversabilityEstimator> = Box::new(MaskedEstimator {
                inner,
                obstacles: state.obstacles.clone(),
            });
            Some((section.kind.as_str(), masked))
        }
        _ => None,
    };
    let mut with_layer = loaded.clone();
    with_layer
        .config
        .keep_sections(&[WorldStage::NAME, TraversabilityStage::NAME]);
    with_layer.config.team = None;
    let layered = Pipeline::assemble_with(&with_layer, Some((world, None)), estimator)?;
    let world = layered.world.clone().ok_or(AppError::NoWorld)?;
    Ok((world, mission))
}

/// The targets not visited (failed PoIs left out) with their restrictions, and the
/// targets skipped: every PoI failed, or only lost robots may serve it.
pub(crate) fn remaining_targets(
    config: &TeamConfig,
    original: &Mission,
    allowed: &[Option<Vec<usize>>],
    state: &TeamState,
) -> Remaining {
    let lost = |r: usize| state.robot(&config.robots[r].name).is_some_and(|s| s.lost);
    let mut remaining = Remaining {
        mission: Mission {
            targets: Vec::new(),
            ..original.clone()
        },
        allowed: Vec::new(),
        skipped: Vec::new(),
    };
    for (target, allowed) in original.targets.iter().zip(allowed) {
        if state.visited.contains(&target.id) {
            continue;
        }
        let failed = |k: usize| {
            state
                .failed_pois
                .iter()
                .any(|(t, i)| *t == target.id && *i == k)
        };
        let pois: Vec<Pose2> = (0..target.pois.len())
            .filter(|&k| !failed(k))
            .map(|k| target.pois[k])
            .collect();
        let reason = if pois.is_empty() {
            Some("every PoI failed".to_string())
        } else if let Some(robots) = allowed.as_ref().filter(|a| a.iter().all(|&r| lost(r))) {
            let names: Vec<&str> = robots
                .iter()
                .map(|&r| config.robots[r].name.as_str())
                .collect();
            Some(format!(
                "only lost robots may serve it (restricted to {})",
                names.join(", ")
            ))
        } else {
            None
        };
        match reason {
            Some(reason) => remaining.skipped.push(SkippedTarget {
                target: target.id.clone(),
                reason,
            }),
            None => {
                remaining.mission.targets.push(Target {
                    pois,
                    ..target.clone()
                });
                remaining.allowed.push(allowed.clone());
            }
        }
    }
    remaining
}

/// The robots not lost, each from its pose in `state` to its end: its configured end,
/// else back at its start (a robot still at its start keeps a closed tour).
pub(crate) fn deployments(config: &TeamConfig, state: &TeamState) -> Vec<Deployment> {
    config
        .robots
        .iter()
        .enumerate()
        .filter_map(|(robot, r)| {
            let s = state.robot(&r.name).filter(|s| !s.lost)?;
            let [x, y, yaw] = s.pose?;
            let start = Pose2::new(x, y, yaw);
            let end = match r.end {
                Some(end) => Some(end),
                None if start == r.start => None,
                None => Some(r.start),
            };
            Some(Deployment { robot, start, end })
        })
        .collect()
}
