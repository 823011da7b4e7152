//! Motion validity stage: is the space's local motion between two poses (a straight SE(2)
//! motion, or a car's curve) safe?

use crate::pose::Pose2;

/// Result of a motion check.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MotionCheck {
    /// The whole motion is valid.
    Valid,
    /// The motion is invalid; `last_valid` is the last valid state before the first
    /// invalid one and its fraction along the motion, when known.
    Invalid {
        /// Last valid state and its fraction in `[0, 1)`.
        last_valid: Option<(Pose2, f64)>,
    },
}

impl MotionCheck {
    /// True for [`MotionCheck::Valid`].
    pub fn is_valid(&self) -> bool {
        matches!(self, MotionCheck::Valid)
    }
}

/// Decides whether the robot may take the space's local motion (straight, or a car's
/// curve) from one pose to another.
pub trait MotionValidator: Send + Sync {
    /// True when the motion `a → b` is valid (both endpoints included). Fast: checks
    /// in whatever order finds collisions soonest.
    fn is_valid_motion(&self, a: &Pose2, b: &Pose2) -> bool;

    /// [`is_valid_motion`](Self::is_valid_motion) for a caller that knows both
    /// endpoints valid (it asked the pipeline's state checker): the validator may skip
    /// them. A lattice planner, whose poses are each the end of many motions, asks this.
    fn is_valid_motion_between_valid(&self, a: &Pose2, b: &Pose2) -> bool {
        self.is_valid_motion(a, b)
    }

    /// Checks the motion `a → b` in order from `a`, reporting the last valid state
    /// before the first invalid one.
    fn check_motion(&self, a: &Pose2, b: &Pose2) -> MotionCheck;

    /// The states, ends included, that the validator checks along `a → b` when its
    /// verdict is theirs alone (a fixed set of states at its resolution, from `a` to
    /// `b`), so that a caller whose motions are translated copies of one another (a
    /// lattice's primitives) can compute them once and translate them; `None` (the
    /// default) when the validator checks motions otherwise.
    fn check_states(&self, a: &Pose2, b: &Pose2) -> Option<Vec<Pose2>> {
        let _ = (a, b);
        None
    }

    /// The verdict of [`is_valid_motion_between_valid`](Self::is_valid_motion_between_valid)
    /// on the motion through `states`: those [`check_states`](Self::check_states) gives
    /// for it (possibly translated), its two ends known valid. The default asks for the
    /// motion between the first and the last state (`true` for none).
    fn states_valid_between_valid(&self, states: &[Pose2]) -> bool {
        match (states.first(), states.last()) {
            (Some(a), Some(b)) => self.is_valid_motion_between_valid(a, b),
            _ => true,
        }
    }

    /// Counters accumulated so far.
    fn counters(&self) -> super::Counters {
        super::Counters::new()
    }
}
