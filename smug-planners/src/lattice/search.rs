//! The lattice search: A* from a start to a set of goals over lattice poses, the
//! start joined to the lattice by the model's curves, goals reached by lazily checked
//! analytic shots, caches of state and primitive validity kept across queries.

use super::primitives::{Layout, StateId};
use super::{heuristic, LatticePlanner};
use smug_core::{Budget, NoPathReason, Path, PlannerOutcome, Pose2, Proof};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::Arc;
use std::time::Instant;

/// The start's node id (lattice poses are `0..len`).
const START: u32 = u32::MAX;
/// How many obstacle-aware heuristics of goal sets are kept.
const HEURISTICS_KEPT: usize = 32;

/// Per-search arrays over the lattice, reused across searches (generation stamps
/// instead of clearing).
pub(crate) struct Buffers {
    generation: u32,
    stamp: Vec<u32>,
    closed: Vec<u32>,
    g: Vec<f64>,
    parent: Vec<u32>,
    /// Gear of the motion that reached the pose: 0 forward, 1 reverse.
    gear: Vec<u8>,
}

impl Buffers {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            generation: 0,
            stamp: vec![0; n],
            closed: vec![0; n],
            g: vec![0.0; n],
            parent: vec![0; n],
            gear: vec![0; n],
        }
    }

    fn next_generation(&mut self) {
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.stamp.fill(0);
            self.closed.fill(0);
            self.generation = 1;
        }
    }
}

/// What the heap holds: a lattice pose (or the start) to expand, or a shot to a goal.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Item {
    /// A lattice pose (or the start) reached from `parent` at cost `g`; unless
    /// `verified`, by primitive `prim` of the parent's heading, not yet checked, `g`
    /// from the primitive's contract bound.
    Node {
        id: u32,
        parent: u32,
        g: f64,
        prim: u16,
        reverse: bool,
        verified: bool,
    },
    Shot {
        from: u32,
        goal: u32,
        costed: bool,
    },
}

#[derive(Clone, Copy, Debug)]
struct Entry {
    key: f64,
    seq: u64,
    item: Item,
}

impl PartialEq for Entry {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Entry {
    // A min-heap on the key, ties to the earlier push (deterministic).
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .key
            .total_cmp(&self.key)
            .then_with(|| other.seq.cmp(&self.seq))
    }
}

/// One goal of a search.
struct Goal {
    pose: Pose2,
    /// Settled: the search's cost and the lattice pose (or start) its shot leaves from.
    reached: Option<(f64, u32)>,
}

/// What checking a queued primitive gave.
enum Verified {
    /// Valid, at no more than its queued cost: the search's cost now.
    Now(f64),
    /// Valid but dearer than queued: (key, cost) to queue it at.
    Later(f64, f64),
    /// Invalid, or beaten by a cheaper way.
    Invalid,
}

/// How a search ended.
enum End {
    AllReached,
    Exhausted,
    Budget(Budget),
}

/// A search in progress.
struct Run {
    heap: BinaryHeap<Entry>,
    seq: u64,
    goals: Vec<Goal>,
    open_goals: usize,
    h2d: Option<Arc<Vec<f32>>>,
}

impl Run {
    fn push(&mut self, key: f64, item: Item) {
        self.seq += 1;
        self.heap.push(Entry {
            key,
            seq: self.seq,
            item,
        });
    }
}

impl LatticePlanner {
    /// Plans from `start` to every goal with one search.
    pub(super) fn search(&mut self, start: &Pose2, goals: &[Pose2]) -> Vec<PlannerOutcome> {
        let started = Instant::now();
        self.counts.searches += 1;
        self.last_costs = vec![None; goals.len()];
        if !self.states.is_valid(start) {
            return vec![PlannerOutcome::InvalidStart; goals.len()];
        }
        let mut outcomes: Vec<Option<PlannerOutcome>> = vec![None; goals.len()];
        let mut asked = Vec::new();
        let mut index = Vec::new();
        for (k, goal) in goals.iter().enumerate() {
            if !self.states.is_valid(goal) {
                outcomes[k] = Some(PlannerOutcome::InvalidGoal);
            } else if goal.xy_distance(start) < 1e-12 && goal.yaw == start.yaw {
                self.last_costs[k] = Some(0.0);
                outcomes[k] = Some(PlannerOutcome::Exact(Path {
                    states: vec![*start],
                    cost: 0.0,
                }));
            } else {
                index.push(k);
                asked.push(Goal {
                    pose: *goal,
                    reached: None,
                });
            }
        }
        if !asked.is_empty() {
            let (reached, end) = self.run(start, asked);
            for (goal, k) in reached.into_iter().zip(index) {
                outcomes[k] = Some(self.outcome(start, &goal, &end, k));
            }
        }
        self.counts.breakdown.astar_s += started.elapsed().as_secs_f64();
        outcomes
            .into_iter()
            .map(|o| o.expect("every goal answered"))
            .collect()
    }

