//! `team-lns`: ruin and recreate with simulated annealing for team problems of any size.
//!
//! 1. First solution: every target at its cheapest (robot, position, PoI) in a random
//!    order — for the makespan, the cheapest is what raises the largest route least plus
//!    a small weight on the total, so idle robots take targets whenever that lowers the
//!    makespan — or, when the robots average more than `split_above` targets, the best
//!    cut of one TSP tour into a route per robot (route-first, cluster-second; see
//!    `split`), whichever is better; or the warm start.
//! 2. Each iteration removes targets (SISR strings around a seed's neighbours, random,
//!    costliest, or a route's stretch; for the makespan half of them start on the
//!    longest route), reinserts each at its cheapest place (skipping positions with a
//!    small "blink" probability), and on promising candidates improves the changed
//!    routes (Or-opt, 2-opt on symmetric costs, PoI re-choice; on long routes only the
//!    moves between near targets; for the total, the closest ones also get granular
//!    relocate / swap / SWAP* between routes, see `exchange`). Annealing decides. For
//!    the total, a ruin removes at most `sum_removed_per_route` of a mean route, and
//!    recreate fills routes below their minimum size only when it must.
//!    On routes of at most `split_above` targets on average, the budget is shared by a
//!    small population (see `population`), for the makespan only on problems of at most
//!    `makespan_pool_max_targets` targets: `sum_elite` (for the makespan
//!    `makespan_elite`) searches from their own first solutions, then
//!    `sum_offspring` (`makespan_offspring`) or more searches from crossovers of two of
//!    the best; a child whose search stalls (`sum_stall_per_target`,
//!    `makespan_stall_per_target`) leaves its budget to more.
//! 3. For the total on three robots or more, each pair of near routes of the best
//!    solution is solved again as a two-robot problem of its own, from its routes
//!    (`pair_iterations` per pair, or `pair_fraction` of a time budget; see `pairs`),
//!    and kept when the pair costs less.
//! 4. The best solution's routes are reordered by the TSP [`LocalSearch`] (their PoIs
//!    fixed) and kept where shorter. One robot with one PoI per target and no size
//!    bounds is a TSP: the local search gets the whole budget.
//!
//! With `time_limit_s = 0` a seed and `max_iterations` give bit-identical solutions.

mod cross;
mod exchange;
mod improve;
mod pairs;
mod params;
mod population;
mod ruin;
mod search;
mod split;
mod state;

use crate::local_search::{LocalSearch, LocalSearchParams};
use pairs::{reoptimise_pairs, PairBudget};
use params::Pool;
use population::evolve;
use rand::Rng;
use search::{better, construct, search, Budget};
use smug_core::rng::{stage_rng, StageRng};
use smug_core::{
    CostMatrix, Deadline, Sequencer, TeamProblem, TeamSequencer, TeamSolution, TourKind, Visit,
};
use split::{split_tour, TourBudget};
use state::{Setting, State};
use std::time::Instant;

