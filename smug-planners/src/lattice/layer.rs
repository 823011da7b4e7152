//! A DP layer in one search: many sources, each with the cost already paid to be
//! there, to a set of goals; each goal settles at the least offset plus path cost
//! over all sources (the multi-source form of the one-to-many search).

use super::search::Worker;
use super::search::{Goal, Until};
use super::sources::MAX_SOURCES;
use smug_core::{LayerOutcome, PlannerOutcome, Pose2};
use std::time::Instant;

impl Worker<'_> {
    /// One search from every valid source of `sources` to every goal, of at most
    /// `max_expansions` expansions (0: as many as the lattice has). A source's offset
    /// is the cost its node starts at, so a goal settles at `min_s offset_s + c(s, goal)`
    /// on the lattice, as the least of one search per source would give (the path from
    /// the winning source is then shortcut as every path is).
    pub(super) fn search_layer(
        &mut self,
        sources: &[(Pose2, f64)],
        goals: &[Pose2],
        max_expansions: u64,
    ) -> Vec<LayerOutcome> {
        let started = Instant::now();
        self.me.counts.searches += 1;
        let (valid, searched) = self.valid_sources(sources);
        let no_path = |outcome| LayerOutcome { source: 0, outcome };
        if valid.is_empty() {
            return vec![no_path(PlannerOutcome::InvalidStart); goals.len()];
        }
        let mut answers = vec![no_path(PlannerOutcome::InvalidGoal); goals.len()];
        let (index, asked) = self.valid_goals(goals);
        if !asked.is_empty() {
            let poses: Vec<Pose2> = searched.iter().map(|s| s.0).collect();
            let (reached, end) = self.run(&searched, asked, max_expansions, Until::EveryGoal);
            for (goal, k) in reached.iter().zip(index) {
                let (s, outcome) = self.outcome(&poses, goal, &end);
                answers[k] = LayerOutcome {
                    source: valid[s],
                    outcome,
                };
            }
        }
        self.me.counts.breakdown.astar_s += started.elapsed().as_secs_f64();
        answers
    }

    /// The search of [`Self::search_layer`] run only for what it leaves in the caches
    /// (the next layer's, run ahead at offsets not known yet): no outcome is built.
    pub(super) fn warm_layer(
        &mut self,
        sources: &[(Pose2, f64)],
        goals: &[Pose2],
        max_expansions: u64,
    ) {
        let (_, searched) = self.valid_sources(sources);
        let (_, asked) = self.valid_goals(goals);
        if !searched.is_empty() && !asked.is_empty() {
            self.run(&searched, asked, max_expansions, Until::EveryGoal);
        }
    }

    /// The sources a search can start from (finite offset, valid pose; at most
    /// [`MAX_SOURCES`]): their indices in `sources`, and themselves.
    fn valid_sources(&self, sources: &[(Pose2, f64)]) -> (Vec<usize>, Vec<(Pose2, f64)>) {
        (0..sources.len().min(MAX_SOURCES))
            .filter(|&s| sources[s].1.is_finite() && self.sh.states.is_valid(&sources[s].0))
            .map(|s| (s, sources[s]))
            .unzip()
    }

    /// The valid goals of `goals`: their indices, and each as a search's goal.
    fn valid_goals(&self, goals: &[Pose2]) -> (Vec<usize>, Vec<Goal>) {
        (0..goals.len())
            .filter(|&k| self.sh.states.is_valid(&goals[k]))
            .map(|k| (k, self.goal(&goals[k])))
            .unzip()
    }

    /// A goal of a search, its shot table shared with every search to it.
    pub(super) fn goal(&self, pose: &Pose2) -> Goal {
        Goal {
            pose: *pose,
            dir: pose.yaw.sin_cos(),
            reached: None,
            proved_out: false,
            shots: self.sh.caches.shot_table(pose, || {
                super::caches::ShotTable::new(&self.sh.lattice, pose, self.sh.shot_radius)
            }),
        }
    }
}
