//! Missions from TOML or JSON files.

use smug_core::Mission;
use std::path::Path;

/// Why a mission file could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum MissionFileError {
    /// The file could not be read.
    #[error("{path}: cannot read mission: {source}")]
    Read {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// The file is not a valid mission.
    #[error("{path}: invalid mission: {message}")]
    Parse {
        /// The file.
        path: String,
        /// The parser's message (with line and column).
        message: String,
    },
    /// The mission is inconsistent.
    #[error("{path}: {source}")]
    Invalid {
        /// The file.
        path: String,
        /// What is wrong.
        source: smug_core::mission::MissionError,
    },
}

/// Loads a mission from `path`: JSON when the extension is `.json`, TOML otherwise.
pub fn load_mission(path: &Path) -> Result<Mission, MissionFileError> {
    let shown = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| MissionFileError::Read {
        path: shown.clone(),
        source,
    })?;
    let parse = |message: String| MissionFileError::Parse {
        path: shown.clone(),
        message,
    };
    let mission: Mission = if path.extension().is_some_and(|e| e == "json") {
        serde_json::from_str(&text).map_err(|e| parse(e.to_string()))?
    } else {
        toml::from_str(&text).map_err(|e| parse(e.to_string().trim().replace('\n', " ")))?
    };
    mission
        .validate()
        .map_err(|source| MissionFileError::Invalid {
            path: shown,
            source,
        })?;
    Ok(mission)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loads_toml_and_json_and_reports_errors() {
        let dir = std::env::temp_dir().join(format!("smug-mission-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let toml_path = dir.join("m.toml");
        std::fs::write(
            &toml_path,
            "start = { x = 1.0, y = 2.0 }\n[[targets]]\nid = \"a\"\nposition = { x = 3.0, y = 2.0 }\npois = [{ x = 2.0, y = 2.0 }]\n",
        )
        .unwrap();
        let mission = load_mission(&toml_path).unwrap();
        let json_path = dir.join("m.json");
        std::fs::write(&json_path, serde_json::to_string(&mission).unwrap()).unwrap();
        assert_eq!(load_mission(&json_path).unwrap(), mission);

        std::fs::write(&toml_path, "start = { x = 1.0 }\n").unwrap();
        let err = load_mission(&toml_path).unwrap_err().to_string();
        assert!(err.contains("missing field `y`"), "{err}");
        assert!(load_mission(&dir.join("absent.toml")).is_err());
        std::fs::remove_dir_all(&dir).ok();
    }
}
