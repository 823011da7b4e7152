//! `team-lns`: ruin and recreate with simulated annealing for team problems of any size.
//!
//! 1. First solution: every target at its cheapest (robot, position, PoI) in a random
//!    order — for the makespan, the cheapest is what raises the largest route least plus
//!    a small weight on the total, so idle robots take targets whenever that lowers the
//!    makespan — or the warm start.
//! 2. Each iteration removes targets (SISR strings around a seed's neighbours, random,
//!    costliest, or a route's stretch; for the makespan half of them start on the
//!    longest route), reinserts each at its cheapest place (skipping positions with a
//!    small "blink" probability), and on promising candidates improves the changed
//!    routes (Or-opt, 2-opt on symmetric costs, PoI re-choice). Annealing decides.
//! 3. The best solution's routes are reordered by the TSP [`LocalSearch`] (their PoIs
//!    fixed) and kept where shorter. One robot with one PoI per target and no size
//!    bounds is a TSP: the local search gets the whole budget.
//!
//! With `time_limit_s = 0` a seed and `max_iterations` give bit-identical solutions.

mod cross;
mod improve;
mod ruin;
mod search;
mod state;

use crate::local_search::{check_search_budget, LocalSearch, LocalSearchParams};
use crate::ParamError;
use rand::Rng;
use search::{better, construct, search, Budget};
use serde::{Deserialize, Serialize};
use smug_core::rng::{stage_rng, StageRng};
use smug_core::{
    CostMatrix, Deadline, Sequencer, TeamProblem, TeamSequencer, TeamSolution, TourKind, Visit,
};
use state::{Setting, State};

/// Parameters of [`TeamLns`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TeamLnsParams {
    /// Wall-time budget in seconds (0 = none: then `max_iterations` alone, reproducible).
    pub time_limit_s: f64,
    /// Budget of ruin-and-recreate iterations (0 = none).
    pub max_iterations: u64,
    /// Mean number of targets a ruin removes.
    pub mean_removed: f64,
    /// Longest string a ruin removes from one route.
    pub max_string: usize,
    /// Probability of skipping an insertion position (SISR's blinks).
    pub blink_rate: f64,
    /// Start temperature, in mean legs of the first solution.
    pub temp_start: f64,
    /// End temperature, in mean legs of the first solution.
    pub temp_end: f64,
    /// Makespan objective: weight of the mean route cost (the total over the robots) in
    /// the annealed value.
    pub sum_weight: f64,
    /// Candidates within this fraction of the best get their routes improved.
    pub improve_within: f64,
    /// Fraction of the time budget left for reordering the best routes with the TSP
    /// local search (iteration budgets: 200 rounds per route).
    pub polish_fraction: f64,
}

impl Default for TeamLnsParams {
    fn default() -> Self {
        Self {
            time_limit_s: 0.0,
            max_iterations: 20_000,
            mean_removed: 20.0,
            max_string: 10,
            blink_rate: 0.01,
            temp_start: 1.0,
            temp_end: 0.03,
            sum_weight: 0.02,
            improve_within: 0.02,
            polish_fraction: 0.05,
        }
    }
}

impl TeamLnsParams {
    /// Checks the values; the message names the offending parameter.
    pub fn validate(&self) -> Result<(), ParamError> {
        check_search_budget(self.time_limit_s, self.max_iterations)?;
        for (name, value, most) in [
            ("blink_rate", self.blink_rate, 1.0),
            ("sum_weight", self.sum_weight, 1.0),
            ("improve_within", self.improve_within, 10.0),
            ("polish_fraction", self.polish_fraction, 0.9),
            ("temp_start", self.temp_start, 1e6),
            ("temp_end", self.temp_end, self.temp_start.max(0.0)),
        ] {
            if !(value >= 0.0 && value <= most) {
                return Err(ParamError::OutOfRange { name, value, most });
            }
        }
        if !(self.mean_removed >= 1.0 && self.mean_removed.is_finite()) || self.max_string == 0 {
            return Err(ParamError::OutOfRange {
                name: "mean_removed / max_string",
                value: self.mean_removed.min(self.max_string as f64),
                most: f64::INFINITY,
            });
        }
        if self.temp_end <= 0.0 {
            return Err(ParamError::OutOfRange {
                name: "temp_end (must be > 0)",
                value: self.temp_end,
                most: self.temp_start,
            });
        }
        Ok(())
    }
}

/// Large-neighbourhood team sequencer. Each solve starts from a copy of the seeded
/// generator, so solves do not influence each other.
#[derive(Clone, Debug)]
pub struct TeamLns {
    params: TeamLnsParams,
    rng: StageRng,
    deadline: Deadline,
}

impl TeamLns {
    /// A solver drawing its randomness from `rng` (e.g. `ctx.rng("team_sequencer")`).
    pub fn new(params: TeamLnsParams, rng: StageRng) -> smug_core::Result<Self> {
        params.validate().map_err(|m| {
            smug_core::Error::invalid_param("team_sequencer", format!("team-lns: {m}"))
        })?;
        Ok(Self {
            params,
            rng,
            deadline: Deadline::new(),
        })
    }

    /// A solver seeded with `seed`.
    pub fn with_seed(params: TeamLnsParams, seed: u64) -> smug_core::Result<Self> {
        Self::new(params, stage_rng(seed, "team_sequencer"))
    }

    /// Stops at `deadline` (a run's; by default one that is never armed).
    pub fn with_deadline(mut self, deadline: Deadline) -> Self {
        self.deadline = deadline;
        self
    }

