//! The validity checks LazyPRM*'s searches and post-processing run, counted and timed.

use crate::roadmap::memo::{CheckMemo, MemoEvaluator};
use crate::roadmap::{Evaluator, Roadmap, Validity};
use smug_core::{Counter, TimeBreakdown};
use smug_core::{MotionCheck, MotionValidator, Pose2, StateValidityChecker};
use std::time::Instant;

/// Counters kept across queries.
#[derive(Clone, Debug, Default)]
pub(super) struct Counts {
    pub(super) queries: u64,
    pub(super) samples: u64,
    pub(super) vertex_checks: u64,
    pub(super) edge_checks: u64,
    pub(super) searches: u64,
    /// Attempts answered by repairing the previous search.
    pub(super) repairs: u64,
    /// Queries answered "no path" at once: an endpoint was cut off.
    pub(super) cut_off_queries: u64,
    /// Queries answered "no path exists" at once: the endpoints lie in different
    /// components of the free cells (a disc on a grid).
    pub(super) proved_no_path: u64,
    pub(super) breakdown: TimeBreakdown,
}

/// A state check, counted and timed as vertex checking.
pub(super) fn timed_state_check(
    states: &dyn StateValidityChecker,
    counts: &mut Counts,
    state: &Pose2,
) -> bool {
    let started = Instant::now();
    let valid = states.is_valid(state);
    counts.vertex_checks += 1;
    counts.breakdown.vertex_checking_s += started.elapsed().as_secs_f64();
    valid
}

/// A motion validator that counts and times the checks made through it (those of
/// path post-processing, booked as edge checks).
pub(super) struct CountedMotions<'a> {
    pub(super) inner: &'a dyn MotionValidator,
    pub(super) checks: Counter,
    pub(super) nanoseconds: Counter,
}

impl<'a> CountedMotions<'a> {
    pub(super) fn new(inner: &'a dyn MotionValidator) -> Self {
        Self {
            inner,
            checks: Counter::new(),
            nanoseconds: Counter::new(),
        }
    }

    fn timed<T>(&self, check: impl FnOnce() -> T) -> T {
        self.checks.increment();
        timed_into(&self.nanoseconds, check)
    }
}

impl MotionValidator for CountedMotions<'_> {
    fn is_valid_motion(&self, a: &Pose2, b: &Pose2) -> bool {
        self.timed(|| self.inner.is_valid_motion(a, b))
    }

    fn is_valid_motion_between_valid(&self, a: &Pose2, b: &Pose2) -> bool {
        self.timed(|| self.inner.is_valid_motion_between_valid(a, b))
    }

    fn check_motion(&self, a: &Pose2, b: &Pose2) -> MotionCheck {
        self.timed(|| self.inner.check_motion(a, b))
    }

    fn check_states(&self, a: &Pose2, b: &Pose2) -> Option<Vec<Pose2>> {
        self.inner.check_states(a, b)
    }

    fn states_valid_between_valid(&self, states: &[Pose2]) -> bool {
        self.timed(|| self.inner.states_valid_between_valid(states))
    }
}

/// The checks the searches run, with their counters.
pub(super) struct Checks<'a> {
    pub(super) states: &'a dyn StateValidityChecker,
    pub(super) motions: &'a dyn MotionValidator,
    pub(super) counts: &'a mut Counts,
}

impl Evaluator for Checks<'_> {
    fn vertex(&mut self, map: &mut Roadmap, v: u32) -> bool {
        match map.vertex_validity(v) {
            Validity::Valid => true,
            Validity::Invalid => false,
            Validity::Unknown => {
                let valid = timed_state_check(self.states, self.counts, map.pose(v));
                if valid {
                    map.mark_vertex_valid(v);
                } else {
                    map.remove_vertex(v);
                }
                valid
            }
        }
    }

    fn edge(&mut self, map: &mut Roadmap, e: u32) -> bool {
        let edge = *map.edge(e);
        match edge.validity {
            Validity::Valid => true,
            Validity::Invalid => false,
            Validity::Unknown => {
                let started = Instant::now();
                let valid = self
                    .motions
                    .is_valid_motion(map.pose(edge.a), map.pose(edge.b));
                self.counts.edge_checks += 1;
                self.counts.breakdown.edge_checking_s += started.elapsed().as_secs_f64();
                if valid {
                    map.mark_edge_valid(e);
                } else {
                    map.remove_edge(e);
                }
                valid
            }
        }
    }
}

/// Checks and their time, added up by searches side by side.
#[derive(Default)]
pub(super) struct Tally {
    vertex_checks: Counter,
    edge_checks: Counter,
    vertex_nanoseconds: Counter,
    edge_nanoseconds: Counter,
}

impl Tally {
    /// Adds the counts and times to `counts`; returns the checking time in seconds.
    pub(super) fn book(&self, counts: &mut Counts) -> f64 {
        counts.vertex_checks += self.vertex_checks.total();
        counts.edge_checks += self.edge_checks.total();
        let vertex_s = self.vertex_nanoseconds.total() as f64 * 1e-9;
        let edge_s = self.edge_nanoseconds.total() as f64 * 1e-9;
        counts.breakdown.vertex_checking_s += vertex_s;
        counts.breakdown.edge_checking_s += edge_s;
        vertex_s + edge_s
    }
}

/// Runs `check`, adding its time to `nanoseconds`.
fn timed_into<T>(nanoseconds: &Counter, check: impl FnOnce() -> T) -> T {
    let started = Instant::now();
    let result = check();
    let elapsed = started.elapsed().as_nanos().min(u128::from(u64::MAX)) as u64;
    nanoseconds.add(elapsed);
    result
}

/// The checks searches on a roadmap held still make through a shared memo: each
/// element counted once (by the search that remembered it), every check timed.
pub(super) struct MemoChecks<'a> {
    pub(super) memo: &'a CheckMemo,
    pub(super) states: &'a dyn StateValidityChecker,
    pub(super) motions: &'a dyn MotionValidator,
    pub(super) tally: &'a Tally,
}

impl MemoEvaluator for MemoChecks<'_> {
    fn vertex(&mut self, map: &Roadmap, v: u32) -> bool {
        let tally = self.tally;
        self.memo.vertex(
            map,
            v,
            || {
                timed_into(&tally.vertex_nanoseconds, || {
                    self.states.is_valid(map.pose(v))
                })
            },
            || {
                tally.vertex_checks.increment();
            },
        )
    }

    fn edge(&mut self, map: &Roadmap, e: u32) -> bool {
        let tally = self.tally;
        self.memo.edge(
            map,
            e,
            || {
                // The edge's ends are read only when it is checked: known edges are
                // answered from the roadmap's compact validity copy.
                let edge = *map.edge(e);
                timed_into(&tally.edge_nanoseconds, || {
                    self.motions
                        .is_valid_motion(map.pose(edge.a), map.pose(edge.b))
                })
            },
            || {
                tally.edge_checks.increment();
            },
        )
    }
}
