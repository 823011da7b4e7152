//! Lower bounds of the lattice's path costs around obstacles, from the goals' 2D
//! obstacle-aware distances (module `heuristic`): what a sequencer orders targets by
//! before it plans the legs (a lazy cost matrix), far tighter among stones than the
//! objective's straight-line bound.

use super::search::Worker;
use smug_core::Pose2;

/// What the obstacle-aware bound is shrunk by: a path's cost is its sampled states'
/// (chords of its arcs: 0.04% below the arcs at 0.1 m on a 1 m radius), and
/// shortcutting takes it below the lattice's a little more.
const SLACK: f64 = 0.99;

impl Worker<'_> {
    /// For each of `goals`, a lower bound of the cost of every path this planner finds
    /// from `from` to it: the objective's contract bound, and the least, over the ways
    /// a search leaves `from`, of what they cost at least. A search reaches a goal by a
    /// direct shot (only within the shot radius), or joins a lattice point within the
    /// shot radius (at `w_t` per metre of straight distance at least) and goes on from
    /// there (at least the goal's obstacle-aware distance from that point).
    /// The obstacle-aware part is shrunk by [`SLACK`]: a path's sampled states and its
    /// shortcuts cost a little less than its lattice curves.
    pub(super) fn cost_bounds(&mut self, from: &Pose2, goals: &[Pose2]) -> Vec<f64> {
        let cheap: Vec<f64> = goals.iter().map(|g| self.cheap_bound(from, g)).collect();
        if !self.sh.params.obstacle_heuristic {
            return cheap;
        }
        self.keep_missing_heuristics(goals);
        let (w_t, _) = self.sh.objective.bound_weights();
        let (lattice, reach) = (&self.sh.lattice, self.sh.shot_radius);
        let joined: Vec<(usize, f64)> = lattice
            .points_near(from.x, from.y, reach)
            .into_iter()
            .map(|(ix, iy)| {
                let [x, y] = lattice.position(ix, iy);
                let point = lattice.id(ix, iy, 0) as usize / lattice.headings;
                (point, w_t * (x - from.x).hypot(y - from.y))
            })
            .collect();
        goals
            .iter()
            .zip(cheap)
            .map(|(goal, cheap)| {
                let field = self.goal_heuristic(std::slice::from_ref(goal));
                let mut least = if from.xy_distance(goal) <= reach {
                    cheap
                } else {
                    f64::INFINITY
                };
                for &(point, join) in &joined {
                    // f32 rounding: stay below the exact distance.
                    let onward = f64::from(field[point]) * (1.0 - 1e-6);
                    least = least.min(join + onward);
                }
                // No lattice path at all: the planner proves that when asked.
                if least.is_finite() {
                    (SLACK * least).max(cheap)
                } else {
                    cheap
                }
            })
            .collect()
    }
}
