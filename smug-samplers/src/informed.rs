//! `informed`: uniform samples in the informed set of the current query.
//!
//! A state `x` can improve a path from `s1` to `s2` of cost `c_best` only if
//! `w_t(‖xy − xy1‖ + ‖xy − xy2‖) < c_best − w_r·d(yaw1, yaw2)`: an ellipse with foci
//! `xy1`, `xy2` and transverse diameter `(c_best − w_r·d(yaw1, yaw2)) / w_t`, where
//! `(w_t, w_r)` are the objective's bound weights. Samples are uniform in that
//! ellipse intersected with the map bounds (exactly: by rejection from whichever of
//! the ellipse and the bounds is smaller), yaw uniform.

use crate::uniform::{uniform_in_rectangle, uniform_yaw};
use rand::Rng;
use serde::{Deserialize, Serialize};
use smug_core::pose::angle_distance;
use smug_core::rng::StageRng;
use smug_core::{Bounds2, InformedSet, Objective, Pose2, Sampler};
use std::f64::consts::PI;
use std::sync::Arc;

/// Parameters of the informed sampler.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct InformedParams {
    /// Rejection attempts before reporting the region (ellipse ∩ bounds) as empty.
    pub max_attempts: u32,
}

impl Default for InformedParams {
    fn default() -> Self {
        Self {
            max_attempts: 10_000,
        }
    }
}

/// The informed ellipse of a query in the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InformedEllipse {
    /// Midpoint of the foci.
    pub center: [f64; 2],
    /// Angle of the major axis.
    pub angle: f64,
    /// Semi-major axis (half the transverse diameter).
    pub semi_major: f64,
    /// Semi-minor axis.
    pub semi_minor: f64,
    foci: [[f64; 2]; 2],
}

impl InformedEllipse {
    /// The ellipse of `set` under lower-bound weights `(w_t, w_r)`; `None` when it is
    /// empty (no state can improve the path) and unbounded (`INFINITY` cost) is `None` too.
    pub fn new(set: &InformedSet, w_t: f64, w_r: f64) -> Option<Self> {
        let budget = set.best_cost - w_r * angle_distance(set.start.yaw, set.goal.yaw);
        let transverse = budget / w_t;
        let focal = set.start.xy_distance(&set.goal);
        if !transverse.is_finite() || transverse <= focal {
            return None;
        }
        let semi_major = transverse / 2.0;
        let semi_minor = (semi_major * semi_major - focal * focal / 4.0)
            .max(0.0)
            .sqrt();
        Some(Self {
            center: [
                (set.start.x + set.goal.x) / 2.0,
                (set.start.y + set.goal.y) / 2.0,
            ],
            angle: (set.goal.y - set.start.y).atan2(set.goal.x - set.start.x),
            semi_major,
            semi_minor,
            foci: [set.start.xy(), set.goal.xy()],
        })
    }

    /// True when `(x, y)` lies inside (sum of focal distances ≤ transverse diameter).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let d = |f: [f64; 2]| (x - f[0]).hypot(y - f[1]);
        d(self.foci[0]) + d(self.foci[1]) <= 2.0 * self.semi_major * (1.0 + 1e-12)
    }

    /// Area.
    pub fn area(&self) -> f64 {
        PI * self.semi_major * self.semi_minor
    }

    /// Axis-aligned bounding box.
    pub fn bounding_box(&self) -> Bounds2 {
        let (s, c) = self.angle.sin_cos();
        let hx = ((self.semi_major * c).powi(2) + (self.semi_minor * s).powi(2)).sqrt();
        let hy = ((self.semi_major * s).powi(2) + (self.semi_minor * c).powi(2)).sqrt();
        Bounds2 {
            min: [self.center[0] - hx, self.center[1] - hy],
            max: [self.center[0] + hx, self.center[1] + hy],
        }
    }

    /// Maps a point of the unit disc into the ellipse.
    pub fn from_unit_disc(&self, u: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.angle.sin_cos();
        let (a, b) = (u[0] * self.semi_major, u[1] * self.semi_minor);
        [
            self.center[0] + c * a - s * b,
            self.center[1] + s * a + c * b,
        ]
    }

    /// Maps a point of the ellipse back into the unit disc.
    pub fn to_unit_disc(&self, p: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.angle.sin_cos();
        let (dx, dy) = (p[0] - self.center[0], p[1] - self.center[1]);
        [
            (c * dx + s * dy) / self.semi_major,
            (-s * dx + c * dy) / self.semi_minor,
        ]
    }
}

/// Informed SE(2) sampling; uniform in the bounds when no informed set is given.
#[derive(Clone, Debug)]
pub struct InformedSampler {
    rng: StageRng,
    weights: (f64, f64),
    max_attempts: u32,
}

