//! Team missions from a team config (`[team]`, issue 32): the world built once, one
//! pipeline per robot on it (its own profile: box, model, checkers, objective,
//! planner), the targets split among them by the `team_sequencer` stage (`team-auto`
//! unless the config names another) for the sum of their costs or the makespan.

use crate::no_plan::NoPlan;
use crate::{AppError, Outcome, Result};
use smug_core::config::{team_key, PluginSection, TeamConfig, TeamUnit};
use smug_core::registry::{
    ObjectiveStage, Stage, TeamSequencerStage, TraversabilityStage, WorldStage,
};
use smug_core::{LoadedConfig, Mission, Objective, Pipeline, RobotConfig, TeamObjective, TeamPlan};
use smug_core::{PlanStats, Pose2, TeamSequencer, World};
use smug_mission::{plan_team, TeamMember, TeamMission};
use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

/// The team sequencer a team config gets without a `[team_sequencer]` section.
pub const DEFAULT_TEAM_SEQUENCER: &str = "team-auto";

/// A team assembled from its config: the robots' pipelines on one world, the mission
/// and who may serve what, the team sequencer.
pub struct Team {
    /// The robots, in the config's order.
    pub members: Vec<TeamMember>,
    /// The targets and their restrictions.
    pub mission: TeamMission,
    /// The team sequencer.
    pub sequencer: Box<dyn TeamSequencer>,
    /// The shared world (with its traversability layer).
    pub world: Arc<World>,
    /// What the config says the team minimises.
    pub objective: TeamObjective,
}

/// Team plans with the team that made them.
pub struct TeamPlanned {
    /// One plan per objective asked for (the config's: one).
    pub plans: Vec<TeamPlan>,
    /// The team (its robots' planners keep their roadmaps).
    pub team: Team,
}

/// True when `loaded` is a team config.
pub fn is_team(loaded: &LoadedConfig) -> bool {
    loaded.config.team.is_some()
}

/// The `[team]` section, or an error saying the config has none.
pub(crate) fn team_config(loaded: &LoadedConfig) -> Result<&TeamConfig> {
    loaded.config.team.as_ref().ok_or(AppError::NotATeam)
}

/// Builds the shared world once, then every robot's pipeline on it.
pub fn assemble_team(loaded: &LoadedConfig) -> Result<Team> {
    let team = team_config(loaded)?;
    let (world, mission) = shared_world(loaded)?;
    let allowed = restrictions(loaded, team, &mission)?;
    assemble_on_all(loaded, world, mission, &allowed)
}

/// Every robot of the config from its configured start, on `world` for `mission`
/// (`allowed` as [`assemble_on`] takes it).
pub(crate) fn assemble_on_all(
    loaded: &LoadedConfig,
    world: Arc<World>,
    mission: Mission,
    allowed: &[Option<Vec<usize>>],
) -> Result<Team> {
    let everyone = everyone(team_config(loaded)?);
    assemble_on(loaded, world, mission, allowed, &everyone)
}

/// Every robot of `team`, from its configured start to its configured end.
pub(crate) fn everyone(team: &TeamConfig) -> Vec<Deployment> {
    team.robots
        .iter()
        .enumerate()
        .map(|(robot, r)| Deployment {
            robot,
            start: r.start,
            end: r.end,
        })
        .collect()
}

/// One robot of the config sent on a mission: its index in `[[team.robots]]`, where it
/// starts and ends (`None`: back at its start).
pub(crate) struct Deployment {
    /// Index in the config's robots.
    pub(crate) robot: usize,
    /// Start pose.
    pub(crate) start: Pose2,
    /// End pose.
    pub(crate) end: Option<Pose2>,
}

