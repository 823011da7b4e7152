//! Searches on the roadmap: A* with a cached heuristic (here), its incremental repair
//! ([`repair`]), Lazy Weighted A* ([`lazy`]), the one-to-many lazy Dijkstra ([`many`]),
//! and Dijkstra distances (for tests and diagnostics). A* and its repair share one
//! expansion loop and one relaxation rule ([`Relax`]); Lazy Weighted A* shares the rule.

mod lazy;
mod many;
mod records;
mod repair;
#[cfg(test)]
mod tests;

use self::records::{
    cached_heuristic, Candidate, HeuristicKey, Marks, Open, Reached, VertexRecord, NO_PARENT,
};
use super::{Roadmap, Validity};
use smug_core::{Objective, Pose2};
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

/// Checks roadmap elements for the lazy search (and records what it finds).
pub trait Evaluator {
    /// Checks vertex `v` if unknown; true when valid (invalid ones are removed).
    fn vertex(&mut self, map: &mut Roadmap, v: u32) -> bool;
    /// Checks edge `e` if unknown; true when valid (invalid ones are removed).
    fn edge(&mut self, map: &mut Roadmap, e: u32) -> bool;
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
    many_heap: BinaryHeap<Reached>,
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

/// The goal a search estimates toward: its pose, and the objective whose bound is the
/// heuristic.
#[derive(Clone, Copy)]
struct Target<'a> {
    pose: Pose2,
    objective: &'a dyn Objective,
}

/// Which vertices a relaxation may (re)open, and which estimates it keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Relax {
    /// A search: closed vertices stay closed; estimates up to `bound` are kept.
    Search {
        /// The largest estimate kept (`f64::INFINITY`: no bound).
        bound: f64,
    },
    /// A repair: settled (closed) vertices reopen when reached more cheaply; estimates
    /// below `bound`, the known path's cost, are kept.
    Repair {
        /// The cost of the known path.
        bound: f64,
    },
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
        let target = Target {
            pose: *map.pose(goal),
            objective,
        };
        let f_start = self.heuristic(map, start, &target.pose, objective);
        let record = &mut self.records[start as usize];
        (record.mark, record.g, record.parent) = (marks.open, 0.0, NO_PARENT);
        self.heap.push(Candidate::new(f_start, 0.0, start));
        let cost = self.run(map, goal, target, marks, Relax::Search { bound })?;
        self.settled = Some(Settled {
            closed: marks.closed,
            roadmap: map.id,
            removals: map.removals,
            start,
            goal,
            cost,
        });
        Some(self.trace(start, goal))
    }

    /// Expands the open list until `goal` is closed: its cost, or `None` when the open
    /// list runs out first. Neighbours are relaxed by `rule`.
    fn run(
        &mut self,
        map: &Roadmap,
        goal: u32,
        target: Target,
        marks: Marks,
        rule: Relax,
    ) -> Option<f64> {
        while let Some((g, v)) = self.close_next(marks) {
            if v == goal {
                return Some(g);
            }
            self.expansions += 1;
            for (w, e, cost) in map.neighbours_with_costs(v) {
                self.relax(map, (v, e), (w, g + cost), target, marks, rule);
            }
        }
        None
    }

    /// Pops the open list down to its cheapest entry that is still current (its vertex
    /// open, not reached more cheaply since), closes that vertex and returns its cost
    /// and id; `None` once the list is empty.
    fn close_next(&mut self, marks: Marks) -> Option<(f64, u32)> {
        while let Some(candidate) = self.heap.pop() {
            let (g, v) = (candidate.g(), candidate.v);
            let record = &mut self.records[v as usize];
            if record.mark != marks.open || g > record.g {
                continue;
            }
            record.mark = marks.closed;
            return Some((g, v));
        }
        None
    }

    /// Reaches `w` at cost `g` from `v` over edge `e`: when [`admit`](Self::admit)ted,
    /// opens it with that cost and parent and pushes it on the open list.
    fn relax(
        &mut self,
        map: &Roadmap,
        (v, e): (u32, u32),
        (w, g): (u32, f64),
        target: Target,
        marks: Marks,
        rule: Relax,
    ) {
        if let Some(h) = self.admit(map, w, g, target, marks, rule) {
            let record = &mut self.records[w as usize];
            (record.mark, record.g, record.parent) = (marks.open, g, (v, e));
            self.heap.push(Candidate::new(g + h, g, w));
        }
    }

    /// The heuristic of `w` when reaching it at cost `g` improves on its record under
    /// `rule` and the estimate `g + h` is within the rule's bound; `None` otherwise
    /// (nothing changes but the heuristic cache).
    fn admit(
        &mut self,
        map: &Roadmap,
        w: u32,
        g: f64,
        target: Target,
        marks: Marks,
        rule: Relax,
    ) -> Option<f64> {
        let record = &mut self.records[w as usize];
        let known = match rule {
            Relax::Search { .. } => {
                if record.mark == marks.closed {
                    return None;
                }
                record.mark == marks.open
            }
            Relax::Repair { .. } => record.mark == marks.open || record.mark == marks.closed,
        };
        if known && g >= record.g {
            return None;
        }
        let h = cached_heuristic(record, self.h_stamp, || {
            target.objective.cost_bound(map.pose(w), &target.pose)
        });
        let pruned = match rule {
            Relax::Search { bound } => g + h > bound,
            Relax::Repair { bound } => g + h >= bound,
        };
        (!pruned).then_some(h)
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
