//! `geometric`: traversability from the elevation layer. Per cell, a plane is fitted
//! to the elevation within a robot-sized window: its slope, the roughness (RMS
//! residual) and the step height (max − min in the window) are each mapped to
//! `[0, 1]` against a critical value (`1 − value / critical`, clamped) and combined
//! (minimum or weighted mean). Cells without elevation data get no data (NaN).

use serde::{Deserialize, Serialize};
use smug_core::{Error, GridLayer};

/// How the three scores combine.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Combine {
    /// The smallest score (conservative).
    #[default]
    Min,
    /// The weighted mean with `weights`.
    Weighted,
}

/// Parameters of the geometric estimator.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GeometricParams {
    /// Radius of the fitting window, metres; absent: robot-sized (half the diagonal
    /// of the robot's footprint), so that obstacles under any part of the base count.
    pub window_radius: Option<f64>,
    /// Slope (radians) at which the slope score reaches 0.
    pub critical_slope: f64,
    /// RMS residual (metres) at which the roughness score reaches 0.
    pub critical_roughness: f64,
    /// Height difference (metres) at which the step score reaches 0.
    pub critical_step: f64,
    /// `min` or `weighted`.
    pub combine: Combine,
    /// Weights of slope, roughness and step for `weighted`.
    pub weights: [f64; 3],
}

impl Default for GeometricParams {
    fn default() -> Self {
        Self {
            window_radius: None,
            critical_slope: 0.6,
            critical_roughness: 0.05,
            critical_step: 0.3,
            combine: Combine::Min,
            weights: [0.4, 0.3, 0.3],
        }
    }
}

/// Slope, roughness and step height of the terrain around one cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TerrainFeatures {
    /// Angle of the fitted plane, radians.
    pub slope: f64,
    /// RMS residual of the fit, metres.
    pub roughness: f64,
    /// Max − min elevation in the window, metres.
    pub step: f64,
}

/// The geometric traversability estimator.
#[derive(Clone, Copy, Debug)]
pub struct GeometricEstimator {
    params: GeometricParams,
    window_radius: f64,
}

impl GeometricEstimator {
    /// An estimator; every critical value and the window must be > 0. `robot_window`
    /// is the window radius used when the parameters give none.
    pub fn new(params: GeometricParams, robot_window: f64) -> Result<Self, Error> {
        let window_radius = params.window_radius.unwrap_or(robot_window);
        let positive = [
            ("window_radius", window_radius),
            ("critical_slope", params.critical_slope),
            ("critical_roughness", params.critical_roughness),
            ("critical_step", params.critical_step),
        ];
        if let Some((name, v)) = positive.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
            return Err(Error::invalid_param(
                "traversability",
                format!("{name} must be > 0, got {v}"),
            ));
        }
        if params.weights.iter().any(|w| !(w.is_finite() && *w >= 0.0))
            || params.weights.iter().sum::<f64>() <= 0.0
        {
            return Err(Error::invalid_param(
                "traversability",
                "weights must be ≥ 0 with a positive sum",
            ));
        }
        Ok(Self {
            params,
            window_radius,
        })
    }

    /// The terrain features around cell `(i, j)`; `None` without enough data.
    pub fn features(&self, elevation: &GridLayer, i: usize, j: usize) -> Option<TerrainFeatures> {
        let window = Window::new(self.window_radius, elevation.geometry.resolution);
        window.features(elevation, i, j)
    }

    /// The traversability score of some features.
    pub fn score(&self, f: &TerrainFeatures) -> f64 {
        let p = &self.params;
        let scores = [
            1.0 - f.slope / p.critical_slope,
            1.0 - f.roughness / p.critical_roughness,
            1.0 - f.step / p.critical_step,
        ]
        .map(|s| s.clamp(0.0, 1.0));
        match p.combine {
            Combine::Min => scores.iter().copied().fold(1.0, f64::min),
            Combine::Weighted => {
                let total: f64 = p.weights.iter().sum();
                scores
                    .iter()
                    .zip(&p.weights)
                    .map(|(s, w)| s * w)
                    .sum::<f64>()
                    / total
            }
        }
    }
}

