//! A planner's roadmap saved after a mission and loaded before a replan (`smug plan
//! --save-roadmap`, `smug replan --roadmap`): a planner-independent snapshot, its file
//! format (a header line, then the body) and the fingerprint of what it was built for.
//!
//! Floats are stored as their IEEE-754 bits, so a loaded roadmap is bit-identical to
//! the saved one.

use crate::config::LoadedConfig;
use crate::pose::Pose2;
use crate::world::World;
use serde::{Deserialize, Serialize};
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

/// A pose as the bits of its `x`, `y` and `yaw`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct PoseBits(pub [u64; 3]);

impl From<Pose2> for PoseBits {
    fn from(p: Pose2) -> Self {
        Self([p.x.to_bits(), p.y.to_bits(), p.yaw.to_bits()])
    }
}

impl From<PoseBits> for Pose2 {
    fn from(p: PoseBits) -> Self {
        Pose2 {
            x: f64::from_bits(p.0[0]),
            y: f64::from_bits(p.0[1]),
            yaw: f64::from_bits(p.0[2]),
        }
    }
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

/// A planner's roadmap, independent of the planner's own data structures.
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

/// A disc of the plane where the world changed, already widened by the robot's
/// extent: vertices and edges that reach into it are checked again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChangedDisc {
    /// Centre `[x, y]`, metres.
    pub center: [f64; 2],
    /// Radius, metres.
    pub radius: f64,
}

impl ChangedDisc {
    /// True when a pose at `p` lies in the disc.
    pub fn contains(&self, p: &Pose2) -> bool {
        (p.x - self.center[0]).hypot(p.y - self.center[1]) <= self.radius
    }

    /// True when a motion from `a` to `b` of planar length `length` may pass through
    /// the disc: every point of such a motion lies in the ellipse
    /// `|p − a| + |p − b| ≤ length`, which is tested against the disc.
    pub fn may_touch(&self, a: &Pose2, b: &Pose2, length: f64) -> bool {
        let da = (a.x - self.center[0]).hypot(a.y - self.center[1]);
        let db = (b.x - self.center[0]).hypot(b.y - self.center[1]);
        // NaN anywhere: touched (checked again rather than trusted).
        let beyond = da + db - 2.0 * self.radius > length * (1.0 + 1e-9) + 1e-9;
        !beyond
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

/// FNV-1a (64 bits) of `bytes`, continuing from `hash`.
fn fnv1a(mut hash: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        hash ^= u64::from(b);
        hash = hash.wrapping_mul(0x0100_0000_01b3);
    }
    hash
}

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;

fn hex(hash: u64) -> String {
    format!("{hash:016x}")
}

/// What a roadmap was built for: hashes of the world (name and elevation grid before
/// any mission-state obstacles), the robot section and the resolved config.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Fingerprint {
    /// The world's name and elevation grid.
    pub world: String,
    /// The config's `[robot]` section.
    pub robot: String,
    /// The resolved config table (after includes and overrides).
    pub config: String,
}

impl Fingerprint {
    /// The fingerprint of `loaded` on `world` (the world as built from the config,
    /// before a mission state's obstacles are added).
    pub fn of(loaded: &LoadedConfig, world: &World) -> Self {
        let mut w = fnv1a(FNV_OFFSET, world.name.as_bytes());
        let g = &world.elevation;
        w = fnv1a(w, format!("{:?}", g.geometry).as_bytes());
        for v in &g.data {
            w = fnv1a(w, &v.to_bits().to_le_bytes());
        }
        let robot = format!("{:?}", loaded.config.robot);
        let config = loaded.table.to_string();
        Self {
            world: hex(w),
            robot: hex(fnv1a(FNV_OFFSET, robot.as_bytes())),
            config: hex(fnv1a(FNV_OFFSET, config.as_bytes())),
        }
    }
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

/// Writes `snapshot` with its `fingerprint` to `path` (atomically).
pub fn write_roadmap(
    path: &FsPath,
    snapshot: &RoadmapSnapshot,
    fingerprint: &Fingerprint,
) -> Result<(), RoadmapFileError> {
    let file = path.display().to_string();
    let body = serde_json::to_vec(snapshot).map_err(|e| RoadmapFileError::Unusable {
        file: file.clone(),
        reason: e.to_string(),
    })?;
    let header = Header {
        format: ROADMAP_FORMAT.into(),
        version: ROADMAP_VERSION,
        fingerprint: fingerprint.clone(),
        body_bytes: body.len(),
        checksum: hex(fnv1a(FNV_OFFSET, &body)),
    };
    let mut bytes = serde_json::to_vec(&header).map_err(|e| RoadmapFileError::Unusable {
        file: file.clone(),
        reason: e.to_string(),
    })?;
    bytes.push(b'\n');
    bytes.extend_from_slice(&body);
    crate::output::write_atomic(path, &bytes)
        .map_err(|source| RoadmapFileError::Io { file, source })
}

/// Reads the roadmap at `path`, refusing it unless it is intact, of this version and
/// built for `expected`.
pub fn read_roadmap(
    path: &FsPath,
    expected: &Fingerprint,
) -> Result<RoadmapSnapshot, RoadmapFileError> {
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
    if hex(fnv1a(FNV_OFFSET, body)) != header.checksum {
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
    serde_json::from_slice(body).map_err(|e| not_a_roadmap(format!("body: {e}")))
}

/// A planner cannot use a snapshot (another planner's, another motion model's, or
/// inconsistent).
#[derive(Debug, thiserror::Error)]
#[error("the roadmap cannot be loaded: {reason}")]
pub struct IncompatibleRoadmap {
    /// Why.
    pub reason: String,
}
