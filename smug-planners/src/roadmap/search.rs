//! Searches on the roadmap: A* with a cached heuristic, its incremental repair, Lazy
//! Weighted A*, and Dijkstra distances (for tests and diagnostics).

mod many;

use super::{Roadmap, Validity};
use crate::nn::{from_total_order_key, total_order_key};
use smug_core::{Objective, Pose2};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A path found by A*: vertices and the edges between them.
#[derive(Clone, Debug, PartialEq)]
pub struct GraphPath {
    /// Vertices from start to goal.
    pub vertices: Vec<u32>,
    /// Edge ids, `vertices.len() − 1` of them.
    pub edges: Vec<u32>,
    /// Sum of the edge costs.
    pub cost: f64,
}

/// The open-list order: smallest `f` first, then larger `g` (deeper), then smaller id.
/// A strict total order, so every correct priority queue pops the same sequence.
fn open_order((f, g, v): (f64, f64, u32), (of, og, ov): (f64, f64, u32)) -> Ordering {
    of.total_cmp(&f).then(g.total_cmp(&og)).then(ov.cmp(&v))
}

/// An open-list entry of the lazy search and of Dijkstra: a vertex, its cost so far
/// and estimate, and the parent edge it is reached through.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Open {
    f: f64,
    g: f64,
    v: u32,
    parent: (u32, u32),
}

/// No parent (the search's start).
const NO_PARENT: (u32, u32) = (u32::MAX, u32::MAX);

/// Checks roadmap elements for the lazy search (and records what it finds).
pub trait Evaluator {
    /// Checks vertex `v` if unknown; true when valid (invalid ones are removed).
    fn vertex(&mut self, map: &mut Roadmap, v: u32) -> bool;
    /// Checks edge `e` if unknown; true when valid (invalid ones are removed).
    fn edge(&mut self, map: &mut Roadmap, e: u32) -> bool;
}

impl Eq for Open {}

impl Ord for Open {
    fn cmp(&self, other: &Self) -> Ordering {
        open_order((self.f, self.g, self.v), (other.f, other.g, other.v))
    }
}

impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// An open-list entry of the optimistic search (its parent is in the vertex record):
/// 24 bytes, `f` and `g` stored as integers ordered like `f64::total_cmp` so that the
/// heap compares integers (the order is [`open_order`]'s).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Candidate {
    f_key: u64,
    g_key: u64,
    v: u32,
}

impl Candidate {
    fn new(f: f64, g: f64, v: u32) -> Self {
        Self {
            f_key: total_order_key(f),
            g_key: total_order_key(g),
            v,
        }
    }

    /// The cost so far.
    fn g(&self) -> f64 {
        from_total_order_key(self.g_key)
    }
}

impl Ord for Candidate {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .f_key
            .cmp(&self.f_key)
            .then(self.g_key.cmp(&other.g_key))
            .then(other.v.cmp(&self.v))
    }
}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// What a search knows about one vertex, packed into 32 aligned bytes so that relaxing
/// an edge touches one cache line (the roadmap's vertices are visited in random order).
#[derive(Clone, Copy, Debug)]
#[repr(align(32))]
struct VertexRecord {
    /// Cost so far. The lazy search keeps here the best cost through a checked-valid
    /// edge while the vertex is open, then its cost once closed.
    g: f64,
    /// The heuristic, valid when `h_stamp` equals [`AStar`]'s current heuristic stamp.
    h: f64,
    /// The vertex and edge it is reached through.
    parent: (u32, u32),
    /// [`Marks::open`] of the search that opened it, or [`Marks::closed`] once closed.
    mark: u32,
    /// The heuristic stamp `h` was computed for.
    h_stamp: u32,
}

impl Default for VertexRecord {
    fn default() -> Self {
        Self {
            g: f64::INFINITY,
            h: 0.0,
            parent: NO_PARENT,
            mark: 0,
            h_stamp: 0,
        }
    }
}

/// The record marks of the current search (stamps instead of clearing the records).
#[derive(Clone, Copy, Debug)]
struct Marks {
    /// Seen (opened) in this search.
    open: u32,
    /// Expanded (closed) in this search.
    closed: u32,
}