impl InformedSampler {
    /// A sampler for the informed sets of `objective` (its bound weights) drawing from `rng`.
    pub fn new(params: InformedParams, objective: Arc<dyn Objective>, rng: StageRng) -> Self {
        Self {
            rng,
            weights: objective.bound_weights(),
            max_attempts: params.max_attempts.max(1),
        }
    }

    fn uniform_in_disc(&mut self) -> [f64; 2] {
        let r = self.rng.random::<f64>().sqrt();
        let theta = self.rng.random_range(-PI..PI);
        [r * theta.cos(), r * theta.sin()]
    }

    /// A point uniform in `ellipse ∩ bounds`, by rejection from the smaller of the two.
    fn sample_xy(&mut self, ellipse: &InformedEllipse, bounds: &Bounds2) -> Option<[f64; 2]> {
        let bbox = ellipse.bounding_box();
        let clipped = Bounds2 {
            min: [
                bbox.min[0].max(bounds.min[0]),
                bbox.min[1].max(bounds.min[1]),
            ],
            max: [
                bbox.max[0].min(bounds.max[0]),
                bbox.max[1].min(bounds.max[1]),
            ],
        };
        let [w, h] = clipped.extent();
        if w < 0.0 || h < 0.0 {
            return None;
        }
        let from_ellipse = ellipse.area() <= w * h;
        for _ in 0..self.max_attempts {
            let p = if from_ellipse {
                ellipse.from_unit_disc(self.uniform_in_disc())
            } else {
                uniform_in_rectangle(&mut self.rng, clipped.min, clipped.max)
            };
            if bounds.contains(p[0], p[1]) && ellipse.contains(p[0], p[1]) {
                return Some(p);
            }
        }
        None
    }
}

impl Sampler for InformedSampler {
    fn sample(&mut self, bounds: &Bounds2, informed: Option<&InformedSet>) -> Option<Pose2> {
        let (w_t, w_r) = self.weights;
        let xy = match informed {
            Some(set) if set.best_cost.is_finite() => {
                let ellipse = InformedEllipse::new(set, w_t, w_r)?;
                self.sample_xy(&ellipse, bounds)?
            }
            _ => uniform_in_rectangle(&mut self.rng, bounds.min, bounds.max),
        };
        Some(Pose2::new(xy[0], xy[1], uniform_yaw(&mut self.rng)))
    }
}

