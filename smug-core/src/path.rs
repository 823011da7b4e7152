//! Paths: sequences of SE(2) states with their cost.

use crate::objective::Objective;
use crate::pose::Pose2;
use serde::{Deserialize, Serialize};

/// A path in SE(2): states joined by the space's local motions, and its cost under the
/// planning objective.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Path {
    /// States from start to goal.
    pub states: Vec<Pose2>,
    /// Sum of the objective's motion costs over consecutive states.
    pub cost: f64,
}

impl Path {
    /// A path through `states`, its cost computed with `objective`.
    pub fn new(states: Vec<Pose2>, objective: &dyn Objective) -> Self {
        let cost = objective.path_cost(&states);
        Self { states, cost }
    }

    /// The same path traversed backwards (same cost under a symmetric objective and space;
    /// the caller decides whether that holds).
    pub fn reversed(&self) -> Self {
        let mut states = self.states.clone();
        states.reverse();
        Self {
            states,
            cost: self.cost,
        }
    }

    /// First state, if any.
    pub fn start(&self) -> Option<&Pose2> {
        self.states.first()
    }

    /// Last state, if any.
    pub fn goal(&self) -> Option<&Pose2> {
        self.states.last()
    }
}
