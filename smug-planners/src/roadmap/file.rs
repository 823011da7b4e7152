//! LazyPRM*'s roadmap saved after a mission and loaded before a replan (`smug plan
//! --save-roadmap`, `smug replan --roadmap`): the roadmap as a planner-independent
//! snapshot (the bytes [`save_roadmap`](smug_core::PointToPointPlanner::save_roadmap)
//! hands out), and the file that stores such bytes (a header line, then the body)
//! with the [`Fingerprint`] the caller supplies of what they were built for.
//!
//! Floats are stored as their IEEE-754 bits, so a loaded roadmap is bit-identical to
//! the saved one.

use serde::{Deserialize, Serialize};
use smug_core::digest::Digest;
use smug_core::{Fingerprint, PoseBits};
use std::path::Path as FsPath;

/// The format name in a roadmap file's header.
pub const ROADMAP_FORMAT: &str = "smug-roadmap";
/// The format version this build writes and reads.
pub const ROADMAP_VERSION: u32 = 1;

/// What is known about a saved vertex or edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CheckStatus {
    /// Not checked yet.
    Unchecked,
    /// Checked: valid.
    Valid,
    /// Checked: invalid.
    Invalid,
}

/// A saved roadmap vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SavedVertex {
    /// Its pose.
    pub pose: PoseBits,
    /// Its check status.
    pub status: CheckStatus,
}

/// A saved roadmap edge between two vertices (by index).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SavedEdge {
    /// One end (where a directed edge starts).
    pub a: u32,
    /// The other end.
    pub b: u32,
    /// The bits of the cost of `a → b`.
    pub cost: u64,
    /// The bits of the cost of `b → a` (the same as `cost` on a directed roadmap).
    pub cost_back: u64,
    /// Its check status.
    pub status: CheckStatus,
}

/// A query answered during the mission: its endpoints and the path returned.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SavedAnswer {
    /// The query's start.
    pub start: PoseBits,
    /// The query's goal.
    pub goal: PoseBits,
    /// The returned path's states.
    pub states: Vec<PoseBits>,
    /// The bits of the path's cost.
    pub cost: u64,
    /// The bits of the metric distance to the goal of an approximate path (absent:
    /// an exact path).
    pub goal_distance: Option<u64>,
}

/// A planner's roadmap, independent of the planner's own data structures; saved as
/// JSON ([`to_bytes`](Self::to_bytes)).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RoadmapSnapshot {
    /// The planner that built it (a loading planner refuses another's).
    pub planner: String,
    /// Whether each motion and its reverse are separate edges.
    pub directed: bool,
    /// The vertices, in id order.
    pub vertices: Vec<SavedVertex>,
    /// The edges, in id order.
    pub edges: Vec<SavedEdge>,
    /// The answered queries (their paths are reused while no change touches them).
    pub answers: Vec<SavedAnswer>,
}

impl RoadmapSnapshot {
    /// The snapshot as the bytes a planner saves (JSON; `None` only if it cannot be
    /// written, which plain data never is).
    pub fn to_bytes(&self) -> Option<Vec<u8>> {
        serde_json::to_vec(self).ok()
    }

    /// The snapshot saved as `bytes`.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, IncompatibleRoadmap> {
        serde_json::from_slice(bytes).map_err(|e| IncompatibleRoadmap {
            reason: format!("not a roadmap snapshot: {e}"),
        })
    }
}

/// How loading a roadmap (file) failed.
#[derive(Debug, thiserror::Error)]
pub enum RoadmapFileError {
    /// The file could not be read or written.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Not a roadmap file, or its header is damaged.
    #[error("{file}: not a SMUG roadmap file ({reason})")]
    NotARoadmap {
        /// The file.
        file: String,
        /// What is wrong.
        reason: String,
    },
    /// Written by another format version.
    #[error("{file}: roadmap format version {found}, this build reads version {expected}")]
    Version {
        /// The file.
        file: String,
        /// The file's version.
        found: u32,
        /// The version read.
        expected: u32,
    },
    /// Shorter than its header says.
    #[error("{file}: truncated: body of {found} bytes, the header says {expected}")]
    Truncated {
        /// The file.
        file: String,
        /// Bytes found.
        found: usize,
        /// Bytes expected.
        expected: usize,
    },
    /// The body does not match its checksum.
    #[error("{file}: checksum mismatch (the file is damaged)")]
    Checksum {
        /// The file.
        file: String,
    },
    /// Built for another world, robot or config.
    #[error("{file}: built for another {what} (fingerprint {found}, this run's is {expected})")]
    Foreign {
        /// The file.
        file: String,
        /// `world`, `robot` or `config`.
        what: &'static str,
        /// The file's fingerprint of it.
        found: String,
        /// This run's.
        expected: String,
    },
    /// The planner cannot load it.
    #[error("{file}: {reason}")]
    Unusable {
        /// The file.
        file: String,
        /// Why.
        reason: String,
    },
}

