//! Curves of bounded curvature: a few arcs of the minimum turning radius and straight
//! pieces, in unit-radius form, and how to sample them.

use smug_core::pose::Pose2;
use smug_core::space::MotionExtent;

/// The length in turning radii of segments of these `lengths` (Σ |length|, added in
/// driving order): what [`Curve::unit_length`] gives for a curve of them, to the bit,
/// so that solvers comparing words before building one pick the word it would.
pub(crate) fn unit_length(lengths: impl IntoIterator<Item = f64>) -> f64 {
    lengths.into_iter().map(f64::abs).sum()
}

/// How a segment steers: full left, straight, or full right.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Steer {
    /// Turning left (counter-clockwise when driving forwards) on the minimum radius.
    Left,
    /// Straight ahead.
    Straight,
    /// Turning right (clockwise when driving forwards) on the minimum radius.
    Right,
}

/// One segment of a curve in unit-radius form: `length` is the arc angle in radians
/// (or the straight length in turning radii); negative when driven in reverse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Steering along the segment.
    pub steer: Steer,
    /// Signed length in turning radii (< 0: reverse gear).
    pub length: f64,
}

/// The most segments of a word (Reeds–Shepp `CC|SC|C`).
pub const MAX_SEGMENTS: usize = 5;

/// A curve of at most [`MAX_SEGMENTS`] segments in unit-radius form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Curve {
    segments: [Segment; MAX_SEGMENTS],
    count: usize,
}

impl Curve {
    /// A curve of these segments in order (at most [`MAX_SEGMENTS`]).
    pub fn new(segments: &[Segment]) -> Self {
        assert!(
            segments.len() <= MAX_SEGMENTS,
            "at most {MAX_SEGMENTS} segments"
        );
        let mut all = [Segment {
            steer: Steer::Straight,
            length: 0.0,
        }; MAX_SEGMENTS];
        all[..segments.len()].copy_from_slice(segments);
        Self {
            segments: all,
            count: segments.len(),
        }
    }

    /// A curve from steering letters and signed lengths, paired in order.
    pub fn from_word(steers: &[Steer], lengths: &[f64]) -> Self {
        debug_assert_eq!(steers.len(), lengths.len());
        let mut segments = [Segment {
            steer: Steer::Straight,
            length: 0.0,
        }; MAX_SEGMENTS];
        for (i, (&steer, &length)) in steers.iter().zip(lengths).enumerate() {
            segments[i] = Segment { steer, length };
        }
        Self::new(&segments[..steers.len()])
    }

    /// The segments in driving order.
    pub fn segments(&self) -> &[Segment] {
        &self.segments[..self.count]
    }

    /// Total length in turning radii (Σ |length|).
    pub fn unit_length(&self) -> f64 {
        unit_length(self.segments().iter().map(|s| s.length))
    }

    /// Total turning in radians: Σ |length| over the arcs.
    pub fn turning(&self) -> f64 {
        self.segments()
            .iter()
            .filter(|s| s.steer != Steer::Straight)
            .map(|s| s.length.abs())
            .sum()
    }

    /// Planar length and total turning for turning radius `radius`.
    pub fn extent(&self, radius: f64) -> MotionExtent {
        MotionExtent {
            length: radius * self.unit_length(),
            turning: self.turning(),
        }
    }

    /// The pose after driving `fraction ∈ [0, 1]` of the curve's length from `start`
    /// with turning radius `radius` (the heading is the car's, also when reversing).
    pub fn sample(&self, start: &Pose2, radius: f64, fraction: f64) -> Pose2 {
        let mut remaining = fraction.clamp(0.0, 1.0) * self.unit_length();
        // Unit-radius frame at the start: position (0, 0), heading `start.yaw`.
        let (mut x, mut y, mut yaw) = (0.0, 0.0, start.yaw);
        for segment in self.segments() {
            if remaining <= 0.0 {
                break;
            }
            let step = segment.length.abs().min(remaining);
            remaining -= step;
            let v = step * segment.length.signum();
            match segment.steer {
                Steer::Straight => {
                    x += v * yaw.cos();
                    y += v * yaw.sin();
                }
                Steer::Left => {
                    x += (yaw + v).sin() - yaw.sin();
                    y += -(yaw + v).cos() + yaw.cos();
                    yaw += v;
                }
                Steer::Right => {
                    x += -(yaw - v).sin() + yaw.sin();
                    y += (yaw - v).cos() - yaw.cos();
                    yaw -= v;
                }
            }
        }
        Pose2::new(start.x + radius * x, start.y + radius * y, yaw)
    }

    /// True when the car drives in reverse at `fraction` of the curve's length (on a
    /// gear change, the segment that starts there).
    pub fn is_reversing(&self, fraction: f64) -> bool {
        let total = self.unit_length();
        let mut s = fraction.clamp(0.0, 1.0) * total;
        for segment in self.segments() {
            let length = segment.length.abs();
            if length == 0.0 {
                continue;
            }
            if s < length {
                return segment.length < 0.0;
            }
            s -= length;
        }
        self.segments()
            .iter()
            .rev()
            .find(|s| s.length != 0.0)
            .is_some_and(|s| s.length < 0.0)
    }
}

/// The goal `b` in `a`'s frame, scaled to unit turning radius: `(x, y, Δyaw)`.
pub(crate) fn relative(a: &Pose2, b: &Pose2, radius: f64) -> (f64, f64, f64) {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let (s, c) = a.yaw.sin_cos();
    (
        (c * dx + s * dy) / radius,
        (-s * dx + c * dy) / radius,
        b.yaw - a.yaw,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn a_half_left_circle_ends_two_radii_to_the_left_facing_back() {
        let curve = Curve::from_word(&[Steer::Left], &[PI]);
        let end = curve.sample(&Pose2::new(1.0, 1.0, 0.0), 2.0, 1.0);
        assert!((end.x - 1.0).abs() < 1e-12 && (end.y - 5.0).abs() < 1e-12);
        assert!((end.yaw.abs() - PI).abs() < 1e-12);
        assert!((curve.extent(2.0).length - 2.0 * PI).abs() < 1e-12);
    }

    #[test]
    fn reverse_right_then_straight_reports_the_gear() {
        let curve = Curve::from_word(&[Steer::Right, Steer::Straight], &[-PI / 2.0, 1.0]);
        assert!(curve.is_reversing(0.1));
        assert!(!curve.is_reversing(0.9));
        let end = curve.sample(&Pose2::new(0.0, 0.0, 0.0), 1.0, 1.0);
        // Reversing on a right turn: back and to the right, heading +90°.
        assert!((end.x + 1.0).abs() < 1e-12 && end.y.abs() < 1e-12);
        assert!((end.yaw - PI / 2.0).abs() < 1e-12);
    }
}
