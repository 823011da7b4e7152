//! What a run carries explicitly besides its stages: its deadline, memory limit and
//! progress.

use crate::deadline::Deadline;
use crate::limits::MemoryLimit;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// What a run carries besides its stages: its deadline, its memory limit and its
/// progress. A pipeline owns one and hands it to every stage it builds (through the
/// [`BuildContext`](crate::pipeline::BuildContext)); nothing is process-wide.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunContext {
    /// The run's deadline (unarmed until a run with a deadline starts).
    pub deadline: Deadline,
    /// The largest allocation of one structure.
    pub memory: MemoryLimit,
    /// The running stage and the legs planned so far, for a progress display.
    pub progress: RunProgress,
}

impl RunContext {
    /// A context with a new, unarmed deadline, the memory limit `memory` and progress
    /// at nothing.
    pub fn new(memory: MemoryLimit) -> Self {
        Self {
            deadline: Deadline::new(),
            memory,
            progress: RunProgress::default(),
        }
    }
}

/// A run's progress: the mission stage running, the legs (pose pairs) asked of the
/// planner so far and how many of them are answered. The path oracle counts what it
/// asks; planners that answer many legs in one call count each row as it ends (else
/// the batch counts as answered when it returns). A handle: clones share one progress,
/// which a display reads from another thread; it never changes what is planned.
#[derive(Clone, Debug, Default)]
pub struct RunProgress(Arc<ProgressCounts>);

#[derive(Debug, Default)]
struct ProgressCounts {
    stage: Mutex<&'static str>,
    asked: AtomicU64,
    answered: AtomicU64,
}

impl PartialEq for RunProgress {
    /// Two handles are equal when they share one progress.
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl RunProgress {
    /// The mission stage now running (`sequencing`, `selection`, …).
    pub fn enter(&self, stage: &'static str) {
        if let Ok(mut now) = self.0.stage.lock() {
            *now = stage;
        }
    }

    /// The stage running ("" before the first).
    pub fn stage(&self) -> &'static str {
        self.0.stage.lock().map(|s| *s).unwrap_or("")
    }

    /// `legs` more legs are asked of the planner; returns the total asked so far.
    pub fn ask(&self, legs: u64) -> u64 {
        self.0.asked.fetch_add(legs, Ordering::Relaxed) + legs
    }

    /// `legs` of the legs asked are answered (a row of a batch ended).
    pub fn answer(&self, legs: u64) {
        self.0.answered.fetch_add(legs, Ordering::Relaxed);
    }

    /// Every leg asked up to a total of `asked` is answered (a batch returned).
    pub fn answered_up_to(&self, asked: u64) {
        self.0.answered.fetch_max(asked, Ordering::Relaxed);
    }

    /// (legs answered, legs asked) so far.
    pub fn legs(&self) -> (u64, u64) {
        let asked = self.0.asked.load(Ordering::Relaxed);
        let answered = self.0.answered.load(Ordering::Relaxed);
        (answered.min(asked), asked)
    }
}
