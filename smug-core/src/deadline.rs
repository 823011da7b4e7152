//! A wall-clock deadline for a whole run (`smug plan --deadline S`) on the thread that
//! set it. At the deadline every [`TerminationClock`](crate::termination::TerminationClock)
//! says stop: anytime loops (planner queries, local search) keep their best result, and
//! later path queries search only the roadmap built so far. At the hard stop, a quarter
//! of the deadline later (at least one second), the path oracle plans nothing more and
//! the run ends.

use std::cell::Cell;
use std::time::{Duration, Instant};

/// The two instants of a run's deadline.
#[derive(Clone, Copy, Debug)]
struct Limits {
    soft: Instant,
    hard: Instant,
}

thread_local! {
    static LIMITS: Cell<Option<Limits>> = const { Cell::new(None) };
    static REACHED: Cell<bool> = const { Cell::new(false) };
}

/// The deadline of this thread while the guard lives; the previous one after.
#[must_use = "the deadline is lifted when the guard is dropped"]
pub struct DeadlineGuard {
    previous: Option<Limits>,
    previously_reached: bool,
}

/// Sets this thread's deadline to `seconds` from now (`None` lifts it) until the
/// returned guard is dropped; the hard stop follows [`grace`] later.
pub fn set(seconds: Option<f64>) -> DeadlineGuard {
    let limits = seconds.map(|s| {
        let s = s.clamp(0.0, 1e9);
        let now = Instant::now();
        Limits {
            soft: now + Duration::from_secs_f64(s),
            hard: now + Duration::from_secs_f64(s + grace(s)),
        }
    });
    DeadlineGuard {
        previous: LIMITS.with(|d| d.replace(limits)),
        previously_reached: REACHED.with(|r| r.replace(false)),
    }
}

/// This thread's deadline, for threads working on its behalf ([`adopt`]).
#[derive(Clone, Copy, Debug)]
pub struct Carried(Option<Limits>);

/// This thread's deadline as it stands, to hand to worker threads.
pub fn carry() -> Carried {
    Carried(LIMITS.with(Cell::get))
}

/// Sets this (worker) thread's deadline to `carried` until the guard is dropped.
pub fn adopt(carried: Carried) -> DeadlineGuard {
    DeadlineGuard {
        previous: LIMITS.with(|d| d.replace(carried.0)),
        previously_reached: REACHED.with(|r| r.replace(false)),
    }
}

/// Seconds between the deadline and the hard stop for a deadline of `seconds`.
pub fn grace(seconds: f64) -> f64 {
    (0.25 * seconds).max(1.0)
}

impl Drop for DeadlineGuard {
    fn drop(&mut self) {
        LIMITS.with(|d| d.set(self.previous));
        REACHED.with(|r| r.set(self.previously_reached));
    }
}

/// True once this thread's deadline has passed (and records that it did).
pub fn passed() -> bool {
    let Some(limits) = LIMITS.with(Cell::get) else {
        return false;
    };
    let passed = Instant::now() >= limits.soft;
    if passed {
        REACHED.with(|r| r.set(true));
    }
    passed
}

/// True once this thread's hard stop has passed: nothing more may be planned.
pub fn hard_stop_passed() -> bool {
    LIMITS
        .with(Cell::get)
        .is_some_and(|limits| Instant::now() >= limits.hard)
}

/// True when [`passed`] has said so since the deadline was set: some loop was cut short.
pub fn reached() -> bool {
    REACHED.with(Cell::get)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_deadline_holds_while_its_guard_lives() {
        assert!(!passed());
        {
            let _guard = set(Some(0.0));
            assert!(!reached());
            assert!(passed());
            assert!(reached());
            assert!(!hard_stop_passed(), "a second of grace");
            {
                let _inner = set(Some(3600.0));
                assert!(!passed());
            }
            assert!(passed(), "the outer deadline is back");
        }
        assert!(!passed() && !reached() && !hard_stop_passed());
    }
}