smug_core::register_plugin!(
    smug_core::registry::SamplerStage,
    name = "informed",
    summary = "uniform in the query's informed ellipse ∩ map bounds once a path is known",
    params = InformedParams,
    build = |params, ctx| Ok(Box::new(InformedSampler::new(
        params,
        ctx.objective(),
        ctx.rng("sampler")
    ))),
);

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use smug_core::objective::{PathLength, PathLengthParams};
    use smug_core::rng::stage_rng;

    fn length(w_t: f64, w_r: f64) -> PathLength {
        PathLength::from_params(PathLengthParams {
            translation_weight: w_t,
            rotation_weight: w_r,
        })
        .unwrap()
    }

    fn sampler(w_t: f64, w_r: f64, seed: u64) -> InformedSampler {
        let metric = Arc::new(length(w_t, w_r));
        InformedSampler::new(
            InformedParams::default(),
            metric,
            stage_rng(seed, "sampler"),
        )
    }

    const BIG: Bounds2 = Bounds2 {
        min: [-100.0, -100.0],
        max: [100.0, 100.0],
    };

    proptest! {
        #[test]
        fn samples_lie_in_the_informed_set_and_bounds(
            x1 in -10.0f64..10.0, y1 in -10.0f64..10.0, yaw1 in -PI..PI,
            x2 in -10.0f64..10.0, y2 in -10.0f64..10.0, yaw2 in -PI..PI,
            slack in 0.01f64..20.0, w_t in 0.1f64..3.0, w_r in 0.0f64..2.0, seed in 0u64..1000,
            clip in 0.0f64..8.0,
        ) {
            let (start, goal) = (Pose2::new(x1, y1, yaw1), Pose2::new(x2, y2, yaw2));
            let metric = length(w_t, w_r);
            let set = InformedSet { start, goal, best_cost: metric.motion_cost(&start, &goal) + slack };
            let bounds = Bounds2 { min: [-10.0 + clip, -10.0], max: [10.0, 10.0 - clip] };
            let mut s = sampler(w_t, w_r, seed);
            for _ in 0..50 {
                let Some(p) = s.sample(&bounds, Some(&set)) else { break };
                prop_assert!(bounds.contains(p.x, p.y));
                // Every sample could improve the path: its straight-line lower bound
                // through p is below the best cost.
                let through = w_t * (p.xy_distance(&start) + p.xy_distance(&goal))
                    + w_r * angle_distance(start.yaw, goal.yaw);
                prop_assert!(through <= set.best_cost * (1.0 + 1e-9), "{through} > {}", set.best_cost);
            }
        }
    }

    #[test]
    fn empty_informed_set_gives_no_sample() {
        let (start, goal) = (Pose2::new(0.0, 0.0, 0.0), Pose2::new(4.0, 0.0, PI / 2.0));
        // Exactly the straight-line cost: nothing can improve on it.
        let set = InformedSet {
            start,
            goal,
            best_cost: 4.0 + 0.5 * PI / 2.0,
        };
        assert_eq!(sampler(1.0, 0.5, 1).sample(&BIG, Some(&set)), None);
    }

    #[test]
    fn the_rotational_bound_shrinks_the_ellipse_correctly() {
        // Reference-code bug 2: the yaw term must be subtracted from the budget.
        let (start, goal) = (Pose2::new(0.0, 0.0, 0.0), Pose2::new(4.0, 0.0, PI));
        let set = InformedSet {
            start,
            goal,
            best_cost: 6.0 + 0.5 * PI,
        };
        let e = InformedEllipse::new(&set, 1.0, 0.5).unwrap();
        assert!((e.semi_major - 3.0).abs() < 1e-12);
        assert!(
            (e.semi_minor - 5f64.sqrt()).abs() < 1e-12,
            "second axis must differ from the first"
        );
    }

    /// Chi-square statistic of counts against equal expected frequencies.
    fn chi_square(counts: &[u32]) -> f64 {
        let total: u32 = counts.iter().sum();
        let expected = total as f64 / counts.len() as f64;
        counts
            .iter()
            .map(|&c| (c as f64 - expected).powi(2) / expected)
            .sum()
    }

    #[test]
    fn samples_cover_the_ellipse_uniformly() {
        // Map samples back to the unit disc: uniform there means r² and the angle are
        // uniform and independent. 10×8 bins, 40 000 samples, fixed seed.
        let (start, goal) = (Pose2::new(-3.0, 1.0, 0.3), Pose2::new(5.0, 4.0, -2.0));
        let metric = PathLength::default();
        let set = InformedSet {
            start,
            goal,
            best_cost: metric.motion_cost(&start, &goal) * 1.3,
        };
        let ellipse = InformedEllipse::new(&set, 1.0, 0.5).unwrap();
        let mut s = sampler(1.0, 0.5, 42);
        let mut bins = vec![0u32; 80];
        let mut yaw_bins = vec![0u32; 8];
        for _ in 0..40_000 {
            let p = s.sample(&BIG, Some(&set)).unwrap();
            let [u, v] = ellipse.to_unit_disc([p.x, p.y]);
            let r2 = (u * u + v * v).min(1.0 - 1e-12);
            let angle = (v.atan2(u) + PI) / (2.0 * PI);
            let (i, j) = ((r2 * 10.0) as usize, ((angle * 8.0) as usize).min(7));
            bins[i * 8 + j] += 1;
            yaw_bins[(((p.yaw + PI) / (2.0 * PI) * 8.0) as usize).min(7)] += 1;
        }
        // 79 degrees of freedom: the 99.9% quantile is about 124.
        let chi2 = chi_square(&bins);
        assert!(
            chi2 < 124.0,
            "chi² = {chi2}: samples are not uniform in the ellipse"
        );
        // 7 degrees of freedom: the 99.9% quantile is about 24.3.
        let chi2 = chi_square(&yaw_bins);
        assert!(chi2 < 24.3, "chi² = {chi2}: yaw is not uniform");
    }

    #[test]
    fn clipped_ellipse_is_sampled_uniformly_inside_the_bounds() {
        // Half of the ellipse lies outside the bounds: samples must fill the other half
        // uniformly (compare left and right quarters of the kept half).
        let (start, goal) = (Pose2::new(-4.0, 0.0, 0.0), Pose2::new(4.0, 0.0, 0.0));
        let set = InformedSet {
            start,
            goal,
            best_cost: 10.0,
        };
        let bounds = Bounds2 {
            min: [-100.0, 0.0],
            max: [100.0, 100.0],
        };
        let mut s = sampler(1.0, 0.5, 7);
        let (mut left, mut right) = (0u32, 0u32);
        for _ in 0..20_000 {
            let p = s.sample(&bounds, Some(&set)).unwrap();
            assert!(p.y >= 0.0);
            if p.x < 0.0 {
                left += 1
            } else {
                right += 1
            }
        }
        assert!(chi_square(&[left, right]) < 10.8, "{left} vs {right}");
    }

    #[test]
    fn without_a_solution_samples_the_whole_bounds() {
        let mut s = sampler(1.0, 0.5, 3);
        let bounds = Bounds2 {
            min: [0.0, 0.0],
            max: [2.0, 1.0],
        };
        let infinite = InformedSet {
            start: Pose2::new(0.0, 0.0, 0.0),
            goal: Pose2::new(1.0, 0.0, 0.0),
            best_cost: f64::INFINITY,
        };
        for informed in [None, Some(&infinite)] {
            let p = s.sample(&bounds, informed).unwrap();
            assert!(bounds.contains(p.x, p.y));
        }
    }
}
