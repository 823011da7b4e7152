//! How a mission is planned: the plan options and their modes.

use serde::{Deserialize, Serialize};

/// Which pose stands in for a target when the visiting order is computed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Representative {
    /// The PoI nearest the target's centre.
    #[default]
    NearestPoi,
    /// The target's first PoI.
    FirstPoi,
}

/// How the sequencer's ToI cost matrix is filled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SequencingCosts {
    /// Plan only the legs the tour uses: solve on lower bounds (straight-line metric
    /// costs, or the planner's own where it has tighter ones: the lattice's go around
    /// obstacles) where no path is planned yet, plan the tour's unplanned legs (as the
    /// rows of a matrix that only orders targets), repeat until
    /// the tour uses planned legs only. With an exact solver the order is optimal for
    /// the planned costs, as with the full matrix, from far fewer paths (IDP's idea
    /// applied to sequencing). With `refine_legs`, legs planned on a sparser roadmap
    /// are planned again where they decide the order, until it is optimal even if every
    /// leg not planned twice fell to its lower bound.
    #[default]
    Lazy,
    /// `Lazy` without planning legs again for the order (faster; on a roadmap that
    /// grows during the run the order can be a little worse than the full matrix's).
    LazyUnsettled,
    /// Plan a path between every pair of representatives (the paper's way). A
    /// `smug_mission::MissionSession`'s replans serve the pairs it kept paths
    /// for and fill the others lazily (only the pairs the tour uses are planned).
    Full,
}

/// Whether the order and the PoIs are chosen one after the other or together.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlanMode {
    /// The paper's way: the target order from representative poses (sequencer), then
    /// one PoI per target along it (selector).
    #[default]
    Sequential,
    /// Order and PoIs together: a generalized TSP over every PoI with lazy path costs,
    /// solved by the sequencer's `solve_clusters` (a GTSP solver, e.g. `gtsp-lns` or
    /// `gtsp-exact`); the selector is not used.
    Joint,
}

/// How the mission is run (the config's `[plan]` section).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlanOptions {
    /// The pose that stands in for each target when sequencing.
    pub representative: Representative,
    /// Leave out targets none of whose PoIs can be reached (and say so) instead of failing.
    pub skip_unreachable: bool,
    /// Keep the roadmap's headings instead of aligning waypoints with the direction of travel.
    pub keep_headings: bool,
    /// How the sequencer's cost matrix is filled: `"lazy"` (default) or `"full"`.
    pub sequencing_costs: SequencingCosts,
    /// `"sequential"` (default: order, then PoIs) or `"joint"` (both at once, GTSP).
    pub mode: PlanMode,
    /// Seconds from the start of the run (world building included) after which anytime
    /// searches stop with their best result and path queries search only the roadmap
    /// built so far; nothing is planned after a grace of a quarter of it (≥ 1 s). `None`:
    /// no deadline. Results then depend on the machine's speed.
    pub deadline: Option<f64>,
    /// Once the route is chosen (either mode), plan each of its legs that costs more
    /// than its lower bound again, on the roadmap as grown since the leg was planned,
    /// and keep the cheaper path. The choice stays optimal for the planned costs: only
    /// its own legs got cheaper.
    pub refine_legs: bool,
}

impl Default for PlanOptions {
    fn default() -> Self {
        Self {
            representative: Representative::default(),
            skip_unreachable: false,
            keep_headings: false,
            sequencing_costs: SequencingCosts::default(),
            mode: PlanMode::default(),
            deadline: None,
            refine_legs: true,
        }
    }
}

impl PlanOptions {
    /// The first option with a value outside its domain: `(key, message)`.
    pub fn invalid_field(&self) -> Option<(&'static str, String)> {
        let deadline = self.deadline?;
        (!(deadline.is_finite() && deadline > 0.0)).then(|| {
            (
                "deadline",
                format!("must be a finite number of seconds > 0, got {deadline}"),
            )
        })
    }
}
