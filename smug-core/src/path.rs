//! Paths: sequences of SE(2) states with their cost.

use crate::metric::{polyline_cost, CostMetric};
use crate::pose::Pose2;
use serde::{Deserialize, Serialize};

/// A piecewise-straight path in SE(2) and its cost under the planning metric.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Path {
    /// States from start to goal.
    pub states: Vec<Pose2>,
    /// Sum of the metric over consecutive states.
    pub cost: f64,
}

impl Path {
    /// A path through `states`, its cost computed with `metric`.
    pub fn new(states: Vec<Pose2>, metric: &dyn CostMetric) -> Self {
        let cost = polyline_cost(metric, &states);
        Self { states, cost }
    }

    /// The same path traversed backwards (same cost under a symmetric metric).
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
