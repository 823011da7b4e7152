//! One robot of a team on the shared node set: its path oracle (its own planner and
//! roadmap), which nodes it may use (its start and end, the PoIs valid for it), and
//! its row of the team problem: planned costs where planned, the objective's lower
//! bounds elsewhere, `INFINITY` on nodes it may not use.

use crate::oracle::PathOracle;
use smug_core::error::{Error, Result};
use smug_core::mission::Mission;
use smug_core::pipeline::Pipeline;
use smug_core::pose::Pose2;
use smug_core::stages::CostMatrix;

/// The shared nodes of a team problem: robot `r`'s start is node `2r`, its end node
/// `2r + 1`, PoI `k` of target `t` node `2m + offset[t] + k`.
pub(super) struct Nodes {
    /// Robots.
    pub(super) robots: usize,
    /// First PoI node of each target, past the robots' nodes.
    pub(super) offsets: Vec<usize>,
    /// Node count.
    pub(super) n: usize,
}

impl Nodes {
    /// The nodes of `robots` robots and `mission`'s PoIs.
    pub(super) fn new(robots: usize, mission: &Mission) -> Self {
        let mut offsets = Vec::with_capacity(mission.targets.len());
        let mut next = 2 * robots;
        for target in &mission.targets {
            offsets.push(next);
            next += target.pois.len();
        }
        Self {
            robots,
            offsets,
            n: next,
        }
    }

    /// The nodes of target `t`'s PoIs.
    pub(super) fn pois(&self, t: usize, mission: &Mission) -> std::ops::Range<usize> {
        self.offsets[t]..self.offsets[t] + mission.targets[t].pois.len()
    }

    /// `(target, PoI index)` of a PoI node.
    pub(super) fn poi_of(&self, node: usize) -> Option<(usize, usize)> {
        if node < 2 * self.robots {
            return None;
        }
        let t = self.offsets.partition_point(|&o| o <= node) - 1;
        Some((t, node - self.offsets[t]))
    }
}

/// One robot's oracle and where the shared nodes sit in it.
pub(super) struct RobotOracle {
    /// The oracle over the robot's planner.
    pub(super) oracle: PathOracle,
    /// For each shared node, its index in the oracle (`None`: not the robot's).
    pub(super) local: Vec<Option<usize>>,
    /// The robot's start and end nodes (shared numbering).
    pub(super) start: usize,
    /// End node (its start's node when it returns).
    pub(super) end: usize,
    /// Costs over the shared nodes: planned, else bound, `INFINITY` where not its own.
    costs: Vec<f64>,
    /// How many entries of the oracle's log of stored pairs `costs` has seen.
    seen: usize,
}

impl RobotOracle {
    /// Robot `r` of `nodes` with `pipeline`'s planner, objective and checkers: its
    /// start and end (checked valid for it) and the PoIs of `mission` valid for it.
    /// The planner is taken from the pipeline (given back by [`Self::into_planner`]).
    pub(super) fn new(
        r: usize,
        name: &str,
        pipeline: &mut Pipeline,
        (start, end): (Pose2, Option<Pose2>),
        mission: &Mission,
        nodes: &Nodes,
    ) -> Result<Self> {
        let mut oracle = PathOracle::of_pipeline(pipeline, "team plan")?;
        let valid = |pose: &Pose2| {
            pipeline
                .state_validity
                .as_ref()
                .is_none_or(|c| c.is_valid(pose))
        };
        for (what, pose) in [("start", Some(start)), ("end", end)] {
            if let Some(pose) = pose.filter(|p| !valid(p)) {
                return Err(Error::InvalidInput(format!(
                    "robot `{name}`: its {what} pose ({:.3}, {:.3}, yaw {:.3}) is not valid \
                     for it (in collision, untraversable or off the map)",
                    pose.x, pose.y, pose.yaw
                )));
            }
        }
        let mut local = vec![None; nodes.n];
        local[2 * r] = Some(oracle.add_pose(start));
        local[2 * r + 1] = Some(match end {
            Some(end) => oracle.add_pose(end),
            None => local[2 * r].expect("start registered"),
        });
        for (t, target) in mission.targets.iter().enumerate() {
            for (k, pose) in target.pois.iter().enumerate() {
                if valid(pose) {
                    local[nodes.offsets[t] + k] = Some(oracle.add_pose(*pose));
                }
            }
        }
        let end_node = if end.is_some() { 2 * r + 1 } else { 2 * r };
        let mut robot = Self {
            oracle,
            local,
            start: 2 * r,
            end: end_node,
            costs: Vec::new(),
            seen: 0,
        };
        robot.costs = robot.initial_costs(nodes.n);
        Ok(robot)
    }

