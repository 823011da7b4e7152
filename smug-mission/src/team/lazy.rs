//! Lazy team sequencing: every robot's matrix holds its objective's lower bounds until a
//! leg is planned; the team sequencer solves, the legs its routes use are planned by
//! their robots, and it solves again (warm-started) until its routes use planned legs
//! only. With an exact sequencer the result is optimal for the planned costs (IDP's
//! argument, per robot: a bound never exceeds the cost it stands for).

use super::robots::{Nodes, RobotOracle};
use crate::unreachable::Unreachable;
use smug_core::error::{Error, Result};
use smug_core::mission::Mission;
use smug_core::stages::{
    better_of, TeamObjective, TeamProblem, TeamRobot, TeamSequencer, TeamSolution, TeamTarget,
};
use std::sync::Arc;

/// The robots of a team problem and what they share.
pub(super) struct LazyTeam<'a> {
    /// One oracle per robot.
    pub(super) robots: &'a mut [RobotOracle],
    /// Robot names, for messages.
    pub(super) names: Vec<String>,
    /// The shared nodes.
    pub(super) nodes: &'a Nodes,
    /// The shared mission.
    pub(super) mission: &'a Mission,
    /// Per target, the robots allowed to serve it (`None`: every robot).
    pub(super) allowed: &'a [Option<Vec<usize>>],
    /// Rounds of solving so far.
    pub(super) rounds: u64,
}

impl LazyTeam<'_> {
    /// The team problem on the costs planned so far (bounds elsewhere); a target no
    /// allowed robot can serve is an [`Unreachable`] naming it and why.
    fn problem(&mut self, objective: TeamObjective) -> Result<TeamProblem> {
        let n = self.nodes.n;
        let mut robots = Vec::with_capacity(self.robots.len());
        for robot in self.robots.iter_mut() {
            robots.push(TeamRobot {
                costs: Arc::new(robot.matrix(n)?),
                start: robot.start,
                end: robot.end,
            });
        }
        let mut targets = Vec::with_capacity(self.mission.targets.len());
        for t in 0..self.mission.targets.len() {
            let able: Vec<usize> = (0..robots.len())
                .filter(|&r| self.may_serve(t, r, &robots[r]))
                .collect();
            if able.is_empty() {
                return Err(self.unservable(t, robots.len()));
            }
            targets.push(TeamTarget {
                nodes: self.nodes.pois(t, self.mission).collect(),
                robots: Some(able),
            });
        }
        Ok(TeamProblem::new(robots, targets, objective, None)?)
    }

    /// Whether robot `r` is allowed to serve target `t` and has a PoI of it with a
    /// finite way in from its start and out to its end.
    fn may_serve(&self, t: usize, r: usize, robot: &TeamRobot) -> bool {
        let allowed = self.allowed[t].as_ref().is_none_or(|a| a.contains(&r));
        allowed
            && self.nodes.pois(t, self.mission).any(|p| {
                robot.costs.get(robot.start, p).is_finite()
                    && robot.costs.get(p, robot.end).is_finite()
            })
    }

    /// Why no robot can serve target `t`: robot by robot.
    fn unservable(&self, t: usize, robots: usize) -> Error {
        let target = &self.mission.targets[t];
        let why = (0..robots)
            .map(|r| {
                let name = &self.names[r];
                let valid = self
                    .nodes
                    .pois(t, self.mission)
                    .filter(|&p| self.robots[r].has(p))
                    .count();
                let reason = if let Some(allowed) =
                    self.allowed[t].as_ref().filter(|a| !a.contains(&r))
                {
                    let names: Vec<&str> =
                        allowed.iter().map(|&a| self.names[a].as_str()).collect();
                    format!(
                        "not allowed (the target is restricted to {})",
                        names.join(", ")
                    )
                } else if valid == 0 {
                    format!(
                        "none of its {} PoIs is valid for it (in collision, untraversable or \
                         off the map)",
                        target.pois.len()
                    )
                } else {
                    format!("no path joins its start, any of its {valid} valid PoIs and its end")
                };
                format!("target `{}`, robot `{name}`: {reason}", target.id)
            })
            .collect();
        Error::stage(
            "team plan",
            Unreachable {
                targets: vec![target.id.clone()],
                why,
                legs: Vec::new(),
            },
        )
    }

    /// Each robot's legs of `solution` (shared nodes), start to end.
    fn legs(&self, solution: &TeamSolution) -> Vec<Vec<(usize, usize)>> {
        solution
            .routes
            .iter()
            .zip(self.robots.iter())
            .map(|(route, robot)| {
                let mut stops = vec![robot.start];
                stops.extend(route.iter().map(|v| v.node));
                stops.push(robot.end);
                stops.windows(2).map(|w| (w[0], w[1])).collect()
            })
            .collect()
    }

    /// The best routes for `objective` whose legs are all planned, warm-started from
    /// the best of `seeds` (solutions whose legs are planned, e.g. another objective's):
    /// none of them is better on the final costs.
    pub(super) fn solve(
        &mut self,
        sequencer: &dyn TeamSequencer,
        objective: TeamObjective,
        seeds: &[TeamSolution],
    ) -> Result<TeamSolution> {
        let mut previous: Option<TeamSolution> = None;
        loop {
            let problem = self.problem(objective)?;
            let warm = previous
                .iter()
                .chain(seeds)
                .map(|s| problem.solution(s.routes.clone()))
                .filter(|s| s.total.is_finite() && problem.validate(s).is_ok())
                .reduce(|a, b| better_of(&problem, a, b));
            self.rounds += 1;
            let solution = match &warm {
                Some(warm) => sequencer.solve_from(&problem, warm)?,
                None => sequencer.solve(&problem)?,
            };
            if !solution.total.is_finite() {
                return Err(Error::stage(
                    "team plan",
                    Unreachable {
                        targets: vec!["(some targets)".into()],
                        why: vec![
                            "the team sequencer found no routes of finite cost that serve \
                             every target (restrictions and paths leave none)"
                                .into(),
                        ],
                        legs: Vec::new(),
                    },
                ));
            }
            let open: Vec<Vec<(usize, usize)>> = self
                .legs(&solution)
                .into_iter()
                .zip(self.robots.iter())
                .map(|(legs, robot)| {
                    legs.into_iter()
                        .filter(|&(a, b)| !robot.is_planned(a, b))
                        .collect()
                })
                .collect();
            if open.iter().all(Vec::is_empty) {
                return Ok(solution);
            }
            for ((robot, open), route) in self.robots.iter_mut().zip(open).zip(&solution.routes) {
                if open.is_empty() {
                    continue;
                }
                // Rows to every PoI of the route's targets: the PoI choices along the
                // route get planned costs at once (one search per row).
                let mut goals: Vec<usize> = route
                    .iter()
                    .flat_map(|v| self.nodes.pois(v.target, self.mission))
                    .collect();
                goals.push(robot.end);
                robot.plan_rows_of(&open, &goals)?;
            }
            previous = Some(solution);
        }
    }
}
