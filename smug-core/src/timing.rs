//! Where a planner's time went.

use serde::{Deserialize, Serialize};

/// Where the point-to-point planning time went (the paper's Table III columns), seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TimeBreakdown {
    /// Graph search.
    pub astar_s: f64,
    /// Drawing samples and connecting them into the roadmap.
    pub sampling_s: f64,
    /// Lazy edge (motion) validation.
    pub edge_checking_s: f64,
    /// Lazy vertex (state) validation.
    pub vertex_checking_s: f64,
    /// Everything else inside the planner.
    pub misc_s: f64,
}

impl TimeBreakdown {
    /// Sum of all parts.
    pub fn total_s(&self) -> f64 {
        self.astar_s + self.sampling_s + self.edge_checking_s + self.vertex_checking_s + self.misc_s
    }

    /// Component-wise sum.
    pub fn add(&mut self, other: &TimeBreakdown) {
        self.astar_s += other.astar_s;
        self.sampling_s += other.sampling_s;
        self.edge_checking_s += other.edge_checking_s;
        self.vertex_checking_s += other.vertex_checking_s;
        self.misc_s += other.misc_s;
    }
}