/// What the cached heuristic values depend on: the roadmap, the goal and the
/// objective (by address and bound weights).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct HeuristicKey {
    roadmap: u64,
    goal: u32,
    objective_address: usize,
    objective_weights: (u64, u64),
}

impl HeuristicKey {
    fn new(map: &Roadmap, goal: u32, objective: &dyn Objective) -> Self {
        let (w_t, w_r) = objective.bound_weights();
        Self {
            roadmap: map.id,
            goal,
            objective_address: objective as *const dyn Objective as *const () as usize,
            objective_weights: (w_t.to_bits(), w_r.to_bits()),
        }
    }
}

/// A* with buffers reused across searches (generation stamps instead of clearing).
///
/// The heuristic `objective.cost_bound(v, goal)` of each vertex is computed once and kept while the
/// searches go to the same goal on the same roadmap with the same objective (LazyPRM*
/// searches each query's roadmap many times); vertex poses never change, so the cached
/// values are exactly the ones recomputing would give.
#[derive(Default)]
pub struct AStar {
    records: Vec<VertexRecord>,
    generation: u32,
    heuristic_key: Option<HeuristicKey>,
    h_stamp: u32,
    heap: BinaryHeap<Candidate>,
    lazy_heap: BinaryHeap<Open>,
    many_heap: BinaryHeap<many::Reached>,
    /// What the latest optimistic search (and the repairs since) left in the records.
    settled: Option<Settled>,
    /// Vertices expanded over all searches.
    pub expansions: u64,
}

/// What [`AStar::repair`] found.
#[derive(Clone, Debug, PartialEq)]
pub enum Repair {
    /// The cheapest path, cheaper than the one known.
    Cheaper(GraphPath),
    /// No path is cheaper than the one known.
    NoCheaper,
    /// The records are not a search for this query on this roadmap: search instead.
    NoBase,
}

/// The distances a finished [`AStar::search`] from `start` to `goal` leaves behind,
/// kept exact by [`AStar::repair`]: every vertex `v` with `d(v) + h(v) < cost` is
/// marked `closed` and its record holds `d(v)`, its shortest distance from `start`
/// (other `closed` records hold the cost of a real path to them). Valid while the
/// roadmap only grows (no removal since).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Settled {
    closed: u32,
    roadmap: u64,
    removals: u64,
    start: u32,
    goal: u32,
    cost: f64,
}

impl AStar {
    /// The base [`AStar::repair`] would start from for a query from `start` to `goal`
    /// on `map`: the latest optimistic search's (and repairs'), if it was between the
    /// same vertices and nothing was removed since.
    fn settled_for(&self, map: &Roadmap, start: u32, goal: u32) -> Option<Settled> {
        self.settled.filter(|b| {
            (b.roadmap, b.removals, b.start, b.goal) == (map.id, map.removals, start, goal)
        })
    }

    /// The cost of the cheapest path from `start` to `goal` that the latest search
    /// (with the repairs since) found, when it is still exact for `map`.
    #[cfg(test)]
    fn settled_path_cost(&self, map: &Roadmap, start: u32, goal: u32) -> Option<f64> {
        self.settled_for(map, start, goal).map(|b| b.cost)
    }

    /// The cheapest path from `start` to `goal` over the live edges, with the objective's bound
    /// as (admissible, consistent) heuristic; `None` when disconnected or when every
    /// path costs more than `bound` (`f64::INFINITY`: no bound). Vertices whose
    /// estimate exceeds `bound` are never opened, so a bound from a known path (the
    /// cheapest path costs at most that) saves work without changing the result.
    pub fn search(
        &mut self,
        map: &Roadmap,
        start: u32,
        goal: u32,
        objective: &dyn Objective,
        bound: f64,
    ) -> Option<GraphPath> {
        let marks = self.prepare(map, goal, objective);
        self.settled = None;
        let goal_pose = *map.pose(goal);
        let f_start = self.heuristic(map, start, &goal_pose, objective);
        let record = &mut self.records[start as usize];
        (record.mark, record.g, record.parent) = (marks.open, 0.0, NO_PARENT);
        self.heap.push(Candidate::new(f_start, 0.0, start));
        while let Some(candidate) = self.heap.pop() {
            let (g, v) = (candidate.g(), candidate.v);
            let record = &mut self.records[v as usize];
            if record.mark == marks.closed || g > record.g {
                continue;
            }
            record.mark = marks.closed;
            if v == goal {
                self.settled = Some(Settled {
                    closed: marks.closed,
                    roadmap: map.id,
                    removals: map.removals,
                    start,
                    goal,
                    cost: g,
                });
                return Some(self.trace(start, goal));
            }
            self.expansions += 1;
            self.relax_neighbours(map, v, g, &goal_pose, objective, marks, bound);
        }
        None
    }

