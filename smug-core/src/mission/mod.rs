//! Missions: start, optional end, targets of interest with their poses of interest, and
//! what a run needs to know about it (options, state, obstacles); planning it is
//! `smug-mission`'s.

mod obstacles;
mod options;
mod state;
mod team_state;

pub use obstacles::{add_obstacles, mask_layer, DiscObstacle, MaskedEstimator};
pub use options::{PlanMode, PlanOptions, Representative, SequencingCosts};
pub use state::{MissionState, StateError};
pub use team_state::{RobotState, TeamState};

use crate::pose::{Bounds2, Point3, Pose2};
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;

/// A target of interest (ToI): something to inspect from one of its poses of interest.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Target {
    /// Unique name, used in plans and error messages.
    pub id: String,
    /// Where the target is (its centroid); may lie inside an obstacle.
    pub position: Point3,
    /// Poses of interest (PoIs): the robot inspects the target from any one of them.
    pub pois: Vec<Pose2>,
}

/// The multi-goal task: start at `start`, visit one PoI of every target, end at
/// `end` (or back at `start` when `end` is `None`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mission {
    /// Start pose.
    pub start: Pose2,
    /// End pose of an open path; `None` returns to the start.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub end: Option<Pose2>,
    /// Targets to visit, in no particular order.
    #[serde(default)]
    pub targets: Vec<Target>,
}

/// What is wrong with a mission.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MissionError {
    /// Two targets share an id.
    #[error("target id `{0}` is used twice")]
    DuplicateTargetId(String),
    /// A target has no PoI.
    #[error("target `{0}` has no pose of interest")]
    NoPoses(String),
    /// A pose or position holds NaN or infinity.
    #[error("{0} has a non-finite coordinate")]
    NonFinite(String),
}

impl Mission {
    /// The pose the plan ends at.
    pub fn end_pose(&self) -> Pose2 {
        self.end.unwrap_or(self.start)
    }

    /// Total number of PoIs.
    pub fn poi_count(&self) -> usize {
        self.targets.iter().map(|t| t.pois.len()).sum()
    }

    /// Describes the first pose (start, end, then PoIs in order) outside `bounds`, e.g.
    /// ``"PoI 3 of target `stone-2`"``; `None` when all lie inside.
    pub fn first_pose_outside(&self, bounds: &Bounds2) -> Option<String> {
        let outside = |p: &Pose2| !bounds.contains(p.x, p.y);
        if outside(&self.start) {
            return Some("the start pose".to_string());
        }
        if self.end.as_ref().is_some_and(outside) {
            return Some("the end pose".to_string());
        }
        self.targets.iter().find_map(|t| {
            t.pois
                .iter()
                .position(outside)
                .map(|k| format!("PoI {k} of target `{}`", t.id))
        })
    }

    /// Checks ids are unique, every target has a PoI, all numbers are finite.
    pub fn validate(&self) -> Result<(), MissionError> {
        if !self.start.is_finite() {
            return Err(MissionError::NonFinite("the start pose".into()));
        }
        if self.end.is_some_and(|e| !e.is_finite()) {
            return Err(MissionError::NonFinite("the end pose".into()));
        }
        let mut ids = BTreeSet::new();
        for target in &self.targets {
            if !ids.insert(target.id.as_str()) {
                return Err(MissionError::DuplicateTargetId(target.id.clone()));
            }
            if target.pois.is_empty() {
                return Err(MissionError::NoPoses(target.id.clone()));
            }
            let p = target.position;
            if !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()) {
                return Err(MissionError::NonFinite(format!("target `{}`", target.id)));
            }
            if let Some(k) = target.pois.iter().position(|p| !p.is_finite()) {
                return Err(MissionError::NonFinite(format!(
                    "PoI {k} of target `{}`",
                    target.id
                )));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MISSION: &str = r#"
        start = { x = 0.0, y = 0.0, yaw = 0.0 }
        [[targets]]
        id = "stone-1"
        position = { x = 2.0, y = 1.0 }
        pois = [{ x = 1.0, y = 1.0, yaw = 0.0 }, { x = 3.0, y = 1.0, yaw = 3.14 }]
    "#;

    #[test]
    fn loads_from_toml_and_validates() {
        let m: Mission = toml::from_str(MISSION).unwrap();
        assert_eq!(m.targets[0].pois.len(), 2);
        assert_eq!(m.end_pose(), m.start);
        m.validate().unwrap();
    }

    #[test]
    fn rejects_duplicate_ids_and_empty_targets() {
        let mut m: Mission = toml::from_str(MISSION).unwrap();
        m.targets.push(m.targets[0].clone());
        assert_eq!(
            m.validate(),
            Err(MissionError::DuplicateTargetId("stone-1".into()))
        );
        m.targets[1].id = "b".into();
        m.targets[1].pois.clear();
        assert_eq!(m.validate(), Err(MissionError::NoPoses("b".into())));
    }
}
