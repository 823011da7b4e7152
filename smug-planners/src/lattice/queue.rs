//! The search's priority queue: a two-level bucket queue over the entries' keys that
//! pops in exactly the order of a binary heap of the same entries.
//!
//! Entries are filed into buckets of keys `width` wide; the buckets after the current
//! one are plain vectors, so a push beyond the current bucket is an append. When a
//! bucket becomes the current one it is sorted once (by the entries' own total order)
//! and popped from its end; keys pushed at or below the current bucket (an A*
//! search's keys never fall by much) join a small heap, and a pop takes the lesser of
//! the two fronts. The sorted run also tells the search which entries pop next
//! ([`BucketQueue::ahead`]), so their data can be fetched early.
//! `key / width` rounds monotonically, so a key below another never lands in a later
//! bucket: the lowest non-empty bucket holds the queue's least entry, and the pops are
//! the same as one heap's, ties included.

use dary_heap::OctonaryHeap as Heap;
use std::cmp::Ordering;

/// What the queue holds: a lattice pose (or the start) to expand, or a shot to a goal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Item {
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
        /// The heuristic's focus (`Run::focus`) the entry's key was computed with
        /// (not part of the order: a key computed with an older focus is computed
        /// again when popped, see `Worker::refocus`).
        focus: u32,
    },
    Shot {
        from: u32,
        goal: u32,
        costed: bool,
    },
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Entry {
    pub(super) key: f64,
    pub(super) item: Item,
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
    // A min-heap on the key, ties broken by the item: a total order, so the order of
    // pops does not depend on which other entries were pushed (whether a motion's
    // validity was already known, learnt by a search on another thread, changes what
    // is pushed, never what is popped first).
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .key
            .total_cmp(&self.key)
            .then_with(|| other.item.rank().cmp(&self.item.rank()))
    }
}

impl Item {
    /// The tie-break of equal keys: shots before nodes (a goal settled ends a search
    /// sooner), then by ids, cost and motion.
    fn rank(&self) -> (u8, u32, u32, u64, u16, bool) {
        match *self {
            Item::Node {
                id,
                parent,
                g,
                prim,
                reverse,
                ..
            } => (1, id, parent, g.to_bits(), prim, reverse),
            Item::Shot { from, goal, costed } => (0, goal, from, 0, 0, costed),
        }
    }
}

/// The bucket index keys at or above `LAST_BUCKET · width` share.
const LAST_BUCKET: usize = 1 << 16;

/// A min-queue of search entries by key (ties in the entries' order).
pub(super) struct BucketQueue {
    /// How wide a bucket's key range is.
    width: f64,
    /// The entries of the buckets after the current one (index: bucket).
    buckets: Vec<Vec<Entry>>,
    /// The current bucket's index: entries filed at or below it are in `sorted` or
    /// `heap`.
    current: usize,
    /// The current bucket's entries as it became current, sorted: the least last.
    sorted: Vec<Entry>,
    /// The entries pushed at or below the current bucket since it became current.
    heap: Heap<Entry>,
    /// Entries in the buckets after the current one.
    later: usize,
}

impl BucketQueue {
    /// An empty queue with buckets `width` wide (> 0).
    pub(super) fn new(width: f64) -> Self {
        assert!(width > 0.0, "bucket width must be positive");
        Self {
            width,
            buckets: Vec::new(),
            current: 0,
            sorted: Vec::new(),
            heap: Heap::new(),
            later: 0,
        }
    }

    /// The bucket a key is filed in (monotone in the key).
    fn bucket_of(&self, key: f64) -> usize {
        let index = (key / self.width).floor();
        if index >= LAST_BUCKET as f64 {
            LAST_BUCKET
        } else if index > 0.0 {
            index as usize
        } else {
            0
        }
    }