/// The `deployed` robots' pipelines on `world` for `mission`; `allowed` holds per
/// target the config's robot indices that may serve it (renumbered for the team).
pub(crate) fn assemble_on(
    loaded: &LoadedConfig,
    world: Arc<World>,
    mission: Mission,
    allowed: &[Option<Vec<usize>>],
    deployed: &[Deployment],
) -> Result<Team> {
    let team = team_config(loaded)?;
    let mut members = Vec::with_capacity(deployed.len());
    for d in deployed {
        let name = &team.robots[d.robot].name;
        let member = assemble_member(loaded, d.robot, team.unit, &world).map_err(|source| {
            AppError::Robot {
                robot: name.clone(),
                source: Box::new(source),
            }
        })?;
        members.push(TeamMember {
            name: name.clone(),
            start: d.start,
            end: d.end,
            time: match team.unit {
                TeamUnit::Time => None,
                TeamUnit::Objective => Some(time_objective(&member)?),
            },
            pipeline: member,
        });
    }
    let sequencer = team_sequencer(loaded, &members[0].pipeline)?;
    let unit = match team.unit {
        TeamUnit::Time => "time".to_string(),
        TeamUnit::Objective => "objective".to_string(),
    };
    let robots: Vec<usize> = deployed.iter().map(|d| d.robot).collect();
    Ok(Team {
        mission: TeamMission {
            mission,
            allowed: renumbered(allowed, &robots),
            unit,
            keep_headings: loaded.config.plan.keep_headings,
            deadline_s: loaded.config.plan.deadline,
            spent_s: 0.0,
        },
        members,
        sequencer,
        world,
        objective: team.objective,
    })
}

/// `allowed` (per target, the config's robot indices that may serve it) in the
/// numbering of a team made of the config's robots `robots`, in that order.
pub(crate) fn renumbered(
    allowed: &[Option<Vec<usize>>],
    robots: &[usize],
) -> Vec<Option<Vec<usize>>> {
    let renumber = |able: &Vec<usize>| -> Vec<usize> {
        able.iter()
            .filter_map(|r| robots.iter().position(|d| d == r))
            .collect()
    };
    allowed.iter().map(|a| a.as_ref().map(renumber)).collect()
}

/// Plans an assembled team for `objectives` (see [`plan_team`]); unreachable or
/// unservable targets are no solution, with the report plan.json gets.
pub fn plan_assembled(
    mut team: Team,
    objectives: &[TeamObjective],
) -> Result<Outcome<TeamPlanned, NoPlan>> {
    let started = Instant::now();
    let planned = plan_team(
        &mut team.members,
        &team.mission,
        team.sequencer.as_ref(),
        objectives,
    );
    match planned {
        Ok(plans) => Ok(Outcome::Solved(TeamPlanned { plans, team })),
        Err(error) => {
            let total_s = team.mission.spent_s + started.elapsed().as_secs_f64();
            no_team_plan(error, total_s)
        }
    }
}

/// The no-plan outcome of a team run's library `error` (other errors stay errors); its
/// report's stats hold the run's total time (`stage_times_s.total`), the robots' own
/// counters being per robot.
pub(crate) fn no_team_plan<T>(error: smug_core::Error, total_s: f64) -> Result<Outcome<T, NoPlan>> {
    let stats = PlanStats {
        stage_times_s: BTreeMap::from([("total".to_string(), total_s)]),
        ..PlanStats::default()
    };
    match NoPlan::of(&error, stats) {
        Some(why) => Ok(Outcome::NoSolution { why }),
        None => Err(error.into()),
    }
}

/// Assembles and plans a team config for its own objective, as `smug plan` does
/// (a `[plan] deadline` counts from the start, assembly included).
pub fn plan_team_config(loaded: &LoadedConfig) -> Result<Outcome<TeamPlanned>> {
    Ok(plan_team_config_with(loaded, &mut |_| {})?.map_no_solution(|no_plan| no_plan.why))
}

/// [`plan_team_config`], showing `assembled` the team before it plans (e.g. for a
/// display following each robot's progress); without a plan, also what plan.json
/// reports.
pub fn plan_team_config_with(
    loaded: &LoadedConfig,
    assembled: &mut dyn FnMut(&Team),
) -> Result<Outcome<TeamPlanned, NoPlan>> {
    let started = Instant::now();
    let mut team = assemble_team(loaded)?;
    assembled(&team);
    team.spend(started.elapsed().as_secs_f64());
    let objective = team.objective;
    plan_assembled(team, &[objective])
}

