//! The lattice search: A* from a start to a set of goals over lattice poses, the
//! start joined to the lattice by the model's curves, goals reached by lazily checked
//! analytic shots, caches of state and primitive validity kept across queries.

use super::LatticePlanner;
use smug_core::{Budget, NoPathReason, Path, PlannerOutcome, Pose2, Proof};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::Arc;
use std::time::Instant;

/// The start's node id (lattice poses are `0..len`).
pub(super) const START: u32 = u32::MAX;

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
    /// A lattice pose (or the start) reached from `parent` at cost `g` by primitive
    /// `prim` of the parent's heading, whose validity is checked when popped unless
    /// `verified`.
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
    // A min-heap on the key (ties as the heap leaves them: the same pushes and pops
    // give the same order, so runs are reproducible).
    fn cmp(&self, other: &Self) -> Ordering {
        other.key.total_cmp(&self.key)
    }
}

/// One goal of a search.
pub(super) struct Goal {
    /// Where it is.
    pub(super) pose: Pose2,
    /// Settled: the search's cost and the lattice pose (or start) its shot leaves from.
    pub(super) reached: Option<(f64, u32)>,
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
    goals: Vec<Goal>,
    open_goals: usize,
    h2d: Option<Arc<Vec<f32>>>,
}

impl Run {
    fn push(&mut self, key: f64, item: Item) {
        self.heap.push(Entry { key, item });
    }
}

impl LatticePlanner {
    /// Plans from `start` to every goal with one search of at most `max_expansions`
    /// expansions (0: as many as the lattice has).
    pub(super) fn search(
        &mut self,
        start: &Pose2,
        goals: &[Pose2],
        max_expansions: u64,
    ) -> Vec<PlannerOutcome> {
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
            let (reached, end) = self.run(start, asked, max_expansions);
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
    fn run(&mut self, start: &Pose2, goals: Vec<Goal>, max_expansions: u64) -> (Vec<Goal>, End) {
        self.buffers.next_generation();
        let open_goals = goals.len();
        let mut run = Run {
            heap: BinaryHeap::new(),
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
        let max = match max_expansions {
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
                if self.deadline.passed() {
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
                    if !verified && !self.verify(id, parent, prim) {
                        continue;
                    }
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

    /// Checks the primitive that reached `id` from `parent` (validity cached; its cost
    /// was known when it was queued): false when it is invalid or `id` is closed.
    fn verify(&mut self, id: u32, parent: u32, prim: u16) -> bool {
        let b = &self.buffers;
        if b.closed[id as usize] == b.generation {
            return false;
        }
        let slot = parent as usize * self.primitives.stride + prim as usize;
        let cached = self.caches.edge[slot];
        if cached < 0.0 {
            let valid = self.edge_valid(parent, id);
            self.caches.edge[slot] = if valid { -cached } else { f32::INFINITY };
        }
        self.caches.edge[slot].is_finite()
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
        for j in 0..run.goals.len() {
            let goal = &run.goals[j];
            if goal.reached.is_none() && pose.xy_distance(&goal.pose) <= self.shot_radius {
                let bound = self.cheap_bound(&pose, &goal.pose);
                if bound.is_finite() {
                    let item = Item::Shot {
                        from: id,
                        goal: j as u32,
                        costed: false,
                    };
                    run.push(g + bound, item);
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
            let slot = id as usize * stride + p;
            let mut cached = self.caches.edge[slot];
            if cached.is_infinite() {
                continue;
            }
            if cached == 0.0 {
                cached = -self.edge_cost(id, to);
                self.caches.edge[slot] = cached;
            }
            // Negative: the cost is known, the validity not yet (checked when popped).
            let (cost, verified) = (cached.abs() as f64, cached > 0.0);
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
            g + self.params.heuristic_weight * h,
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
}
