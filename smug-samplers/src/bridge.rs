//! `bridge`: the bridge test (Hsu, Jiang, Reif & Sun 2003; OMPL's
//! `BridgeTestValidStateSampler`) mixed with informed sampling, for narrow passages.
//!
//! A share `ratio` of the samples are bridges: draw `a` as the `informed` sampler would
//! (in the query's informed set once a path is known, else in the bounds); if `a` is
//! invalid, draw `b` around it (Gaussian, standard deviation `std_dev` per axis, same
//! yaw); if `b` is invalid too and their midpoint is valid, the midpoint is the sample —
//! a state pinched between two nearby obstacles: a door, a gap, a corridor, which
//! uniform samples hit with a probability proportional to its (tiny) area. A bridge
//! that fails `max_bridge_attempts` times in a row gives way to an ordinary informed
//! sample, so every call costs a bounded number of state checks. Samples always lie
//! in the bounds and, when an informed set is given, in it.

use crate::informed::{InformedEllipse, InformedParams, InformedSampler};
use rand::Rng;
use serde::{Deserialize, Serialize};
use smug_core::rng::StageRng;
use smug_core::{
    Bounds2, BuildContext, Error, InformedSet, Objective, Pose2, Sampler, StateValidityChecker,
};
use std::f64::consts::PI;
use std::sync::Arc;

/// Parameters of the bridge-test sampler.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BridgeParams {
    /// Share of the samples drawn by the bridge test, in `[0, 1]` (the rest: informed).
    pub ratio: f64,
    /// Standard deviation of the second end of a bridge around the first, per axis,
    /// metres: about the width of the passages to find.
    pub std_dev: f64,
    /// Bridge tries per sample before falling back to an informed sample.
    pub max_bridge_attempts: u32,
    /// Rejection attempts of the informed part (see `informed`).
    pub max_attempts: u32,
}

impl Default for BridgeParams {
    fn default() -> Self {
        Self {
            ratio: 0.8,
            std_dev: 1.0,
            max_bridge_attempts: 100,
            max_attempts: InformedParams::default().max_attempts,
        }
    }
}

impl BridgeParams {
    /// Checks the ranges; errors name the parameter.
    pub fn validate(&self) -> Result<(), Error> {
        if !(self.ratio.is_finite() && (0.0..=1.0).contains(&self.ratio)) {
            return Err(Error::invalid_param(
                "sampler",
                format!("ratio must be in [0, 1], got {}", self.ratio),
            ));
        }
        if !(self.std_dev.is_finite() && self.std_dev > 0.0) {
            return Err(Error::invalid_param(
                "sampler",
                format!("std_dev must be > 0, got {}", self.std_dev),
            ));
        }
        Ok(())
    }
}

/// Informed sampling with a share of bridge-test samples.
pub struct BridgeSampler {
    params: BridgeParams,
    base: InformedSampler,
    rng: StageRng,
    states: Arc<dyn StateValidityChecker>,
    weights: (f64, f64),
}

impl BridgeSampler {
    /// A sampler for the informed sets of `objective` checking bridges with `states`;
    /// `base_rng` drives the informed part, `bridge_rng` the bridges.
    pub fn new(
        params: BridgeParams,
        objective: Arc<dyn Objective>,
        states: Arc<dyn StateValidityChecker>,
        base_rng: StageRng,
        bridge_rng: StageRng,
    ) -> Result<Self, Error> {
        params.validate()?;
        let informed = InformedParams {
            max_attempts: params.max_attempts,
        };
        Ok(Self {
            params,
            weights: objective.bound_weights(),
            base: InformedSampler::new(informed, objective, base_rng),
            rng: bridge_rng,
            states,
        })
    }

    /// A standard normal variate (Box–Muller).
    fn standard_normal(&mut self) -> f64 {
        let u: f64 = 1.0 - self.rng.random::<f64>(); // (0, 1]: ln stays finite
        let theta = self.rng.random_range(-PI..PI);
        (-2.0 * u.ln()).sqrt() * theta.cos()
    }

    /// The other end of a bridge from `a`: Gaussian around it, same yaw.
    fn bridge_end(&mut self, a: &Pose2) -> Pose2 {
        let dx = self.params.std_dev * self.standard_normal();
        let dy = self.params.std_dev * self.standard_normal();
        Pose2::new(a.x + dx, a.y + dy, a.yaw)
    }

    /// True when `p` may be returned: in the bounds and in the informed set.
    fn admissible(&self, p: &Pose2, bounds: &Bounds2, ellipse: Option<&InformedEllipse>) -> bool {
        bounds.contains(p.x, p.y) && ellipse.is_none_or(|e| e.contains(p.x, p.y))
    }

    /// One bridge try from the informed sample `a`: the valid midpoint between `a` and
    /// a nearby state when both ends are invalid.
    fn try_bridge(
        &mut self,
        a: &Pose2,
        bounds: &Bounds2,
        ellipse: Option<&InformedEllipse>,
    ) -> Option<Pose2> {
        if self.states.is_valid(a) {
            return None;
        }
        let b = self.bridge_end(a);
        if self.states.is_valid(&b) {
            return None;
        }
        let mid = Pose2::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0, a.yaw);
        (self.admissible(&mid, bounds, ellipse) && self.states.is_valid(&mid)).then_some(mid)
    }

    /// The query's informed ellipse, when a finite-cost set is given.
    fn ellipse(&self, informed: Option<&InformedSet>) -> Option<InformedEllipse> {
        let set = informed.filter(|s| s.best_cost.is_finite())?;
        InformedEllipse::new(set, self.weights.0, self.weights.1)
    }
}