#[path = "geometric_window.rs"]
mod window;
use window::Window;

#[path = "geometric_rows.rs"]
mod rows;

#[path = "geometric_estimate.rs"]
mod estimate;

smug_core::register_plugin!(
    smug_core::registry::TraversabilityStage,
    name = "geometric",
    summary = "slope, roughness and step height of a plane fit over a robot-sized window",
    params = GeometricParams,
    build = |params, ctx| {
        let robot = ctx.robot();
        Ok(Box::new(GeometricEstimator::new(
            params,
            0.5 * robot.length.hypot(robot.width),
        )?))
    },
);

#[cfg(test)]
mod tests {
    use super::window::det3;
    use super::*;

    use proptest::prelude::*;
    use smug_core::GridGeometry;
    use smug_core::{TraversabilityEstimator, World};

    /// The original accumulation (heights' range as options), verbatim.
    #[derive(Default)]
    struct ReferenceFit {
        n: f64,
        sx: f64,
        sy: f64,
        sz: f64,
        sxx: f64,
        sxy: f64,
        syy: f64,
        sxz: f64,
        syz: f64,
        szz: f64,
        low: Option<f64>,
        high: Option<f64>,
    }

    impl ReferenceFit {
        fn add(&mut self, x: f64, y: f64, z: f64) {
            self.n += 1.0;
            self.sx += x;
            self.sy += y;
            self.sz += z;
            self.sxx += x * x;
            self.sxy += x * y;
            self.syy += y * y;
            self.sxz += x * z;
            self.syz += y * z;
            self.szz += z * z;
            self.low = Some(self.low.map_or(z, |l| l.min(z)));
            self.high = Some(self.high.map_or(z, |h| h.max(z)));
        }

        /// Solves the 3×3 normal equations (Cramer's rule); flat when under-determined.
        fn features(&self) -> Option<TerrainFeatures> {
            let step = self.high? - self.low?;
            let m = [
                [self.n, self.sx, self.sy],
                [self.sx, self.sxx, self.sxy],
                [self.sy, self.sxy, self.syy],
            ];
            let rhs = [self.sz, self.sxz, self.syz];
            let det = det3(m);
            let (a, b, c) = if self.n >= 3.0 && det.abs() > 1e-12 {
                let solve = |k: usize| {
                    let mut mk = m;
                    for (row, value) in mk.iter_mut().zip(rhs) {
                        row[k] = value;
                    }
                    det3(mk) / det
                };
                (solve(0), solve(1), solve(2))
            } else {
                (self.sz / self.n, 0.0, 0.0)
            };
            // Σ(z − a − bx − cy)² expanded in the accumulated sums.
            let sse = self.szz + a * a * self.n + b * b * self.sxx + c * c * self.syy
                - 2.0 * a * self.sz
                - 2.0 * b * self.sxz
                - 2.0 * c * self.syz
                + 2.0 * a * b * self.sx
                + 2.0 * a * c * self.sy
                + 2.0 * b * c * self.sxy;
            Some(TerrainFeatures {
                slope: (b * b + c * c).sqrt().atan(),
                roughness: (sse.max(0.0) / self.n).sqrt(),
                step,
            })
        }
    }

    /// The straightforward window loop (the distance test per cell of the bounding
    /// square): the reference the row-run window must match bit for bit.
    fn reference_features(
        radius: f64,
        elevation: &GridLayer,
        i: usize,
        j: usize,
    ) -> Option<TerrainFeatures> {
        let g = elevation.geometry;
        let z0 = elevation.get(i, j);
        if z0.is_nan() {
            return None;
        }
        let reach = (radius / g.resolution).floor() as isize;
        let mut fit = ReferenceFit::default();
        for dj in -reach..=reach {
            for di in -reach..=reach {
                let (x, y) = (di as f64 * g.resolution, dj as f64 * g.resolution);
                let (ci, cj) = (i as isize + di, j as isize + dj);
                let inside =
                    ci >= 0 && cj >= 0 && (ci as usize) < g.size[0] && (cj as usize) < g.size[1];
                if inside && x.hypot(y) <= radius + 1e-9 {
                    let z = elevation.get(ci as usize, cj as usize);
                    if !z.is_nan() {
                        fit.add(x, y, z as f64 - z0 as f64);
                    }
                }
            }
        }
        fit.features()
    }