    /// After [`AStar::search`] from `start` to `goal` found the cheapest path, with
    /// vertices only added since (ids from `fresh_from` on): the cheapest path that
    /// costs less, found by propagating from the new vertices only the distances they
    /// improve (incremental A*: it searches the improvement, not the whole ellipse
    /// again), or [`Repair::NoCheaper`]. The distances stay exact for the next repair.
    /// [`Repair::NoBase`] when the records cannot serve (another query, a removal
    /// since, a Lazy Weighted A* search since): search instead.
    pub fn repair(
        &mut self,
        map: &Roadmap,
        start: u32,
        goal: u32,
        fresh_from: u32,
        objective: &dyn Objective,
    ) -> Repair {
        // The repair relaxes edges into fresh vertices with the costs stored from
        // their side: only right when costs are the same both ways.
        if map.asymmetric_costs || self.settled_for(map, start, goal).is_none() {
            return Repair::NoBase;
        }
        let open = self.prepare(map, goal, objective).open;
        // `prepare` forgets the base when the marks wrap around.
        let Some(base) = self.settled_for(map, start, goal) else {
            return Repair::NoBase;
        };
        let marks = Marks {
            open,
            closed: base.closed,
        };
        let goal_pose = *map.pose(goal);
        for u in fresh_from..map.vertex_count() as u32 {
            if map.vertex_validity(u) == Validity::Invalid {
                continue;
            }
            for (a, e, cost) in map.neighbours_with_costs(u) {
                let settled = self.records[a as usize];
                if a < fresh_from && settled.mark == marks.closed {
                    self.improve(
                        map,
                        (a, settled.g),
                        (u, e, cost),
                        &goal_pose,
                        objective,
                        marks,
                        base.cost,
                    );
                }
            }
        }
        while let Some(candidate) = self.heap.pop() {
            let (g, v) = (candidate.g(), candidate.v);
            let record = &mut self.records[v as usize];
            if record.mark != marks.open || g > record.g {
                continue;
            }
            record.mark = marks.closed;
            if v == goal {
                self.settled = Some(Settled { cost: g, ..base });
                return Repair::Cheaper(self.trace(start, goal));
            }
            self.expansions += 1;
            for (w, e, cost) in map.neighbours_with_costs(v) {
                self.improve(
                    map,
                    (v, g),
                    (w, e, cost),
                    &goal_pose,
                    objective,
                    marks,
                    base.cost,
                );
            }
        }
        Repair::NoCheaper
    }

    /// Repair's relaxation: lowers the distance of `w` (reached from `v` at distance
    /// `g` over edge `e`) when that is cheaper than what its record holds (exact for
    /// settled vertices, nothing for the others) and could lead to a path cheaper
    /// than `bound`; then (re)opens it.
    #[allow(clippy::too_many_arguments)]
    fn improve(
        &mut self,
        map: &Roadmap,
        (v, g): (u32, f64),
        (w, e, cost): (u32, u32, f64),
        goal_pose: &Pose2,
        objective: &dyn Objective,
        marks: Marks,
        bound: f64,
    ) {
        let record = &mut self.records[w as usize];
        let known = record.mark == marks.open || record.mark == marks.closed;
        let candidate = g + cost;
        if known && candidate >= record.g {
            return;
        }
        let h = cached_heuristic(record, self.h_stamp, || {
            objective.cost_bound(map.pose(w), goal_pose)
        });
        if candidate + h >= bound {
            return;
        }
        (record.mark, record.g, record.parent) = (marks.open, candidate, (v, e));
        self.heap.push(Candidate::new(candidate + h, candidate, w));
    }

