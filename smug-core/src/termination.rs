//! Combinable termination rules: time budget, iteration budget, either-of.

use crate::deadline::Deadline;
use std::ops::BitOr;
use std::time::{Duration, Instant};

/// When a loop (a planner query, a local search) must stop.
///
/// Rules combine with `|`: `Termination::time(d) | Termination::iterations(n)` stops at
/// whichever comes first.
#[derive(Clone, Debug, PartialEq)]
pub enum Termination {
    /// Never stops on its own (the loop must have another exit).
    Never,
    /// Stops once this much wall time has passed since `start()`.
    Time(Duration),
    /// Stops after this many recorded iterations.
    Iterations(u64),
    /// Stops as soon as any of the rules does.
    AnyOf(Vec<Termination>),
}

impl Termination {
    /// A wall-time budget in seconds (negative or NaN budgets are treated as zero).
    pub fn time(seconds: f64) -> Self {
        Termination::Time(Duration::from_secs_f64(if seconds > 0.0 {
            seconds.min(1e9)
        } else {
            0.0
        }))
    }

    /// An iteration budget.
    pub fn iterations(n: u64) -> Self {
        Termination::Iterations(n)
    }

    /// Either of two optional budgets; `Never` when both are absent.
    pub fn from_budgets(time_limit_s: Option<f64>, max_iterations: Option<u64>) -> Self {
        let rules: Vec<_> = time_limit_s
            .map(Termination::time)
            .into_iter()
            .chain(max_iterations.map(Termination::iterations))
            .collect();
        rules.into_iter().fold(Termination::Never, |acc, r| acc | r)
    }

    /// True when the rule depends on wall time (results may then vary between runs).
    pub fn uses_time(&self) -> bool {
        match self {
            Termination::Time(_) => true,
            Termination::AnyOf(rules) => rules.iter().any(Termination::uses_time),
            _ => false,
        }
    }

    /// Starts the clock and the iteration counter (no run deadline).
    pub fn start(&self) -> TerminationClock<'_> {
        TerminationClock {
            rule: self,
            started: Instant::now(),
            iterations: 0,
            deadline: None,
        }
    }

    /// [`start`](Self::start) within a run's `deadline`: the clock also says stop once
    /// the deadline has passed.
    pub fn start_within<'a>(&'a self, deadline: &'a Deadline) -> TerminationClock<'a> {
        TerminationClock {
            deadline: Some(deadline),
            ..self.start()
        }
    }

    fn is_done_at(&self, elapsed: Duration, iterations: u64) -> bool {
        match self {
            Termination::Never => false,
            Termination::Time(budget) => elapsed >= *budget,
            Termination::Iterations(budget) => iterations >= *budget,
            Termination::AnyOf(rules) => rules.iter().any(|r| r.is_done_at(elapsed, iterations)),
        }
    }
}

impl BitOr for Termination {
    type Output = Termination;

    fn bitor(self, rhs: Termination) -> Termination {
        match (self, rhs) {
            (Termination::Never, r) | (r, Termination::Never) => r,
            (Termination::AnyOf(mut a), Termination::AnyOf(b)) => {
                a.extend(b);
                Termination::AnyOf(a)
            }
            (Termination::AnyOf(mut a), r) | (r, Termination::AnyOf(mut a)) => {
                a.push(r);
                Termination::AnyOf(a)
            }
            (a, b) => Termination::AnyOf(vec![a, b]),
        }
    }
}

/// A running termination rule: counts iterations and measures time since its start.
#[derive(Clone, Debug)]
pub struct TerminationClock<'a> {
    rule: &'a Termination,
    started: Instant,
    iterations: u64,
    deadline: Option<&'a Deadline>,
}

impl TerminationClock<'_> {
    /// Records one iteration.
    pub fn tick(&mut self) {
        self.iterations += 1;
    }

    /// Records `n` iterations.
    pub fn add_iterations(&mut self, n: u64) {
        self.iterations += n;
    }

    /// Iterations recorded so far.
    pub fn iterations(&self) -> u64 {
        self.iterations
    }

    /// Time since the start.
    pub fn elapsed(&self) -> Duration {
        self.started.elapsed()
    }

    /// True once the rule says stop, or the run's deadline (when started within one)
    /// has passed.
    pub fn is_done(&self) -> bool {
        if self.deadline.is_some_and(Deadline::passed) {
            return true;
        }
        // Avoid reading the clock for pure iteration budgets.
        let elapsed = if self.rule.uses_time() {
            self.started.elapsed()
        } else {
            Duration::ZERO
        };
        self.rule.is_done_at(elapsed, self.iterations)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iteration_budget_stops_exactly() {
        let rule = Termination::iterations(3);
        let mut clock = rule.start();
        let mut n = 0;
        while !clock.is_done() {
            clock.tick();
            n += 1;
        }
        assert_eq!(n, 3);
    }

    #[test]
    fn either_of_stops_at_the_first() {
        let rule = Termination::time(0.0) | Termination::iterations(1_000_000);
        assert!(rule.start().is_done());
        let rule = Termination::time(1e6) | Termination::iterations(2);
        let mut clock = rule.start();
        assert!(!clock.is_done());
        clock.add_iterations(2);
        assert!(clock.is_done());
        assert!(rule.uses_time());
    }

    #[test]
    fn a_clock_started_within_a_deadline_stops_at_it() {
        let rule = Termination::iterations(1_000);
        let deadline = Deadline::after(0.0);
        assert!(rule.start_within(&deadline).is_done());
        assert!(!rule.start().is_done(), "another clock does not see it");
        assert!(!rule.start_within(&Deadline::new()).is_done());
    }

    #[test]
    fn never_is_the_identity_of_either_of() {
        assert_eq!(
            Termination::Never | Termination::iterations(4),
            Termination::iterations(4)
        );
        assert_eq!(Termination::from_budgets(None, None), Termination::Never);
        assert!(!Termination::Never.start().is_done());
        assert_eq!(
            Termination::from_budgets(Some(1.0), Some(5)),
            Termination::AnyOf(vec![Termination::time(1.0), Termination::iterations(5)])
        );
    }
}
