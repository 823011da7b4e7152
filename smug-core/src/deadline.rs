//! A wall-clock deadline for a whole run (`smug plan --deadline S`), carried explicitly.
//!
//! A [`Deadline`] is a handle: the pipeline owns one (in its
//! [`RunContext`](crate::run_context::RunContext)) and hands a
//! clone to every stage it builds; a run arms it ([`Deadline::arm`]) and every clone,
//! on any thread (a rayon loop included), sees the same instants. Two pipelines have
//! two handles and do not affect each other.
//!
//! At the deadline every [`TerminationClock`](crate::termination::TerminationClock)
//! started within it says stop: anytime loops (planner queries, local search) keep
//! their best result, and later path queries search only the roadmap built so far. At
//! the hard stop, a quarter of the deadline later (at least one second), the path
//! oracle plans nothing more and the run ends.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// No instant set (nanoseconds since the handle's epoch).
const UNSET: u64 = u64::MAX;

/// The shared state of a deadline handle.
#[derive(Debug)]
struct State {
    /// The instant the nanosecond counts below start from.
    epoch: Instant,
    /// The deadline, in nanoseconds since `epoch` (`UNSET`: none).
    soft_ns: AtomicU64,
    /// The hard stop, in nanoseconds since `epoch` (`UNSET`: none).
    hard_ns: AtomicU64,
    /// Set once [`Deadline::passed`] has said so.
    reached: AtomicBool,
}

/// A run's deadline: unarmed (never passes) until [`arm`](Self::arm)ed; clones share it.
#[derive(Clone, Debug)]
pub struct Deadline(Arc<State>);

impl Default for Deadline {
    fn default() -> Self {
        Self::new()
    }
}

impl PartialEq for Deadline {
    /// Two handles are equal when they share one deadline.
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// The deadline as armed while the guard lives; the previous one after.
#[must_use = "the deadline is lifted when the guard is dropped"]
pub struct ArmedDeadline<'a> {
    deadline: &'a Deadline,
    previous: (u64, u64, bool),
}

impl Deadline {
    /// A new, unarmed deadline (shared by nothing yet).
    pub fn new() -> Self {
        Self(Arc::new(State {
            epoch: Instant::now(),
            soft_ns: AtomicU64::new(UNSET),
            hard_ns: AtomicU64::new(UNSET),
            reached: AtomicBool::new(false),
        }))
    }

    /// A new deadline armed `seconds` from now, for as long as it lives.
    pub fn after(seconds: f64) -> Self {
        let deadline = Self::new();
        deadline.set(Some(seconds));
        deadline
    }

    /// Arms the deadline `seconds` from now (`None` lifts it) until the returned guard
    /// is dropped; the hard stop follows [`grace`] later.
    pub fn arm(&self, seconds: Option<f64>) -> ArmedDeadline<'_> {
        let previous = (
            self.0.soft_ns.load(Ordering::Relaxed),
            self.0.hard_ns.load(Ordering::Relaxed),
            self.0.reached.load(Ordering::Relaxed),
        );
        self.set(seconds);
        ArmedDeadline {
            deadline: self,
            previous,
        }
    }

    fn set(&self, seconds: Option<f64>) {
        let (soft, hard) = match seconds {
            Some(s) => {
                let s = s.clamp(0.0, 1e9);
                (self.nanos_from_now(s), self.nanos_from_now(s + grace(s)))
            }
            None => (UNSET, UNSET),
        };
        self.0.soft_ns.store(soft, Ordering::Relaxed);
        self.0.hard_ns.store(hard, Ordering::Relaxed);
        self.0.reached.store(false, Ordering::Relaxed);
    }

    fn nanos_from_now(&self, seconds: f64) -> u64 {
        let at = self.0.epoch.elapsed() + Duration::from_secs_f64(seconds);
        u64::try_from(at.as_nanos()).unwrap_or(UNSET - 1)
    }

    fn now_ns(&self) -> u64 {
        u64::try_from(self.0.epoch.elapsed().as_nanos()).unwrap_or(UNSET - 1)
    }

    /// True once the deadline has passed (and records that it did).
    pub fn passed(&self) -> bool {
        let soft = self.0.soft_ns.load(Ordering::Relaxed);
        if soft == UNSET {
            return false;
        }
        let passed = self.now_ns() >= soft;
        if passed {
            self.0.reached.store(true, Ordering::Relaxed);
        }
        passed
    }

    /// True once the hard stop has passed: nothing more may be planned.
    pub fn hard_stop_passed(&self) -> bool {
        let hard = self.0.hard_ns.load(Ordering::Relaxed);
        hard != UNSET && self.now_ns() >= hard
    }

    /// True when [`passed`](Self::passed) has said so since the deadline was armed:
    /// some loop was cut short.
    pub fn reached(&self) -> bool {
        self.0.reached.load(Ordering::Relaxed)
    }
}

impl Drop for ArmedDeadline<'_> {
    fn drop(&mut self) {
        let state = &self.deadline.0;
        state.soft_ns.store(self.previous.0, Ordering::Relaxed);
        state.hard_ns.store(self.previous.1, Ordering::Relaxed);
        state.reached.store(self.previous.2, Ordering::Relaxed);
    }
}

/// Seconds between the deadline and the hard stop for a deadline of `seconds`.
pub fn grace(seconds: f64) -> f64 {
    (0.25 * seconds).max(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_deadline_holds_while_its_guard_lives() {
        let deadline = Deadline::new();
        assert!(!deadline.passed());
        {
            let _guard = deadline.arm(Some(0.0));
            assert!(!deadline.reached());
            assert!(deadline.passed());
            assert!(deadline.reached());
            assert!(!deadline.hard_stop_passed(), "a second of grace");
            {
                let _inner = deadline.arm(Some(3600.0));
                assert!(!deadline.passed());
            }
            assert!(deadline.passed(), "the outer deadline is back");
        }
        assert!(!deadline.passed() && !deadline.reached() && !deadline.hard_stop_passed());
    }

    #[test]
    fn clones_share_a_deadline_and_other_deadlines_are_apart() {
        let deadline = Deadline::new();
        let clone = deadline.clone();
        let other = Deadline::new();
        let _guard = deadline.arm(Some(0.0));
        assert!(clone.passed(), "a clone sees the armed deadline");
        assert!(!other.passed(), "another deadline does not");
        let seen = std::thread::spawn(move || clone.passed()).join().unwrap();
        assert!(seen, "so does a clone on another thread");
        assert_eq!(deadline, deadline.clone());
        assert_ne!(deadline, other);
        assert!(Deadline::after(0.0).passed());
    }
}
