//! The search's records and open-list entries: what a search knows about each vertex,
//! the orders its queues pop in, and the stamps that spare clearing them.

use super::super::Roadmap;
use crate::nn::{from_total_order_key, total_order_key};
use smug_core::Objective;
use std::cmp::Ordering;

/// The open-list order: smallest `f` first, then larger `g` (deeper), then smaller id.
/// A strict total order, so every correct priority queue pops the same sequence.
pub(super) fn open_order((f, g, v): (f64, f64, u32), (of, og, ov): (f64, f64, u32)) -> Ordering {
    of.total_cmp(&f).then(g.total_cmp(&og)).then(ov.cmp(&v))
}

/// An open-list entry of the lazy search and of Dijkstra: a vertex, its cost so far
/// and estimate, and the parent edge it is reached through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Open {
    pub(super) f: f64,
    pub(super) g: f64,
    pub(super) v: u32,
    pub(super) parent: (u32, u32),
}

/// No parent (the search's start).
pub(super) const NO_PARENT: (u32, u32) = (u32::MAX, u32::MAX);

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
pub(super) struct Candidate {
    f_key: u64,
    g_key: u64,
    pub(super) v: u32,
}

impl Candidate {
    pub(super) fn new(f: f64, g: f64, v: u32) -> Self {
        Self {
            f_key: total_order_key(f),
            g_key: total_order_key(g),
            v,
        }
    }

    /// The cost so far.
    pub(super) fn g(&self) -> f64 {
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
pub(super) struct VertexRecord {
    /// Cost so far. The lazy search keeps here the best cost through a checked-valid
    /// edge while the vertex is open, then its cost once closed.
    pub(super) g: f64,
    /// The heuristic, valid when `h_stamp` equals [`AStar`](super::AStar)'s current heuristic stamp.
    pub(super) h: f64,
    /// The vertex and edge it is reached through.
    pub(super) parent: (u32, u32),
    /// [`Marks::open`] of the search that opened it, or [`Marks::closed`] once closed.
    pub(super) mark: u32,
    /// The heuristic stamp `h` was computed for.
    pub(super) h_stamp: u32,
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
pub(super) struct Marks {
    /// Seen (opened) in this search.
    pub(super) open: u32,
    /// Expanded (closed) in this search.
    pub(super) closed: u32,
}

/// What the cached heuristic values depend on: the roadmap, the goal and the
/// objective (by address and bound weights).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct HeuristicKey {
    roadmap: u64,
    goal: u32,
    objective_address: usize,
    objective_weights: (u64, u64),
}

impl HeuristicKey {
    pub(super) fn new(map: &Roadmap, goal: u32, objective: &dyn Objective) -> Self {
        let (w_t, w_r) = objective.bound_weights();
        Self {
            roadmap: map.id,
            goal,
            objective_address: objective as *const dyn Objective as *const () as usize,
            objective_weights: (w_t.to_bits(), w_r.to_bits()),
        }
    }
}

/// The record's heuristic if computed under `stamp`, else `compute()` (then stored).
pub(super) fn cached_heuristic(
    record: &mut VertexRecord,
    stamp: u32,
    compute: impl FnOnce() -> f64,
) -> f64 {
    if record.h_stamp != stamp {
        record.h = compute();
        record.h_stamp = stamp;
    }
    record.h
}

/// An open-list entry of the lazy Dijkstra search (24 bytes): the cost so far as an
/// integer ordered like `f64::total_cmp`, the vertex, and the vertex and edge it is
/// reached through. Smallest cost first, then smaller vertex id: a strict order, so
/// every correct priority queue pops the same sequence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Reached {
    pub(super) g_key: u64,
    pub(super) v: u32,
    pub(super) parent: (u32, u32),
}

impl Reached {
    pub(super) fn new(g: f64, v: u32, parent: (u32, u32)) -> Self {
        Self {
            g_key: total_order_key(g),
            v,
            parent,
        }
    }
}

impl Ord for Reached {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .g_key
            .cmp(&self.g_key)
            .then(other.v.cmp(&self.v))
            .then(other.parent.cmp(&self.parent))
    }
}

impl PartialOrd for Reached {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