    /// The outcome for one goal once the search ended.
    fn outcome(&mut self, start: &Pose2, goal: &Goal, end: &End, k: usize) -> PlannerOutcome {
        let Some((cost, from)) = goal.reached else {
            return PlannerOutcome::NoPath(match end {
                End::Budget(b) => NoPathReason::BudgetSpent(*b),
                _ => NoPathReason::Proved(Proof::Exhausted),
            });
        };
        self.last_costs[k] = Some(cost);
        let mut states = vec![goal.pose];
        let mut at = from;
        while at != START {
            states.push(self.lattice.pose(at));
            at = self.buffers.parent[at as usize];
        }
        states.push(*start);
        states.reverse();
        let path = Path::new(states, self.objective.as_ref());
        if !self.params.shortcut || path.states.len() <= 2 {
            return PlannerOutcome::Exact(path);
        }
        let shorter = Path::new(
            crate::shortcut::shortcut_galloping(&path.states, self.motions.as_ref()),
            self.objective.as_ref(),
        );
        PlannerOutcome::Exact(if shorter.cost < path.cost {
            shorter
        } else {
            path
        })
    }

    /// The A* loop: settles the goals it reaches, ends when all are, when nothing is
    /// left to expand, or when a budget runs out.
    fn run(&mut self, start: &Pose2, goals: Vec<Goal>) -> (Vec<Goal>, End) {
        self.buffers.next_generation();
        let open_goals = goals.len();
        let mut run = Run {
            heap: BinaryHeap::new(),
            seq: 0,
            goals,
            open_goals,
            h2d: None,
        };
        if self.params.obstacle_heuristic {
            run.h2d = Some(self.goal_heuristic(&run.goals));
        }
        run.push(
            0.0,
            Item::Node {
                id: START,
                parent: START,
                g: 0.0,
                prim: 0,
                reverse: false,
                verified: true,
            },
        );
        let started = Instant::now();
        let max = match self.params.max_expansions {
            0 => u64::MAX,
            m => m,
        };
        let mut expansions = 0u64;
        while let Some(entry) = run.heap.pop() {
            if expansions % 256 == 0 {
                if expansions >= max {
                    return (run.goals, End::Budget(Budget::Expansions));
                }
                if started.elapsed().as_secs_f64() > self.params.time_limit {
                    return (run.goals, End::Budget(Budget::Time));
                }
                if smug_core::deadline::passed() {
                    return (run.goals, End::Budget(Budget::Deadline));
                }
            }
            match entry.item {
                Item::Node {
                    id,
                    parent,
                    g,
                    prim,
                    reverse,
                    verified,
                } => {
                    let g = if verified {
                        g
                    } else {
                        match self.verify(id, parent, prim, g, reverse, &run) {
                            Verified::Now(g) => g,
                            Verified::Later(key, g) => {
                                run.push(
                                    key,
                                    Item::Node {
                                        id,
                                        parent,
                                        g,
                                        prim,
                                        reverse,
                                        verified: true,
                                    },
                                );
                                continue;
                            }
                            Verified::Invalid => continue,
                        }
                    };
                    if self.close(id, parent, g, reverse) {
                        expansions += 1;
                        self.counts.expansions += 1;
                        self.expand(start, id, g, &mut run);
                    }
                }
                Item::Shot { from, goal, costed } => {
                    self.try_shot(start, from, goal as usize, costed, entry.key, &mut run);
                    if run.open_goals == 0 {
                        return (run.goals, End::AllReached);
                    }
                }
            }
        }
        (run.goals, End::Exhausted)
    }

