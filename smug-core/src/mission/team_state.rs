//! The state of a team mission under way, for a team replan: what the team has done
//! (visited targets, failed PoIs, obstacles seen) and where each robot is, or that it
//! is lost (its remaining targets go to the others).

use super::obstacles::DiscObstacle;
use super::state::{has_top_key, parse_toml, read_toml, MissionState, StateError};
use super::Mission;
use crate::pose::Bounds2;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::path::Path;

/// A team's mission state (TOML): the shared `visited`, `failed_pois` and
/// `[[obstacles]]` of a [`MissionState`], and one `[[robots]]` entry per robot.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TeamState {
    /// Ids of the targets already inspected, by any robot (never visited again).
    #[serde(default)]
    pub visited: Vec<String>,
    /// `[target id, PoI index]` pairs no robot could inspect from (excluded).
    #[serde(default)]
    pub failed_pois: Vec<(String, usize)>,
    /// Obstacles seen since the plan was made.
    #[serde(default)]
    pub obstacles: Vec<DiscObstacle>,
    /// Every robot of the team, by name: its pose now, or lost.
    #[serde(default)]
    pub robots: Vec<RobotState>,
}

/// One robot of a [`TeamState`].
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotState {
    /// Its name in the team config.
    pub name: String,
    /// Its pose now, `[x, y, yaw]` (needed unless it is lost).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pose: Option<[f64; 3]>,
    /// The robot is lost: it plans nothing, its targets go to the others.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub lost: bool,
}

impl TeamState {
    /// Parses a team state from TOML text; `path` names it in errors. One robot's
    /// state (`pose` and no `[[robots]]`) is refused with a message saying what a team
    /// state is.
    pub fn from_toml(text: &str, path: &str) -> Result<Self, StateError> {
        if !has_top_key(text, "robots") && has_top_key(text, "pose") {
            return Err(StateError::Key {
                path: path.into(),
                key: "pose".into(),
                message: "this is one robot's state, but the config plans for a team: a team \
                          state has `[[robots]]` entries with each robot's `name` and `pose` \
                          (or `lost = true`), see docs/teams.md"
                    .into(),
            });
        }
        parse_toml(text, path)
    }

    /// Reads and parses a team state file.
    pub fn from_file(path: &Path) -> Result<Self, StateError> {
        read_toml(path, Self::from_toml)
    }

