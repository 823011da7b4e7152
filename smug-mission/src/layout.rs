//! Where a mission's poses sit in the path oracle.

use crate::oracle::PathOracle;
use smug_core::mission::Mission;

/// Where the mission's poses sit in the oracle.
pub(super) struct Layout {
    pub(super) start: usize,
    pub(super) end: usize,
    /// For each target of the mission, the oracle indices of its PoIs.
    pub(super) pois: Vec<Vec<usize>>,
}

/// Adds the start, the end and every PoI of `mission` to the oracle.
pub(super) fn register_poses(oracle: &mut PathOracle, mission: &Mission) -> Layout {
    let start = oracle.add_pose(mission.start);
    let end = match mission.end {
        Some(end) => oracle.add_pose(end),
        None => start,
    };
    let pois = mission
        .targets
        .iter()
        .map(|t| t.pois.iter().map(|p| oracle.add_pose(*p)).collect())
        .collect();
    Layout { start, end, pois }
}
