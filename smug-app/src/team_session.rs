//! A team session: every robot's pipeline (checkers, planner with its roadmap) kept in
//! memory across the team's replans, as [`smug_app::MissionSession`](crate::MissionSession)
//! keeps one robot's. A replan on the same world plans on the kept roadmaps; a state
//! whose obstacles differ from the ones applied builds the team again on the config's
//! world with the state's obstacles.

use crate::team::{assemble_on_all, assemble_team, everyone, renumbered, Deployment, Team};
use crate::team_replan::{deployments, remaining_targets, replan_info, updated_world};
use crate::{AppError, Outcome, Result};
use smug_core::config::TeamConfig;
use smug_core::mission::{DiscObstacle, TeamState};
use smug_core::{LoadedConfig, TeamPlan};
use smug_mission::{plan_team, NoTargetLeft, TeamMember, TeamMission};

/// A team kept in memory across replans (see the [module](self) documentation).
pub struct TeamSession {
    /// The config, for rebuilding on an updated world.
    loaded: LoadedConfig,
    /// Every robot of the config, in its order, on the world with `obstacles`, for
    /// the whole mission.
    team: Team,
    /// The obstacles the team's world holds.
    obstacles: Vec<DiscObstacle>,
}

impl TeamSession {
    /// Assembles the team of `loaded` (as `smug plan` does) and keeps it.
    pub fn new(loaded: &LoadedConfig) -> Result<Self> {
        Ok(Self {
            team: assemble_team(loaded)?,
            loaded: loaded.clone(),
            obstacles: Vec::new(),
        })
    }

    /// The team as kept: its world, mission and robots.
    pub fn team(&self) -> &Team {
        &self.team
    }

    /// The obstacles the team's world holds (the last replan's state's).
    pub fn obstacles(&self) -> &[DiscObstacle] {
        &self.obstacles
    }

    /// Plans the whole mission from every robot's configured start (the plan of
    /// `smug plan` when called first), on the session's world.
    pub fn plan(&mut self) -> Result<Outcome<TeamPlan>> {
        let everyone = everyone(self.config()?);
        let mission = self.team.mission.mission.clone();
        let allowed = self.team.mission.allowed.clone();
        self.plan_deployed(&everyone, mission, &allowed)
    }

    /// Replans the targets `state` leaves, shared among its robots not lost, each from
    /// its pose (`name` stands for the state in errors and in the plan). The session
    /// stays usable after an error.
    pub fn replan(&mut self, state: &TeamState, name: &str) -> Result<Outcome<TeamPlan>> {
        let config = self.config()?.clone();
        if state.obstacles != self.obstacles {
            let (world, _) = updated_world(&self.loaded, &config, state, name)?;
            let team = &self.team.mission;
            let (mission, allowed) = (team.mission.clone(), team.allowed.clone());
            self.team = assemble_on_all(&self.loaded, world, mission, &allowed)?;
            self.obstacles = state.obstacles.clone();
        } else {
            let names: Vec<String> = config.robots.iter().map(|r| r.name.clone()).collect();
            let world = &self.team.world;
            state.check(&names, &self.team.mission.mission, &world.bounds(), name)?;
        }
        let remaining = remaining_targets(
            &config,
            &self.team.mission.mission,
            &self.team.mission.allowed,
            state,
        );
        if remaining.mission.targets.is_empty() {
            let none_left = NoTargetLeft {
                skipped: remaining.skipped,
            };
            return Ok(Outcome::of(Err(smug_core::Error::stage(
                "replan", none_left,
            )))?);
        }
        let deployed = deployments(&config, state);
        let outcome = self.plan_deployed(&deployed, remaining.mission, &remaining.allowed)?;
        Ok(match outcome {
            Outcome::Solved(mut plan) => {
                let info = replan_info(&config, state, Some(name), remaining.skipped);
                plan.replan = Some(info);
                Outcome::Solved(plan)
            }
            no_solution => no_solution,
        })
    }

    /// The team's `[team]` section.
    fn config(&self) -> Result<&TeamConfig> {
        self.loaded.config.team.as_ref().ok_or(AppError::NotATeam)
    }

    /// Plans `mission` with the `deployed` robots (each from its start to its end) on
    /// their kept pipelines; `allowed` in the config's robot numbering.
    fn plan_deployed(
        &mut self,
        deployed: &[Deployment],
        mission: smug_core::Mission,
        allowed: &[Option<Vec<usize>>],
    ) -> Result<Outcome<TeamPlan>> {
        let robots: Vec<usize> = deployed.iter().map(|d| d.robot).collect();
        let kept = &self.team.mission;
        let team_mission = TeamMission {
            mission,
            allowed: renumbered(allowed, &robots),
            unit: kept.unit.clone(),
            keep_headings: kept.keep_headings,
            deadline_s: kept.deadline_s,
            spent_s: 0.0,
        };
        let mut slots: Vec<Option<TeamMember>> = std::mem::take(&mut self.team.members)
            .into_iter()
            .map(Some)
            .collect();
        let mut active: Vec<TeamMember> = deployed
            .iter()
            .map(|d| {
                let mut member = slots[d.robot].take().expect("each robot deployed once");
                (member.start, member.end) = (d.start, d.end);
                member
            })
            .collect();
        let objective = self.team.objective;
        let sequencer = self.team.sequencer.as_ref();
        let planned = plan_team(&mut active, &team_mission, sequencer, &[objective]);
        for (d, member) in deployed.iter().zip(active) {
            slots[d.robot] = Some(member);
        }
        self.team.members = slots
            .into_iter()
            .map(|m| m.expect("every robot back"))
            .collect();
        Ok(match Outcome::of(planned)? {
            Outcome::Solved(mut plans) => Outcome::Solved(plans.remove(0)),
            Outcome::NoSolution { why } => Outcome::NoSolution { why },
        })
    }
}