    /// Bounds between the robot's own nodes, `INFINITY` elsewhere (0 on the diagonal).
    fn initial_costs(&self, n: usize) -> Vec<f64> {
        let mut costs = vec![f64::INFINITY; n * n];
        for (i, li) in self.local.iter().enumerate() {
            costs[i * n + i] = 0.0;
            let Some(li) = *li else { continue };
            for (j, lj) in self.local.iter().enumerate() {
                if let Some(lj) = *lj {
                    if i != j {
                        costs[i * n + j] = self.oracle.lower_bound(li, lj);
                    }
                }
            }
        }
        costs
    }

    /// Whether PoI node `node` is valid for the robot.
    pub(super) fn has(&self, node: usize) -> bool {
        self.local[node].is_some()
    }

    /// The robot's cost matrix over the shared nodes, with every pair planned so far
    /// at its planned cost.
    pub(super) fn matrix(&mut self, n: usize) -> Result<CostMatrix> {
        // A pose may be two nodes (the end at the start): both get its costs.
        let mut nodes_at: Vec<Vec<usize>> = vec![Vec::new(); self.oracle.len()];
        for (node, l) in self.local.iter().enumerate() {
            if let Some(l) = *l {
                nodes_at[l].push(node);
            }
        }
        let stored = self.oracle.stored_since(self.seen).to_vec();
        self.seen += stored.len();
        for (li, lj) in stored {
            let cost = self.oracle.planned_cost(li, lj).unwrap_or(f64::INFINITY);
            for &i in &nodes_at[li] {
                for &j in nodes_at[lj].iter().filter(|&&j| j != i) {
                    self.costs[i * n + j] = cost;
                }
            }
        }
        CostMatrix::from_rows(n, self.costs.clone())
    }

    /// Plans the legs `(from, to)` (shared nodes) not planned yet.
    pub(super) fn plan_legs(&mut self, legs: &[(usize, usize)]) -> Result<()> {
        let pairs: Vec<(usize, usize)> = legs
            .iter()
            .filter_map(|&(a, b)| Some((self.local[a]?, self.local[b]?)))
            .filter(|&(a, b)| !self.oracle.is_planned(a, b))
            .collect();
        self.oracle.plan_pairs(&pairs)
    }

    /// Plans, for each unplanned leg `(from, to)` (shared nodes), the row from `from` to
    /// every node of `goals` (one search per row where the planner answers many goals
    /// at once; only the legs themselves otherwise).
    pub(super) fn plan_rows_of(&mut self, legs: &[(usize, usize)], goals: &[usize]) -> Result<()> {
        if !self.oracle.answers_many() {
            return self.plan_legs(legs);
        }
        let goals: Vec<usize> = goals.iter().filter_map(|&g| self.local[g]).collect();
        let mut rows: Vec<(usize, Vec<usize>)> = Vec::new();
        for &(a, b) in legs {
            let (Some(from), Some(to)) = (self.local[a], self.local[b]) else {
                continue;
            };
            let mut row: Vec<usize> = goals.iter().copied().filter(|&g| g != from).collect();
            if !row.contains(&to) {
                row.push(to);
            }
            rows.push((from, row));
        }
        self.oracle.plan_rows(&rows)
    }

    /// True when the leg `from → to` (shared nodes) has been planned.
    pub(super) fn is_planned(&self, from: usize, to: usize) -> bool {
        match (self.local[from], self.local[to]) {
            (Some(a), Some(b)) => self.oracle.is_planned(a, b),
            _ => true,
        }
    }
}