    /// Solves from `initial` (or from scratch); returns the solution and the iterations.
    pub fn solve_with_iterations(
        &self,
        problem: &TeamProblem,
        initial: Option<&TeamSolution>,
    ) -> smug_core::Result<(TeamSolution, u64)> {
        if let Some(initial) = initial {
            problem.validate(initial)?;
        }
        let mut rng = self.rng.clone();
        let setting = Setting::new(problem, self.params.sum_weight);
        if is_single_tsp(&setting) {
            let state = self.solve_single_tsp(&setting, initial, &mut rng)?;
            return Ok((state.solution(&setting), 0));
        }
        let start = match initial {
            Some(solution) => State::of(&setting, solution),
            None => construct(&setting, &mut rng),
        };
        let polish = self.params.polish_fraction;
        let budget = Budget {
            time_limit_s: self.params.time_limit_s * (1.0 - polish),
            max_iterations: self.params.max_iterations,
            deadline: &self.deadline,
        };
        let (best, iterations) = search(&setting, start, &self.params, &budget, &mut rng);
        let routes = best.routes.iter().filter(|r| r.len() > 2).count().max(1);
        let per_route = self.params.time_limit_s * polish / routes as f64;
        let polished = self.polish(&setting, &best, per_route, &mut rng)?;
        let best = if better(&setting, &polished, &best) {
            polished
        } else {
            best
        };
        Ok((best.solution(&setting), iterations))
    }

    /// Each route reordered by the TSP local search (PoIs fixed), kept where cheaper.
    fn polish(
        &self,
        setting: &Setting,
        state: &State,
        time_s: f64,
        rng: &mut StageRng,
    ) -> smug_core::Result<State> {
        let mut polished = state.clone();
        for r in 0..state.routes.len() {
            if state.routes[r].len() <= 2 || self.deadline.passed() {
                continue;
            }
            let params = LocalSearchParams {
                time_limit_s: time_s,
                max_iterations: if time_s > 0.0 { 0 } else { 200 },
                ..LocalSearchParams::default()
            };
            let solver = LocalSearch::with_seed(params, rng.random())?
                .with_deadline(self.deadline.clone());
            let route = reorder(setting, r, &state.routes[r], &solver)?;
            let mut trial = polished.clone();
            trial.routes[r] = route;
            trial.refresh(setting, r);
            if trial.costs[r] < polished.costs[r] {
                polished = trial;
            }
        }
        Ok(polished)
    }

    /// One robot, one PoI per target, no size bounds: the TSP local search with the
    /// whole budget (never worse than the warm start).
    fn solve_single_tsp(
        &self,
        setting: &Setting,
        initial: Option<&TeamSolution>,
        rng: &mut StageRng,
    ) -> smug_core::Result<State> {
        let route: Vec<Visit> = match initial {
            Some(solution) => solution.routes[0].clone(),
            None => (0..setting.problem.targets().len())
                .map(|target| Visit {
                    target,
                    node: setting.problem.targets()[target].nodes[0],
                })
                .collect(),
        };
        let params = LocalSearchParams {
            time_limit_s: self.params.time_limit_s,
            max_iterations: if self.params.time_limit_s > 0.0 {
                0
            } else {
                self.params.max_iterations.clamp(1, 1000)
            },
            ..LocalSearchParams::default()
        };
        let solver =
            LocalSearch::with_seed(params, rng.random())?.with_deadline(self.deadline.clone());
        let mut found = State::empty(setting);
        found.routes[0] = reorder(setting, 0, &route, &solver)?;
        found.refresh(setting, 0);
        match initial {
            Some(solution) => {
                let start = State::of(setting, solution);
                Ok(if better(setting, &found, &start) {
                    found
                } else {
                    start
                })
            }
            None => Ok(found),
        }
    }
}

/// Whether the problem is a plain TSP for one robot.
fn is_single_tsp(setting: &Setting) -> bool {
    setting.problem.robots().len() == 1
        && setting.single_nodes
        && setting.problem.route_size().is_none()
        && setting.problem.targets().len() > 2
}

/// Route `route` of robot `r` reordered by `solver` over its nodes (start first; its
/// end last when it differs from the start).
fn reorder(
    setting: &Setting,
    r: usize,
    route: &[Visit],
    solver: &LocalSearch,
) -> smug_core::Result<Vec<Visit>> {
    let robot = &setting.problem.robots()[r];
    let closed = robot.start == robot.end;
    let mut nodes = vec![robot.start];
    nodes.extend(route.iter().map(|v| v.node));
    if !closed {
        nodes.push(robot.end);
    }
    let c = &robot.costs;
    let sub = CostMatrix::from_fn(nodes.len(), |i, j| c.get(nodes[i], nodes[j]))?;
    let kind = if closed {
        TourKind::Closed
    } else {
        TourKind::OpenTo(nodes.len() - 1)
    };
    let tour = solver.solve(&sub, kind)?;
    Ok(tour
        .order
        .iter()
        .filter(|&&i| i >= 1 && i <= route.len())
        .map(|&i| route[i - 1])
        .collect())
}

impl TeamSequencer for TeamLns {
    fn solve(&self, problem: &TeamProblem) -> smug_core::Result<TeamSolution> {
        Ok(self.solve_with_iterations(problem, None)?.0)
    }

    fn solve_from(
        &self,
        problem: &TeamProblem,
        initial: &TeamSolution,
    ) -> smug_core::Result<TeamSolution> {
        Ok(self.solve_with_iterations(problem, Some(initial))?.0)
    }
}

smug_core::register_plugin!(
    smug_core::registry::TeamSequencerStage,
    name = "team-lns",
    summary = "ruin-and-recreate with simulated annealing for team problems (any size): SISR strings, PoI choice, Or-opt/2-opt, TSP polish",
    params = TeamLnsParams,
    build = |params, ctx| Ok(Box::new(
        TeamLns::new(params, ctx.rng("team_sequencer"))?.with_deadline(ctx.deadline())
    )),
);