    /// Opens (or reopens, cheaper) every neighbour of `v`, reached at cost `g`, that is
    /// not closed and whose estimate is within `bound`, and pushes it on the open list.
    #[allow(clippy::too_many_arguments)]
    fn relax_neighbours(
        &mut self,
        map: &Roadmap,
        v: u32,
        g: f64,
        goal_pose: &Pose2,
        objective: &dyn Objective,
        marks: Marks,
        bound: f64,
    ) {
        for (w, e, cost) in map.neighbours_with_costs(v) {
            let record = &mut self.records[w as usize];
            if record.mark == marks.closed {
                continue;
            }
            let candidate = g + cost;
            if record.mark != marks.open || candidate < record.g {
                let h = cached_heuristic(record, self.h_stamp, || {
                    objective.cost_bound(map.pose(w), goal_pose)
                });
                if candidate + h > bound {
                    continue;
                }
                (record.mark, record.g, record.parent) = (marks.open, candidate, (v, e));
                self.heap.push(Candidate::new(candidate + h, candidate, w));
            }
        }
    }

    /// Lazy Weighted A* (Cohen, Phillips & Likhachev 2014): one search that checks an
    /// element only when the vertex it leads to is about to be expanded. Returns the
    /// cheapest valid path over the live edges (every element on it checked), or `None`
    /// (also when every valid path costs more than `bound`, as in [`AStar::search`]).
    pub fn search_lazy(
        &mut self,
        map: &mut Roadmap,
        start: u32,
        goal: u32,
        objective: &dyn Objective,
        evaluator: &mut dyn Evaluator,
        bound: f64,
    ) -> Option<GraphPath> {
        let marks = self.prepare(map, goal, objective);
        self.settled = None;
        let goal_pose = *map.pose(goal);
        let mut open = std::mem::take(&mut self.lazy_heap);
        open.clear();
        let h0 = self.heuristic(map, start, &goal_pose, objective);
        open.push(Open {
            f: h0,
            g: 0.0,
            v: start,
            parent: NO_PARENT,
        });
        let mut found = None;
        while let Some(Open { g, v, parent, .. }) = open.pop() {
            if self.records[v as usize].mark == marks.closed {
                continue;
            }
            let (_, e) = parent;
            let reachable = (e == u32::MAX
                || map.edge(e).validity != Validity::Invalid && evaluator.edge(map, e))
                && evaluator.vertex(map, v);
            if !reachable {
                continue;
            }
            let record = &mut self.records[v as usize];
            (record.mark, record.g, record.parent) = (marks.closed, g, parent);
            if v == goal {
                found = Some(self.trace(start, goal));
                break;
            }
            self.expansions += 1;
            self.push_lazy_successors(&mut open, map, v, g, &goal_pose, objective, marks, bound);
        }
        self.lazy_heap = open;
        found
    }

    /// Pushes every neighbour of `v` (reached at cost `g`) that is not closed, not
    /// already reached as cheaply through a checked-valid edge, and estimated within
    /// `bound`.
    #[allow(clippy::too_many_arguments)]
    fn push_lazy_successors(
        &mut self,
        open: &mut BinaryHeap<Open>,
        map: &Roadmap,
        v: u32,
        g: f64,
        goal_pose: &Pose2,
        objective: &dyn Objective,
        marks: Marks,
        bound: f64,
    ) {
        for (w, e, cost) in map.neighbours_with_costs(v) {
            let record = &mut self.records[w as usize];
            if record.mark == marks.closed {
                continue;
            }
            let candidate = g + cost;
            let known = record.mark == marks.open;
            if known && candidate >= record.g {
                continue;
            }
            let h = cached_heuristic(record, self.h_stamp, || {
                objective.cost_bound(map.pose(w), goal_pose)
            });
            if candidate + h > bound {
                continue;
            }
            if map.edge(e).validity == Validity::Valid {
                (record.mark, record.g) = (marks.open, candidate);
            }
            open.push(Open {
                f: candidate + h,
                g: candidate,
                v: w,
                parent: (v, e),
            });
        }
    }

