//! `team-exact`: the optimum of a small team problem by dynamic programming.
//!
//! 1. Per robot, Held–Karp over clusters: `f[S][(t, node)]`, the cheapest path from the
//!    robot's start through the targets of `S` ending at `node` of target `t ∈ S`; then
//!    `g[S]`, the cheapest route serving exactly `S` (to the robot's end), `∞` when `S`
//!    holds a target the robot may not serve or breaks the route-size bounds.
//! 2. Robots combined over subset partitions: for the sum, `h_j[S] = min_{T ⊆ S}
//!    h_{j−1}[S∖T] + g_j[T]` (3^k · m steps); for the makespan the same recursion with
//!    `max` gives the optimal makespan `M*`, and the sum recursion over the routes with
//!    `g_j[T] ≤ M*` the least total among the makespan-optimal solutions.

use serde::{Deserialize, Serialize};
use smug_core::{TeamObjective, TeamProblem, TeamSequencer, TeamSolution, Visit};

/// Parameters of [`TeamExact`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TeamExactParams {
    /// Most targets it accepts (the tables grow as 2^targets, the combination as 3^targets).
    pub max_targets: usize,
}

impl Default for TeamExactParams {
    fn default() -> Self {
        Self { max_targets: 14 }
    }
}

/// Most entries (12 bytes each) of one robot's table: 2^targets × PoIs.
pub const MAX_TABLE_ENTRIES: u128 = 1 << 24;

/// Hard limit on [`TeamExactParams::max_targets`].
pub const TEAM_EXACT_LIMIT: usize = 20;

/// Exact team sequencer for small problems.
#[derive(Clone, Debug)]
pub struct TeamExact {
    params: TeamExactParams,
}

impl TeamExact {
    /// The solver; refuses a `max_targets` above [`TEAM_EXACT_LIMIT`].
    pub fn new(params: TeamExactParams) -> smug_core::Result<Self> {
        if params.max_targets > TEAM_EXACT_LIMIT {
            return Err(smug_core::Error::invalid_param(
                "team_sequencer",
                format!(
                    "team-exact: max_targets = {} is above its limit of {TEAM_EXACT_LIMIT}",
                    params.max_targets
                ),
            ));
        }
        Ok(Self { params })
    }

    /// Whether a problem with `targets` targets is within its limit.
    pub fn fits(&self, targets: usize) -> bool {
        targets <= self.params.max_targets
    }
}

/// The flattened (target, node) slots of a problem.
struct Slots {
    /// `(target, node)` per slot.
    slots: Vec<(usize, usize)>,
}

impl Slots {
    fn new(problem: &TeamProblem) -> Self {
        let slots = problem
            .targets()
            .iter()
            .enumerate()
            .flat_map(|(t, target)| target.nodes.iter().map(move |&n| (t, n)))
            .collect();
        Self { slots }
    }
}

/// One robot's DP: `g[S]` and how to rebuild the route serving `S`.
struct RobotTable {
    /// `f[S · slots + s]`.
    paths: Vec<f64>,
    /// The slot before `s` on the best path of `f[S][s]` (`u32::MAX`: the start).
    parents: Vec<u32>,
    /// Cheapest route serving exactly `S`.
    routes: Vec<f64>,
    /// The last slot of that route (`u32::MAX`: empty route).
    last: Vec<u32>,
}

const NONE: u32 = u32::MAX;

/// A route with an infinite leg: usable (the problem may have no finite solution; the
/// solution then states its true infinite cost), but worse than any finite one; sums of
/// up to 10⁶ such routes stay finite.
const UNREACHABLE: f64 = f64::MAX / 1e6;

impl RobotTable {
    fn build(problem: &TeamProblem, slots: &Slots, r: usize) -> Self {
        let k = problem.targets().len();
        let robot = &problem.robots()[r];
        let c = &robot.costs;
        let ns = slots.slots.len();
        let full = 1usize << k;
        let allowed: usize = (0..k)
            .filter(|&t| problem.allows(t, r))
            .fold(0, |m, t| m | (1 << t));
        let mut paths = vec![f64::INFINITY; full * ns];
        let mut parents = vec![NONE; full * ns];
        let mut routes = vec![f64::INFINITY; full];
        let mut last = vec![NONE; full];
        for set in 1..full {
            if set & !allowed != 0 {
                continue;
            }
            for (s, &(t, node)) in slots.slots.iter().enumerate() {
                if set & (1 << t) == 0 {
                    continue;
                }
                let rest = set & !(1 << t);
                let (best, parent) = if rest == 0 {
                    (c.get(robot.start, node), NONE)
                } else {
                    best_predecessor(&paths[rest * ns..(rest + 1) * ns], slots, rest, |from| {
                        c.get(from, node)
                    })
                };
                paths[set * ns + s] = best;
                parents[set * ns + s] = parent;
            }
        }
        for set in 0..full {
            if set & !allowed != 0 || !size_ok(problem, set.count_ones() as usize) {
                continue;
            }
            let (best, parent) = if set == 0 {
                (c.get(robot.start, robot.end), NONE)
            } else {
                best_predecessor(&paths[set * ns..(set + 1) * ns], slots, set, |from| {
                    c.get(from, robot.end)
                })
            };
            routes[set] = best.min(UNREACHABLE);
            last[set] = parent;
        }
        Self {
            paths,
            parents,
            routes,
            last,
        }
    }

