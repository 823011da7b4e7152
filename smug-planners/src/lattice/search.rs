//! The lattice search: A* from a start to a set of goals over lattice poses, the
//! start joined to the lattice by the model's curves, goals reached by lazily checked
//! analytic shots, caches of state and primitive validity kept across queries.

use super::buffers::{Node, Searcher};
use super::caches::{holds, ShotTable};
use super::queue::{BucketQueue, Entry, Item};
use super::sources::{is_source, source_id, source_of, Source};
use super::Shared;
use smug_core::{Budget, NoPathReason, Path, PlannerOutcome, Pose2, Proof};
use std::sync::atomic::{AtomicBool, Ordering::Relaxed};
use std::sync::Arc;
use std::time::Instant;

/// How wide the queue's buckets are, in lattice cells (of path cost at `w_t` = 1).
const QUEUE_BUCKET_CELLS: f64 = 1.0 / 32.0;

/// How many pops ahead the search fetches the data of the entry that pops then (the
/// pose's search data and primitives): enough for the fetch to land in time.
const FETCH_AHEAD: usize = 6;

/// One goal of a search.
pub(super) struct Goal {
    /// Where it is.
    pub(super) pose: Pose2,
    /// The sine and cosine of its heading.
    pub(super) dir: (f64, f64),
    /// Settled: the search's cost (its source's offset included) and the lattice pose
    /// (or source) its shot leaves from.
    pub(super) reached: Option<(f64, u32)>,
    /// Proved unreachable before the search (by an earlier search's exhaustion): the
    /// search does not wait for it.
    pub(super) proved_out: bool,
    /// The shots to it known so far (shared with every search to it).
    pub(super) shots: Arc<ShotTable>,
}

/// How a search ended.
pub(super) enum End {
    AllReached,
    Exhausted,
    Budget(Budget),
}

/// When a search that has not run out of poses or budget ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Until {
    /// Once every goal is settled or proved unreachable.
    EveryGoal,
    /// Once some goal is settled (a probe: one way out proves nothing is boxed in).
    FirstGoal,
}

/// A search in progress.
pub(super) struct Run {
    pub(super) heap: BucketQueue,
    pub(super) goals: Vec<Goal>,
    /// Goals neither settled nor proved unreachable.
    pub(super) open_goals: usize,
    pub(super) h2d: Option<Arc<Vec<f32>>>,
    /// The goals the heuristic aims at: those not settled when it was last focused.
    pub(super) aimed: Vec<Pose2>,
    /// The sources (one for a plain search from a start).
    pub(super) sources: Vec<Source>,
    /// How many times the heuristic was re-aimed (the focus of the keys computed now).
    pub(super) focus: u32,
    /// Lattice poses a kept proof shows no goal left can be reached from (a bitmap):
    /// never queued, as no path to those goals passes through them.
    pub(super) pruned: Option<Arc<Vec<u64>>>,
    /// The lattice poses closed so far, in order (what an exhausted search's proof
    /// holds: listed, not found by a scan of the whole lattice).
    pub(super) closed: Vec<u32>,
}

impl Run {
    /// The poses of the goals the search waits for: neither settled nor proved
    /// unreachable before it.
    pub(super) fn awaited(&self) -> Vec<Pose2> {
        self.goals
            .iter()
            .filter(|g| g.reached.is_none() && !g.proved_out)
            .map(|g| g.pose)
            .collect()
    }

    fn push(&mut self, key: f64, item: Item) {
        self.heap.push(Entry { key, item });
    }
}

/// A search's view: the planner's shared, read-only data and caches, and this
/// thread's buffers and counters.
pub(super) struct Worker<'a> {
    pub(super) sh: &'a Shared,
    pub(super) me: &'a mut Searcher,
    /// The heuristic's weight in this worker's searches (`heuristic_weight`, or
    /// `order_heuristic_weight` for the rows of a matrix that only orders targets).
    pub(super) weight: f64,
    /// Set when this worker's search is no longer wanted (a search run ahead to warm
    /// the caches, once the search it ran beside has ended): it stops as at a budget.
    pub(super) stop: Option<&'a AtomicBool>,
}

/// A search's answers: one outcome per goal, and the search's cost of each path
/// before shortcutting.
pub(super) struct Answers {
    pub(super) outcomes: Vec<PlannerOutcome>,
    pub(super) costs: Vec<Option<f64>>,
}