    /// Sizes the records for `map`, starts a new search generation (and a new heuristic
    /// stamp when the goal, roadmap or objective changed); returns the search's marks.
    fn prepare(&mut self, map: &Roadmap, goal: u32, objective: &dyn Objective) -> Marks {
        let n = map.vertex_count();
        if self.records.len() < n {
            self.records.resize(n, VertexRecord::default());
        }
        self.heap.clear();
        let key = HeuristicKey::new(map, goal, objective);
        if self.heuristic_key != Some(key) {
            self.heuristic_key = Some(key);
            self.next_heuristic_stamp();
        }
        self.next_generation()
    }

    /// Advances the search generation, clearing the marks when the stamps run out.
    fn next_generation(&mut self) -> Marks {
        self.generation += 1;
        if self.generation > u32::MAX / 2 - 1 {
            self.records.iter_mut().for_each(|r| r.mark = 0);
            self.generation = 1;
            self.settled = None;
        }
        Marks {
            open: 2 * self.generation,
            closed: 2 * self.generation + 1,
        }
    }

    /// Invalidates every cached heuristic value.
    fn next_heuristic_stamp(&mut self) {
        self.h_stamp = self.h_stamp.wrapping_add(1);
        if self.h_stamp == 0 {
            self.records.iter_mut().for_each(|r| r.h_stamp = 0);
            self.h_stamp = 1;
        }
    }

    /// The heuristic of `v` (cached).
    fn heuristic(
        &mut self,
        map: &Roadmap,
        v: u32,
        goal_pose: &Pose2,
        objective: &dyn Objective,
    ) -> f64 {
        cached_heuristic(&mut self.records[v as usize], self.h_stamp, || {
            objective.cost_bound(map.pose(v), goal_pose)
        })
    }

    fn trace(&self, start: u32, goal: u32) -> GraphPath {
        let mut vertices = vec![goal];
        let mut edges = Vec::new();
        let mut v = goal;
        while v != start {
            let (p, e) = self.records[v as usize].parent;
            vertices.push(p);
            edges.push(e);
            v = p;
        }
        vertices.reverse();
        edges.reverse();
        GraphPath {
            vertices,
            edges,
            cost: self.records[goal as usize].g,
        }
    }
}

/// The record's heuristic if computed under `stamp`, else `compute()` (then stored).
fn cached_heuristic(record: &mut VertexRecord, stamp: u32, compute: impl FnOnce() -> f64) -> f64 {
    if record.h_stamp != stamp {
        record.h = compute();
        record.h_stamp = stamp;
    }
    record.h
}

