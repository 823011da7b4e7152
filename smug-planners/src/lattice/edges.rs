//! What the lattice search asks of the world, cached across queries: valid lattice
//! poses, valid primitives and their costs, valid shots, the start's curves onto the
//! lattice, and the heuristic (the objective's bound and the obstacle-aware distances
//! of a goal set).

use super::heuristic;
use super::primitives::{Lattice, Layout, Primitives, StateId};
use super::search::Worker;
use super::shots::sideways_bound;
use super::Shared;
use rayon::prelude::*;
use smug_core::{Objective, Pose2};
use std::sync::Arc;

/// The objective's cost of every primitive (`k · stride + p`: primitive `p` of heading
/// `k`), as [`Worker::edge_cost`] gives it, for an objective whose costs do not depend on
/// where a motion is: computed once from the origin, not once per lattice pose.
pub(super) fn primitive_costs(
    lattice: &Lattice,
    primitives: &Primitives,
    objective: &dyn Objective,
) -> Vec<f32> {
    let mut costs = vec![0.0; lattice.headings * primitives.stride];
    for (slot, from, to) in primitives.from_origin(lattice) {
        costs[slot] = motion_cost_f32(objective, &from, &to);
    }
    costs
}

/// A motion's cost as the edge cache keeps it: an `f32`, never 0 (0 marks an unknown
/// edge).
fn motion_cost_f32(objective: &dyn Objective, a: &Pose2, b: &Pose2) -> f32 {
    (objective.motion_cost(a, b) as f32).max(f32::MIN_POSITIVE)
}

