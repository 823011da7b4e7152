//! Bridge samples for narrow passages (Hsu et al. 2003, the bridge test): a query
//! that has gone `expand_after` samples without a path turns each invalid sample into
//! a bridge attempt. A second pose is drawn near it (a Gaussian step); when that is
//! invalid too, the pose halfway between them is checked, and kept when valid: it lies
//! between two obstacles, where a passage a little wider than the robot is — the thin
//! set of poses uniform samples seldom hit (a doorway, the gap a new rock leaves beside
//! a wall). Valid samples are kept as drawn, so a query loses none of its uniform
//! samples; an attempt is one sample of the budget.

use rand_distr::{Distribution, Normal};
use smug_core::rng::StageRng;
use smug_core::{Pose2, StateSpace};

/// The bridge attempts of the current planner.
pub(super) struct Bridge {
    rng: StageRng,
    /// The Gaussian step's standard deviation in x and y, metres (0: no bridges).
    sigma: f64,
}

/// The step's standard deviation in heading per metre of `sigma` (radians): a bridge
/// across a passage turns the robot little, its halfway pose keeps a heading close to
/// the invalid sample's.
const YAW_SIGMA_PER_METRE: f64 = 0.5;

impl Bridge {
    /// Bridges with steps of standard deviation `sigma` metres (0: none).
    pub(super) fn new(rng: StageRng, sigma: f64) -> Self {
        Self { rng, sigma }
    }

    /// True when bridges are drawn at all.
    pub(super) fn is_on(&self) -> bool {
        self.sigma > 0.0
    }

    /// The other end of a bridge from the invalid pose `from`: a Gaussian step in x, y
    /// and heading.
    pub(super) fn partner(&mut self, from: &Pose2) -> Pose2 {
        let step = Normal::new(0.0, self.sigma).expect("a finite, positive sigma");
        let turn = Normal::new(0.0, self.sigma * YAW_SIGMA_PER_METRE).expect("finite");
        let (dx, dy, dyaw) = (
            step.sample(&mut self.rng),
            step.sample(&mut self.rng),
            turn.sample(&mut self.rng),
        );
        Pose2::new(from.x + dx, from.y + dy, from.yaw + dyaw)
    }

    /// The pose halfway along the model's curve between the bridge's ends.
    pub(super) fn midpoint(space: &dyn StateSpace, a: &Pose2, b: &Pose2) -> Pose2 {
        space.interpolate(a, b, 0.5)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::rng::stage_rng;
    use smug_core::Se2Space;

    #[test]
    fn partners_lie_near_their_pose_and_midpoints_halfway() {
        let mut bridge = Bridge::new(stage_rng(1, "bridge"), 0.5);
        let from = Pose2::new(3.0, -2.0, 0.5);
        let partners: Vec<Pose2> = (0..500).map(|_| bridge.partner(&from)).collect();
        let mean_step =
            partners.iter().map(|p| p.xy_distance(&from)).sum::<f64>() / partners.len() as f64;
        // The mean length of a 2D Gaussian step is sigma * sqrt(pi / 2) ~ 0.63.
        assert!((0.5..0.75).contains(&mean_step), "{mean_step}");
        let p = partners[0];
        let mid = Bridge::midpoint(&Se2Space::default(), &from, &p);
        assert!((mid.xy_distance(&from) - mid.xy_distance(&p)).abs() < 1e-9);
    }

    #[test]
    fn no_sigma_is_off() {
        assert!(!Bridge::new(stage_rng(1, "bridge"), 0.0).is_on());
        assert!(Bridge::new(stage_rng(1, "bridge"), 1.0).is_on());
    }
}