impl Team {
    /// Counts `seconds` (spent assembling it) against the run's deadline, if any.
    pub fn spend(&mut self, seconds: f64) {
        self.mission.spent_s += seconds;
    }
}

/// The world and its mission from the shared `[world]` and `[traversability]`.
fn shared_world(loaded: &LoadedConfig) -> Result<(Arc<World>, Mission)> {
    let mut world_only = loaded.clone();
    world_only
        .config
        .keep_sections(&[WorldStage::NAME, TraversabilityStage::NAME]);
    world_only.config.team = None;
    let pipeline = Pipeline::assemble(&world_only)?;
    let world = pipeline.world.clone().ok_or(AppError::NoWorld)?;
    let mission = pipeline.given_mission.clone().ok_or(AppError::NoWorld)?;
    Ok((world, mission))
}

/// Per target of `mission`, the robots allowed to serve it; a restriction naming a
/// target the mission does not have is an error naming its key.
pub(crate) fn restrictions(
    loaded: &LoadedConfig,
    team: &TeamConfig,
    mission: &Mission,
) -> Result<Vec<Option<Vec<usize>>>> {
    let mut allowed = vec![None; mission.targets.len()];
    for (k, restriction) in team.targets.iter().enumerate() {
        let Some(t) = mission.targets.iter().position(|t| t.id == restriction.id) else {
            let ids: Vec<&str> = mission.targets.iter().map(|t| t.id.as_str()).collect();
            let message = format!(
                "the mission has no target `{}` (its targets: {})",
                restriction.id,
                ids.join(", ")
            );
            return Err(loaded
                .sources
                .key_error(&team_key("targets", k, "id"), message)
                .into());
        };
        let robots = restriction
            .robots
            .iter()
            .filter_map(|name| team.robot_index(name))
            .collect();
        allowed[t] = Some(robots);
    }
    Ok(allowed)
}

/// Robot `k`'s pipeline on `world`: its config without the world's sections, with the
/// `time` objective at its speed when the team compares in time.
fn assemble_member(
    loaded: &LoadedConfig,
    k: usize,
    unit: TeamUnit,
    world: &World,
) -> std::result::Result<Pipeline, smug_core::Error> {
    let mut member = loaded.member(k).expect("robot k exists")?;
    member.config.world = None;
    member.config.traversability = None;
    if unit == TeamUnit::Time {
        member.config.objective = Some(time_section(&member.config.robot));
    }
    Pipeline::assemble_with(&member, Some((world.clone(), None)), None)
}

/// The `time` objective's section at the robot's speed and turning rate (its
/// `[robot] max_speed` and `turn_rate`; the objective's defaults where absent).
fn time_section(robot: &RobotConfig) -> PluginSection {
    let mut section = PluginSection::new(ObjectiveStage::NAME, "time");
    for (key, value) in [
        ("max_speed", robot.max_speed),
        ("turn_rate", robot.turn_rate),
    ] {
        if let Some(value) = value {
            section.params.insert(key.into(), toml::Value::Float(value));
        }
    }
    section
}

/// The `time` objective at the robot's speed, in its pipeline's context.
fn time_objective(pipeline: &Pipeline) -> Result<Arc<dyn Objective>> {
    let built = pipeline
        .context()
        .build::<ObjectiveStage>(&time_section(&pipeline.config.robot))?;
    Ok(built.object.into())
}

/// The config's `[team_sequencer]` (else [`DEFAULT_TEAM_SEQUENCER`]), built in the first
/// robot's context (the config's seed, its run context).
fn team_sequencer(loaded: &LoadedConfig, pipeline: &Pipeline) -> Result<Box<dyn TeamSequencer>> {
    let section =
        loaded.config.team_sequencer.clone().unwrap_or_else(|| {
            PluginSection::new(TeamSequencerStage::NAME, DEFAULT_TEAM_SEQUENCER)
        });
    Ok(pipeline
        .context()
        .build::<TeamSequencerStage>(&section)?
        .object)
}