impl Worker<'_> {
    /// The objective's bound as its contract gives it without solving for a curve:
    /// `w_t·‖Δxy‖ + w_r·d(yaw)`.
    pub(super) fn cheap_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        let (w_t, w_r) = self.sh.objective.bound_weights();
        w_t * a.xy_distance(b) + w_r * smug_core::pose::angle_distance(a.yaw, b.yaw)
    }

    /// The heuristic at a lattice pose: the obstacle-aware distance and, for one goal,
    /// the objective's contract bound to it (`w_t·‖Δxy‖ + w_r·d(yaw)`), the larger.
    /// (The model's curve bound, solved per queued pose, cost a tenth more time on
    /// lunar for the same plans.)
    pub(super) fn heuristic(&self, id: u32, goals: &[Pose2], h2d: Option<&Vec<f32>>) -> f64 {
        let mut h = 0.0;
        if let Some(d) = h2d {
            h = d[id as usize / self.sh.lattice.headings] as f64;
            if h.is_infinite() {
                return h;
            }
            // f32 rounding: stay below the exact distance.
            h *= 1.0 - 1e-6;
        }
        if let [goal] = goals {
            h = h.max(self.cheap_bound(&self.sh.lattice.pose(id), goal));
        }
        h
    }

    /// [`Self::start_successors`] of `start`, kept across searches.
    pub(super) fn joins_of(&mut self, start: &Pose2) -> Arc<super::sources::Joins> {
        let sh = self.sh;
        sh.caches.joins(start, || self.start_successors(start))
    }

    /// The lattice poses the start joins with the model's curves (one gear, no loops),
    /// valid, with their costs: the poses around it with headings near its own; for a
    /// start hemmed in there (a car facing a stone, its back to another), poses of any
    /// heading in rings twice as wide each time, up to the shot radius (the distance
    /// at which goals are joined).
    pub(super) fn start_successors(&mut self, start: &Pose2) -> Vec<(u32, f64, bool)> {
        let near = 2.0 * std::f64::consts::SQRT_2 * self.sh.lattice.cell * 1.5;
        let joined = self.joins(start, near);
        if !joined.is_empty() {
            return joined;
        }
        let mut reach = near;
        while reach < self.sh.shot_radius {
            let inner = reach;
            reach = (2.0 * reach).min(self.sh.shot_radius);
            let joined = self.joins_ring(start, inner, reach);
            if !joined.is_empty() {
                return joined;
            }
        }
        Vec::new()
    }

    /// The valid one-gear curves from `start` to lattice poses between `inner` and
    /// `outer` metres from it, with every fourth heading (a start that needs them
    /// leaves by any way out, not the best one; the search does the rest), at most half
    /// a turn longer than the straight line.
    fn joins_ring(&mut self, start: &Pose2, inner: f64, outer: f64) -> Vec<(u32, f64, bool)> {
        let sh = self.sh;
        let mut out = Vec::new();
        let from = (start, start.yaw.sin_cos());
        for (ix, iy) in sh.lattice.points_near(start.x, start.y, outer) {
            let [x, y] = sh.lattice.position(ix, iy);
            let direct = (x - start.x).hypot(y - start.y);
            if direct <= inner {
                continue;
            }
            for k in (0..sh.lattice.headings).step_by(4) {
                let id = sh.lattice.id(ix, iy, k);
                if !self.state_valid(id) {
                    continue;
                }
                let to = sh.lattice.pose(id);
                let longest = direct + std::f64::consts::PI * sh.radius;
                if sideways_bound(sh.radius, from, (&to, to.yaw.sin_cos())) > longest
                    || sh.space.motion_extent(start, &to).length > longest
                {
                    continue;
                }
                out.extend(self.join(start, id, &to));
            }
        }
        out
    }

    /// The start's curve to lattice pose `id` (at `to`) when it keeps one gear, ends on
    /// a valid pose and is valid: the pose, the curve's cost and its gear.
    fn join(&mut self, start: &Pose2, id: u32, to: &Pose2) -> Option<(u32, f64, bool)> {
        let sh = self.sh;
        let layout = Layout {
            space: sh.space.as_ref(),
            radius: sh.radius,
            reverse: sh.space.has_reverse_gear(),
        };
        let reverse = sh.space.is_reversing(start, to, 0.5);
        if !layout.one_gear(start, to, reverse) || !self.state_valid(id) {
            return None;
        }
        self.me.counts.edge_checks += 1;
        sh.motions
            .is_valid_motion_between_valid(start, to)
            .then(|| (id, sh.objective.motion_cost(start, to), reverse))
    }

    /// The valid one-gear curves from `start` to lattice poses within `reach` with
    /// headings near the start's, nearly straight.
    fn joins(&mut self, start: &Pose2, reach: f64) -> Vec<(u32, f64, bool)> {
        let sh = self.sh;
        let cell = sh.lattice.cell;
        let h = sh.lattice.headings as i64;
        let k0 = sh.lattice.heading_bin(start.yaw) as i64;
        let spread =
            (reach / (sh.radius * 2.0 * std::f64::consts::PI / h as f64)).ceil() as i64 + 1;
        let mut out = Vec::new();
        let from = (start, start.yaw.sin_cos());
        for (ix, iy) in sh.lattice.points_near(start.x, start.y, reach) {
            for dk in -spread..=spread {
                let k = (k0 + dk).rem_euclid(h) as usize;
                let id = sh.lattice.id(ix, iy, k);
                let to = sh.lattice.pose(id);
                let direct = start.xy_distance(&to);
                if direct < 1e-9 && dk == 0 {
                    continue;
                }
                // Every curve is at least this long: no need to solve for one.
                let longest = 1.3 * direct + cell;
                if sideways_bound(sh.radius, from, (&to, to.yaw.sin_cos())) > longest {
                    continue;
                }
                let extent = sh.space.motion_extent(start, &to);
                let turn = smug_core::pose::angle_distance(start.yaw, to.yaw);
                if extent.length > longest || extent.turning > turn + 0.6 {
                    continue;
                }
                out.extend(self.join(start, id, &to));
            }
        }
        out
    }

    /// The objective's cost of the motion between two lattice poses (never 0: 0 marks
    /// an unknown edge).
    pub(super) fn edge_cost(&self, from: StateId, to: StateId) -> f32 {
        let (a, b) = (self.sh.lattice.pose(from), self.sh.lattice.pose(to));
        motion_cost_f32(self.sh.objective.as_ref(), &a, &b)
    }

    /// Whether primitive `prim` from lattice pose `from`, to `to`, is valid (its end
    /// state cached): through its states computed once and translated here, when the
    /// validator checks motions by their states ([`super::samples`]).
    pub(super) fn edge_valid(&mut self, from: StateId, to: StateId, prim: usize) -> bool {
        if !self.state_valid(to) {
            return false;
        }
        self.me.counts.edge_checks += 1;
        let sh = self.sh;
        let (a, b) = (sh.lattice.pose(from), sh.lattice.pose(to));
        let k = from as usize % sh.lattice.headings;
        let along = &mut self.me.along;
        match &sh.primitive_states {
            Some(states) if states.translated(k, prim, (&a, &b), along) => {
                sh.motions.states_valid_between_valid(along)
            }
            _ => sh.motions.is_valid_motion_between_valid(&a, &b),
        }
    }

    /// Whether a lattice pose is valid (cached).
    pub(super) fn state_valid(&mut self, id: StateId) -> bool {
        state_valid(self.sh, id, &mut self.me.counts.state_checks)
    }

    /// The obstacle-aware distances to a goal set, from the cache or computed.
    pub(super) fn goal_heuristic(&mut self, goals: &[Pose2]) -> Arc<Vec<f32>> {
        let key = heuristic_key(goals);
        if let Some(values) = self.sh.caches.heuristic(&key) {
            return values;
        }
        let values = match goals {
            [first, rest @ ..] if !rest.is_empty() => {
                self.keep_missing_heuristics(goals);
                // The least of each goal's distances (kept for later sets): the set's
                // own bit for bit, as `heuristic::least` says.
                let mut least = (*self.goal_heuristic(std::slice::from_ref(first))).clone();
                for goal in rest {
                    let one = self.goal_heuristic(std::slice::from_ref(goal));
                    heuristic::least(&mut least, &one);
                }
                Arc::new(least)
            }
            _ => self.distances_to(goals),
        };
        self.sh.caches.keep_heuristic(key, values.clone());
        values
    }

    /// Computes and keeps, side by side, the distances to each goal of `goals` not
    /// kept yet (the same values as one at a time: each is a pure function of the
    /// world and its goal). A mission's first search (the probe of its start, towards
    /// every PoI) asks for all of them at once.
    pub(super) fn keep_missing_heuristics(&mut self, goals: &[Pose2]) {
        let mut missing: Vec<&Pose2> = Vec::new();
        for goal in goals {
            let key = heuristic_key(std::slice::from_ref(goal));
            let new = !missing
                .iter()
                .any(|m| heuristic_key(std::slice::from_ref(*m)) == key);
            if new && self.sh.caches.heuristic(&key).is_none() {
                missing.push(goal);
            }
        }
        if missing.len() < 2 {
            return;
        }
        let sh = self.sh;
        let computed: Vec<(Vec<f32>, u64)> = missing
            .par_iter()
            .with_max_len(1)
            .map(|goal| {
                let mut checks = 0;
                let values = distances_to(sh, std::slice::from_ref(*goal), &mut checks);
                (values, checks)
            })
            .collect();
        for (goal, (values, checks)) in missing.into_iter().zip(computed) {
            self.me.counts.state_checks += checks;
            let key = heuristic_key(std::slice::from_ref(goal));
            sh.caches.keep_heuristic(key, Arc::new(values));
        }
    }

    /// The obstacle-aware distances to a goal set, computed.
    fn distances_to(&mut self, goals: &[Pose2]) -> Arc<Vec<f32>> {
        Arc::new(distances_to(
            self.sh,
            goals,
            &mut self.me.counts.state_checks,
        ))
    }
}