/// A roadmap file's header (its first line).
#[derive(Debug, Serialize, Deserialize)]
struct Header {
    format: String,
    version: u32,
    fingerprint: Fingerprint,
    body_bytes: usize,
    checksum: String,
}

/// Writes a planner's saved roadmap (its bytes) with the `fingerprint` of what it was
/// built for to `path` (atomically).
pub fn write_roadmap(
    path: &FsPath,
    saved: &[u8],
    fingerprint: &Fingerprint,
) -> Result<(), RoadmapFileError> {
    let file = path.display().to_string();
    let header = Header {
        format: ROADMAP_FORMAT.into(),
        version: ROADMAP_VERSION,
        fingerprint: fingerprint.clone(),
        body_bytes: saved.len(),
        checksum: Digest::hex_of(saved),
    };
    let mut bytes = serde_json::to_vec(&header).map_err(|e| RoadmapFileError::Unusable {
        file: file.clone(),
        reason: e.to_string(),
    })?;
    bytes.push(b'\n');
    bytes.extend_from_slice(saved);
    smug_core::output::write_atomic(path, &bytes)
        .map_err(|source| RoadmapFileError::Io { file, source })
}

/// Reads the roadmap at `path` (the bytes a planner saved), refusing it unless it is
/// intact, of this version and built for `expected`.
pub fn read_roadmap(path: &FsPath, expected: &Fingerprint) -> Result<Vec<u8>, RoadmapFileError> {
    let file = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| RoadmapFileError::Io {
        file: file.clone(),
        source,
    })?;
    let not_a_roadmap = |reason: String| RoadmapFileError::NotARoadmap {
        file: file.clone(),
        reason,
    };
    let newline = bytes
        .iter()
        .position(|&b| b == b'\n')
        .ok_or_else(|| not_a_roadmap("no header line: empty or truncated".into()))?;
    let header: Header = serde_json::from_slice(&bytes[..newline])
        .map_err(|e| not_a_roadmap(format!("header: {e}")))?;
    if header.format != ROADMAP_FORMAT {
        return Err(not_a_roadmap(format!("format `{}`", header.format)));
    }
    if header.version != ROADMAP_VERSION {
        return Err(RoadmapFileError::Version {
            file,
            found: header.version,
            expected: ROADMAP_VERSION,
        });
    }
    let body = &bytes[newline + 1..];
    if body.len() != header.body_bytes {
        return Err(RoadmapFileError::Truncated {
            file,
            found: body.len(),
            expected: header.body_bytes,
        });
    }
    if Digest::hex_of(body) != header.checksum {
        return Err(RoadmapFileError::Checksum { file });
    }
    let found = &header.fingerprint;
    for (what, f, e) in [
        ("world", &found.world, &expected.world),
        ("robot", &found.robot, &expected.robot),
        ("config", &found.config, &expected.config),
    ] {
        if f != e {
            return Err(RoadmapFileError::Foreign {
                file,
                what,
                found: f.clone(),
                expected: e.clone(),
            });
        }
    }
    serde_json::from_slice::<serde::de::IgnoredAny>(body)
        .map_err(|e| not_a_roadmap(format!("body: {e}")))?;
    Ok(body.to_vec())
}

/// A planner cannot use a snapshot (another planner's, another motion model's, or
/// inconsistent).
#[derive(Debug, thiserror::Error)]
#[error("the roadmap cannot be loaded: {reason}")]
pub struct IncompatibleRoadmap {
    /// Why.
    pub reason: String,
}
