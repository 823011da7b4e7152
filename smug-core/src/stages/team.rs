//! Team sequencer stage: which robot serves which target, at which of its nodes (PoIs),
//! in which order (a multi-vehicle generalised TSP with per-robot asymmetric costs).
//!
//! The problem holds one full cost matrix per robot over one shared node set (PoIs,
//! starts, ends). A mission layer that plans legs lazily fills the matrices with
//! admissible bounds, solves, replaces the legs the solution uses by planned costs and
//! warm-starts the next round from the previous solution
//! ([`TeamSequencer::solve_from`]), as single-robot lazy mode does with
//! [`Sequencer::solve_clusters_from`](super::Sequencer::solve_clusters_from).

use super::sequencer::CostMatrix;
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// What a team minimises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TeamObjective {
    /// The sum of the robots' route costs.
    Sum,
    /// The largest route cost (makespan); ties broken on the sum.
    Makespan,
}

/// One robot of a team problem: its cost matrix and where its route starts and ends.
#[derive(Clone, Debug)]
pub struct TeamRobot {
    /// The robot's costs over the problem's nodes (asymmetric; `INFINITY` = no path).
    pub costs: Arc<CostMatrix>,
    /// Start node.
    pub start: usize,
    /// End node (may equal `start`: a closed route).
    pub end: usize,
}

/// A target: its candidate nodes (PoIs) and who may serve it.
#[derive(Clone, Debug, PartialEq)]
pub struct TeamTarget {
    /// The nodes any one of which serves the target.
    pub nodes: Vec<usize>,
    /// The robots (indices) allowed to serve it; `None` = every robot.
    pub robots: Option<Vec<usize>>,
}

/// Bounds on the number of targets per route (mTSP benchmark variants; a mission has none).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct RouteSize {
    /// Fewest targets per robot.
    pub min: usize,
    /// Most targets per robot.
    pub max: usize,
}

/// A multi-robot generalised TSP.
#[derive(Clone, Debug)]
pub struct TeamProblem {
    robots: Vec<TeamRobot>,
    targets: Vec<TeamTarget>,
    objective: TeamObjective,
    route_size: Option<RouteSize>,
}

/// Why a team problem cannot be solved; names the target or robot at fault.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TeamError {
    /// A team of zero robots.
    #[error("the team has no robot")]
    NoRobots,
    /// Robots' matrices differ in size.
    #[error("robot {robot}'s cost matrix has {got} nodes, robot 0's has {expected}")]
    MatrixSize {
        /// The robot.
        robot: usize,
        /// Its node count.
        got: usize,
        /// Robot 0's node count.
        expected: usize,
    },
    /// A node index outside the matrices.
    #[error("{what} is node {node}, but the cost matrices have {n} nodes")]
    BadNode {
        /// Whose node (e.g. "robot 1's start", "target 3's PoI").
        what: String,
        /// The node.
        node: usize,
        /// Node count.
        n: usize,
    },
    /// A target without candidate nodes.
    #[error("target {target} has no PoI")]
    NoNodes {
        /// The target.
        target: usize,
    },
    /// A target's restriction names a robot that does not exist, or none.
    #[error("target {target} is restricted to robot {robot}, but the team has {robots} robots")]
    UnknownRobot {
        /// The target.
        target: usize,
        /// The robot named.
        robot: usize,
        /// Team size.
        robots: usize,
    },
    /// A target no allowed robot can serve at a finite cost.
    #[error("target {target} cannot be served: {why}")]
    Unservable {
        /// The target.
        target: usize,
        /// Why (no allowed robot, or no PoI reachable from an allowed robot's start and
        /// back to its end).
        why: String,
    },
    /// Route-size bounds no assignment can meet.
    #[error("route sizes {min}..={max} cannot hold {targets} targets on {robots} robots")]
    RouteSize {
        /// Fewest targets per route.
        min: usize,
        /// Most targets per route.
        max: usize,
        /// Number of targets.
        targets: usize,
        /// Number of robots.
        robots: usize,
    },
    /// A solution (e.g. a warm start) that does not fit the problem.
    #[error("invalid solution: {0}")]
    BadSolution(String),
}

impl From<TeamError> for Error {
    fn from(err: TeamError) -> Self {
        Error::stage("team_sequencer", err)
    }
}

