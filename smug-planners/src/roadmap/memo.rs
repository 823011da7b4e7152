//! What searches on a roadmap held still find out: the validity of the vertices and
//! edges they check, shared by every search (on any thread) and written into the
//! roadmap once they are done, in id order.
//!
//! A search reads the roadmap as it was when the searches began and asks the memo for
//! what it checks, so its answer depends only on that roadmap (and the true validity),
//! never on which search checked an element first: searches side by side give the
//! answers one after another would.

use super::{Roadmap, Validity};
use std::sync::atomic::{AtomicU8, Ordering::Relaxed};

const UNKNOWN: u8 = 0;
const VALID: u8 = 1;
const INVALID: u8 = 2;

/// Checks a search makes through a memo (the vertices and edges of a roadmap held still).
pub trait MemoEvaluator {
    /// True when vertex `v` is valid (checked if nobody knows yet).
    fn vertex(&mut self, map: &Roadmap, v: u32) -> bool;
    /// True when edge `e` is valid (checked if nobody knows yet).
    fn edge(&mut self, map: &Roadmap, e: u32) -> bool;
}

/// Validity found by the searches on a roadmap held still.
pub struct CheckMemo {
    vertices: Vec<AtomicU8>,
    edges: Vec<AtomicU8>,
}

impl CheckMemo {
    /// An empty memo for `map`'s vertices and edges.
    pub fn new(map: &Roadmap) -> Self {
        let unknown = |n: usize| (0..n).map(|_| AtomicU8::new(UNKNOWN)).collect();
        Self {
            vertices: unknown(map.vertex_count()),
            edges: unknown(map.edges.len()),
        }
    }

    /// Whether vertex `v` is valid: as the roadmap knows, as the memo knows, or as
    /// `check` says (then remembered). `counted` is called once per vertex, by the
    /// search whose answer was remembered first.
    pub fn vertex(
        &self,
        map: &Roadmap,
        v: u32,
        check: impl FnOnce() -> bool,
        counted: impl FnOnce(),
    ) -> bool {
        known_or_checked(
            map.vertex_validity(v),
            &self.vertices[v as usize],
            check,
            counted,
        )
    }

    /// Whether edge `e` is valid, as [`vertex`](Self::vertex) for vertices.
    pub fn edge(
        &self,
        map: &Roadmap,
        e: u32,
        check: impl FnOnce() -> bool,
        counted: impl FnOnce(),
    ) -> bool {
        known_or_checked(
            map.edge_validity(e),
            &self.edges[e as usize],
            check,
            counted,
        )
    }

    /// Writes what was found into `map` (the roadmap the memo was made for): valid
    /// elements marked, invalid ones removed, edges first (a vertex found invalid takes
    /// its edges with it, even those found valid), each in id order.
    pub fn apply(self, map: &mut Roadmap) {
        for (e, found) in self.edges.into_iter().enumerate() {
            match found.into_inner() {
                VALID => map.mark_edge_valid(e as u32),
                INVALID => map.remove_edge(e as u32),
                _ => {}
            }
        }
        for (v, found) in self.vertices.into_iter().enumerate() {
            match found.into_inner() {
                VALID => map.mark_vertex_valid(v as u32),
                INVALID => map.remove_vertex(v as u32),
                _ => {}
            }
        }
    }
}

/// The validity the roadmap knows, else the memo's, else `check`'s (remembered; the
/// first search to remember it is `counted`).
fn known_or_checked(
    known: Validity,
    slot: &AtomicU8,
    check: impl FnOnce() -> bool,
    counted: impl FnOnce(),
) -> bool {
    match known {
        Validity::Valid => return true,
        Validity::Invalid => return false,
        Validity::Unknown => {}
    }
    match slot.load(Relaxed) {
        VALID => return true,
        INVALID => return false,
        _ => {}
    }
    let valid = check();
    let found = if valid { VALID } else { INVALID };
    if slot
        .compare_exchange(UNKNOWN, found, Relaxed, Relaxed)
        .is_ok()
    {
        counted();
    }
    valid
}
