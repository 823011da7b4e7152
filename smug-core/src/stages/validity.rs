//! State validity stage: is the robot safe at this pose?

use crate::pose::Pose2;
use std::collections::BTreeMap;

/// Named counters a stage reports (validity queries, ESDF lookups, …).
pub type Counters = BTreeMap<String, u64>;

/// Decides whether the robot may stand at a pose.
pub trait StateValidityChecker: Send + Sync {
    /// True when the robot at `state` is safe (traversable and collision-free).
    fn is_valid(&self, state: &Pose2) -> bool;

    /// Counters accumulated so far (e.g. `"checks"`, `"esdf_queries"`).
    fn counters(&self) -> Counters {
        Counters::new()
    }
}
