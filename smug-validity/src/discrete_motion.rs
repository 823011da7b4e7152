//! `discrete`: a motion is valid when the states along it, at a fixed resolution,
//! are valid and the terrain inclination between consecutive states stays below a
//! limit. States are checked in bisection order (collisions are found early);
//! `check_motion` scans in order from the start to report the last valid state.

use serde::{Deserialize, Serialize};
use smug_core::{
    BuildContext, CostMetric, Counters, Error, MotionCheck, MotionValidator, Pose2,
    StateValidityChecker, World,
};
use std::collections::VecDeque;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::sync::Arc;

/// Parameters of the discrete motion validator.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DiscreteMotionParams {
    /// Longest metric distance between checked states (OMPL's
    /// `longest_valid_segment_length`; reference: 0.5).
    pub resolution: f64,
    /// Largest terrain slope |Δz| / horizontal distance between consecutive states
    /// (reference: 0.58); needs the world's elevation. Absent: no limit.
    pub max_inclination: Option<f64>,
}

impl Default for DiscreteMotionParams {
    fn default() -> Self {
        Self {
            resolution: 0.5,
            max_inclination: Some(0.58),
        }
    }
}

/// Checks straight motions state by state.
pub struct DiscreteMotionValidator {
    states: Arc<dyn StateValidityChecker>,
    metric: Arc<dyn CostMetric>,
    terrain: Option<(Arc<World>, f64)>,
    resolution: f64,
    motions_checked: AtomicU64,
    states_checked: AtomicU64,
}

impl DiscreteMotionValidator {
    /// A validator over `states` under `metric`; `terrain` = the world and its
    /// inclination limit, when the limit applies.
    pub fn new(
        states: Arc<dyn StateValidityChecker>,
        metric: Arc<dyn CostMetric>,
        terrain: Option<(Arc<World>, f64)>,
        resolution: f64,
    ) -> Result<Self, Error> {
        if !(resolution.is_finite() && resolution > 0.0) {
            return Err(Error::invalid_param(
                "motion",
                format!("resolution must be > 0, got {resolution}"),
            ));
        }
        if let Some((_, limit)) = &terrain {
            if limit.is_nan() || *limit < 0.0 {
                return Err(Error::invalid_param(
                    "motion",
                    format!("max_inclination must be ≥ 0, got {limit}"),
                ));
            }
        }
        Ok(Self {
            states,
            metric,
            terrain,
            resolution,
            motions_checked: AtomicU64::new(0),
            states_checked: AtomicU64::new(0),
        })
    }

    /// Number of segments the motion `a → b` is split into.
    fn segment_count(&self, a: &Pose2, b: &Pose2) -> usize {
        let n = (self.metric.distance(a, b) / self.resolution).ceil();
        if n.is_finite() {
            (n as usize).max(1)
        } else {
            1
        }
    }

    fn state_at(&self, a: &Pose2, b: &Pose2, k: usize, n: usize) -> Pose2 {
        self.metric.interpolate(a, b, k as f64 / n as f64)
    }

    fn is_valid_state(&self, s: &Pose2) -> bool {
        self.states_checked.fetch_add(1, Relaxed);
        self.states.is_valid(s)
    }

    /// True when the terrain between consecutive states is not too steep.
    fn inclination_ok(&self, p: &Pose2, q: &Pose2) -> bool {
        let Some((world, limit)) = &self.terrain else {
            return true;
        };
        let heights = (world.height_at(p.x, p.y), world.height_at(q.x, q.y));
        slope_ok(p.xy_distance(q), heights, *limit)
    }

    /// [`Self::inclination_ok`] for every pair of consecutive states of the
    /// `n`-segment motion `a → b`, looking each state's height up once.
    fn slopes_ok(&self, a: &Pose2, b: &Pose2, n: usize) -> bool {
        let Some((world, limit)) = &self.terrain else {
            return true;
        };
        let mut p = *a;
        let mut zp = world.height_at(p.x, p.y);
        for k in 1..=n {
            let q = self.state_at(a, b, k, n);
            let zq = world.height_at(q.x, q.y);
            if !slope_ok(p.xy_distance(&q), (zp, zq), *limit) {
                return false;
            }
            (p, zp) = (q, zq);
        }
        true
    }

    /// Interior state indices `1..n` in bisection order (midpoints first).
    fn bisection_order(n: usize) -> impl Iterator<Item = usize> {
        let mut queue = VecDeque::from([(0usize, n)]);
        std::iter::from_fn(move || {
            while let Some((lo, hi)) = queue.pop_front() {
                if hi - lo >= 2 {
                    let mid = lo + (hi - lo) / 2;
                    queue.push_back((lo, mid));
                    queue.push_back((mid, hi));
                    return Some(mid);
                }
            }
            None
        })
    }
}

/// True when the slope between two states `horizontal` apart with heights `(zp, zq)`
/// is at most `limit` (no horizontal move: always; a height off the map: never).
fn slope_ok(horizontal: f64, (zp, zq): (Option<f64>, Option<f64>), limit: f64) -> bool {
    if horizontal <= 1e-12 {
        return true;
    }
    match (zp, zq) {
        (Some(zp), Some(zq)) => (zq - zp).abs() / horizontal <= limit,
        _ => false,
    }
}

impl MotionValidator for DiscreteMotionValidator {
    fn is_valid_motion(&self, a: &Pose2, b: &Pose2) -> bool {
        self.motions_checked.fetch_add(1, Relaxed);
        let n = self.segment_count(a, b);
        self.slopes_ok(a, b, n)
            && self.is_valid_state(b)
            && self.is_valid_state(a)
            && Self::bisection_order(n).all(|k| self.is_valid_state(&self.state_at(a, b, k, n)))
    }