impl TeamProblem {
    /// A checked problem: nodes in range, every target servable by some allowed robot
    /// at a finite cost (a PoI reachable from its start and its end reachable from it),
    /// route-size bounds satisfiable.
    pub fn new(
        robots: Vec<TeamRobot>,
        targets: Vec<TeamTarget>,
        objective: TeamObjective,
        route_size: Option<RouteSize>,
    ) -> std::result::Result<Self, TeamError> {
        let problem = Self {
            robots,
            targets,
            objective,
            route_size,
        };
        problem.check()?;
        Ok(problem)
    }

    fn check(&self) -> std::result::Result<(), TeamError> {
        let first = self.robots.first().ok_or(TeamError::NoRobots)?;
        let n = first.costs.len();
        let node_ok = |what: String, node: usize| {
            if node < n {
                Ok(())
            } else {
                Err(TeamError::BadNode { what, node, n })
            }
        };
        for (r, robot) in self.robots.iter().enumerate() {
            if robot.costs.len() != n {
                return Err(TeamError::MatrixSize {
                    robot: r,
                    got: robot.costs.len(),
                    expected: n,
                });
            }
            node_ok(format!("robot {r}'s start"), robot.start)?;
            node_ok(format!("robot {r}'s end"), robot.end)?;
        }
        for (t, target) in self.targets.iter().enumerate() {
            if target.nodes.is_empty() {
                return Err(TeamError::NoNodes { target: t });
            }
            for &node in &target.nodes {
                node_ok(format!("target {t}'s PoI"), node)?;
            }
            if let Some(&robot) = target
                .robots
                .iter()
                .flatten()
                .find(|&&r| r >= self.robots.len())
            {
                return Err(TeamError::UnknownRobot {
                    target: t,
                    robot,
                    robots: self.robots.len(),
                });
            }
            self.check_servable(t)?;
        }
        self.check_route_size()
    }

    fn check_servable(&self, t: usize) -> std::result::Result<(), TeamError> {
        let allowed: Vec<usize> = (0..self.robots.len())
            .filter(|&r| self.allows(t, r))
            .collect();
        if allowed.is_empty() {
            return Err(TeamError::Unservable {
                target: t,
                why: "its robot restriction is empty".into(),
            });
        }
        let reachable = allowed.iter().any(|&r| {
            let robot = &self.robots[r];
            self.targets[t].nodes.iter().any(|&node| {
                robot.costs.get(robot.start, node).is_finite()
                    && robot.costs.get(node, robot.end).is_finite()
            })
        });
        if reachable {
            Ok(())
        } else {
            Err(TeamError::Unservable {
                target: t,
                why: format!(
                    "no PoI of it is reachable from the start (and back to the end) of \
                     any robot allowed to serve it (robots {allowed:?})"
                ),
            })
        }
    }

    fn check_route_size(&self) -> std::result::Result<(), TeamError> {
        let Some(size) = self.route_size else {
            return Ok(());
        };
        let (k, m) = (self.targets.len(), self.robots.len());
        if size.min > size.max || size.min * m > k || size.max * m < k {
            return Err(TeamError::RouteSize {
                min: size.min,
                max: size.max,
                targets: k,
                robots: m,
            });
        }
        Ok(())
    }

    /// The robots.
    pub fn robots(&self) -> &[TeamRobot] {
        &self.robots
    }

    /// The targets.
    pub fn targets(&self) -> &[TeamTarget] {
        &self.targets
    }

    /// The objective.
    pub fn objective(&self) -> TeamObjective {
        self.objective
    }

    /// The route-size bounds, if any.
    pub fn route_size(&self) -> Option<RouteSize> {
        self.route_size
    }

    /// Whether robot `r` may serve target `t`.
    pub fn allows(&self, t: usize, r: usize) -> bool {
        self.targets[t]
            .robots
            .as_ref()
            .is_none_or(|allowed| allowed.contains(&r))
    }

    /// Cost of robot `r` driving `route` from its start to its end.
    pub fn route_cost(&self, r: usize, route: &[Visit]) -> f64 {
        let robot = &self.robots[r];
        let mut at = robot.start;
        let mut cost = 0.0;
        for visit in route {
            cost += robot.costs.get(at, visit.node);
            at = visit.node;
        }
        cost + robot.costs.get(at, robot.end)
    }