    /// The features' bits (every NaN alike).
    fn feature_bits(f: Option<TerrainFeatures>) -> Option<[u64; 3]> {
        let bits = |v: f64| if v.is_nan() { u64::MAX } else { v.to_bits() };
        f.map(|f| [bits(f.slope), bits(f.roughness), bits(f.step)])
    }

    /// Features equal to within `tolerance` (the step, a difference of two heights,
    /// exactly; missing alike).
    fn features_close(
        a: Option<TerrainFeatures>,
        b: Option<TerrainFeatures>,
        tolerance: f64,
    ) -> bool {
        let close = |x: f64, y: f64| (x.is_nan() && y.is_nan()) || (x - y).abs() <= tolerance;
        match (a, b) {
            (None, None) => true,
            (Some(a), Some(b)) => {
                close(a.slope, b.slope)
                    && close(a.roughness, b.roughness)
                    && feature_bits(Some(a)).map(|f| f[2]) == feature_bits(Some(b)).map(|f| f[2])
            }
            _ => false,
        }
    }

    #[test]
    fn lunar_traversability_equals_the_reference() {
        use rand::SeedableRng;
        use smug_worlds::lunar::{lunar_world, LunarParams};
        let mut rng = smug_core::rng::StageRng::seed_from_u64(3);
        let world = lunar_world(&LunarParams::default(), &mut rng)
            .unwrap()
            .world;
        let radius = 0.5 * 1.07f64.hypot(0.55); // the ANYmal window
        let estimator = GeometricEstimator::new(GeometricParams::default(), radius).unwrap();
        let layer = estimator.estimate(&world).unwrap();
        let e = &world.elevation;
        let reference = GridLayer::from_fn(e.geometry, |i, j| {
            reference_features(radius, e, i, j).map_or(f32::NAN, |f| estimator.score(&f) as f32)
        });
        let mut differing = 0;
        for (k, (&v, &r)) in layer.data.iter().zip(&reference.data).enumerate() {
            assert!(
                (v.is_nan() && r.is_nan()) || (v - r).abs() <= 1e-6,
                "cell {k}: {v} vs {r}"
            );
            differing += usize::from(v.to_bits() != r.to_bits());
        }
        // The sums differ from the reference's in their last bits only.
        assert!(
            differing * 1000 < layer.data.len(),
            "{differing} cells differ"
        );
    }

    proptest! {
        /// Random terrain with holes and a few infinite heights, any window: the
        /// cell-by-cell fit is the reference's to the bit, the row-sum fit of every
        /// cell of any rectangle equals it to rounding, and a cell's row-sum fit does
        /// not depend on the rectangle it is computed in.
        #[test]
        fn row_sums_equal_the_reference(
            nx in 1usize..24, ny in 1usize..24, resolution in 0.05f64..0.3,
            radius in 0.01f64..2.0, holes in 0.0f64..0.3, seed in any::<u64>(),
            corner in (0usize..24, 0usize..24),
        ) {
            use rand::{Rng, SeedableRng};
            let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
            let g = GridGeometry::new([0.0, 0.0], resolution, [nx, ny]).unwrap();
            let elevation = GridLayer::from_fn(g, |_, _| {
                match rng.random::<f64>() {
                    r if r < holes => f32::NAN,
                    r if r < holes + 0.002 => f32::INFINITY,
                    _ => rng.random_range(-3.0f32..3.0),
                }
            });
            let window = Window::new(radius, resolution);
            let runs = rows::RowRuns::new(&window).expect("a symmetric window");
            let whole = smug_core::CellRect { i0: 0, j0: 0, i1: nx, j1: ny };
            let mut fast = vec![None; nx * ny];
            runs.rect_features(&window, &elevation, whole, |i, j, f| fast[j * nx + i] = Some(f));
            let part = smug_core::CellRect { i0: corner.0.min(nx), j0: corner.1.min(ny), i1: nx, j1: ny };
            runs.rect_features(&window, &elevation, part, |i, j, f| {
                assert_eq!(feature_bits(f), feature_bits(fast[j * nx + i].flatten()), "cell ({}, {})", i, j);
            });
            for j in 0..ny {
                for i in 0..nx {
                    let slow = reference_features(radius, &elevation, i, j);
                    prop_assert_eq!(feature_bits(window.features(&elevation, i, j)), feature_bits(slow), "cell ({}, {})", i, j);
                    let by_rows = fast[j * nx + i].expect("every cell emitted");
                    prop_assert!(features_close(by_rows, slow, 1e-9), "cell ({}, {}): {:?} vs {:?}", i, j, by_rows, slow);
                }
            }
        }
    }

