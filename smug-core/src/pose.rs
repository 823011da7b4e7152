//! SE(2) poses and SE(3) waypoints.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Wraps an angle into `[-π, π)`.
pub fn wrap_angle(angle: f64) -> f64 {
    if (-PI..PI).contains(&angle) {
        return angle;
    }
    let wrapped = (angle + PI).rem_euclid(2.0 * PI) - PI;
    // `rem_euclid` may round up to exactly 2π for tiny negative inputs.
    if wrapped >= PI {
        wrapped - 2.0 * PI
    } else {
        wrapped
    }
}

/// Shortest angular distance between two yaws, in `[0, π]`.
pub fn angle_distance(a: f64, b: f64) -> f64 {
    let d = (a - b).abs();
    // Fast path for yaws in range (`rem_euclid` would return `d` itself).
    let d = if d < 2.0 * PI {
        d
    } else {
        d.rem_euclid(2.0 * PI)
    };
    d.min(2.0 * PI - d)
}

/// A planar pose `(x, y, yaw)`; `yaw` is kept in `[-π, π)` by [`Pose2::new`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, from = "RawPose2")]
pub struct Pose2 {
    /// x in metres.
    pub x: f64,
    /// y in metres.
    pub y: f64,
    /// Heading in radians, in `[-π, π)`.
    pub yaw: f64,
}

/// The serialised form of a pose: yaw is optional and wrapped on load.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPose2 {
    x: f64,
    y: f64,
    #[serde(default)]
    yaw: f64,
}

impl From<RawPose2> for Pose2 {
    fn from(raw: RawPose2) -> Self {
        Pose2::new(raw.x, raw.y, raw.yaw)
    }
}

impl Pose2 {
    /// A pose with its yaw wrapped into `[-π, π)`.
    pub fn new(x: f64, y: f64, yaw: f64) -> Self {
        Self {
            x,
            y,
            yaw: wrap_angle(yaw),
        }
    }

    /// The position `(x, y)`.
    pub fn xy(&self) -> [f64; 2] {
        [self.x, self.y]
    }

    /// Euclidean distance between the positions of two poses.
    #[inline]
    pub fn xy_distance(&self, other: &Pose2) -> f64 {
        let (dx, dy) = (self.x - other.x, self.y - other.y);
        // `hypot` guards against overflow of huge coordinates, at 5× the cost.
        (dx * dx + dy * dy).sqrt()
    }

    /// True when every component is finite.
    pub fn is_finite(&self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.yaw.is_finite()
    }
}

/// A 3D point, for target positions (z defaults to 0).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Point3 {
    /// x in metres.
    pub x: f64,
    /// y in metres.
    pub y: f64,
    /// z in metres.
    #[serde(default)]
    pub z: f64,
}

/// A waypoint for a local planner: SE(2) pose plus terrain height, `[x, y, z, yaw]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(from = "[f64; 4]", into = "[f64; 4]")]
pub struct Waypoint {
    /// x in metres.
    pub x: f64,
    /// y in metres.
    pub y: f64,
    /// Terrain height (plus base offset, if the caller adds it) in metres.
    pub z: f64,
    /// Heading in radians, in `[-π, π)`.
    pub yaw: f64,
}

impl Waypoint {
    /// A waypoint at `pose` with height `z`.
    pub fn from_pose(pose: &Pose2, z: f64) -> Self {
        Self {
            x: pose.x,
            y: pose.y,
            z,
            yaw: pose.yaw,
        }
    }

    /// The planar pose of this waypoint.
    pub fn pose(&self) -> Pose2 {
        Pose2::new(self.x, self.y, self.yaw)
    }
}

impl From<[f64; 4]> for Waypoint {
    fn from([x, y, z, yaw]: [f64; 4]) -> Self {
        Self {
            x,
            y,
            z,
            yaw: wrap_angle(yaw),
        }
    }
}

impl From<Waypoint> for [f64; 4] {
    fn from(w: Waypoint) -> Self {
        [w.x, w.y, w.z, w.yaw]
    }
}

/// An axis-aligned rectangle in the plane.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bounds2 {
    /// Lower-left corner `(x, y)`.
    pub min: [f64; 2],
    /// Upper-right corner `(x, y)`.
    pub max: [f64; 2],
}

impl Bounds2 {
    /// True when `(x, y)` lies inside (borders included).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        x >= self.min[0] && x <= self.max[0] && y >= self.min[1] && y <= self.max[1]
    }

    /// Width and height.
    pub fn extent(&self) -> [f64; 2] {
        [self.max[0] - self.min[0], self.max[1] - self.min[1]]
    }
}

/// A pose as the bits of its `x`, `y` and `yaw`: a hash key, and what a saved roadmap
/// stores (bit-identical when read back).
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn wrapped_angles_lie_in_half_open_range(a in -1e4f64..1e4) {
            let w = wrap_angle(a);
            prop_assert!((-PI..PI).contains(&w), "{a} -> {w}");
            prop_assert!(angle_distance(w, a) < 1e-9);
        }

        #[test]
        fn angle_distance_is_symmetric_and_bounded(a in -10f64..10.0, b in -10f64..10.0) {
            let d = angle_distance(a, b);
            prop_assert!((0.0..=PI + 1e-12).contains(&d));
            prop_assert!((d - angle_distance(b, a)).abs() < 1e-12);
        }
    }

    #[test]
    fn pi_wraps_to_minus_pi() {
        assert_eq!(wrap_angle(PI), -PI);
        assert_eq!(Pose2::new(0.0, 0.0, 3.0 * PI).yaw, -PI);
        assert_eq!(wrap_angle(-PI), -PI);
    }

    #[test]
    fn pose_loads_with_wrapped_yaw_and_rejects_unknown_keys() {
        let p: Pose2 = toml::from_str("x = 1.0\ny = 2\nyaw = 4.0").unwrap();
        assert!((p.yaw - (4.0 - 2.0 * PI)).abs() < 1e-12);
        assert_eq!(p.y, 2.0);
        assert!(toml::from_str::<Pose2>("x = 1.0\ny = 2\nz = 3").is_err());
    }

    #[test]
    fn waypoint_serialises_as_array() {
        let w = Waypoint {
            x: 1.0,
            y: 2.0,
            z: 3.0,
            yaw: 0.5,
        };
        let json = serde_json::to_string(&w).unwrap();
        assert_eq!(json, "[1.0,2.0,3.0,0.5]");
        assert_eq!(serde_json::from_str::<Waypoint>(&json).unwrap(), w);
    }
}
