//! Expansion of a query's endpoints: samples along the motion model's own curves out of
//! the start and into the goal, for queries that uniform samples do not connect (a car
//! parked facing a rock: only a thin set of poses behind it reach it by one curve).
//!
//! Each endpoint grows a tree of the valid samples expanded from it (PRM's expansion
//! step, Kavraki et al. 1996): a base is drawn uniformly from the tree, a target pose
//! uniformly within `reach` of it (any heading), and the sample is the pose a random
//! fraction along the model's curve from the base to the target (for the goal: along
//! the curve from the target into the base, so that the goal is reachable from it in a
//! directed model). A shortest curve's pieces are shortest curves, so the roadmap edge
//! between the base and the sample is the piece already drawn. A sample joins its tree
//! only when that piece is valid, so a tree holds only poses its endpoint reaches.

use rand::Rng;
use smug_core::rng::StageRng;
use smug_core::{Bounds2, Pose2, StateSpace};
use std::f64::consts::PI;

/// Which end of the query a sample is expanded from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum End {
    /// Out of the start (curves leave the tree).
    Start,
    /// Into the goal (curves enter the tree).
    Goal,
}

/// The expansion trees of the current query.
pub(super) struct Expansion {
    rng: StageRng,
    reach: f64,
    share: f64,
    start_tree: Vec<Pose2>,
    goal_tree: Vec<Pose2>,
    next: End,
}

impl Expansion {
    /// Expansion with targets within `reach` of the base, used for `share` of the samples.
    pub(super) fn new(rng: StageRng, reach: f64, share: f64) -> Self {
        Self {
            rng,
            reach,
            share,
            start_tree: Vec::new(),
            goal_tree: Vec::new(),
            next: End::Start,
        }
    }

    /// Starts the trees of a new query at its endpoints.
    pub(super) fn begin(&mut self, start: &Pose2, goal: &Pose2) {
        self.start_tree = vec![*start];
        self.goal_tree = vec![*goal];
        self.next = End::Start;
    }

    /// True when the next sample is to be expanded (drawn with this expansion's own
    /// generator, so that the sampler's sequence is untouched until expansion begins).
    pub(super) fn is_due(&mut self) -> bool {
        self.share > 0.0 && self.rng.random::<f64>() < self.share
    }

    /// The next expansion sample, alternating the ends, with the motion that joins it
    /// to its tree (`(from, to)`, in driving order); `None` when it falls outside
    /// `bounds`.
    pub(super) fn sample(
        &mut self,
        space: &dyn StateSpace,
        bounds: &Bounds2,
    ) -> Option<(End, Pose2, (Pose2, Pose2))> {
        let end = self.next;
        self.next = match end {
            End::Start => End::Goal,
            End::Goal => End::Start,
        };
        let tree = match end {
            End::Start => &self.start_tree,
            End::Goal => &self.goal_tree,
        };
        let base = tree[self.rng.random_range(0..tree.len())];
        let target = self.target_near(&base);
        let t = 1.0 - self.rng.random::<f64>(); // (0, 1]
        let (sample, motion) = match end {
            End::Start => {
                let sample = space.interpolate(&base, &target, t);
                (sample, (base, sample))
            }
            End::Goal => {
                let sample = space.interpolate(&target, &base, 1.0 - t);
                (sample, (sample, base))
            }
        };
        bounds
            .contains(sample.x, sample.y)
            .then_some((end, sample, motion))
    }

    /// Adds a valid sample to the tree of `end`.
    pub(super) fn grow(&mut self, end: End, sample: Pose2) {
        match end {
            End::Start => self.start_tree.push(sample),
            End::Goal => self.goal_tree.push(sample),
        }
    }

    /// A pose uniformly within `reach` of `base` (by area), any heading.
    fn target_near(&mut self, base: &Pose2) -> Pose2 {
        let r = self.reach * self.rng.random::<f64>().sqrt();
        let angle = self.rng.random_range(-PI..PI);
        let yaw = self.rng.random_range(-PI..PI);
        Pose2::new(base.x + r * angle.cos(), base.y + r * angle.sin(), yaw)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::rng::stage_rng;
    use smug_core::Se2Space;

    #[test]
    fn samples_lie_on_straight_motions_from_the_trees_within_reach() {
        let bounds = Bounds2 {
            min: [-10.0, -10.0],
            max: [10.0, 10.0],
        };
        let (start, goal) = (Pose2::new(0.0, 0.0, 0.0), Pose2::new(5.0, 0.0, 1.0));
        let mut expansion = Expansion::new(stage_rng(1, "expansion"), 1.0, 0.5);
        expansion.begin(&start, &goal);
        let mut ends = Vec::new();
        for _ in 0..50 {
            let (end, sample, motion) = expansion
                .sample(&Se2Space::default(), &bounds)
                .expect("inside the bounds");
            let base = if end == End::Start { start } else { goal };
            let expected = if end == End::Start {
                (base, sample)
            } else {
                (sample, base)
            };
            assert_eq!(motion, expected, "the motion joins the sample to its tree");
            assert!(sample.xy_distance(&base) <= 1.0 + 1e-12, "{sample:?}");
            ends.push(end);
        }
        assert!(ends.windows(2).all(|w| w[0] != w[1]), "the ends alternate");
        expansion.grow(End::Start, Pose2::new(0.9, 0.0, 0.0));
        let far = (0..200)
            .filter_map(|_| expansion.sample(&Se2Space::default(), &bounds))
            .map(|(_, p, _)| p)
            .any(|p| p.xy_distance(&start) > 1.0 && p.xy_distance(&goal) > 1.0);
        assert!(far, "the start tree grows from its new vertex");
    }

    #[test]
    fn no_share_is_never_due() {
        let mut expansion = Expansion::new(stage_rng(1, "expansion"), 1.0, 0.0);
        assert!((0..100).all(|_| !expansion.is_due()));
    }
}
