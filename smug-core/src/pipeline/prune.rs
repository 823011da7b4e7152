//! The mission without the PoIs the validity checker rejects.

use crate::error::{Error, Result};
use crate::mission::Mission;
use crate::pose::Pose2;
use crate::stages::StateValidityChecker;

/// A PoI left out of the mission.
#[derive(Clone, Debug, PartialEq)]
pub struct DroppedPoi {
    /// Target id.
    pub target: String,
    /// Index of the PoI in the target's list.
    pub index: usize,
    /// The PoI.
    pub pose: Pose2,
}

/// The mission without invalid PoIs. An invalid start or end, or a target left with
/// no valid PoI, is an error that names it.
pub fn prune_mission(
    mission: &Mission,
    checker: &dyn StateValidityChecker,
) -> Result<(Mission, Vec<DroppedPoi>)> {
    let describe = |p: &Pose2| format!("({:.3}, {:.3}, yaw {:.3})", p.x, p.y, p.yaw);
    if !checker.is_valid(&mission.start) {
        return Err(Error::InvalidInput(format!(
            "the start pose {} is not valid for the robot (in collision, untraversable or off the map)",
            describe(&mission.start)
        )));
    }
    if let Some(end) = mission.end.filter(|e| !checker.is_valid(e)) {
        return Err(Error::InvalidInput(format!(
            "the end pose {} is not valid for the robot (in collision, untraversable or off the map)",
            describe(&end)
        )));
    }
    let mut pruned = mission.clone();
    let mut dropped = Vec::new();
    for target in &mut pruned.targets {
        let mut index = 0;
        target.pois.retain(|pose| {
            let keep = checker.is_valid(pose);
            if !keep {
                dropped.push(DroppedPoi {
                    target: target.id.clone(),
                    index,
                    pose: *pose,
                });
            }
            index += 1;
            keep
        });
        if target.pois.is_empty() {
            return Err(Error::InvalidInput(format!(
                "target `{}` has no valid pose of interest: all {index} PoIs are in collision, \
                 untraversable or off the map",
                target.id
            )));
        }
    }
    Ok((pruned, dropped))
}