    /// A solution from routes, with its costs computed here.
    pub fn solution(&self, routes: Vec<Vec<Visit>>) -> TeamSolution {
        let costs: Vec<f64> = routes
            .iter()
            .enumerate()
            .map(|(r, route)| self.route_cost(r, route))
            .collect();
        TeamSolution {
            total: costs.iter().sum(),
            makespan: costs.iter().copied().fold(0.0, f64::max),
            routes,
            costs,
        }
    }

    /// Checks that `solution` serves every target exactly once, by an allowed robot at
    /// one of its nodes, within the route-size bounds, with the costs it states.
    pub fn validate(&self, solution: &TeamSolution) -> std::result::Result<(), TeamError> {
        let bad = |message: String| Err(TeamError::BadSolution(message));
        if solution.routes.len() != self.robots.len() {
            return bad(format!(
                "{} routes for {} robots",
                solution.routes.len(),
                self.robots.len()
            ));
        }
        let mut served = vec![false; self.targets.len()];
        for (r, route) in solution.routes.iter().enumerate() {
            if let Some(size) = self.route_size {
                if route.len() < size.min || route.len() > size.max {
                    return bad(format!("robot {r} serves {} targets", route.len()));
                }
            }
            for visit in route {
                let Some(target) = self.targets.get(visit.target) else {
                    return bad(format!("robot {r} visits unknown target {}", visit.target));
                };
                if std::mem::replace(&mut served[visit.target], true) {
                    return bad(format!("target {} is served twice", visit.target));
                }
                if !target.nodes.contains(&visit.node) || !self.allows(visit.target, r) {
                    return bad(format!(
                        "robot {r} serves target {} at node {}, which it may not",
                        visit.target, visit.node
                    ));
                }
            }
        }
        if let Some(t) = served.iter().position(|s| !s) {
            return bad(format!("target {t} is not served"));
        }
        let fresh = self.solution(solution.routes.clone());
        if !same_cost(fresh.total, solution.total) || !same_cost(fresh.makespan, solution.makespan)
        {
            return bad(format!(
                "stated costs {} / {} but the routes cost {} / {}",
                solution.total, solution.makespan, fresh.total, fresh.makespan
            ));
        }
        Ok(())
    }

    /// The objective's value of `solution` as `(primary, tie-break)`, compared
    /// lexicographically: `(total, 0)` for the sum, `(makespan, total)` for the makespan.
    pub fn score(&self, solution: &TeamSolution) -> (f64, f64) {
        match self.objective {
            TeamObjective::Sum => (solution.total, 0.0),
            TeamObjective::Makespan => (solution.makespan, solution.total),
        }
    }
}

fn same_cost(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
}

/// A target served: which one, at which node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Visit {
    /// The target.
    pub target: usize,
    /// The node (one of the target's PoIs) it is served at.
    pub node: usize,
}

/// Routes for every robot (possibly empty), their costs, the sum and the makespan.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TeamSolution {
    /// Per robot, the targets in visiting order.
    pub routes: Vec<Vec<Visit>>,
    /// Per robot, the cost from its start through its route to its end.
    pub costs: Vec<f64>,
    /// Sum of the route costs.
    pub total: f64,
    /// Largest route cost.
    pub makespan: f64,
}

/// Solves team problems: a plugin of the `team_sequencer` stage.
pub trait TeamSequencer: Send + Sync {
    /// The best solution it finds within its budget.
    fn solve(&self, problem: &TeamProblem) -> Result<TeamSolution>;

    /// [`solve`](Self::solve) warm-started from `initial` (a replan, a lazy round); never
    /// returns a worse solution than `initial`. The default solves from scratch and keeps
    /// the better one.
    fn solve_from(&self, problem: &TeamProblem, initial: &TeamSolution) -> Result<TeamSolution> {
        problem.validate(initial)?;
        let fresh = self.solve(problem)?;
        Ok(better_of(problem, fresh, initial.clone()))
    }
}

/// The better of two solutions by the problem's objective (`a` on ties).
pub fn better_of(problem: &TeamProblem, a: TeamSolution, b: TeamSolution) -> TeamSolution {
    if lex_less(problem.score(&b), problem.score(&a)) {
        b
    } else {
        a
    }
}

/// `a < b` lexicographically.
pub fn lex_less(a: (f64, f64), b: (f64, f64)) -> bool {
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
}