pub use params::TeamLnsParams;

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
        let started = Instant::now();
        let mut rng = self.rng.clone();
        let setting = Setting::new(
            problem,
            self.params.sum_weight,
            self.params.near_moves_above,
        );
        if is_single_tsp(&setting) {
            let state = self.solve_single_tsp(&setting, initial, &mut rng)?;
            return Ok((state.solution(&setting), 0));
        }
        let start = match initial {
            Some(solution) => State::of(&setting, solution),
            None => self.first_state(&setting, &mut rng),
        };
        let polish = self.params.polish_fraction;
        let pairs = self.pair_budget(&setting);
        let time_limit_s = self.params.time_limit_s;
        let budget = Budget {
            // What the construction used is taken from the search (at least a moment
            // left: a zero would mean no time limit).
            time_limit_s: if time_limit_s > 0.0 {
                (time_limit_s * (1.0 - polish) - pairs.time_s - started.elapsed().as_secs_f64())
                    .max(1e-3)
            } else {
                0.0
            },
            max_iterations: self.params.max_iterations,
            deadline: &self.deadline,
        };
        let (best, iterations) = match self.pool(&setting) {
            Some(pool) => evolve(&setting, start, &self.params, pool, &budget, &mut rng),
            None => search(&setting, start, &self.params, &budget, 0, &mut rng),
        };
        let (best, paired) = match pairs.iterations {
            0 => (best, 0),
            _ => reoptimise_pairs(
                &setting,
                best,
                pairs,
                &self.deadline,
                &mut rng,
                &mut |sub, warm, budget, seed| {
                    solve_pair_problem(&self.params, sub, warm, budget, seed, &self.deadline)
                },
            ),
        };
        let iterations = iterations + paired;
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

    /// What pair re-optimisation may spend (`iterations == 0`: none; always none
    /// where it does not apply: see [`pairs::applies`]).
    fn pair_budget(&self, setting: &Setting) -> PairBudget {
        let p = &self.params;
        let on = p.pair_iterations > 0 && pairs::applies(setting);
        PairBudget {
            iterations: if on { p.pair_iterations } else { 0 },
            total_iterations: p.max_iterations,
            time_s: if on {
                p.time_limit_s * p.pair_fraction
            } else {
                0.0
            },
        }
    }

    /// The population the search keeps, if any: the objective's pool when it has
    /// members, on routes short enough for insertion to start well (no route-first
    /// construction).
    fn pool(&self, setting: &Setting) -> Option<Pool> {
        let targets = setting.problem.targets().len();
        let per_robot = targets / setting.problem.robots().len();
        let pool = self.params.pool(setting.problem.objective(), targets);
        (pool.elite > 0 && per_robot <= self.params.split_above).then_some(pool)
    }

    /// The better of insertion and the route-first construction (when it has a budget
    /// and the routes are long).
    fn first_state(&self, setting: &Setting, rng: &mut StageRng) -> State {
        let inserted = construct(setting, rng);
        let fraction = self.params.split_fraction;
        let targets = setting.problem.targets().len();
        let per_robot = targets / setting.problem.robots().len();
        if fraction <= 0.0 || targets < 3 || per_robot <= self.params.split_above {
            return inserted;
        }
        let seed: u64 = rng.random();
        let budget = if self.params.time_limit_s > 0.0 {
            TourBudget {
                time_limit_s: self.params.time_limit_s * fraction,
                max_iterations: 0,
            }
        } else {
            TourBudget {
                time_limit_s: 0.0,
                max_iterations: (self.params.max_iterations / 20).clamp(1, 1000),
            }
        };
        match split_tour(setting, &budget, seed, &self.deadline) {
            Some(split) if better(setting, &split, &inserted) => split,
            _ => inserted,
        }
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
            let solver =
                LocalSearch::with_seed(params, rng.random())?.with_deadline(self.deadline.clone());
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

/// A pair's problem (see `pairs`) solved by `team-lns` with `params` but the budget
/// `(seconds, iterations)` (seconds 0: iterations only) and no pair re-optimisation of
/// its own, from `warm`; `None` when the solver refuses it.
fn solve_pair_problem(
    params: &TeamLnsParams,
    problem: &TeamProblem,
    warm: &TeamSolution,
    (time_s, iterations): (f64, u64),
    seed: u64,
    deadline: &Deadline,
) -> Option<(TeamSolution, u64)> {
    let params = TeamLnsParams {
        time_limit_s: time_s,
        max_iterations: if time_s > 0.0 { 0 } else { iterations.max(1) },
        pair_iterations: 0,
        pair_fraction: 0.0,
        ..params.clone()
    };
    let solver = TeamLns::with_seed(params, seed)
        .ok()?
        .with_deadline(deadline.clone());
    solver.solve_with_iterations(problem, Some(warm)).ok()
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