    /// The state as TOML (what [`TeamState::from_toml`] reads back).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).unwrap_or_default()
    }

    /// The state of robot `name` (`None`: not listed).
    pub fn robot(&self, name: &str) -> Option<&RobotState> {
        self.robots.iter().find(|r| r.name == name)
    }

    /// Robot `k`'s view of the state: its pose and the shared keys, as one robot's
    /// [`MissionState`] (`None`: the robot is lost or has no pose).
    pub fn robot_state(&self, k: usize) -> Option<MissionState> {
        let robot = self.robots.get(k).filter(|r| !r.lost)?;
        Some(MissionState {
            pose: robot.pose?,
            visited: self.visited.clone(),
            failed_pois: self.failed_pois.clone(),
            obstacles: self.obstacles.clone(),
        })
    }

    /// Checks the state against the team (`names`, in the config's order), the mission
    /// and the map: every robot listed once by a name of the team, with a pose unless
    /// lost, at least one not lost, every pose and shared key as
    /// [`MissionState::check`] checks them; `path` names the file.
    pub fn check(
        &self,
        names: &[String],
        mission: &Mission,
        bounds: &Bounds2,
        path: &str,
    ) -> Result<(), StateError> {
        let error = |key: String, message: String| StateError::Key {
            path: path.into(),
            key,
            message,
        };
        self.check_robots(names).map_err(|(k, m)| error(k, m))?;
        for k in 0..self.robots.len() {
            let Some(state) = self.robot_state(k) else {
                continue;
            };
            state.check(mission, bounds, path).map_err(|e| match e {
                StateError::Key { key, message, .. } if key == "pose" => {
                    error(format!("robots[{k}].pose"), message)
                }
                other => other,
            })?;
        }
        Ok(())
    }

    /// The `[[robots]]` entries against the team's robot names: `(key, message)`.
    fn check_robots(&self, names: &[String]) -> Result<(), (String, String)> {
        let team = || names.join(", ");
        let mut seen = BTreeSet::new();
        for (k, robot) in self.robots.iter().enumerate() {
            if !names.contains(&robot.name) {
                let message = format!(
                    "the team has no robot `{}` (its robots: {})",
                    robot.name,
                    team()
                );
                return Err((format!("robots[{k}].name"), message));
            }
            if !seen.insert(robot.name.as_str()) {
                let message = format!("robot `{}` is listed twice", robot.name);
                return Err((format!("robots[{k}].name"), message));
            }
            if !robot.lost && robot.pose.is_none() {
                let message = format!(
                    "robot `{}` has no pose: give `pose = [x, y, yaw]`, or `lost = true`",
                    robot.name
                );
                return Err((format!("robots[{k}]"), message));
            }
        }
        if let Some(missing) = names.iter().find(|n| !seen.contains(n.as_str())) {
            let message = format!(
                "robot `{missing}` of the team is not listed: every robot needs an entry \
                 with its `pose`, or `lost = true`"
            );
            return Err(("robots".into(), message));
        }
        if self.robots.iter().all(|r| r.lost) {
            let message = "every robot is lost: no robot is left to plan for".to_string();
            return Err(("robots".into(), message));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STATE: &str = r#"
        visited = ["a"]
        [[robots]]
        name = "legged"
        pose = [2.0, 1.0, 0.5]
        [[robots]]
        name = "rover"
        lost = true
    "#;

    fn names() -> Vec<String> {
        vec!["legged".into(), "rover".into()]
    }

    fn mission() -> Mission {
        toml::from_str(
            r#"
            start = { x = 0.0, y = 0.0, yaw = 0.0 }
            [[targets]]
            id = "a"
            position = { x = 2.0, y = 2.0 }
            pois = [{ x = 1.0, y = 2.0, yaw = 0.0 }]
            "#,
        )
        .unwrap()
    }

    fn bounds() -> Bounds2 {
        Bounds2 {
            min: [0.0, 0.0],
            max: [10.0, 10.0],
        }
    }

    fn check(text: &str) -> Result<(), StateError> {
        TeamState::from_toml(text, "s.toml")?.check(&names(), &mission(), &bounds(), "s.toml")
    }

    fn key_of(text: &str) -> String {
        match check(text) {
            Err(StateError::Key { key, .. }) => key,
            other => panic!("expected a key error, got {other:?}"),
        }
    }

    #[test]
    fn a_good_state_reads_back_and_gives_each_robot_its_view() {
        let state = TeamState::from_toml(STATE, "s.toml").unwrap();
        state.check(&names(), &mission(), &bounds(), "s").unwrap();
        assert_eq!(
            TeamState::from_toml(&state.to_toml(), "again").unwrap(),
            state
        );
        assert_eq!(state.robot_state(0).unwrap().pose, [2.0, 1.0, 0.5]);
        assert_eq!(state.robot_state(0).unwrap().visited, vec!["a".to_string()]);
        assert!(state.robot_state(1).is_none(), "a lost robot has no view");
    }

    #[test]
    fn each_kind_of_state_is_refused_for_the_other_naming_its_key() {
        let one = TeamState::from_toml("pose = [1.0, 1.0, 0.0]", "s.toml").unwrap_err();
        assert!(
            matches!(&one, StateError::Key { key, .. } if key == "pose"),
            "{one}"
        );
        assert!(one.to_string().contains("[[robots]]"), "{one}");
        let team = MissionState::from_toml(STATE, "s.toml").unwrap_err();
        assert!(
            matches!(&team, StateError::Key { key, .. } if key == "robots"),
            "{team}"
        );
        assert!(team.to_string().contains("team state"), "{team}");
    }

    #[test]
    fn bad_robot_entries_name_their_key() {
        let unknown = STATE.replace("name = \"rover\"", "name = \"drone\"");
        assert_eq!(key_of(&unknown), "robots[1].name");
        let twice = STATE.replace("name = \"rover\"", "name = \"legged\"");
        assert_eq!(key_of(&twice), "robots[1].name");
        let no_pose = STATE.replace("lost = true", "");
        assert_eq!(key_of(&no_pose), "robots[1]");
        let missing = "[[robots]]\nname = \"legged\"\npose = [1.0, 1.0, 0.0]\n";
        assert_eq!(key_of(missing), "robots");
        let all_lost = STATE.replace("pose = [2.0, 1.0, 0.5]", "lost = true");
        assert_eq!(key_of(&all_lost), "robots");
    }

    #[test]
    fn a_robot_pose_off_the_map_and_shared_keys_are_checked() {
        let off = STATE.replace("[2.0, 1.0, 0.5]", "[20.0, 1.0, 0.5]");
        assert_eq!(key_of(&off), "robots[0].pose");
        let unknown = STATE.replace("visited = [\"a\"]", "visited = [\"z\"]");
        assert_eq!(key_of(&unknown), "visited[0]");
    }
}