/// The heuristic cache's key of a goal set: the goals' poses as bits.
fn heuristic_key(goals: &[Pose2]) -> Vec<u64> {
    goals
        .iter()
        .flat_map(|g| [g.x.to_bits(), g.y.to_bits(), g.yaw.to_bits()])
        .collect()
}

/// Whether a lattice pose is valid (cached; `checks` counts the poses checked).
fn state_valid(sh: &Shared, id: StateId, checks: &mut u64) -> bool {
    if let Some(valid) = sh.caches.state(id) {
        return valid;
    }
    *checks += 1;
    let valid = sh.states.is_valid(&sh.lattice.pose(id));
    sh.caches.set_state(id, valid);
    valid
}

/// Whether some heading is valid at a lattice point (the 2D relaxation's nodes; cached).
fn point_open(sh: &Shared, ix: usize, iy: usize, checks: &mut u64) -> bool {
    let point = iy * sh.lattice.nx + ix;
    if let Some(open) = sh.caches.point(point) {
        return open;
    }
    let open = (0..sh.lattice.headings).any(|k| state_valid(sh, sh.lattice.id(ix, iy, k), checks));
    sh.caches.set_point(point, open);
    open
}

/// A lower bound of the length of every shot from the point `(x, y)`, whatever its
/// heading there, to `goal` (its heading's sine and cosine `dir`): the straight
/// distance, and for `curved` models also [`sideways_bound`] with turning radius
/// `radius`. Given the point with the goal's own heading, that bound only sees how far
/// the point lies beside the goal's heading line, which holds for every heading at the
/// point (the shot driven backwards leaves the goal along that line).
fn seed_length(
    radius: f64,
    (x, y): (f64, f64),
    goal: &Pose2,
    dir: (f64, f64),
    curved: bool,
) -> f64 {
    let straight = (x - goal.x).hypot(y - goal.y);
    if !curved {
        return straight;
    }
    let at = Pose2::new(x, y, goal.yaw);
    straight.max(sideways_bound(radius, (&at, dir), (goal, dir)))
}

/// The obstacle-aware distances to a goal set, computed (`checks` counts the lattice
/// poses checked for validity).
fn distances_to(sh: &Shared, goals: &[Pose2], checks: &mut u64) -> Vec<f32> {
    let (w_t, _) = sh.objective.bound_weights();
    // An objective that costs the model's curves by their length: a shot is at
    // least as long as `sideways_bound` says.
    let curved = sh.primitive_costs.is_some();
    let mut seeds = Vec::new();
    for goal in goals {
        let dir = goal.yaw.sin_cos();
        for (ix, iy) in sh.lattice.points_near(goal.x, goal.y, sh.shot_radius) {
            let [x, y] = sh.lattice.position(ix, iy);
            let length = seed_length(sh.radius, (x, y), goal, dir, curved);
            seeds.push(((ix, iy), w_t * length));
        }
    }
    let weighted: Vec<(i32, i32, f64)> = sh
        .displacements
        .iter()
        .map(|&(di, dj, len)| (di, dj, w_t * len))
        .collect();
    let (nx, ny) = (sh.lattice.nx, sh.lattice.ny);
    heuristic::distances(nx, ny, &weighted, &seeds, |ix, iy| {
        point_open(sh, ix, iy, checks)
    })
}
