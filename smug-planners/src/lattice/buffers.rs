//! What one search thread owns: per-pose search data over the whole lattice (reused
//! across searches by generation stamps) and its counters.

use super::Counts;

/// One lattice pose's entry in a search: its cost, parent and gear once closed (or
/// the best way queued by a verified motion), stamped with the search's generation.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Node {
    pub(super) g: f64,
    pub(super) parent: u32,
    /// The primitive (of the parent's heading) of the best verified way queued.
    pub(super) prim: u16,
    /// Generation in which `g` was last set.
    pub(super) stamp: u32,
    /// Generation in which the pose was closed.
    pub(super) closed: u32,
    /// Gear of the motion that reached the pose: 0 forward, 1 reverse.
    pub(super) gear: u8,
}

/// Per-search arrays over the lattice, reused across searches (generation stamps
/// instead of clearing); one entry per pose, so a pose's data is one cache line.
pub(crate) struct Buffers {
    pub(super) generation: u32,
    pub(super) nodes: Vec<Node>,
}

impl Buffers {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            generation: 0,
            nodes: vec![Node::default(); n],
        }
    }

    pub(super) fn next_generation(&mut self) {
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.nodes.fill(Node::default());
            self.generation = 1;
        }
    }

    pub(super) fn is_closed(&self, i: usize) -> bool {
        self.nodes[i].closed == self.generation
    }

    /// The cost of a verified way to pose `i` known in this search, if any.
    pub(super) fn known_g(&self, i: usize) -> Option<f64> {
        let node = &self.nodes[i];
        (node.stamp == self.generation).then_some(node.g)
    }

    /// True when a verified way to pose `i` is queued or closed that pops before a
    /// way from `parent` by `prim` and `reverse` at cost `g` would: by cost, then as the
    /// search's heap breaks ties (so that what is queued never changes what pops).
    pub(super) fn beaten(&self, i: usize, g: f64, parent: u32, prim: u16, reverse: bool) -> bool {
        let node = &self.nodes[i];
        node.stamp == self.generation
            && (g > node.g
                || (g == node.g
                    && (parent, prim, reverse) > (node.parent, node.prim, node.gear == 1)))
    }
}

/// Asks the processor to fetch `value`'s cache line soon (a hint: the search reads
/// it shortly, and waiting for each such line in turn is what its loop spends most of
/// its time on).
#[inline]
pub(super) fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch is a hint to the cache; it never faults and reads nothing
    // the program sees (the pointer comes from a reference, so it is valid anyway).
    unsafe {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        _mm_prefetch::<_MM_HINT_T0>((value as *const T).cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}

/// What one thread needs to search: its buffers and counters.
pub(crate) struct Searcher {
    pub(super) buffers: Buffers,
    pub(super) counts: Counts,
    /// The states of the primitive being checked (reused).
    pub(super) along: Vec<smug_core::Pose2>,
}

impl Searcher {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            buffers: Buffers::new(n),
            counts: Counts::default(),
            along: Vec::new(),
        }
    }
}
