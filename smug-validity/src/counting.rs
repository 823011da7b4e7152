//! A wrapper that counts state checks and the time they take.

use smug_core::Counter;
use smug_core::{Counters, Pose2, StateValidityChecker};
use std::sync::Arc;
use std::time::Instant;

/// Counts checks, valid answers and nanoseconds spent in the wrapped checker; its
/// counters also include the wrapped checker's own (e.g. `esdf_queries`).
pub struct CountingChecker {
    inner: Arc<dyn StateValidityChecker>,
    checks: Counter,
    valid: Counter,
    nanos: Counter,
}

impl CountingChecker {
    /// Wraps `inner`.
    pub fn new(inner: Arc<dyn StateValidityChecker>) -> Self {
        Self {
            inner,
            checks: Counter::new(),
            valid: Counter::new(),
            nanos: Counter::new(),
        }
    }

    /// Seconds spent checking so far.
    pub fn seconds(&self) -> f64 {
        self.nanos.total() as f64 * 1e-9
    }
}

impl StateValidityChecker for CountingChecker {
    fn is_valid(&self, state: &Pose2) -> bool {
        let started = Instant::now();
        let valid = self.inner.is_valid(state);
        self.nanos.add(started.elapsed().as_nanos() as u64);
        self.checks.increment();
        self.valid.add(valid as u64);
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
        counters.insert("checks".into(), self.checks.total());
        counters.insert("valid".into(), self.valid.total());
        counters.insert("time_ns".into(), self.nanos.total());
        counters
    }
}