    fn check_motion(&self, a: &Pose2, b: &Pose2) -> MotionCheck {
        self.motions_checked.fetch_add(1, Relaxed);
        if !self.is_valid_state(a) {
            return MotionCheck::Invalid { last_valid: None };
        }
        let n = self.segment_count(a, b);
        let mut previous = *a;
        for k in 1..=n {
            let state = self.state_at(a, b, k, n);
            if !(self.inclination_ok(&previous, &state) && self.is_valid_state(&state)) {
                let fraction = (k - 1) as f64 / n as f64;
                return MotionCheck::Invalid {
                    last_valid: Some((previous, fraction)),
                };
            }
            previous = state;
        }
        MotionCheck::Valid
    }

    fn counters(&self) -> Counters {
        Counters::from([
            (
                "motion_checks".to_string(),
                self.motions_checked.load(Relaxed),
            ),
            (
                "motion_state_checks".to_string(),
                self.states_checked.load(Relaxed),
            ),
        ])
    }
}

fn build_validator(
    params: DiscreteMotionParams,
    ctx: &BuildContext,
) -> Result<DiscreteMotionValidator, Error> {
    let terrain = match params.max_inclination {
        Some(limit) => Some((ctx.world()?, limit)),
        None => None,
    };
    DiscreteMotionValidator::new(
        ctx.state_validity()?,
        ctx.metric(),
        terrain,
        params.resolution,
    )
}

smug_core::register_plugin!(
    smug_core::registry::MotionStage,
    name = "discrete",
    summary = "states at a fixed resolution in bisection order, plus a terrain inclination limit",
    params = DiscreteMotionParams,
    build = |params, ctx| Ok(Box::new(build_validator(params, ctx)?)),
);

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use smug_core::{Mission, Se2Metric};
    use smug_worlds::flat::{flat_world, BoxObstacle, FlatParams};

    /// Valid everywhere except inside the disc of radius 1 around (5, 5).
    struct DiscObstacle;

    impl StateValidityChecker for DiscObstacle {
        fn is_valid(&self, s: &Pose2) -> bool {
            (s.x - 5.0).hypot(s.y - 5.0) > 1.0
        }
    }

    fn validator(resolution: f64, terrain: Option<(Arc<World>, f64)>) -> DiscreteMotionValidator {
        DiscreteMotionValidator::new(
            Arc::new(DiscObstacle),
            Arc::new(Se2Metric::default()),
            terrain,
            resolution,
        )
        .unwrap()
    }

    #[test]
    fn bisection_visits_every_interior_state_once() {
        for n in 1..40 {
            let mut seen: Vec<usize> = DiscreteMotionValidator::bisection_order(n).collect();
            assert_eq!(seen[..1.min(seen.len())], [n / 2][..1.min(seen.len())]);
            seen.sort();
            assert_eq!(seen, (1..n).collect::<Vec<_>>());
        }
    }

    #[test]
    fn finds_the_obstacle_and_the_last_valid_state() {
        let v = validator(0.1, None);
        let (a, b) = (Pose2::new(0.0, 5.0, 0.0), Pose2::new(10.0, 5.0, 0.0));
        assert!(!v.is_valid_motion(&a, &b));
        let MotionCheck::Invalid {
            last_valid: Some((state, fraction)),
        } = v.check_motion(&a, &b)
        else {
            panic!("expected an invalid motion with a last valid state");
        };
        assert!(state.x < 4.0 && state.x > 3.85, "{state:?}");
        assert!((fraction - state.x / 10.0).abs() < 1e-9);
        let (c, d) = (Pose2::new(0.0, 0.0, 0.0), Pose2::new(10.0, 0.0, 1.0));
        assert!(v.is_valid_motion(&c, &d));
        assert_eq!(v.check_motion(&c, &d), MotionCheck::Valid);
        assert!(v.counters()["motion_state_checks"] > 0);
    }

    proptest! {
        #[test]
        fn fast_and_ordered_checks_agree(x1 in 0.0f64..10.0, y1 in 0.0f64..10.0, x2 in 0.0f64..10.0, y2 in 0.0f64..10.0) {
            let v = validator(0.05, None);
            let (a, b) = (Pose2::new(x1, y1, 0.0), Pose2::new(x2, y2, 1.0));
            prop_assert_eq!(v.is_valid_motion(&a, &b), v.check_motion(&a, &b).is_valid());
        }
    }

    #[test]
    fn steep_terrain_is_rejected() {
        let mission: Mission = smug_core::toml::from_str("start = { x = 1.0, y = 1.0 }").unwrap();
        let params = FlatParams {
            obstacles: vec![BoxObstacle {
                min: [0.0, 8.0],
                max: [10.0, 10.0],
                height: 0.3,
            }],
            ..FlatParams::default()
        };
        let world = Arc::new(flat_world(&params, mission).unwrap());
        let v = validator(0.1, Some((world.clone(), 0.58)));
        // A 0.3 m step crossed within 0.1 m is far steeper than 0.58.
        assert!(!v.is_valid_motion(&Pose2::new(1.0, 7.0, 0.0), &Pose2::new(1.0, 9.0, 0.0)));
        assert!(v.is_valid_motion(&Pose2::new(1.0, 2.0, 0.0), &Pose2::new(1.0, 4.0, 0.0)));
        let lenient = validator(0.1, Some((world, 10.0)));
        assert!(lenient.is_valid_motion(&Pose2::new(1.0, 7.0, 0.0), &Pose2::new(1.0, 9.0, 0.0)));
    }
}