impl Sampler for BridgeSampler {
    fn sample(&mut self, bounds: &Bounds2, informed: Option<&InformedSet>) -> Option<Pose2> {
        let first = self.base.sample(bounds, informed)?;
        if self.rng.random::<f64>() >= self.params.ratio {
            return Some(first);
        }
        let ellipse = self.ellipse(informed);
        let mut a = first;
        for _ in 0..self.params.max_bridge_attempts {
            if let Some(mid) = self.try_bridge(&a, bounds, ellipse.as_ref()) {
                return Some(mid);
            }
            a = self.base.sample(bounds, informed)?;
        }
        Some(a)
    }
}

fn build_bridge(params: BridgeParams, ctx: &BuildContext) -> Result<BridgeSampler, Error> {
    BridgeSampler::new(
        params,
        ctx.objective(),
        ctx.state_validity()?,
        ctx.rng("sampler"),
        ctx.rng("sampler-bridge"),
    )
}

smug_core::register_plugin!(
    smug_core::registry::SamplerStage,
    name = "bridge",
    summary = "informed sampling plus a share of bridge-test samples (narrow passages, doors)",
    params = BridgeParams,
    build = |params, ctx| Ok(Box::new(build_bridge(params, ctx)?)),
);

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::objective::PathLength;
    use smug_core::rng::stage_rng;

    /// A 10 × 10 m map split by a wall `x ∈ [4.6, 5.4]` with a door `y ∈ [4.7, 5.3]`.
    struct WallWithDoor;

    const BOUNDS: Bounds2 = Bounds2 {
        min: [0.0, 0.0],
        max: [10.0, 10.0],
    };

    fn in_door(p: &Pose2) -> bool {
        (4.6..=5.4).contains(&p.x) && (4.7..=5.3).contains(&p.y)
    }

    impl StateValidityChecker for WallWithDoor {
        fn is_valid(&self, p: &Pose2) -> bool {
            BOUNDS.contains(p.x, p.y) && (!(4.6..=5.4).contains(&p.x) || in_door(p))
        }
    }

    fn sampler(params: BridgeParams, seed: u64) -> BridgeSampler {
        BridgeSampler::new(
            params,
            Arc::new(PathLength::default()),
            Arc::new(WallWithDoor),
            stage_rng(seed, "sampler"),
            stage_rng(seed, "sampler-bridge"),
        )
        .unwrap()
    }

    fn door_share(s: &mut dyn Sampler, informed: Option<&InformedSet>, n: usize) -> f64 {
        let inside = (0..n)
            .filter(|_| in_door(&s.sample(&BOUNDS, informed).unwrap()))
            .count();
        inside as f64 / n as f64
    }

    #[test]
    fn bridges_find_the_door_far_more_often_than_uniform_samples() {
        // The door is 0.48% of the map; only bridges give that much more.
        let params = BridgeParams {
            ratio: 1.0,
            max_bridge_attempts: 100,
            ..BridgeParams::default()
        };
        let bridge = door_share(&mut sampler(params, 1), None, 4000);
        let plain = door_share(
            &mut sampler(
                BridgeParams {
                    ratio: 0.0,
                    ..params
                },
                1,
            ),
            None,
            4000,
        );
        assert!(bridge > 0.05, "door share {bridge}");
        assert!(bridge > 10.0 * plain, "bridge {bridge} vs uniform {plain}");
    }

    #[test]
    fn samples_stay_in_the_bounds_and_the_informed_set() {
        let (start, goal) = (Pose2::new(1.0, 5.0, 0.0), Pose2::new(9.0, 5.0, 0.0));
        let set = InformedSet {
            start,
            goal,
            best_cost: 9.0,
        };
        let params = BridgeParams {
            ratio: 0.7,
            ..BridgeParams::default()
        };
        let mut s = sampler(params, 2);
        let mut in_door_count = 0;
        for _ in 0..3000 {
            let p = s.sample(&BOUNDS, Some(&set)).unwrap();
            assert!(BOUNDS.contains(p.x, p.y));
            assert!(p.xy_distance(&start) + p.xy_distance(&goal) <= 9.0 + 1e-9);
            in_door_count += usize::from(in_door(&p));
        }
        assert!(in_door_count > 0);
    }

    #[test]
    fn runs_are_reproducible_for_a_seed() {
        let draw = |seed| {
            let mut s = sampler(BridgeParams::default(), seed);
            (0..200)
                .map(|_| s.sample(&BOUNDS, None).unwrap())
                .collect::<Vec<_>>()
        };
        assert_eq!(draw(3), draw(3));
        assert_ne!(draw(3), draw(4));
    }

    #[test]
    fn an_empty_informed_set_gives_no_sample() {
        let (start, goal) = (Pose2::new(1.0, 1.0, 0.0), Pose2::new(3.0, 1.0, 0.0));
        let set = InformedSet {
            start,
            goal,
            best_cost: 2.0,
        };
        assert_eq!(
            sampler(BridgeParams::default(), 5).sample(&BOUNDS, Some(&set)),
            None
        );
    }

    #[test]
    fn out_of_range_params_are_rejected() {
        for params in [
            BridgeParams {
                ratio: 1.5,
                ..BridgeParams::default()
            },
            BridgeParams {
                std_dev: 0.0,
                ..BridgeParams::default()
            },
            BridgeParams {
                std_dev: f64::NAN,
                ..BridgeParams::default()
            },
        ] {
            assert!(params.validate().is_err(), "{params:?}");
        }
    }
}
