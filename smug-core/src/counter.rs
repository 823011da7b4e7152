//! [`Counter`]: a statistics counter (checks made, queries answered) that the threads of
//! a parallel loop add to side by side. One atomic shared by two cores bounces its cache
//! line between them on every increment: the hot checks (tens of millions of state
//! checks per mission, several counters each) then run slower on two threads than on
//! one. A counter here keeps one cache-padded slot per thread of rayon's pool and sums
//! them when read.

use crossbeam_utils::CachePadded;
use std::fmt;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

/// Slots per counter: threads outside a rayon pool share slot 0, a pool's thread `i`
/// takes slot `(i + 1) % SLOTS`.
const SLOTS: usize = 8;

/// A counter many threads add to without contending for one cache line; read with
/// [`total`](Self::total).
#[derive(Default)]
pub struct Counter {
    slots: [CachePadded<AtomicU64>; SLOTS],
}

impl Counter {
    /// A counter at zero.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `n`.
    #[inline]
    pub fn add(&self, n: u64) {
        let slot = rayon::current_thread_index().map_or(0, |i| (i + 1) % SLOTS);
        self.slots[slot].fetch_add(n, Relaxed);
    }

    /// Adds one.
    #[inline]
    pub fn increment(&self) {
        self.add(1);
    }

    /// The sum of everything added so far (exact once the adding threads are done).
    pub fn total(&self) -> u64 {
        self.slots.iter().map(|slot| slot.load(Relaxed)).sum()
    }
}

impl fmt::Debug for Counter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_tuple("Counter").field(&self.total()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::Counter;
    use rayon::prelude::*;

    #[test]
    fn adds_from_every_thread_of_a_pool_and_from_outside_are_all_counted() {
        let counter = Counter::new();
        counter.add(5);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(11)
            .build()
            .unwrap();
        pool.install(|| {
            (0..10_000u64)
                .into_par_iter()
                .for_each(|_| counter.increment())
        });
        (0..100u64).into_par_iter().for_each(|k| counter.add(k));
        assert_eq!(counter.total(), 5 + 10_000 + 4950);
        assert_eq!(format!("{counter:?}"), "Counter(14955)");
    }
}
