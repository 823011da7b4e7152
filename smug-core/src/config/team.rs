//! A team config (`[team]`): the robots of a team mission, each a robot profile with a
//! name and a start pose on the shared world and mission, and who may serve which
//! target. [`LoadedConfig::member`](super::LoadedConfig::member) turns one robot into a
//! whole single-robot config: the shared sections, then the robot's includes, then its
//! inline sections.

use super::source::{KeyPath, KeySegment};
use crate::pose::Pose2;
use crate::stages::TeamObjective;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;

/// The unit a team's robots' costs are compared in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TeamUnit {
    /// Every robot plans with the `time` objective at its own speed (`[robot]
    /// max_speed`, `turn_rate`): sums and makespans in seconds.
    #[default]
    Time,
    /// Every robot keeps its own `[objective]` (costs of different robots are then
    /// only comparable when their objectives are).
    Objective,
}

/// `[team]`: the robots, what the team minimises and who may serve which target.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TeamConfig {
    /// `"sum"` (default: the sum of the robots' costs) or `"makespan"` (the largest).
    #[serde(default = "sum")]
    pub objective: TeamObjective,
    /// The unit of the robots' costs (default `"time"`).
    #[serde(default)]
    pub unit: TeamUnit,
    /// The robots (`[[team.robots]]`).
    #[serde(default)]
    pub robots: Vec<TeamMemberConfig>,
    /// Targets only some robots may serve (`[[team.targets]]`).
    #[serde(default)]
    pub targets: Vec<TargetRestriction>,
}

fn sum() -> TeamObjective {
    TeamObjective::Sum
}

/// One robot of a team: its name, where it starts (and ends), its profile.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TeamMemberConfig {
    /// Unique name, used in plans and error messages.
    pub name: String,
    /// Robot profile file(s), relative to the main config's directory, layered above
    /// the shared sections (e.g. `"robots/rover.toml"`).
    #[serde(default, deserialize_with = "one_or_many")]
    pub include: Vec<String>,
    /// Start pose.
    pub start: Pose2,
    /// End pose; absent: back at the start.
    #[serde(default)]
    pub end: Option<Pose2>,
    /// Inline sections (`robot`, `space`, `objective`, `validity`, `motion`, `planner`,
    /// …), layered above the includes; checked as a whole config by
    /// [`LoadedConfig::member`](super::LoadedConfig::member).
    #[serde(flatten)]
    pub sections: toml::Table,
}

/// A target only the named robots may serve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TargetRestriction {
    /// The target's id in the mission.
    pub id: String,
    /// The robots (names) allowed to serve it.
    pub robots: Vec<String>,
}

fn one_or_many<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<String>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum OneOrMany {
        One(String),
        Many(Vec<String>),
    }
    Ok(match OneOrMany::deserialize(d)? {
        OneOrMany::One(path) => vec![path],
        OneOrMany::Many(paths) => paths,
    })
}

/// The key path `team.robots[k]` (or `team.targets[k]`) joined with `field`.
pub fn team_key(list: &str, k: usize, field: &str) -> KeyPath {
    let mut key = KeyPath::dotted("team").join(list);
    key.0.push(KeySegment::Index(k));
    key.join(field)
}

impl TeamConfig {
    /// The first bad value and why: no robot, two robots of one name, a restriction
    /// naming no robot or one the team does not have, a target restricted twice.
    pub fn invalid_field(&self) -> Option<(KeyPath, String)> {
        if self.robots.is_empty() {
            return Some((
                KeyPath::dotted("team.robots"),
                "a team needs at least one robot ([[team.robots]] with name and start)".into(),
            ));
        }
        let mut names = BTreeSet::new();
        for (k, robot) in self.robots.iter().enumerate() {
            if robot.name.trim().is_empty() {
                return Some((team_key("robots", k, "name"), "must not be empty".into()));
            }
            if !names.insert(robot.name.as_str()) {
                return Some((
                    team_key("robots", k, "name"),
                    format!("robot name `{}` is used twice", robot.name),
                ));
            }
            let bad_pose = !robot.start.is_finite() || robot.end.is_some_and(|e| !e.is_finite());
            if bad_pose {
                return Some((
                    team_key("robots", k, "start"),
                    "the start and end poses must be finite".into(),
                ));
            }
        }
        let mut restricted = BTreeSet::new();
        for (k, restriction) in self.targets.iter().enumerate() {
            if !restricted.insert(restriction.id.as_str()) {
                return Some((
                    team_key("targets", k, "id"),
                    format!("target `{}` is restricted twice", restriction.id),
                ));
            }
            if restriction.robots.is_empty() {
                return Some((
                    team_key("targets", k, "robots"),
                    format!("target `{}` names no robot", restriction.id),
                ));
            }
            if let Some(unknown) = restriction
                .robots
                .iter()
                .find(|r| !names.contains(r.as_str()))
            {
                return Some((
                    team_key("targets", k, "robots"),
                    format!(
                        "target `{}` is restricted to robot `{unknown}`, which the team does \
                         not have (robots: {})",
                        restriction.id,
                        names.iter().copied().collect::<Vec<_>>().join(", ")
                    ),
                ));
            }
        }
        None
    }

    /// The index of the robot called `name`.
    pub fn robot_index(&self, name: &str) -> Option<usize> {
        self.robots.iter().position(|r| r.name == name)
    }
}