    /// The route serving `set` in visiting order.
    fn route(&self, slots: &Slots, set: usize) -> Vec<Visit> {
        let ns = slots.slots.len();
        let mut route = Vec::new();
        let (mut set, mut slot) = (set, self.last[set]);
        while slot != NONE {
            let (target, node) = slots.slots[slot as usize];
            route.push(Visit { target, node });
            let parent = self.parents[set * ns + slot as usize];
            set &= !(1 << target);
            slot = parent;
        }
        debug_assert!(self.paths.len() >= ns);
        route.reverse();
        route
    }
}

/// The best `row[s] + leg(node of s)` over the slots `s` whose target is in `set`.
fn best_predecessor(
    row: &[f64],
    slots: &Slots,
    set: usize,
    leg: impl Fn(usize) -> f64,
) -> (f64, u32) {
    let mut best = (f64::INFINITY, NONE);
    for (s, &(t, node)) in slots.slots.iter().enumerate() {
        if set & (1 << t) == 0 {
            continue;
        }
        let cost = row[s] + leg(node);
        if cost < best.0 || best.1 == NONE {
            best = (cost, s as u32);
        }
    }
    best
}

fn size_ok(problem: &TeamProblem, size: usize) -> bool {
    problem
        .route_size()
        .is_none_or(|b| size >= b.min && size <= b.max)
}

/// Combines the robots' route tables: per robot `j` and set `S`, the best value of
/// robots `0..=j` serving exactly `S` and the subset robot `j` takes.
fn combine(routes: &[Vec<f64>], join: impl Fn(f64, f64) -> f64) -> (Vec<f64>, Vec<Vec<usize>>) {
    let full = routes[0].len();
    let mut value = routes[0].clone();
    let mut choices = vec![(0..full).collect::<Vec<_>>()];
    for g in &routes[1..] {
        let mut next = vec![f64::INFINITY; full];
        let mut choice = vec![0usize; full];
        for set in 0..full {
            // Every subset `mine` of `set`, the empty one last.
            let mut mine = set;
            loop {
                let cost = join(value[set & !mine], g[mine]);
                if cost < next[set] {
                    next[set] = cost;
                    choice[set] = mine;
                }
                if mine == 0 {
                    break;
                }
                mine = (mine - 1) & set;
            }
        }
        value = next;
        choices.push(choice);
    }
    (value, choices)
}

impl TeamSequencer for TeamExact {
    fn solve(&self, problem: &TeamProblem) -> smug_core::Result<TeamSolution> {
        let k = problem.targets().len();
        if !self.fits(k) {
            return Err(smug_core::Error::invalid_param(
                "team_sequencer",
                format!(
                    "team-exact: {k} targets exceed max_targets = {}; use team-lns or team-auto",
                    self.params.max_targets
                ),
            ));
        }
        let slots = Slots::new(problem);
        let entries = (1u128 << k) * slots.slots.len() as u128;
        if entries > MAX_TABLE_ENTRIES {
            return Err(smug_core::Error::invalid_param(
                "team_sequencer",
                format!(
                    "team-exact: {k} targets with {} PoIs need {entries} table entries per \
                     robot, more than {MAX_TABLE_ENTRIES}; use team-lns or team-auto",
                    slots.slots.len()
                ),
            ));
        }
        let tables: Vec<RobotTable> = (0..problem.robots().len())
            .map(|r| RobotTable::build(problem, &slots, r))
            .collect();
        let mut routes: Vec<Vec<f64>> = tables.iter().map(|t| t.routes.clone()).collect();
        if problem.objective() == TeamObjective::Makespan {
            let (best, _) = combine(&routes, f64::max);
            let makespan = best[(1 << k) - 1];
            for g in &mut routes {
                for cost in g.iter_mut().filter(|c| **c > makespan) {
                    *cost = f64::INFINITY;
                }
            }
        }
        let (_, choices) = combine(&routes, |a, b| a + b);
        let mut rest = (1usize << k) - 1;
        let mut sets = vec![0; tables.len()];
        for j in (0..tables.len()).rev() {
            sets[j] = choices[j][rest];
            rest &= !sets[j];
        }
        let routes = tables
            .iter()
            .zip(sets)
            .map(|(table, set)| table.route(&slots, set))
            .collect();
        Ok(problem.solution(routes))
    }
}

smug_core::register_plugin!(
    smug_core::registry::TeamSequencerStage,
    name = "team-exact",
    summary = "exact DP for small team problems: Held-Karp over clusters per robot, robots combined over subset partitions (≤ ~14 targets)",
    params = TeamExactParams,
    build = |params, _ctx| Ok(Box::new(TeamExact::new(params)?)),
);
