//! The search's view of a problem ([`Setting`]) and its working solution ([`State`]):
//! routes with their costs, the scalar the annealing compares, and cheapest insertion.

use rand::Rng;
use smug_core::{TeamObjective, TeamProblem, TeamSolution, Visit};

/// What the search precomputes once per problem.
pub(super) struct Setting<'a> {
    /// The problem.
    pub problem: &'a TeamProblem,
    /// Every robot's matrix is symmetric: reversing a segment keeps its cost.
    pub symmetric: bool,
    /// Every target has exactly one node (no PoI choice).
    pub single_nodes: bool,
    /// Weight of the total in the makespan objective's scalar (keeps other routes short):
    /// the parameter over the number of robots, so that it weighs a mean route.
    pub sum_weight: f64,
    /// Cost of one target too few or too many on a route (route-size bounds).
    pub penalty: f64,
    /// Per target, the nearest other targets (by robot 0's or the first allowed robot's
    /// costs, either direction, nearest nodes).
    pub neighbours: Vec<Vec<usize>>,
    /// Per target, the robots allowed to serve it.
    pub allowed: Vec<Vec<usize>>,
    /// Routes longer than this are improved with moves between near targets only.
    pub near_above: usize,
}

/// Neighbours kept per target.
const NEIGHBOURS: usize = 48;

impl<'a> Setting<'a> {
    /// The setting of `problem`; `sum_weight` and `near_above` as in [`super::TeamLnsParams`].
    pub fn new(problem: &'a TeamProblem, sum_weight: f64, near_above: usize) -> Self {
        let k = problem.targets().len();
        let m = problem.robots().len();
        let allowed: Vec<Vec<usize>> = (0..k)
            .map(|t| (0..m).filter(|&r| problem.allows(t, r)).collect())
            .collect();
        let symmetric = problem
            .robots()
            .iter()
            .all(|robot| robot.costs.is_symmetric(0.0));
        let single_nodes = problem.targets().iter().all(|t| t.nodes.len() == 1);
        let neighbours = (0..k)
            .map(|t| nearest_targets(problem, &allowed, t))
            .collect();
        Self {
            problem,
            symmetric,
            single_nodes,
            sum_weight: sum_weight / m as f64,
            penalty: penalty_per_target(problem),
            neighbours,
            allowed,
            near_above,
        }
    }

    /// Most targets robot routes may hold.
    pub fn max_size(&self) -> usize {
        self.problem.route_size().map_or(usize::MAX, |b| b.max)
    }

    /// How far a route of `len` targets is outside the bounds.
    pub fn size_violation(&self, len: usize) -> usize {
        self.problem
            .route_size()
            .map_or(0, |b| b.min.saturating_sub(len) + len.saturating_sub(b.max))
    }
}

/// A penalty larger than any finite route change: the largest finite cost times 4.
fn penalty_per_target(problem: &TeamProblem) -> f64 {
    let robot = &problem.robots()[0];
    let n = robot.costs.len();
    let mut largest: f64 = 1.0;
    for i in 0..n {
        for j in 0..n {
            let c = robot.costs.get(i, j);
            if c.is_finite() {
                largest = largest.max(c);
            }
        }
    }
    4.0 * largest
}

/// Distance between targets `a` and `b` for relatedness: the nearest pair of their
/// nodes, either direction, by the first robot allowed to serve `a`.
fn target_distance(problem: &TeamProblem, robot: usize, a: usize, b: usize) -> f64 {
    let c = &problem.robots()[robot].costs;
    let mut best = f64::INFINITY;
    for &x in &problem.targets()[a].nodes {
        for &y in &problem.targets()[b].nodes {
            best = best.min(c.get(x, y)).min(c.get(y, x));
        }
    }
    best
}

fn nearest_targets(problem: &TeamProblem, allowed: &[Vec<usize>], t: usize) -> Vec<usize> {
    let robot = allowed[t].first().copied().unwrap_or(0);
    let mut others: Vec<(f64, usize)> = (0..problem.targets().len())
        .filter(|&u| u != t)
        .map(|u| (target_distance(problem, robot, t, u), u))
        .collect();
    let keep = NEIGHBOURS.min(others.len());
    if keep < others.len() {
        others.select_nth_unstable_by(keep, |a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        others.truncate(keep);
    }
    others.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    others.into_iter().map(|(_, u)| u).collect()
}

/// A working solution: routes and their costs.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct State {
    /// Per robot, its visits in order.
    pub routes: Vec<Vec<Visit>>,
    /// Per robot, its route's cost.
    pub costs: Vec<f64>,
}