    /// Queues an entry.
    pub(super) fn push(&mut self, entry: Entry) {
        let bucket = self.bucket_of(entry.key);
        if bucket <= self.current {
            self.heap.push(entry);
            return;
        }
        if bucket >= self.buckets.len() {
            self.buckets.resize_with(bucket + 1, Vec::new);
        }
        self.buckets[bucket].push(entry);
        self.later += 1;
    }

    /// Takes the least entry.
    pub(super) fn pop(&mut self) -> Option<Entry> {
        if self.sorted.is_empty() && self.heap.is_empty() && !self.advance() {
            return None;
        }
        // `Ord` is reversed (the least key is the greatest entry).
        match (self.sorted.last(), self.heap.peek()) {
            (Some(run), Some(pushed)) if pushed > run => self.heap.pop(),
            (Some(_), _) => self.sorted.pop(),
            (None, _) => self.heap.pop(),
        }
    }

    /// An entry of the current bucket that pops `n` pops after the next one, or soon
    /// after (entries pushed since the bucket became current may pop before it).
    pub(super) fn ahead(&self, n: usize) -> Option<&Entry> {
        self.sorted
            .len()
            .checked_sub(n + 1)
            .map(|k| &self.sorted[k])
    }

    /// Makes the next non-empty bucket the current one; false when none is left.
    fn advance(&mut self) -> bool {
        if self.later == 0 {
            return false;
        }
        let next = (self.current + 1..self.buckets.len())
            .find(|&b| !self.buckets[b].is_empty())
            .expect("a later bucket holds the later entries");
        self.current = next;
        let mut entries = std::mem::take(&mut self.buckets[next]);
        self.later -= entries.len();
        entries.sort_unstable();
        // Keep the emptied run's allocation for the bucket just taken.
        self.buckets[next] = std::mem::replace(&mut self.sorted, entries);
        true
    }

    /// How many entries are queued.
    #[cfg(test)]
    pub(super) fn len(&self) -> usize {
        self.sorted.len() + self.heap.len() + self.later
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn entry(key: f64, id: u32, shot: bool) -> Entry {
        let item = if shot {
            Item::Shot {
                from: id,
                goal: id % 3,
                costed: id.is_multiple_of(2),
            }
        } else {
            Item::Node {
                id,
                parent: id / 2,
                g: key / 2.0,
                prim: (id % 7) as u16,
                reverse: id % 2 == 1,
                verified: false,
                focus: 0,
            }
        };
        Entry { key, item }
    }

    /// A sequence of pushes (key, id, shot) and pops, keys from a few values (ties) to
    /// many, some below what was popped last, some far beyond the last bucket.
    fn ops() -> impl Strategy<Value = Vec<Option<(f64, u32, bool)>>> {
        let key = prop_oneof![
            (0u32..8).prop_map(|k| k as f64 * 0.25),
            0.0f64..50.0,
            Just(1e12),
        ];
        proptest::collection::vec(
            prop_oneof![
                3 => (key, 0u32..50, any::<bool>()).prop_map(Some),
                2 => Just(None),
            ],
            0..400,
        )
    }

    proptest! {
        /// Pops the same entries in the same order as a heap of the same entries.
        #[test]
        fn pops_as_a_heap_does(ops in ops(), width in 0.01f64..2.0) {
            let mut queue = BucketQueue::new(width);
            let mut heap = Heap::new();
            for op in &ops {
                match *op {
                    Some((key, id, shot)) => {
                        queue.push(entry(key, id, shot));
                        heap.push(entry(key, id, shot));
                    }
                    None => {
                        let (a, b) = (queue.pop(), heap.pop());
                        prop_assert_eq!(a.map(|e| (e.key.to_bits(), e.item)), b.map(|e| (e.key.to_bits(), e.item)));
                    }
                }
                prop_assert_eq!(queue.len(), heap.len());
            }
            while let Some(b) = heap.pop() {
                let a = queue.pop().expect("as many entries as the heap");
                prop_assert_eq!((a.key.to_bits(), a.item), (b.key.to_bits(), b.item));
            }
            prop_assert!(queue.pop().is_none());
        }
    }
}
