//! `uniform`: states uniform in the map bounds, yaw uniform in `[-π, π)`.

use rand::Rng;
use serde::{Deserialize, Serialize};
use smug_core::rng::StageRng;
use smug_core::{Bounds2, InformedSet, Pose2, Sampler};
use std::f64::consts::PI;

/// Parameters of the uniform sampler (none).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UniformParams {}

/// Uniform SE(2) sampling in the bounds; ignores the informed set.
#[derive(Clone, Debug)]
pub struct UniformSampler {
    rng: StageRng,
}

impl UniformSampler {
    /// A sampler drawing from `rng`.
    pub fn new(rng: StageRng) -> Self {
        Self { rng }
    }
}

/// A uniform yaw in `[-π, π)`.
pub(crate) fn uniform_yaw(rng: &mut StageRng) -> f64 {
    rng.random_range(-PI..PI)
}

/// A uniform point in `[min, max)` per axis (the point `min` for empty ranges).
pub(crate) fn uniform_in_rectangle(rng: &mut StageRng, min: [f64; 2], max: [f64; 2]) -> [f64; 2] {
    std::array::from_fn(|axis| {
        let u: f64 = rng.random();
        min[axis] + u * (max[axis] - min[axis]).max(0.0)
    })
}

impl Sampler for UniformSampler {
    fn sample(&mut self, bounds: &Bounds2, _informed: Option<&InformedSet>) -> Option<Pose2> {
        let [x, y] = uniform_in_rectangle(&mut self.rng, bounds.min, bounds.max);
        Some(Pose2::new(x, y, uniform_yaw(&mut self.rng)))
    }
}

smug_core::register_plugin!(
    smug_core::registry::SamplerStage,
    name = "uniform",
    summary = "uniform SE(2) states in the map bounds (ignores the informed set)",
    params = UniformParams,
    build = |_params, ctx| Ok(Box::new(UniformSampler::new(ctx.rng("sampler")))),
);

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::rng::stage_rng;

    #[test]
    fn samples_stay_in_bounds_and_are_reproducible() {
        let bounds = Bounds2 {
            min: [-2.0, 1.0],
            max: [3.0, 4.0],
        };
        let mut a = UniformSampler::new(stage_rng(1, "sampler"));
        let mut b = UniformSampler::new(stage_rng(1, "sampler"));
        for _ in 0..1000 {
            let s = a.sample(&bounds, None).unwrap();
            assert!(bounds.contains(s.x, s.y));
            assert!((-PI..PI).contains(&s.yaw));
            assert_eq!(Some(s), b.sample(&bounds, None));
        }
    }
}
