//! Team sequencers: which robot serves which target, at which PoI, in which order (the
//! multi-vehicle generalised TSP of [`smug_core::TeamProblem`]), for the sum of the
//! route costs or the makespan.
//!
//! Plugins of the `team_sequencer` stage: `team-exact` (DP, ≤ ~14 targets), `team-lns`
//! (ruin and recreate, any size) and `team-auto` (exact while small). The problem takes
//! one full matrix per robot: a lazy mission layer fills them with bounds and
//! warm-starts each round from the last ([`smug_core::TeamSequencer::solve_from`]).

pub mod auto;
pub mod brute_force;
pub mod exact;
pub mod lns;
pub mod mtsp;

pub use auto::{TeamAuto, TeamAutoParams};
pub use brute_force::{brute_force_team, BRUTE_FORCE_TEAM_MAX_TARGETS};
pub use exact::{TeamExact, TeamExactParams};
pub use lns::{TeamLns, TeamLnsParams};
pub use mtsp::{mtsp_costs, mtsp_problem, MtspDistance, MtspError};