    /// Closes a popped node (its cost and parent final); false when it was already
    /// closed, or a cheaper way to it is known.
    fn close(&mut self, id: u32, parent: u32, g: f64, reverse: bool) -> bool {
        if id == START {
            return true;
        }
        let b = &mut self.buffers;
        let i = id as usize;
        if b.closed[i] == b.generation || (b.stamp[i] == b.generation && g > b.g[i]) {
            return false;
        }
        b.closed[i] = b.generation;
        b.stamp[i] = b.generation;
        b.g[i] = g;
        b.parent[i] = parent;
        b.gear[i] = reverse as u8;
        true
    }

    /// Checks the primitive that reached `id` from `parent` (cached): its true cost now
    /// when it is no more than the bound it was queued with, else later at its true key.
    fn verify(
        &mut self,
        id: u32,
        parent: u32,
        prim: u16,
        g: f64,
        reverse: bool,
        run: &Run,
    ) -> Verified {
        let b = &self.buffers;
        if b.closed[id as usize] == b.generation {
            return Verified::Invalid;
        }
        let slot = parent as usize * self.primitives.stride + prim as usize;
        let mut cost = self.caches.edge[slot];
        if cost == 0.0 {
            cost = self.edge_cost(parent, id);
            self.caches.edge[slot] = cost;
        }
        if !cost.is_finite() {
            return Verified::Invalid;
        }
        let parent_g = self.buffers.g[parent as usize];
        let true_g = parent_g + self.step_cost(parent, cost as f64, reverse);
        if true_g <= g * (1.0 + 1e-9) {
            return Verified::Now(true_g);
        }
        let b = &mut self.buffers;
        let i = id as usize;
        if b.stamp[i] == b.generation && true_g >= b.g[i] {
            return Verified::Invalid; // a verified way at least as cheap is queued
        }
        b.stamp[i] = b.generation;
        b.g[i] = true_g;
        let h = self.heuristic(id, &run.goals, run.h2d.as_deref());
        Verified::Later(true_g + h, true_g)
    }

    /// The search's cost of a motion of objective cost `cost` from `parent`: reverse
    /// penalty and gear change cost added.
    fn step_cost(&self, parent: u32, cost: f64, reverse: bool) -> f64 {
        let mut step = cost;
        if reverse {
            step *= self.params.reverse_penalty;
        }
        if parent != START && self.buffers.gear[parent as usize] != reverse as u8 {
            step += self.params.gear_change_cost;
        }
        step
    }

    fn pose_of(&self, start: &Pose2, id: u32) -> Pose2 {
        if id == START {
            *start
        } else {
            self.lattice.pose(id)
        }
    }

    /// Pushes the shots from `id` to the goals near it and relaxes its successors.
    fn expand(&mut self, start: &Pose2, id: u32, g: f64, run: &mut Run) {
        let pose = self.pose_of(start, id);
        for (j, goal) in run.goals.iter().enumerate() {
            if goal.reached.is_none() && pose.xy_distance(&goal.pose) <= self.shot_radius {
                let bound = self.cheap_bound(&pose, &goal.pose);
                if bound.is_finite() {
                    let item = Item::Shot {
                        from: id,
                        goal: j as u32,
                        costed: false,
                    };
                    run.seq += 1;
                    run.heap.push(Entry {
                        key: g + bound,
                        seq: run.seq,
                        item,
                    });
                }
            }
        }
        if id == START {
            for (to, cost, reverse) in self.start_successors(start) {
                let ng = g + self.step_cost(START, cost, reverse);
                self.queue(run, to, START, ng, 0, reverse, true);
            }
            return;
        }
        let (ix, iy, k) = self.lattice.decode(id);
        let stride = self.primitives.stride;
        for p in 0..self.primitives.by_heading[k].len() {
            let prim = self.primitives.by_heading[k][p];
            let Some((jx, jy)) = self.lattice.offset(ix, iy, prim.di, prim.dj) else {
                continue;
            };
            let to = self.lattice.id(jx, jy, prim.to_heading);
            let cached = self.caches.edge[id as usize * stride + p];
            if cached.is_infinite() {
                continue;
            }
            let (cost, verified) = if cached == 0.0 {
                (self.primitive_bounds[k][p], false)
            } else {
                (cached as f64, true)
            };
            let ng = g + self.step_cost(id, cost, prim.reverse);
            self.queue(run, to, id, ng, p as u16, prim.reverse, verified);
        }
    }

