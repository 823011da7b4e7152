//! The mission state a replan starts from: where the robot stands, what it has done,
//! which poses failed and which obstacles appeared (a small TOML file, every key
//! checked; see `docs/replanning.md`).

use super::obstacles::DiscObstacle;
use super::Mission;
use crate::pose::{Bounds2, Pose2};
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::path::Path;

/// Where the mission stands when it is replanned.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MissionState {
    /// The robot's pose now, `[x, y, yaw]`.
    pub pose: [f64; 3],
    /// Ids of the targets already inspected (never visited again).
    #[serde(default)]
    pub visited: Vec<String>,
    /// `[target id, PoI index]` pairs the robot could not inspect from (excluded).
    #[serde(default)]
    pub failed_pois: Vec<(String, usize)>,
    /// Obstacles seen since the plan was made.
    #[serde(default)]
    pub obstacles: Vec<DiscObstacle>,
}

/// What is wrong with a mission state: the key and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StateError {
    /// The file could not be read.
    #[error("{path}: cannot read: {message}")]
    Read {
        /// The file.
        path: String,
        /// Why.
        message: String,
    },
    /// The TOML is malformed, a key is unknown, missing or of the wrong type.
    #[error("{path}: {message}")]
    Parse {
        /// The file.
        path: String,
        /// The parser's message (line, column, key).
        message: String,
    },
    /// A key has a value that does not fit the mission or the world.
    #[error("{path}: `{key}`: {message}")]
    Key {
        /// The file.
        path: String,
        /// The key, e.g. `failed_pois[1]`.
        key: String,
        /// What is wrong, with the value.
        message: String,
    },
}

impl MissionState {
    /// The state of a mission that has not begun: at `start`, nothing done or failed.
    pub fn at_start(mission: &Mission) -> Self {
        let s = mission.start;
        Self {
            pose: [s.x, s.y, s.yaw],
            ..Self::default()
        }
    }

    /// The robot's pose.
    pub fn pose(&self) -> Pose2 {
        Pose2::new(self.pose[0], self.pose[1], self.pose[2])
    }

    /// Parses a state from TOML text; `path` names it in errors. A team state
    /// (`[[robots]]`) is refused with a message saying what a robot's state is.
    pub fn from_toml(text: &str, path: &str) -> Result<Self, StateError> {
        if has_top_key(text, "robots") {
            return Err(StateError::Key {
                path: path.into(),
                key: "robots".into(),
                message: "this is a team state, but the config plans for one robot: its \
                          state has the robot's `pose = [x, y, yaw]` instead (see \
                          docs/replanning.md)"
                    .into(),
            });
        }
        parse_toml(text, path)
    }

    /// Reads and parses a state file.
    pub fn from_file(path: &Path) -> Result<Self, StateError> {
        read_toml(path, Self::from_toml)
    }

    /// The state as TOML (what [`MissionState::from_toml`] reads back).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).unwrap_or_default()
    }

    /// Checks every key against the mission (ids, PoI indices) and the map `bounds`
    /// (the pose on the map and outside every obstacle); `path` names the file.
    pub fn check(&self, mission: &Mission, bounds: &Bounds2, path: &str) -> Result<(), StateError> {
        let error = |key: String, message: String| StateError::Key {
            path: path.into(),
            key,
            message,
        };
        self.check_pose(bounds)
            .map_err(|m| error("pose".into(), m.to_string()))?;
        for (k, o) in self.obstacles.iter().enumerate() {
            check_obstacle(o).map_err(|m| error(format!("obstacles[{k}]"), m.to_string()))?;
            if o.contains(self.pose[0], self.pose[1]) {
                let message = format!(
                    "{:?} lies inside obstacles[{k}] (centre {:?}, radius {})",
                    self.pose, o.center, o.radius
                );
                return Err(error("pose".into(), message));
            }
        }
        let target = |id: &str| mission.targets.iter().find(|t| t.id == id);
        let mut visited = BTreeSet::new();
        for (k, id) in self.visited.iter().enumerate() {
            if target(id).is_none() {
                return Err(error(format!("visited[{k}]"), unknown(id, mission)));
            }
            visited.insert(id.as_str());
        }
        for (k, (id, poi)) in self.failed_pois.iter().enumerate() {
            let key = format!("failed_pois[{k}]");
            let Some(t) = target(id) else {
                return Err(error(key, unknown(id, mission)));
            };
            if *poi >= t.pois.len() {
                let message = format!(
                    "PoI index {poi} is out of range: target `{id}` has {} PoIs (0..{})",
                    t.pois.len(),
                    t.pois.len()
                );
                return Err(error(key, message));
            }
            if visited.contains(id.as_str()) {
                let message = format!("target `{id}` is both visited and failed");
                return Err(error(key, message));
            }
        }
        Ok(())
    }

    fn check_pose(&self, bounds: &Bounds2) -> Result<(), BadValue> {
        if !self.pose.iter().all(|v| v.is_finite()) {
            return Err(BadValue::NotFinite(format!("{:?}", self.pose)));
        }
        if !bounds.contains(self.pose[0], self.pose[1]) {
            return Err(BadValue::OffMap {
                pose: self.pose,
                bounds: *bounds,
            });
        }
        Ok(())
    }

    /// Whether PoI `index` of target `id` failed.
    pub fn failed(&self, id: &str, index: usize) -> bool {
        self.failed_pois.iter().any(|(t, k)| t == id && *k == index)
    }
}

