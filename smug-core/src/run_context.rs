//! What a run carries explicitly besides its stages: its deadline and memory limit.

use crate::deadline::Deadline;
use crate::limits::MemoryLimit;
use std::sync::Arc;

/// Told the number of paths planned so far after each plan (a progress display; it must
/// not change what is planned).
pub type ProgressFn = Arc<dyn Fn(u64) + Send + Sync>;

/// What a run carries besides its stages: its deadline and its memory limit. A
/// pipeline owns one and hands it to every stage it builds (through the
/// [`BuildContext`](crate::pipeline::BuildContext)); nothing is process-wide.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunContext {
    /// The run's deadline (unarmed until a run with a deadline starts).
    pub deadline: Deadline,
    /// The largest allocation of one structure.
    pub memory: MemoryLimit,
}

impl RunContext {
    /// A context with a new, unarmed deadline and the memory limit `memory`.
    pub fn new(memory: MemoryLimit) -> Self {
        Self {
            deadline: Deadline::new(),
            memory,
        }
    }
}
