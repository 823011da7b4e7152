//! SMUG worlds: where the maps and the mission come from.
//!
//! Plugins: `flat` (a flat floor with box obstacles and a mission written in the config).

#![warn(missing_docs)]

pub mod flat;
pub mod mission_file;

pub use mission_file::{load_mission, MissionFileError};
