//! What a planner's roadmap methods share with their callers: the regions where the
//! world changed since the roadmap was built ([`ChangedDisc`]), and what a saved
//! roadmap was built for ([`Fingerprint`], computed by the caller). The saved roadmap
//! itself is the planner's opaque bytes; its file format lives beside the planner
//! (`smug_planners::roadmap::file`).

use crate::pose::Pose2;
use serde::{Deserialize, Serialize};

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

/// What a saved roadmap was built for: digests ([`Digest`](crate::digest::Digest)) of
/// the world, the robot and the config, as the caller computes them
/// (`smug_mission::fingerprint`); a roadmap file refuses to load under another.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Fingerprint {
    /// The world's name and elevation grid.
    pub world: String,
    /// The config's `[robot]` section.
    pub robot: String,
    /// The resolved config table (after includes and overrides).
    pub config: String,
}
