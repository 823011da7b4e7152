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
    /// For each of `starts`, a lower bound of the cost of every path this planner
    /// finds from it to each of `goals` (a row per start): the objective's contract
    /// bound, and the least, over the ways a search leaves the start, of what they
    /// cost at least. A search reaches a goal by a direct shot (only within the shot
    /// radius), or joins a lattice point within the shot radius (at `w_t` per metre of
    /// straight distance at least) and goes on from there (at least the goal's
    /// obstacle-aware distance from that point). That part is shrunk by [`SLACK`]: a
    /// path's sampled states and its shortcuts cost a little less than its lattice
    /// curves. Each goal's distances are computed once, a few goals at a time side by
    /// side (however many are kept), so the bounds cost one field per goal.
    pub(super) fn cost_bounds(&mut self, starts: &[Pose2], goals: &[Pose2]) -> Vec<Vec<f64>> {
        let mut bounds: Vec<Vec<f64>> = starts
            .iter()
            .map(|s| goals.iter().map(|g| self.cheap_bound(s, g)).collect())
            .collect();
        if !self.sh.params.obstacle_heuristic {
            return bounds;
        }
        let joined: Vec<Vec<(usize, f64)>> = starts.iter().map(|s| self.joined(s)).collect();
        let batch = 2 * rayon::current_num_threads().max(1);
        for (c, chunk) in goals.chunks(batch).enumerate() {
            self.keep_missing_heuristics(chunk);
            for (k, goal) in chunk.iter().enumerate() {
                let field = self.goal_heuristic(std::slice::from_ref(goal));
                for (s, start) in starts.iter().enumerate() {
                    let row = &mut bounds[s][c * batch + k];
                    let direct = start.xy_distance(goal) <= self.sh.shot_radius;
                    let mut least = if direct { *row } else { f64::INFINITY };
                    for &(point, join) in &joined[s] {
                        // f32 rounding: stay below the exact distance.
                        let onward = f64::from(field[point]) * (1.0 - 1e-6);
                        least = least.min(join + onward);
                    }
                    // No lattice path at all: the planner proves that when asked.
                    if least.is_finite() {
                        *row = row.max(SLACK * least);
                    }
                }
            }
        }
        bounds
    }

    /// The lattice points a search from `start` can join (within the shot radius),
    /// each with `w_t` times its straight distance from `start`.
    fn joined(&self, start: &Pose2) -> Vec<(usize, f64)> {
        let (w_t, _) = self.sh.objective.bound_weights();
        let lattice = &self.sh.lattice;
        lattice
            .points_near(start.x, start.y, self.sh.shot_radius)
            .into_iter()
            .map(|(ix, iy)| {
                let [x, y] = lattice.position(ix, iy);
                let point = lattice.id(ix, iy, 0) as usize / lattice.headings;
                (point, w_t * (x - start.x).hypot(y - start.y))
            })
            .collect()
    }
}
