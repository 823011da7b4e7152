//! Post-processing of a found path (shortcutting or smoothing), its checks counted.

use super::*;

impl LazyPrmStar {
    /// The path of `graph_path`, shortcut or smoothed as configured; the motion checks
    /// of that post-processing are counted and timed as edge checks.
    pub(super) fn post_processed(&mut self, graph_path: &GraphPath) -> Path {
        let motions = CountedMotions::new(self.motions.as_ref());
        let path = self.post_process(graph_path, &motions);
        let (checks, nanoseconds) = (motions.checks.total(), motions.nanoseconds.total());
        self.count_post_processing(checks, nanoseconds);
        path
    }

    /// [`post_processed`](Self::post_processed) for many paths, processed in parallel
    /// (each path's processing is deterministic and independent of the others, so
    /// the paths are the same as one by one; the checking time booked is the sum
    /// over the threads).
    pub(super) fn post_processed_all(&mut self, graph_paths: &[GraphPath]) -> Vec<Path> {
        let motions = CountedMotions::new(self.motions.as_ref());
        let this = &*self;
        let paths = graph_paths
            .par_iter()
            .map(|graph_path| this.post_process(graph_path, &motions))
            .collect();
        let (checks, nanoseconds) = (motions.checks.total(), motions.nanoseconds.total());
        self.count_post_processing(checks, nanoseconds);
        paths
    }

    /// Books post-processing checks as edge checks.
    pub(super) fn count_post_processing(&mut self, checks: u64, nanoseconds: u64) {
        self.counts.edge_checks += checks;
        self.counts.breakdown.edge_checking_s += nanoseconds as f64 * 1e-9;
    }

    /// The shortcut or smoothed path of `graph_path`, its checks made through `motions`.
    pub(super) fn post_process(&self, graph_path: &GraphPath, motions: &CountedMotions) -> Path {
        let states: Vec<Pose2> = graph_path
            .vertices
            .iter()
            .map(|&v| *self.roadmap.pose(v))
            .collect();
        let processed = if self.params.smooth {
            smooth(
                &states,
                motions,
                self.space.as_ref(),
                self.objective.as_ref(),
            )
        } else if self.params.shortcut {
            shortcut(&states, motions)
        } else {
            return Path::new(states, self.objective.as_ref());
        };
        let processed = Path::new(processed, self.objective.as_ref());
        // A shortcut never costs more under a metric objective; under others (risk,
        // energy, time) a straighter path may cross costlier ground: keep the cheaper.
        if processed.cost <= graph_path.cost * (1.0 + 1e-9) + 1e-12 {
            processed
        } else {
            Path::new(states, self.objective.as_ref())
        }
    }
}
