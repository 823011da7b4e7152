//! A wrapper that counts state checks and the time they take.

use smug_core::{Counters, Pose2, StateValidityChecker};
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::sync::Arc;
use std::time::Instant;

/// Counts checks, valid answers and nanoseconds spent in the wrapped checker; its
/// counters also include the wrapped checker's own (e.g. `esdf_queries`).
pub struct CountingChecker {
    inner: Arc<dyn StateValidityChecker>,
    checks: AtomicU64,
    valid: AtomicU64,
    nanos: AtomicU64,
}

impl CountingChecker {
    /// Wraps `inner`.
    pub fn new(inner: Arc<dyn StateValidityChecker>) -> Self {
        Self {
            inner,
            checks: AtomicU64::new(0),
            valid: AtomicU64::new(0),
            nanos: AtomicU64::new(0),
        }
    }

    /// Seconds spent checking so far.
    pub fn seconds(&self) -> f64 {
        self.nanos.load(Relaxed) as f64 * 1e-9
    }
}

impl StateValidityChecker for CountingChecker {
    fn is_valid(&self, state: &Pose2) -> bool {
        let started = Instant::now();
        let valid = self.inner.is_valid(state);
        self.nanos
            .fetch_add(started.elapsed().as_nanos() as u64, Relaxed);
        self.checks.fetch_add(1, Relaxed);
        self.valid.fetch_add(valid as u64, Relaxed);
        valid
    }

    fn counters(&self) -> Counters {
        let mut counters: Counters = self
            .inner
            .counters()
            .into_iter()
            .map(|(k, v)| (format!("inner_{k}"), v))
            .collect();
        for key in [
            "esdf_queries",
            "traversability_decided",
            "volumetric_checks",
        ] {
            if let Some(v) = counters.remove(&format!("inner_{key}")) {
                counters.insert(key.to_string(), v);
            }
        }
        counters.insert("checks".into(), self.checks.load(Relaxed));
        counters.insert("valid".into(), self.valid.load(Relaxed));
        counters.insert("time_ns".into(), self.nanos.load(Relaxed));
        counters
    }
}