    /// Queues the way to `to` from `parent` at cost `g` (a bound unless `verified`),
    /// unless `to` is closed, a verified way at least as cheap is queued, or no goal can
    /// be reached from it.
    #[allow(clippy::too_many_arguments)]
    fn queue(
        &mut self,
        run: &mut Run,
        to: u32,
        parent: u32,
        g: f64,
        prim: u16,
        reverse: bool,
        verified: bool,
    ) {
        let b = &self.buffers;
        let i = to as usize;
        if b.closed[i] == b.generation || (b.stamp[i] == b.generation && g >= b.g[i]) {
            return;
        }
        let h = self.heuristic(to, &run.goals, run.h2d.as_deref());
        if h.is_infinite() {
            return; // no goal reachable from there
        }
        if verified {
            let b = &mut self.buffers;
            b.stamp[i] = b.generation;
            b.g[i] = g;
        }
        run.push(
            g + h,
            Item::Node {
                id: to,
                parent,
                g,
                prim,
                reverse,
                verified,
            },
        );
    }

    /// Costs a shot when first popped (pushed again at its cost), checks it when popped
    /// at its cost; a valid shot settles its goal.
    fn try_shot(
        &mut self,
        start: &Pose2,
        from: u32,
        goal: usize,
        costed: bool,
        key: f64,
        run: &mut Run,
    ) {
        if run.goals[goal].reached.is_some() {
            return;
        }
        let pose = self.pose_of(start, from);
        let target = run.goals[goal].pose;
        let g = if from == START {
            0.0
        } else {
            self.buffers.g[from as usize]
        };
        if !costed {
            let cost = self.objective.motion_cost(&pose, &target);
            if !cost.is_finite() {
                return;
            }
            let item = Item::Shot {
                from,
                goal: goal as u32,
                costed: true,
            };
            if g + cost > key {
                run.push(g + cost, item);
                return;
            }
        }
        if self.shot_valid(from, &pose, &target) {
            let cost = g + self.objective.motion_cost(&pose, &target);
            run.goals[goal].reached = Some((cost, from));
            run.open_goals -= 1;
        }
    }

    /// Whether the shot from `from` (at `pose`) to `target` is valid: cached for lattice
    /// poses (the same goals come back in a mission's later searches).
    fn shot_valid(&mut self, from: u32, pose: &Pose2, target: &Pose2) -> bool {
        let key = (
            from,
            [target.x.to_bits(), target.y.to_bits(), target.yaw.to_bits()],
        );
        if from != START {
            if let Some(&valid) = self.caches.shots.get(&key) {
                return valid;
            }
        }
        self.counts.shot_checks += 1;
        let valid = self.motions.is_valid_motion(pose, target);
        if from != START {
            self.caches.shots.insert(key, valid);
        }
        valid
    }

