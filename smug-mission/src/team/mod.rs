//! Team missions: targets shared among robots, each planned with its own pipeline
//! (motion model, box, checkers, objective, planner and roadmap) on one world. Each
//! robot's PoIs are checked for it (a PoI invalid for a robot is never its node), its
//! legs are planned lazily by its own oracle, and the `team_sequencer` stage assigns
//! and orders the targets ([`lazy`]); every robot's route then becomes its plan
//! ([`plans`]), from the paths its oracle planned for the matrix.

mod lazy;
mod member;
mod plans;
mod robots;

pub use member::{TeamMember, TeamMission};

use lazy::LazyTeam;
use plans::{robot_plan, PlanInputs};
use robots::{Nodes, RobotOracle};
use smug_core::deadline::Deadline;
use smug_core::error::{Error, Result};
use smug_core::plan::{PlanStats, TeamPlan};
use smug_core::stages::{TeamObjective, TeamSequencer, TeamSolution};
use std::collections::BTreeMap;
use std::time::Instant;

/// Plans `team` with `members` for each of `objectives` in turn, on the same per-robot
/// oracles: every objective's routes are seeds of the next ones, and the first ones
/// are solved again seeded by the later ones, so each returned plan is at least as
/// good for its objective as every other returned plan (on the same planned costs).
/// One objective is what `smug plan` does; two compare them (`smug bench team`).
pub fn plan_team(
    members: &mut [TeamMember],
    team: &TeamMission,
    sequencer: &dyn TeamSequencer,
    objectives: &[TeamObjective],
) -> Result<Vec<TeamPlan>> {
    let Some(seconds) = team.deadline_s else {
        return plan_team_unbounded(members, team, sequencer, objectives);
    };
    // Every robot's stages (and the team sequencer, built in the first robot's
    // context) hold their pipeline's deadline: arm them all.
    let deadlines: Vec<Deadline> = members
        .iter()
        .map(|m| m.pipeline.run().deadline.clone())
        .collect();
    let left = seconds - team.spent_s;
    let _armed: Vec<_> = deadlines.iter().map(|d| d.arm(Some(left))).collect();
    let reached = || deadlines.iter().any(Deadline::reached);
    match plan_team_unbounded(members, team, sequencer, objectives) {
        Ok(mut plans) => {
            let reached = reached();
            for robot in plans.iter_mut().flat_map(|p| p.robots.iter_mut()) {
                robot.plan.deadline_reached = reached;
            }
            Ok(plans)
        }
        Err(Error::DeadlinePassed { during, .. }) => Err(Error::DeadlinePassed { seconds, during }),
        // An anytime search cut short can look like a missing path: say what happened.
        Err(_) if reached() => Err(Error::DeadlinePassed {
            seconds,
            during: "team planning".into(),
        }),
        Err(other) => Err(other),
    }
}

/// [`plan_team`] without a deadline.
fn plan_team_unbounded(
    members: &mut [TeamMember],
    team: &TeamMission,
    sequencer: &dyn TeamSequencer,
    objectives: &[TeamObjective],
) -> Result<Vec<TeamPlan>> {
    let started = Instant::now();
    let nodes = Nodes::new(members.len(), &team.mission);
    // On an error the planners taken so far are dropped with their oracles: the
    // members are not planned with again.
    let mut robots = members
        .iter_mut()
        .enumerate()
        .map(|(r, member)| {
            let poses = (member.start, member.end);
            RobotOracle::new(
                r,
                &member.name,
                &mut member.pipeline,
                poses,
                &team.mission,
                &nodes,
            )
        })
        .collect::<Result<Vec<RobotOracle>>>()?;
    let planned = plan_on_robots(members, &mut robots, &nodes, team, sequencer, objectives)
        .and_then(|(solutions, rounds, sequencing_s)| {
            let inputs = PlanInputs {
                nodes: &nodes,
                mission: &team.mission,
                world: team_world(members)?,
                keep_headings: team.keep_headings,
            };
            let mut plans = Vec::with_capacity(solutions.len());
            for (objective, solution) in objectives.iter().zip(&solutions) {
                let mut robot_plans = Vec::with_capacity(members.len());
                for (r, member) in members.iter().enumerate() {
                    let (route, cost) = (&solution.routes[r], solution.costs[r]);
                    robot_plans.push(robot_plan(&mut robots[r], member, route, cost, &inputs)?);
                }
                plans.push((*objective, robot_plans));
            }
            Ok((solutions, rounds, sequencing_s, plans))
        });
    let paths: u64 = robots.iter().map(|r| r.oracle.stats().paths_planned).sum();
    give_back(members, robots);
    let (solutions, rounds, sequencing_s, robot_plans) = planned?;
    let total_s = started.elapsed().as_secs_f64();
    Ok(solutions
        .into_iter()
        .zip(robot_plans)
        .map(|(solution, (objective, robots))| TeamPlan {
            objective,
            unit: team.unit.clone(),
            cost: match objective {
                TeamObjective::Sum => solution.total,
                TeamObjective::Makespan => solution.makespan,
            },
            total: solution.total,
            makespan: solution.makespan,
            robots,
            stats: team_stats(paths, rounds, sequencing_s, total_s),
            replan: None,
        })
        .collect())
}

/// The solutions for `objectives` (cross-seeded), the rounds of solving and the time
/// spent in the team sequencer and planning its legs.
fn plan_on_robots(
    members: &[TeamMember],
    robots: &mut [RobotOracle],
    nodes: &Nodes,
    team: &TeamMission,
    sequencer: &dyn TeamSequencer,
    objectives: &[TeamObjective],
) -> Result<(Vec<TeamSolution>, u64, f64)> {
    let started = Instant::now();
    let mut lazy = LazyTeam {
        robots,
        names: members.iter().map(|m| m.name.clone()).collect(),
        nodes,
        mission: &team.mission,
        allowed: &team.allowed,
        rounds: 0,
    };
    let mut solutions: Vec<TeamSolution> = Vec::new();
    for &objective in objectives {
        let solution = lazy.solve(sequencer, objective, &solutions)?;
        solutions.push(solution);
    }
    // The earlier objectives again, seeded by the later ones' routes.
    if objectives.len() > 1 {
        for k in 0..objectives.len() - 1 {
            let seeds: Vec<TeamSolution> = solutions.clone();
            solutions[k] = lazy.solve(sequencer, objectives[k], &seeds)?;
        }
    }
    Ok((solutions, lazy.rounds, started.elapsed().as_secs_f64()))
}

/// The world the members plan in.
fn team_world(members: &[TeamMember]) -> Result<&smug_core::world::World> {
    members
        .first()
        .and_then(|m| m.pipeline.world.as_deref())
        .ok_or(Error::MissingStage {
            stage: "team plan".into(),
            needed: "world",
        })
}

/// Gives each member's planner (with its roadmap) back to its pipeline.
fn give_back(members: &mut [TeamMember], robots: Vec<RobotOracle>) {
    for (member, robot) in members.iter_mut().zip(robots) {
        member.pipeline.planner = Some(robot.oracle.into_planner());
    }
}

/// The team run's statistics.
fn team_stats(paths: u64, rounds: u64, sequencing_s: f64, total_s: f64) -> PlanStats {
    let mut stage_times_s = BTreeMap::new();
    stage_times_s.insert("team-sequencing".to_string(), sequencing_s);
    stage_times_s.insert("total".to_string(), total_s);
    let mut counters = BTreeMap::new();
    counters.insert("team_rounds".to_string(), rounds);
    PlanStats {
        paths_planned: paths,
        stage_times_s,
        counters,
        ..PlanStats::default()
    }
}
