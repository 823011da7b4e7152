//! The single-depot mTSP of the routing literature as a team problem: `m` identical
//! robots starting and ending at node 0 (TSPLIB's node 1), every other node a target.

use crate::tsplib::TsplibInstance;
use smug_core::{
    CostMatrix, RouteSize, TeamError, TeamObjective, TeamProblem, TeamRobot, TeamTarget,
};
use std::sync::Arc;

/// Which distances an mTSP instance uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MtspDistance {
    /// Unrounded Euclidean distances from the coordinates (mTSPLib, He & Hao, SKCP); for
    /// `ATT` files TSPLIB's pseudo-Euclidean distance unrounded, `√((dx² + dy²) / 10)`,
    /// as the He & Hao set's att532 values use.
    Euclid,
    /// The file's own TSPLIB distances (integer, rounded as TSPLIB defines them).
    Tsplib,
}

/// Why an mTSP instance cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MtspError {
    /// Unrounded Euclidean distances asked of a file without coordinates.
    #[error("{0}: has no NODE_COORD_SECTION, so no unrounded Euclidean distances (use the tsplib distance)")]
    NoCoordinates(String),
    /// The team problem is invalid (no robot, size bounds, …).
    #[error(transparent)]
    Team(#[from] TeamError),
}

/// The instance's cost matrix for `distance`.
pub fn mtsp_costs(
    instance: &TsplibInstance,
    distance: MtspDistance,
) -> Result<CostMatrix, MtspError> {
    match distance {
        MtspDistance::Tsplib => Ok(instance.costs.clone()),
        MtspDistance::Euclid => {
            let coords = instance
                .coords
                .as_ref()
                .ok_or_else(|| MtspError::NoCoordinates(instance.name.clone()))?;
            let scale = if instance.weights == "ATT" { 10.0 } else { 1.0 };
            let euclid = |i: usize, j: usize| {
                let (a, b) = (coords[i], coords[j]);
                (((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)) / scale).sqrt()
            };
            CostMatrix::from_fn(coords.len(), euclid)
                .map_err(|e| MtspError::NoCoordinates(format!("{}: {e}", instance.name)))
        }
    }
}

/// `salesmen` robots at depot node 0 sharing `costs`; nodes `1..n` are the targets
/// (target `t` is node `t + 1`).
pub fn mtsp_problem(
    costs: CostMatrix,
    salesmen: usize,
    objective: TeamObjective,
    route_size: Option<RouteSize>,
) -> Result<TeamProblem, MtspError> {
    let costs = Arc::new(costs);
    let robots = (0..salesmen)
        .map(|_| TeamRobot {
            costs: costs.clone(),
            start: 0,
            end: 0,
        })
        .collect();
    let targets = (1..costs.len())
        .map(|node| TeamTarget {
            nodes: vec![node],
            robots: None,
        })
        .collect();
    Ok(TeamProblem::new(robots, targets, objective, route_size)?)
}