    /// The objective's bound as its contract gives it without solving for a curve:
    /// `w_t·‖Δxy‖ + w_r·d(yaw)`.
    fn cheap_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        let (w_t, w_r) = self.objective.bound_weights();
        w_t * a.xy_distance(b) + w_r * smug_core::pose::angle_distance(a.yaw, b.yaw)
    }

    /// The heuristic at a lattice pose: the obstacle-aware distance and, for one goal,
    /// the objective's contract bound to it (`w_t·‖Δxy‖ + w_r·d(yaw)`), the larger.
    /// (The model's curve bound, solved per queued pose, cost a tenth more time on
    /// lunar for the same plans.)
    fn heuristic(&self, id: u32, goals: &[Goal], h2d: Option<&Vec<f32>>) -> f64 {
        let mut h = 0.0;
        if let Some(d) = h2d {
            h = d[id as usize / self.lattice.headings] as f64;
            if h.is_infinite() {
                return h;
            }
            // f32 rounding: stay below the exact distance.
            h *= 1.0 - 1e-6;
        }
        if let [goal] = goals {
            h = h.max(self.cheap_bound(&self.lattice.pose(id), &goal.pose));
        }
        h
    }

    /// The lattice poses the start joins with the model's curves (one gear, no loops),
    /// valid, with their costs.
    fn start_successors(&mut self, start: &Pose2) -> Vec<(u32, f64, bool)> {
        let cell = self.lattice.cell;
        let reach = 2.0 * std::f64::consts::SQRT_2 * cell * 1.5;
        let space = self.space.clone();
        let layout = Layout {
            space: space.as_ref(),
            radius: self.radius,
            reverse: space.has_reverse_gear(),
        };
        let h = self.lattice.headings as i64;
        let k0 = self.lattice.heading_bin(start.yaw) as i64;
        let spread =
            (reach / (self.radius * 2.0 * std::f64::consts::PI / h as f64)).ceil() as i64 + 1;
        let mut out = Vec::new();
        for (ix, iy) in self.lattice.points_near(start.x, start.y, reach) {
            for dk in -spread..=spread {
                let k = (k0 + dk).rem_euclid(h) as usize;
                let id = self.lattice.id(ix, iy, k);
                let to = self.lattice.pose(id);
                let direct = start.xy_distance(&to);
                if direct < 1e-9 && dk == 0 {
                    continue;
                }
                let extent = self.space.motion_extent(start, &to);
                if extent.length > 1.3 * direct + cell
                    || extent.turning > self.space_turn(start, &to) + 0.6
                {
                    continue;
                }
                let reverse = self.space.is_reversing(start, &to, 0.5);
                if !layout.one_gear(start, &to, reverse) || !self.state_valid(id) {
                    continue;
                }
                self.counts.edge_checks += 1;
                if self.motions.is_valid_motion(start, &to) {
                    out.push((id, self.objective.motion_cost(start, &to), reverse));
                }
            }
        }
        out
    }

    fn space_turn(&self, a: &Pose2, b: &Pose2) -> f64 {
        smug_core::pose::angle_distance(a.yaw, b.yaw)
    }

    /// The objective's cost of the motion between two lattice poses, infinity when it
    /// is invalid (never 0: 0 marks an unknown edge).
    fn edge_cost(&mut self, from: StateId, to: StateId) -> f32 {
        if !self.state_valid(to) {
            return f32::INFINITY;
        }
        let (a, b) = (self.lattice.pose(from), self.lattice.pose(to));
        self.counts.edge_checks += 1;
        if !self.motions.is_valid_motion(&a, &b) {
            return f32::INFINITY;
        }
        (self.objective.motion_cost(&a, &b) as f32).max(f32::MIN_POSITIVE)
    }

    /// Whether a lattice pose is valid (cached).
    pub(super) fn state_valid(&mut self, id: StateId) -> bool {
        let i = id as usize;
        if self.caches.state[i] == 0 {
            self.counts.state_checks += 1;
            let valid = self.states.is_valid(&self.lattice.pose(id));
            self.caches.state[i] = if valid { 1 } else { 2 };
        }
        self.caches.state[i] == 1
    }

    /// Whether some heading is valid at a lattice point (the 2D relaxation's nodes).
    fn point_open(&mut self, ix: usize, iy: usize) -> bool {
        (0..self.lattice.headings).any(|k| {
            let id = self.lattice.id(ix, iy, k);
            self.state_valid(id)
        })
    }

    /// The obstacle-aware distances to a goal set, from the cache or computed.
    fn goal_heuristic(&mut self, goals: &[Goal]) -> Arc<Vec<f32>> {
        let key: Vec<u64> = goals
            .iter()
            .flat_map(|g| [g.pose.x.to_bits(), g.pose.y.to_bits()])
            .collect();
        if let Some(pos) = self.caches.heuristics.iter().position(|(k, _)| *k == key) {
            let hit = self.caches.heuristics.remove(pos);
            let values = hit.1.clone();
            self.caches.heuristics.push(hit);
            return values;
        }
        let (w_t, _) = self.objective.bound_weights();
        let mut seeds = Vec::new();
        for goal in goals {
            for (ix, iy) in self
                .lattice
                .points_near(goal.pose.x, goal.pose.y, self.shot_radius)
            {
                let [x, y] = self.lattice.position(ix, iy);
                seeds.push(((ix, iy), w_t * (x - goal.pose.x).hypot(y - goal.pose.y)));
            }
        }
        let weighted: Vec<(i32, i32, f64)> = self
            .displacements
            .iter()
            .map(|&(di, dj, len)| (di, dj, w_t * len))
            .collect();
        let (nx, ny) = (self.lattice.nx, self.lattice.ny);
        let values = Arc::new(heuristic::distances(nx, ny, &weighted, &seeds, |ix, iy| {
            self.point_open(ix, iy)
        }));
        if self.caches.heuristics.len() >= HEURISTICS_KEPT {
            self.caches.heuristics.remove(0);
        }
        self.caches.heuristics.push((key, values.clone()));
        values
    }
}
