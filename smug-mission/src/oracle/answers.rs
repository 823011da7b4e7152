//! What the oracle answers and keeps: a planned path per pose pair, the oracle's
//! counters, and answers kept between missions (re-checked near world changes).

use serde::{Deserialize, Serialize};
use smug_core::path::Path;
use smug_core::pose::{Pose2, PoseBits};
use smug_core::space::StateSpace;
use smug_core::stages::{Budget, ChangedDisc, MotionValidator, NoPathReason, PlannerOutcome};
use std::collections::HashMap;
use std::sync::Arc;

/// The oracle's answer for a pair of poses.
#[derive(Clone, Debug, PartialEq)]
pub struct PlannedPath {
    /// What the planner returned (paths oriented from the asked `i` to `j`).
    pub outcome: PlannerOutcome,
    /// The exact path's cost, `INFINITY` when there is none.
    pub cost: f64,
}

impl PlannedPath {
    /// The answer `outcome`, costed by its exact path (`INFINITY` when it has none).
    pub fn new(outcome: PlannerOutcome) -> Self {
        let cost = outcome.exact_path().map_or(f64::INFINITY, |p| p.cost);
        Self { outcome, cost }
    }

    /// The exact path, if the pair is connected.
    pub fn path(&self) -> Option<&Path> {
        self.outcome.exact_path()
    }

    pub(super) fn reversed(&self) -> Self {
        let outcome = match &self.outcome {
            PlannerOutcome::Exact(path) => PlannerOutcome::Exact(path.reversed()),
            // An approximate path ends short of the goal: it does not reverse into one
            // from the other end, and it is not a path between the pair anyway.
            PlannerOutcome::Approximate { .. } => {
                PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::Unspecified))
            }
            PlannerOutcome::InvalidStart => PlannerOutcome::InvalidGoal,
            PlannerOutcome::InvalidGoal => PlannerOutcome::InvalidStart,
            PlannerOutcome::NoPath(reason) => PlannerOutcome::NoPath(*reason),
        };
        Self {
            outcome,
            cost: self.cost,
        }
    }
}

/// Oracle counters.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct OracleStats {
    /// Calls to the point-to-point planner.
    pub paths_planned: u64,
    /// Answers served from the cache.
    pub cache_hits: u64,
    /// Pairs served from the [`KnownAnswers`] of earlier missions, without planning.
    #[serde(default)]
    pub known_hits: u64,
}

/// Exact paths between poses kept from earlier missions (the memory of a
/// [`MissionSession`](crate::MissionSession)), keyed by the poses' bits, so that an answer is
/// found again whatever index the poses get in the next mission's oracle.
#[derive(Clone, Debug, Default)]
pub struct KnownAnswers {
    paths: HashMap<(PoseBits, PoseBits), Arc<PlannedPath>>,
}

impl KnownAnswers {
    /// Number of pose pairs (each direction counts).
    pub fn len(&self) -> usize {
        self.paths.len()
    }

    /// True when nothing is known.
    pub fn is_empty(&self) -> bool {
        self.paths.is_empty()
    }

    /// The known path from `a` to `b`, if any.
    pub fn get(&self, a: &Pose2, b: &Pose2) -> Option<&Arc<PlannedPath>> {
        self.paths.get(&((*a).into(), (*b).into()))
    }

    /// Keeps `planned` as the answer from `a` to `b` when it is an exact path.
    pub fn insert(&mut self, a: &Pose2, b: &Pose2, planned: Arc<PlannedPath>) {
        if planned.path().is_some() {
            self.paths.insert(((*a).into(), (*b).into()), planned);
        }
    }

    /// Checks again, with `motions` (built for the updated world), every path with a
    /// state in one of `changed` or a motion that may pass through one (see
    /// [`ChangedDisc::may_touch`]): kept if every motion is still valid, dropped if not.
    /// Returns `(checked, dropped)`.
    pub fn recheck_touched(
        &mut self,
        space: &dyn StateSpace,
        changed: &[ChangedDisc],
        motions: &dyn MotionValidator,
    ) -> (usize, usize) {
        if changed.is_empty() {
            return (0, 0);
        }
        let (mut checked, before) = (0, self.paths.len());
        self.paths.retain(|_, planned| {
            let Some(path) = planned.path() else {
                return false;
            };
            let inside = path
                .states
                .iter()
                .any(|s| changed.iter().any(|d| d.contains(s)));
            let crossing = path.states.windows(2).any(|w| {
                let length = space.motion_extent(&w[0], &w[1]).length;
                changed.iter().any(|d| d.may_touch(&w[0], &w[1], length))
            });
            if !(inside || crossing) {
                return true;
            }
            checked += 1;
            match path.states.as_slice() {
                [only] => motions.is_valid_motion(only, only),
                states => states
                    .windows(2)
                    .all(|w| motions.is_valid_motion(&w[0], &w[1])),
            }
        });
        (checked, before - self.paths.len())
    }
}