/// A place to insert a target: robot, position in its route, node, and the objective's
/// increase.
#[derive(Clone, Copy, Debug)]
pub(super) struct Insertion {
    pub robot: usize,
    pub at: usize,
    pub node: usize,
    pub increase: f64,
}

/// What an insertion scan of one route needs besides the route: the makespan, the
/// size bonus of the route, the blink rate.
#[derive(Clone, Copy)]
struct Scan {
    makespan: f64,
    bonus: f64,
    blink: f64,
}

impl State {
    /// Every robot idle.
    pub fn empty(setting: &Setting) -> Self {
        let m = setting.problem.robots().len();
        let mut state = Self {
            routes: vec![Vec::new(); m],
            costs: vec![0.0; m],
        };
        for r in 0..m {
            state.refresh(setting, r);
        }
        state
    }

    /// The state of a solution.
    pub fn of(setting: &Setting, solution: &TeamSolution) -> Self {
        let mut state = Self {
            routes: solution.routes.clone(),
            costs: vec![0.0; solution.routes.len()],
        };
        for r in 0..state.routes.len() {
            state.refresh(setting, r);
        }
        state
    }

    /// Recomputes route `r`'s cost.
    pub fn refresh(&mut self, setting: &Setting, r: usize) {
        self.costs[r] = setting.problem.route_cost(r, &self.routes[r]);
    }

    /// Number of targets too few or too many over all routes.
    pub fn violation(&self, setting: &Setting) -> usize {
        self.routes
            .iter()
            .map(|r| setting.size_violation(r.len()))
            .sum()
    }

    /// The largest route cost.
    pub fn makespan(&self) -> f64 {
        self.costs.iter().copied().fold(0.0, f64::max)
    }

    /// The sum of the route costs.
    pub fn total(&self) -> f64 {
        self.costs.iter().sum()
    }

    /// What the annealing minimises: the objective (the makespan plus a small weight
    /// on the total), plus the size-bound penalty.
    pub fn scalar(&self, setting: &Setting) -> f64 {
        let objective = match setting.problem.objective() {
            TeamObjective::Sum => self.total(),
            TeamObjective::Makespan => self.makespan() + setting.sum_weight * self.total(),
        };
        objective + setting.penalty * self.violation(setting) as f64
    }

    /// `(violation, primary, tie-break)`: smaller is better, lexicographically.
    pub fn key(&self, setting: &Setting) -> (usize, f64, f64) {
        let (a, b) = match setting.problem.objective() {
            TeamObjective::Sum => (self.total(), 0.0),
            TeamObjective::Makespan => (self.makespan(), self.total()),
        };
        (self.violation(setting), a, b)
    }

    /// The solution.
    pub fn solution(&self, setting: &Setting) -> TeamSolution {
        setting.problem.solution(self.routes.clone())
    }

    /// The cheapest place for `target` (skipping each position with probability
    /// `blink`); full routes only when no other robot may take it. `left` targets are
    /// still to insert, this one included: for the total, routes below their minimum
    /// size are preferred only when the targets left are no more than they lack (else
    /// the cheapest place wins); for the makespan, always.
    pub fn best_insertion(
        &self,
        setting: &Setting,
        target: usize,
        left: usize,
        blink: f64,
        rng: &mut impl Rng,
    ) -> Insertion {
        let makespan = self.makespan();
        let fill =
            setting.problem.objective() == TeamObjective::Makespan || left <= self.deficit(setting);
        let mut best: Option<Insertion> = None;
        for pass in 0..2 {
            for &r in &setting.allowed[target] {
                let full = self.routes[r].len() >= setting.max_size();
                if full != (pass == 1) {
                    continue;
                }
                let bonus = if fill {
                    self.size_bonus(setting, r)
                } else {
                    0.0
                };
                let scan = Scan {
                    makespan,
                    bonus,
                    blink,
                };
                self.scan_route(setting, r, target, scan, rng, &mut best);
            }
            if best.is_some() {
                break;
            }
        }
        best.expect("every target has an allowed robot (TeamProblem checks it)")
    }

    /// Targets the routes below their minimum size lack together.
    fn deficit(&self, setting: &Setting) -> usize {
        let min = setting.problem.route_size().map_or(0, |b| b.min);
        self.routes
            .iter()
            .map(|r| min.saturating_sub(r.len()))
            .sum()
    }