impl Worker<'_> {
    /// Plans from `start` to every goal with one search of at most `max_expansions`
    /// expansions (0: as many as the lattice has).
    pub(super) fn search(
        &mut self,
        start: &Pose2,
        goals: &[Pose2],
        max_expansions: u64,
    ) -> Answers {
        let started = Instant::now();
        self.me.counts.searches += 1;
        let mut costs = vec![None; goals.len()];
        if !self.sh.states.is_valid(start) {
            return Answers {
                outcomes: vec![PlannerOutcome::InvalidStart; goals.len()],
                costs,
            };
        }
        let mut outcomes: Vec<Option<PlannerOutcome>> = vec![None; goals.len()];
        let (asked, index) = self.asked_goals(start, goals, |k, at_start| {
            outcomes[k] = Some(if at_start {
                costs[k] = Some(0.0);
                PlannerOutcome::Exact(Path {
                    states: vec![*start],
                    cost: 0.0,
                })
            } else {
                PlannerOutcome::InvalidGoal
            });
        });
        if !asked.is_empty() {
            let (reached, end) =
                self.run(&[(*start, 0.0)], asked, max_expansions, Until::EveryGoal);
            for (goal, k) in reached.into_iter().zip(index) {
                costs[k] = goal.reached.map(|(cost, _)| cost);
                outcomes[k] = Some(self.outcome(&[*start], &goal, &end).1);
            }
        }
        self.me.counts.breakdown.astar_s += started.elapsed().as_secs_f64();
        Answers {
            outcomes: outcomes
                .into_iter()
                .map(|o| o.expect("every goal answered"))
                .collect(),
            costs,
        }
    }

    /// The goals to search for, with their indices in `goals`; the others are passed
    /// to `answered` with whether they are the start itself (else they are invalid).
    pub(super) fn asked_goals(
        &self,
        start: &Pose2,
        goals: &[Pose2],
        mut answered: impl FnMut(usize, bool),
    ) -> (Vec<Goal>, Vec<usize>) {
        let mut asked = Vec::new();
        let mut index = Vec::new();
        for (k, goal) in goals.iter().enumerate() {
            if !self.sh.states.is_valid(goal) {
                answered(k, false);
            } else if goal.xy_distance(start) < 1e-12 && goal.yaw == start.yaw {
                answered(k, true);
            } else {
                index.push(k);
                asked.push(self.goal(goal));
            }
        }
        (asked, index)
    }

    /// The outcome for one goal once the search from `sources` ended, with the source
    /// its path leaves from (0 when it has none).
    pub(super) fn outcome(
        &self,
        sources: &[Pose2],
        goal: &Goal,
        end: &End,
    ) -> (usize, PlannerOutcome) {
        let Some((_, from)) = goal.reached else {
            let reason = match end {
                End::Budget(b) => NoPathReason::BudgetSpent(*b),
                _ => NoPathReason::Proved(Proof::Exhausted),
            };
            return (0, PlannerOutcome::NoPath(reason));
        };
        let mut states = vec![goal.pose];
        let mut at = from;
        while !is_source(at) {
            states.push(self.sh.lattice.pose(at));
            at = self.me.buffers.nodes[at as usize].parent;
        }
        let source = source_of(at).expect("a path leaves from a source");
        states.push(sources[source]);
        states.reverse();
        (source, self.finished(states))
    }

    /// The outcome of a lattice path's states: shortcut or smoothed as configured (the
    /// cost never rises).
    fn finished(&self, states: Vec<Pose2>) -> PlannerOutcome {
        let path = Path::new(states, self.sh.objective.as_ref());
        let (sh, params) = (self.sh, &self.sh.params);
        if !(params.shortcut || params.smooth) || path.states.len() <= 2 {
            return PlannerOutcome::Exact(path);
        }
        let motions = sh.motions.as_ref();
        let shorter = if params.smooth {
            crate::shortcut::smooth(
                &path.states,
                motions,
                sh.space.as_ref(),
                sh.objective.as_ref(),
            )
        } else {
            crate::shortcut::shortcut_galloping(&path.states, motions)
        };
        let shorter = Path::new(shorter, sh.objective.as_ref());
        PlannerOutcome::Exact(if shorter.cost < path.cost {
            shorter
        } else {
            path
        })
    }

    /// The A* loop from `sources` (each with the cost already paid there): settles the
    /// goals it reaches, ends when all are, when nothing is left to expand, or when a
    /// budget runs out.
    pub(super) fn run(
        &mut self,
        sources: &[(Pose2, f64)],
        goals: Vec<Goal>,
        max_expansions: u64,
        until: Until,
    ) -> (Vec<Goal>, End) {
        self.me.buffers.next_generation();
        let open_goals = goals.len();
        let sources = sources
            .iter()
            .map(|&(pose, offset)| Source {
                pose,
                offset,
                joins: self.joins_of(&pose),
            })
            .collect();
        let mut run = Run {
            heap: BucketQueue::new(self.sh.lattice.cell * QUEUE_BUCKET_CELLS),
            goals,
            open_goals,
            h2d: None,
            aimed: Vec::new(),
            sources,
            focus: 0,
            pruned: None,
            closed: Vec::new(),
        };
        self.apply_kept_proofs(&mut run);
        if run.open_goals == 0 {
            return (run.goals, End::AllReached);
        }
        run.pruned = self.proof_bound(&run);
        self.aim(&mut run);
        for s in 0..run.sources.len() {
            let (id, offset) = (source_id(s), run.sources[s].offset);
            let item = Item::Node {
                id,
                parent: id,
                g: offset,
                prim: 0,
                reverse: false,
                verified: true,
                focus: 0,
            };
            run.push(offset, item);
        }
        let started = Instant::now();
        let max = match max_expansions {
            0 => u64::MAX,
            m => m,
        };
        let mut expansions = 0u64;
        while let Some(entry) = run.heap.pop() {
            self.fetch_ahead(&run.heap);
            if expansions >= max {
                return (run.goals, End::Budget(Budget::Expansions));
            }
            if expansions.is_multiple_of(256) {
                if started.elapsed().as_secs_f64() > self.sh.params.time_limit {
                    return (run.goals, End::Budget(Budget::Time));
                }
                if self.sh.deadline.passed() || self.stopped() {
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
                    focus,
                } => {
                    if focus != run.focus && self.rekeyed(&mut run, entry) {
                        continue;
                    }
                    if !verified && !self.verify(id, parent, prim) {
                        continue;
                    }
                    if self.close(id, parent, g, reverse) {
                        if !is_source(id) {
                            run.closed.push(id);
                        }
                        expansions += 1;
                        self.me.counts.expansions += 1;
                        self.expand(id, g, &mut run);
                    }
                }
                Item::Shot { from, goal, costed } => {
                    let open = run.open_goals;
                    self.try_shot(from, goal as usize, costed, entry.key, &mut run);
                    let first = until == Until::FirstGoal && run.open_goals < open;
                    if run.open_goals == 0 || first {
                        return (run.goals, End::AllReached);
                    }
                }
            }
        }
        self.keep_proof(&run);
        (run.goals, End::Exhausted)
    }

    /// Whether this worker was told to stop.
    fn stopped(&self) -> bool {
        self.stop.is_some_and(|stop| stop.load(Relaxed))
    }

    /// Fetches the data of the node entry that pops [`FETCH_AHEAD`] pops from now (its
    /// search data, its primitives, and the motion that reached it when unchecked).
    fn fetch_ahead(&self, heap: &BucketQueue) {
        let Some(Entry {
            item:
                Item::Node {
                    id,
                    parent,
                    prim,
                    verified,
                    ..
                },
            ..
        }) = heap.ahead(FETCH_AHEAD)
        else {
            return;
        };
        if is_source(*id) {
            return;
        }
        let stride = self.sh.primitives.stride;
        super::buffers::prefetch(&self.me.buffers.nodes[*id as usize]);
        self.sh.caches.prefetch_edge(*id as usize * stride);
        if !verified && !is_source(*parent) {
            self.sh
                .caches
                .prefetch_edge(*parent as usize * stride + *prim as usize);
        }
    }

    /// Closes a popped node (its cost and parent final); false when it was already
    /// closed, or a cheaper way to it is known.
    fn close(&mut self, id: u32, parent: u32, g: f64, reverse: bool) -> bool {
        if is_source(id) {
            return true; // queued once
        }
        let b = &mut self.me.buffers;
        let i = id as usize;
        if b.is_closed(i) || b.known_g(i).is_some_and(|known| g > known) {
            return false;
        }
        let generation = b.generation;
        b.nodes[i] = Node {
            g,
            parent,
            prim: 0,
            stamp: generation,
            closed: generation,
            gear: reverse as u8,
        };
        true
    }

    /// Checks the primitive that reached `id` from `parent` (validity cached; its cost
    /// was known when it was queued): false when it is invalid or `id` is closed.
    fn verify(&mut self, id: u32, parent: u32, prim: u16) -> bool {
        if self.me.buffers.is_closed(id as usize) {
            return false;
        }
        let slot = parent as usize * self.sh.primitives.stride + prim as usize;
        let mut cached = self.sh.caches.edge(slot);
        if cached < 0.0 {
            let valid = self.edge_valid(parent, id, prim as usize);
            cached = if valid { -cached } else { f32::INFINITY };
            self.sh.caches.set_edge(slot, cached);
        }
        cached.is_finite()
    }

    /// The search's cost of a motion of objective cost `cost` from `parent`: reverse
    /// penalty and gear change cost added.
    fn step_cost(&self, parent: u32, cost: f64, reverse: bool) -> f64 {
        let mut step = cost;
        if reverse {
            step *= self.sh.params.reverse_penalty;
        }
        if !is_source(parent) && self.me.buffers.nodes[parent as usize].gear != reverse as u8 {
            step += self.sh.params.gear_change_cost;
        }
        step
    }

    /// The pose of a node of `run`: a source's or a lattice pose.
    fn pose_of(&self, run: &Run, id: u32) -> Pose2 {
        match source_of(id) {
            Some(s) => run.sources[s].pose,
            None => self.sh.lattice.pose(id),
        }
    }

    /// Pushes the shots from `id` to the goals near it (from a source: to every goal,
    /// however far, as Hybrid A*'s analytic expansion: the model's own curve is often
    /// the way) and relaxes its successors.
    fn expand(&mut self, id: u32, g: f64, run: &mut Run) {
        let pose = self.pose_of(run, id);
        let mut dir = None;
        for j in 0..run.goals.len() {
            let goal = &run.goals[j];
            let near = is_source(id) || pose.xy_distance(&goal.pose) <= self.sh.shot_radius;
            if goal.reached.is_none() && near {
                let dir = *dir.get_or_insert_with(|| pose.yaw.sin_cos());
                let bound = self.shot_bound((&pose, dir), (&goal.pose, goal.dir));
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
        if let Some(s) = source_of(id) {
            let joins = std::mem::take(&mut run.sources[s].joins);
            for &(to, cost, reverse) in joins.iter() {
                let ng = g + self.step_cost(id, cost, reverse);
                self.queue(run, to, id, ng, 0, reverse, true);
            }
            return;
        }
        let sh = self.sh;
        let (ix, iy, k) = sh.lattice.decode(id);
        let stride = sh.primitives.stride;
        // The successors' search data first, fetched side by side.
        for prim in &sh.primitives.by_heading[k] {
            if let Some((jx, jy)) = sh.lattice.offset(ix, iy, prim.di, prim.dj) {
                let to = sh.lattice.id(jx, jy, prim.to_heading);
                super::buffers::prefetch(&self.me.buffers.nodes[to as usize]);
            }
        }
        for (p, prim) in sh.primitives.by_heading[k].iter().enumerate() {
            let Some((jx, jy)) = sh.lattice.offset(ix, iy, prim.di, prim.dj) else {
                continue;
            };
            let to = sh.lattice.id(jx, jy, prim.to_heading);
            let slot = id as usize * stride + p;
            let mut cached = sh.caches.edge(slot);
            if cached.is_infinite() {
                continue;
            }
            if cached == 0.0 {
                let cost = match &sh.primitive_costs {
                    Some(costs) => costs[k * stride + p],
                    None => self.edge_cost(id, to),
                };
                cached = sh.caches.set_edge_cost(slot, -cost);
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
        let b = &self.me.buffers;
        let i = to as usize;
        if b.is_closed(i) || b.beaten(i, g, parent, prim, reverse) {
            return;
        }
        if run.pruned.as_ref().is_some_and(|p| holds(p, to)) {
            return;
        }
        let h = self.heuristic(to, &run.aimed, run.h2d.as_deref());
        if h.is_infinite() {
            return; // no goal reachable from there
        }
        if verified {
            let b = &mut self.me.buffers;
            let node = &mut b.nodes[i];
            node.stamp = b.generation;
            node.g = g;
            node.parent = parent;
            node.prim = prim;
            node.gear = reverse as u8;
        }
        run.push(
            g + self.weight * h,
            Item::Node {
                id: to,
                parent,
                g,
                prim,
                reverse,
                verified,
                focus: run.focus,
            },
        );
    }

    /// Costs a shot when first popped (pushed again at its cost), checks it when popped
    /// at its cost; a valid shot settles its goal.
    fn try_shot(&mut self, from: u32, goal: usize, costed: bool, key: f64, run: &mut Run) {
        if run.goals[goal].reached.is_some() {
            return;
        }
        let pose = self.pose_of(run, from);
        let target = run.goals[goal].pose;
        let g = match source_of(from) {
            Some(s) => run.sources[s].offset,
            None => self.me.buffers.nodes[from as usize].g,
        };
        if !costed {
            let cost = self.shot_cost_below(from, &pose, &target, &run.goals[goal].shots);
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
        if self.shot_valid(from, &pose, &target, &run.goals[goal].shots) {
            let cost = g + self.sh.objective.motion_cost(&pose, &target);
            run.goals[goal].reached = Some((cost, from));
            if !run.goals[goal].proved_out {
                run.open_goals -= 1;
            }
            if run.open_goals > 0 && self.worth_refocusing(run) {
                self.refocus(run);
            }
        }
    }
}