    fn world_from(f: impl Fn(f64, f64) -> f64) -> World {
        let g = GridGeometry::new([0.0, 0.0], 0.1, [40, 40]).unwrap();
        let elevation = GridLayer::from_fn(g, |i, j| {
            let [x, y] = g.center_of(i, j);
            f(x, y) as f32
        });
        World::new("test", elevation)
    }

    fn score_at_centre(world: &World) -> f64 {
        let layer = GeometricEstimator::new(GeometricParams::default(), 0.3)
            .unwrap()
            .estimate(world)
            .unwrap();
        layer.get(20, 20) as f64
    }

    #[test]
    fn flat_plane_is_fully_traversable() {
        let layer = GeometricEstimator::new(GeometricParams::default(), 0.3)
            .unwrap()
            .estimate(&world_from(|_, _| 1.5))
            .unwrap();
        assert!(layer.data.iter().all(|&v| v == 1.0));
    }

    proptest! {
        #[test]
        fn traversability_falls_with_slope(s1 in 0.0f64..0.5, s2 in 0.0f64..0.5, dir in 0.0f64..std::f64::consts::TAU) {
            let (low, high) = if s1 < s2 { (s1, s2) } else { (s2, s1) };
            let ramp = |s: f64| world_from(move |x, y| s * (x * dir.cos() + y * dir.sin()));
            let (a, b) = (score_at_centre(&ramp(low)), score_at_centre(&ramp(high)));
            prop_assert!(a >= b - 1e-6, "slope {low} scores {a} < slope {high} scores {b}");
        }
    }

    #[test]
    fn slope_is_measured_and_missing_data_stays_missing() {
        let e = GeometricEstimator::new(GeometricParams::default(), 0.3).unwrap();
        let ramp = world_from(|x, _| 0.2 * x);
        let f = e.features(&ramp.elevation, 20, 20).unwrap();
        assert!((f.slope - 0.2f64.atan()).abs() < 1e-3, "{f:?}");
        assert!(f.roughness < 1e-3);
        let mut holes = world_from(|_, _| 0.0);
        holes.elevation.set(5, 5, f32::NAN);
        let layer = e.estimate(&holes).unwrap();
        assert!(layer.get(5, 5).is_nan());
        assert_eq!(layer.get(6, 5), 1.0);
        assert!(GeometricEstimator::new(
            GeometricParams {
                critical_step: 0.0,
                ..Default::default()
            },
            0.3
        )
        .is_err());
    }

    #[test]
    fn steps_and_roughness_lower_the_score() {
        let step = world_from(|x, _| if x > 2.0 { 0.2 } else { 0.0 });
        let layer = GeometricEstimator::new(GeometricParams::default(), 0.3)
            .unwrap()
            .estimate(&step)
            .unwrap();
        assert!(
            layer.get(20, 20) < 0.5,
            "at the step: {}",
            layer.get(20, 20)
        );
        assert_eq!(layer.get(5, 20), 1.0);
    }
}