    fn scan_route(
        &self,
        setting: &Setting,
        r: usize,
        target: usize,
        scan: Scan,
        rng: &mut impl Rng,
        best: &mut Option<Insertion>,
    ) {
        let Scan {
            makespan,
            bonus,
            blink,
        } = scan;
        let robot = &setting.problem.robots()[r];
        let c = &robot.costs;
        let route = &self.routes[r];
        for at in 0..=route.len() {
            if blink > 0.0 && best.is_some() && rng.random::<f64>() < blink {
                continue;
            }
            let prev = if at == 0 {
                robot.start
            } else {
                route[at - 1].node
            };
            let next = route.get(at).map_or(robot.end, |v| v.node);
            let old = c.get(prev, next);
            for &node in &setting.problem.targets()[target].nodes {
                let added = c.get(prev, node) + c.get(node, next);
                let delta = leg_delta(added, old);
                let increase = self.increase(setting, r, delta, makespan) - bonus;
                if best.is_none_or(|b| increase < b.increase) {
                    *best = Some(Insertion {
                        robot: r,
                        at,
                        node,
                        increase,
                    });
                }
            }
        }
    }

    /// The penalty saved by adding a target to route `r` (below its minimum size), or
    /// added (at or above its maximum).
    fn size_bonus(&self, setting: &Setting, r: usize) -> f64 {
        let len = self.routes[r].len();
        let before = setting.size_violation(len) as f64;
        let after = setting.size_violation(len + 1) as f64;
        setting.penalty * (before - after)
    }

    /// The objective's increase when route `r` grows by `delta`.
    pub fn increase(&self, setting: &Setting, r: usize, delta: f64, makespan: f64) -> f64 {
        match setting.problem.objective() {
            TeamObjective::Sum => delta,
            TeamObjective::Makespan => {
                let grown = self.costs[r] + delta;
                (grown.max(makespan) - makespan).max(0.0) + setting.sum_weight * delta
            }
        }
    }

    /// Applies an insertion.
    pub fn insert(&mut self, setting: &Setting, target: usize, place: Insertion) {
        self.routes[place.robot].insert(
            place.at,
            Visit {
                target,
                node: place.node,
            },
        );
        self.refresh(setting, place.robot);
    }

    /// Where every target is: `(robot, position)`.
    pub fn positions(&self, targets: usize) -> Vec<(usize, usize)> {
        let mut at = vec![(usize::MAX, 0); targets];
        for (r, route) in self.routes.iter().enumerate() {
            for (i, v) in route.iter().enumerate() {
                at[v.target] = (r, i);
            }
        }
        at
    }
}

/// `added − removed` for legs that may be infinite: an infinite leg replaced by finite
/// ones is a huge saving, a finite one by an infinite one a huge cost.
pub(super) fn leg_delta(added: f64, removed: f64) -> f64 {
    match (added.is_finite(), removed.is_finite()) {
        (true, true) => added - removed,
        (true, false) => -f64::MAX / 4.0,
        (false, true) => f64::INFINITY,
        (false, false) => f64::MAX / 8.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::team::mtsp::mtsp_problem;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use smug_core::{CostMatrix, RouteSize};

    #[test]
    fn size_aware_insertion_fills_short_routes_only_when_it_must() {
        // Targets on a line away from the depot: the total wants one route; bounds 3..=6.
        let costs = CostMatrix::from_fn(11, |i, j| (i as f64 - j as f64).abs()).unwrap();
        let bounds = RouteSize { min: 3, max: 6 };
        let problem = mtsp_problem(costs, 3, TeamObjective::Sum, Some(bounds)).unwrap();
        let setting = Setting::new(&problem, 0.02, 100);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let mut state = State::empty(&setting);
        // With 10 targets left and 9 lacking, the cheapest place wins (any route)…
        let first = state.best_insertion(&setting, 0, 10, 0.0, &mut rng);
        state.insert(&setting, 0, first);
        // …and once the targets left are what the short routes lack, they get them.
        for t in 1..10 {
            let place = state.best_insertion(&setting, t, 10 - t, 0.0, &mut rng);
            state.insert(&setting, t, place);
        }
        assert_eq!(state.violation(&setting), 0, "{:?}", state.routes);
        assert!(state.routes.iter().all(|r| (3..=6).contains(&r.len())));
    }
}