/// Dijkstra distances from `start` over the live edges (for tests and diagnostics).
pub fn dijkstra(map: &Roadmap, start: u32) -> Vec<f64> {
    let mut dist = vec![f64::INFINITY; map.vertex_count()];
    let mut heap = BinaryHeap::new();
    dist[start as usize] = 0.0;
    heap.push(Open {
        f: 0.0,
        g: 0.0,
        v: start,
        parent: NO_PARENT,
    });
    while let Some(Open { f, v, .. }) = heap.pop() {
        if f > dist[v as usize] {
            continue;
        }
        for (w, e, cost) in map.neighbours_with_costs(v) {
            let d = f + cost;
            if d < dist[w as usize] {
                dist[w as usize] = d;
                heap.push(Open {
                    f: d,
                    g: 0.0,
                    v: w,
                    parent: (v, e),
                });
            }
        }
    }
    dist
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use smug_core::{Bounds2, PathLength, Se2Space};

    proptest! {
        #[test]
        fn astar_finds_the_dijkstra_shortest_path(
            points in proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0), 2..120),
            removed in proptest::collection::vec(0usize..2000, 0..60),
            k in 1usize..8, goal_pick in 0usize..1000, slack in prop_oneof![Just(0.0), 0.0f64..5.0],
        ) {
            let metric = Se2Space::default();
            let objective = PathLength::default();
            let mut map = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
            for &(x, y, t) in &points {
                map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
            }
            for r in removed {
                if r < map.edges.len() { map.remove_edge(r as u32); }
            }
            let goal = (goal_pick % map.vertex_count()) as u32;
            let dist = dijkstra(&map, 0);
            let found = AStar::default().search(&map, 0, goal, &objective, f64::INFINITY);
            // A bound at or above the shortest cost changes nothing; below it, no path.
            let exact = dist[goal as usize];
            let mut bounded = AStar::default();
            prop_assert_eq!(bounded.search(&map, 0, goal, &objective, exact * (1.0 + 1e-9) + slack), found.clone());
            if exact > 0.0 {
                prop_assert_eq!(bounded.search(&map, 0, goal, &objective, exact * (1.0 - 1e-9) - 1e-9), None);
            }
            match found {
                None => prop_assert!(dist[goal as usize].is_infinite()),
                Some(path) => {
                    prop_assert!((path.cost - dist[goal as usize]).abs() < 1e-9, "{} vs {}", path.cost, dist[goal as usize]);
                    let sum: f64 = path.edges.iter().map(|&e| map.edge(e).cost).sum();
                    prop_assert!((sum - path.cost).abs() < 1e-9);
                    prop_assert_eq!(path.vertices.first(), Some(&0));
                    prop_assert_eq!(path.vertices.last(), Some(&goal));
                }
            }
            map.refresh_components();
            prop_assert_eq!(map.maybe_connected(0, goal), dist[goal as usize].is_finite());
        }
    }

    proptest! {
        #[test]
        fn repairs_find_what_searching_again_finds(
            points in proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0), 2..80),
            batches in proptest::collection::vec(
                proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0), 1..6), 1..6),
            k in 1usize..8, goal_pick in 0usize..1000,
        ) {
            let metric = Se2Space::default();
            let objective = PathLength::default();
            let mut map = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
            for &(x, y, t) in &points {
                map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
            }
            let goal = (goal_pick % map.vertex_count()) as u32;
            let mut incremental = AStar::default();
            let Some(mut best) = incremental.search(&map, 0, goal, &objective, f64::INFINITY) else {
                return Ok(());
            };
            for batch in batches {
                let fresh_from = map.vertex_count() as u32;
                for &(x, y, t) in &batch {
                    map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
                }
                let again = AStar::default().search(&map, 0, goal, &objective, f64::INFINITY).unwrap();
                match incremental.repair(&map, 0, goal, fresh_from, &objective) {
                    Repair::Cheaper(path) => {
                        prop_assert!(path.cost < best.cost);
                        prop_assert!((path.cost - again.cost).abs() <= 1e-9 * again.cost);
                        let sum: f64 = path.edges.iter().map(|&e| map.edge(e).cost).sum();
                        prop_assert!((sum - path.cost).abs() <= 1e-9 * path.cost.max(1.0));
                        prop_assert_eq!(path.vertices.first(), Some(&0));
                        prop_assert_eq!(path.vertices.last(), Some(&goal));
                        best = path;
                    }
                    Repair::NoCheaper => prop_assert!(again.cost >= best.cost * (1.0 - 1e-9)),
                    Repair::NoBase => prop_assert!(false, "the base was lost"),
                }
                prop_assert_eq!(incremental.settled_path_cost(&map, 0, goal), Some(best.cost));
            }
            // A removal ends the base: the next attempt must search.
            if let Some(&e) = best.edges.first() {
                map.remove_edge(e);
                prop_assert_eq!(incremental.repair(&map, 0, goal, map.vertex_count() as u32, &objective), Repair::NoBase);
            }
        }
    }

    #[test]
    fn total_order_keys_order_like_total_cmp_and_round_trip() {
        let values = [
            f64::NEG_INFINITY,
            -1e300,
            -1.5,
            -f64::MIN_POSITIVE,
            -0.0,
            0.0,
            f64::MIN_POSITIVE,
            1e-300,
            1.0,
            1.0 + f64::EPSILON,
            1e300,
            f64::INFINITY,
            f64::NAN,
            -f64::NAN,
        ];
        for a in values {
            assert_eq!(
                from_total_order_key(total_order_key(a)).to_bits(),
                a.to_bits()
            );
            for b in values {
                assert_eq!(total_order_key(a).cmp(&total_order_key(b)), a.total_cmp(&b));
                let (ca, cb) = (Candidate::new(a, b, 1), Candidate::new(b, a, 2));
                let expected = open_order((a, b, 1), (b, a, 2));
                assert_eq!(ca.cmp(&cb), expected, "{a} {b}");
            }
        }
    }

    /// Knows which edges are secretly invalid.
    struct Hidden(Vec<bool>);

    impl Evaluator for Hidden {
        fn vertex(&mut self, _: &mut Roadmap, _: u32) -> bool {
            true
        }

        fn edge(&mut self, map: &mut Roadmap, e: u32) -> bool {
            match map.edge(e).validity {
                Validity::Valid => true,
                Validity::Invalid => false,
                Validity::Unknown if self.0[e as usize] => {
                    map.mark_edge_valid(e);
                    true
                }
                Validity::Unknown => {
                    map.remove_edge(e);
                    false
                }
            }
        }
    }

    proptest! {
        #[test]
        fn lazy_weighted_astar_finds_the_shortest_valid_path(
            points in proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0), 2..120),
            validity in proptest::collection::vec(proptest::bool::weighted(0.7), 2000),
            k in 1usize..8, goal_pick in 0usize..1000, bounded: bool,
        ) {
            let metric = Se2Space::default();
            let objective = PathLength::default();
            let mut lazy = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
            for &(x, y, t) in &points {
                lazy.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
            }
            let goal = (goal_pick % lazy.vertex_count()) as u32;
            let mut truth = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
            for &(x, y, t) in &points {
                truth.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
            }
            for e in 0..truth.edges.len() {
                if !validity[e % validity.len()] { truth.remove_edge(e as u32); }
            }
            let hidden: Vec<bool> = (0..lazy.edges.len()).map(|e| validity[e % validity.len()]).collect();
            let best = dijkstra(&truth, 0)[goal as usize];
            // A bound from a known valid path (at or above the cheapest) changes nothing.
            let bound = if bounded { best * (1.0 + 1e-9) } else { f64::INFINITY };
            let found = AStar::default().search_lazy(&mut lazy, 0, goal, &objective, &mut Hidden(hidden), bound);
            match found {
                None => prop_assert!(best.is_infinite()),
                Some(path) => {
                    prop_assert!((path.cost - best).abs() < 1e-9, "{} vs {}", path.cost, best);
                    prop_assert!(path.edges.iter().all(|&e| lazy.edge(e).validity == Validity::Valid || path.vertices.len() == 1));
                }
            }
        }
    }

    /// A cost that charges going up in x twice as much as going down (asymmetric).
    #[derive(Debug)]
    struct Uphill;

    impl Objective for Uphill {
        fn motion_cost(&self, a: &Pose2, b: &Pose2) -> f64 {
            a.xy_distance(b) + (b.x - a.x).max(0.0)
        }
        fn cost_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
            self.motion_cost(a, b)
        }
        fn bound_weights(&self) -> (f64, f64) {
            (1.0, 0.0)
        }
        fn is_symmetric(&self) -> bool {
            false
        }
    }

    proptest! {
        /// Directed edges (both motions of every connection) find the same cheapest
        /// paths as undirected ones, under symmetric and asymmetric costs; removing one
        /// direction leaves the other.
        #[test]
        fn directed_roadmaps_agree_with_undirected_ones(
            points in prop::collection::vec((0.0..10.0f64, 0.0..10.0f64, -3.0..3.0f64), 3..40),
            k in 2usize..6,
            asymmetric in any::<bool>(),
        ) {
            let space = Se2Space::default();
            let (length, uphill) = (PathLength::default(), Uphill);
            let objective: &dyn Objective = if asymmetric { &uphill } else { &length };
            let mut undirected = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
            let mut directed = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] }).with_directed_edges(true);
            for &(x, y, t) in &points {
                for map in [&mut undirected, &mut directed] {
                    map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&space, 1.0), objective);
                }
            }
            let goal = points.len() as u32 - 1;
            for start in [0, goal] {
                let (u, d) = (dijkstra(&undirected, start), dijkstra(&directed, start));
                for (a, b) in u.iter().zip(&d) {
                    prop_assert!(a == b || (a - b).abs() <= 1e-9 * a.max(1.0), "{a} vs {b}");
                }
            }
            prop_assert_eq!(directed.live_edge_count(), 2 * undirected.live_edge_count());
            if let Some(&(w, e)) = directed.neighbours(0).first() {
                directed.remove_edge(e);
                prop_assert!(directed.neighbours(0).iter().all(|&(_, id)| id != e));
                prop_assert!(directed.neighbours(w).iter().any(|&(v, _)| v == 0), "the reverse motion stays");
            }
        }
    }
}