/// Parses a state of type `T` from TOML text; `path` names it in errors.
pub(super) fn parse_toml<T: serde::de::DeserializeOwned>(
    text: &str,
    path: &str,
) -> Result<T, StateError> {
    toml::from_str(text).map_err(|e| StateError::Parse {
        path: path.into(),
        message: e.to_string().trim_end().replace('\n', " "),
    })
}

/// Whether a TOML text has the top-level key `key` (false when it does not parse).
pub(super) fn has_top_key(text: &str, key: &str) -> bool {
    toml::from_str::<toml::Table>(text).is_ok_and(|t| t.contains_key(key))
}

/// Reads a state file and parses it with `parse` (given the text and the file's name).
pub(super) fn read_toml<T>(
    path: &Path,
    parse: impl FnOnce(&str, &str) -> Result<T, StateError>,
) -> Result<T, StateError> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| StateError::Read {
        path: name.clone(),
        message: e.to_string(),
    })?;
    parse(&text, &name)
}

/// What is wrong with a pose or an obstacle of a mission state.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
enum BadValue {
    /// A value (shown as written) is not finite.
    #[error("{0} has a non-finite value")]
    NotFinite(String),
    /// The pose lies outside the map.
    #[error(
        "{pose:?} is off the map (x in [{}, {}], y in [{}, {}])",
        bounds.min[0], bounds.max[0], bounds.min[1], bounds.max[1]
    )]
    OffMap {
        /// The pose.
        pose: [f64; 3],
        /// The map.
        bounds: Bounds2,
    },
    /// A size is not a positive number.
    #[error("{what} must be a positive number, got {value}")]
    NotPositive {
        /// `radius` or `height`.
        what: &'static str,
        /// The value.
        value: f64,
    },
}

fn check_obstacle(o: &DiscObstacle) -> Result<(), BadValue> {
    if !(o.center.iter().all(|v| v.is_finite())) {
        return Err(BadValue::NotFinite(format!("center {:?}", o.center)));
    }
    if !(o.radius.is_finite() && o.radius > 0.0) {
        return Err(BadValue::NotPositive {
            what: "radius",
            value: o.radius,
        });
    }
    if !(o.height.is_finite() && o.height > 0.0) {
        return Err(BadValue::NotPositive {
            what: "height",
            value: o.height,
        });
    }
    Ok(())
}

fn unknown(id: &str, mission: &Mission) -> String {
    let known: Vec<&str> = mission.targets.iter().map(|t| t.id.as_str()).collect();
    format!(
        "unknown target id `{id}`; the mission's targets are {}",
        known.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const STATE: &str = r#"
        pose = [2.0, 1.0, 0.5]
        visited = ["a"]
        failed_pois = [["b", 1]]
        [[obstacles]]
        center = [6.0, 6.0]
        radius = 0.5
        height = 1.0
    "#;

    fn mission() -> Mission {
        toml::from_str(
            r#"
            start = { x = 0.0, y = 0.0, yaw = 0.0 }
            [[targets]]
            id = "a"
            position = { x = 2.0, y = 2.0 }
            pois = [{ x = 1.0, y = 2.0, yaw = 0.0 }]
            [[targets]]
            id = "b"
            position = { x = 5.0, y = 2.0 }
            pois = [{ x = 4.0, y = 2.0, yaw = 0.0 }, { x = 6.0, y = 2.0, yaw = 3.0 }]
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

    fn key_of(state: &MissionState) -> String {
        match state.check(&mission(), &bounds(), "s.toml") {
            Err(StateError::Key { key, .. }) => key,
            other => panic!("expected a key error, got {other:?}"),
        }
    }

    #[test]
    fn parses_checks_and_round_trips() {
        let state = MissionState::from_toml(STATE, "s.toml").unwrap();
        assert_eq!(state.failed_pois, vec![("b".to_string(), 1)]);
        assert_eq!(state.obstacles[0].radius, 0.5);
        state.check(&mission(), &bounds(), "s.toml").unwrap();
        assert!(state.failed("b", 1) && !state.failed("b", 0));
        let again = MissionState::from_toml(&state.to_toml(), "s.toml").unwrap();
        assert_eq!(again, state);
    }

    #[test]
    fn unknown_and_missing_keys_are_refused_naming_them() {
        let err = MissionState::from_toml("pose = [0.0, 0.0, 0.0]\nvisted = []", "s.toml");
        assert!(err.unwrap_err().to_string().contains("visted"));
        let err = MissionState::from_toml("visited = []", "s.toml").unwrap_err();
        assert!(err.to_string().contains("pose"), "{err}");
        let bad = STATE.replace("height = 1.0", "height = 1.0\nheigth = 2.0");
        let err = MissionState::from_toml(&bad, "s.toml").unwrap_err();
        assert!(err.to_string().contains("heigth"), "{err}");
    }

    #[test]
    fn each_bad_value_names_its_key() {
        let good = MissionState::from_toml(STATE, "s.toml").unwrap();
        let mut s = good.clone();
        s.pose = [11.0, 1.0, 0.0];
        assert_eq!(key_of(&s), "pose");
        let mut s = good.clone();
        s.pose = [6.2, 6.1, 0.0];
        assert_eq!(key_of(&s), "pose");
        let mut s = good.clone();
        s.visited.push("zz".into());
        assert_eq!(key_of(&s), "visited[1]");
        let mut s = good.clone();
        s.failed_pois.push(("b".into(), 2));
        assert_eq!(key_of(&s), "failed_pois[1]");
        let mut s = good.clone();
        s.failed_pois.push(("a".into(), 0));
        assert_eq!(key_of(&s), "failed_pois[1]");
        let mut s = good.clone();
        s.obstacles[0].radius = -1.0;
        assert_eq!(key_of(&s), "obstacles[0]");
    }
}
