//! Validity checkers and a sampler for the planner's tests.

use super::{LazyPrmStar, LazyPrmStarParams};
use smug_core::{
    Bounds2, InformedSet, MotionCheck, MotionValidator, PathLength, Pose2, Result, Sampler,
    Se2Space, StateValidityChecker,
};
use std::sync::Arc;

/// A planner on the bounds `[0, 10]²` with the default SE(2) space and path length,
/// drawing from `Lcg(seed)`, `checker` deciding both states and motions.
pub(super) fn planner_on<C>(params: LazyPrmStarParams, seed: u64, checker: C) -> Result<LazyPrmStar>
where
    C: StateValidityChecker + MotionValidator + 'static,
{
    let checker = Arc::new(checker);
    LazyPrmStar::new(
        params,
        Box::new(Lcg(seed)),
        checker.clone(),
        checker,
        (
            Arc::new(Se2Space::default()),
            Arc::new(PathLength::default()),
        ),
        Bounds2 {
            min: [0.0, 0.0],
            max: [10.0, 10.0],
        },
    )
}

/// Everything is valid.
pub(super) struct Free;

impl StateValidityChecker for Free {
    fn is_valid(&self, _: &Pose2) -> bool {
        true
    }
}

impl MotionValidator for Free {
    fn is_valid_motion(&self, _: &Pose2, _: &Pose2) -> bool {
        true
    }

    fn check_motion(&self, _: &Pose2, _: &Pose2) -> MotionCheck {
        MotionCheck::Valid
    }
}

/// A fixed pseudo-random sequence in the bounds (64-bit LCG), informed set ignored.
pub(super) struct Lcg(pub(super) u64);

impl Lcg {
    fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

impl Sampler for Lcg {
    fn sample(&mut self, b: &Bounds2, _: Option<&InformedSet>) -> Option<Pose2> {
        let x = b.min[0] + self.unit() * (b.max[0] - b.min[0]);
        let y = b.min[1] + self.unit() * (b.max[1] - b.min[1]);
        Some(Pose2::new(x, y, 0.0))
    }
}

/// Invalid on a ring 2 to 3 m around (8, 8): the disc inside is a closed pocket.
pub(super) struct Ring;

impl Ring {
    fn free(p: &Pose2) -> bool {
        let d = (p.x - 8.0).hypot(p.y - 8.0);
        !(2.0..=3.0).contains(&d)
    }
}

impl StateValidityChecker for Ring {
    fn is_valid(&self, p: &Pose2) -> bool {
        Self::free(p)
    }
}

impl MotionValidator for Ring {
    fn is_valid_motion(&self, a: &Pose2, b: &Pose2) -> bool {
        let steps = (a.xy_distance(b) / 0.05).ceil().max(1.0) as usize;
        (0..=steps).all(|i| {
            let t = i as f64 / steps as f64;
            Self::free(&Pose2::new(
                a.x + t * (b.x - a.x),
                a.y + t * (b.y - a.y),
                0.0,
            ))
        })
    }

    fn check_motion(&self, a: &Pose2, b: &Pose2) -> MotionCheck {
        if self.is_valid_motion(a, b) {
            MotionCheck::Valid
        } else {
            MotionCheck::Invalid { last_valid: None }
        }
    }
}

/// Invalid inside any of the discs `(x, y, radius)`; motions checked every 5 cm.
pub(super) struct Discs(pub(super) Vec<(f64, f64, f64)>);

impl Discs {
    fn free(&self, p: &Pose2) -> bool {
        self.0.iter().all(|&(x, y, r)| (p.x - x).hypot(p.y - y) > r)
    }
}

impl StateValidityChecker for Discs {
    fn is_valid(&self, p: &Pose2) -> bool {
        self.free(p)
    }
}

impl MotionValidator for Discs {
    fn is_valid_motion(&self, a: &Pose2, b: &Pose2) -> bool {
        let steps = (a.xy_distance(b) / 0.05).ceil().max(1.0) as usize;
        (0..=steps).all(|i| {
            let t = i as f64 / steps as f64;
            self.free(&Pose2::new(
                a.x + t * (b.x - a.x),
                a.y + t * (b.y - a.y),
                0.0,
            ))
        })
    }

    fn check_motion(&self, a: &Pose2, b: &Pose2) -> MotionCheck {
        if self.is_valid_motion(a, b) {
            MotionCheck::Valid
        } else {
            MotionCheck::Invalid { last_valid: None }
        }
    }
}
