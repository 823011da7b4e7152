//! Shots, the model's curves from lattice poses to a goal off the lattice: what each
//! costs and whether it is valid, kept per goal in a table over the lattice poses
//! around it, so every search to that goal (a cost-matrix row, a DP layer, the legs of
//! each IDP round) solves and checks each shot once.
//!
//! A shot's cost is kept as an `f32` rounded down: a lower bound that orders the
//! search's queue, the same whichever search computed it first; the goal's cost once a
//! shot settles it is the objective's own, solved again.

use super::caches::{known, record, ShotTable, UNKNOWN_COST};
use super::search::Worker;
use super::sources::is_source;
use smug_core::pose::angle_distance;
use smug_core::Pose2;
use std::sync::atomic::Ordering::Relaxed;

/// `cost` rounded down to an `f32` (a lower bound of it).
fn f32_below(cost: f64) -> f32 {
    let rounded = cost as f32;
    if f64::from(rounded) > cost {
        rounded.next_down()
    } else {
        rounded
    }
}

/// A lower bound of the length of every curve of curvature at most `1 / radius`
/// (either gear, any number of cusps) from `a` to `b` (each given with the sine and
/// cosine of its heading), from how far each lies beside the other's heading line.
/// Along such a curve the heading turns at most `s / radius` in its first `s` metres,
/// and the curve moves sideways of `a`'s heading line at most `|sin|` of that turn per
/// metre: after `L` metres it is at most `radius · (1 − cos(L / radius))` beside it
/// while `L ≤ radius · π/2`, at most `radius + L − radius · π/2` beyond. So an offset
/// `y ≤ radius` takes at least `radius · acos(1 − y / radius) ≥ √(2 · radius · y)`
/// metres (`1 − cos t ≤ t²/2`; and a curve longer than `radius · π/2` is longer than
/// that anyway), a larger one at least `y + radius · (π/2 − 1)`. The same curve driven
/// backwards from `b` has the same length, so `a`'s offset beside `b`'s heading line
/// bounds it too.
pub fn sideways_bound(radius: f64, a: (&Pose2, (f64, f64)), b: (&Pose2, (f64, f64))) -> f64 {
    let ((a, (a_sin, a_cos)), (b, (b_sin, b_cos))) = (a, b);
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let beside = (a_cos * dy - a_sin * dx)
        .abs()
        .max((b_cos * dy - b_sin * dx).abs());
    if beside <= radius {
        (2.0 * radius * beside).sqrt()
    } else {
        beside + radius * (std::f64::consts::FRAC_PI_2 - 1.0)
    }
}

impl Worker<'_> {
    /// The slot of the shot from `from` in the goal's table `shots`: none from the
    /// source (off the lattice) or from beyond the table's box.
    fn shot_slot(&self, from: u32, shots: &ShotTable) -> Option<usize> {
        (!is_source(from))
            .then(|| shots.slot(&self.sh.lattice, from))
            .flatten()
    }

    /// The key a shot from `pose` to `goal` is queued at before it is costed, less
    /// the cost of reaching `pose`: a lower bound of its cost (each pose given with
    /// the sine and cosine of its heading). The objective's contract bound, and, for an
    /// objective that costs the model's curves by their length
    /// (`Objective::is_translation_invariant`: path length, `w_t` per metre and `w_r`
    /// per radian turned), `w_t` times a bound of the curve's length, the largest of
    /// `‖Δxy‖`, `r·d(yaw)` (a curve turns at most `1/r` per metre, as
    /// `StateSpace::distance_bound` says) and [`sideways_bound`], plus `w_r·d(yaw)`.
    /// Shrunk by a millionth and rounded down to an `f32`, it stays at or below the
    /// `f32` the shot is costed at ([`Self::shot_cost_below`]): a shot popped uncosted
    /// at its cost is checked at once, in the queue's order, where its costed entry
    /// would have been, so every shot is checked where its cost puts it whichever
    /// bound queued it, and a search finds the same paths; a tighter bound only leaves
    /// more shots unsolved (on lunar with the rover, where most poses near a goal face
    /// away from it or lie beside it).
    pub(super) fn shot_bound(&self, from: (&Pose2, (f64, f64)), to: (&Pose2, (f64, f64))) -> f64 {
        let (pose, goal) = (from.0, to.0);
        let (w_t, w_r) = self.sh.objective.bound_weights();
        let (xy, yaw) = (pose.xy_distance(goal), angle_distance(pose.yaw, goal.yaw));
        // The objective's contract bound, as `cheap_bound` computes it.
        let cheap = w_t * xy + w_r * yaw;
        // Primitives costed once per heading: the objective is translation invariant.
        if self.sh.primitive_costs.is_none() {
            return cheap;
        }
        let radius = self.sh.radius;
        let length = xy.max(radius * yaw).max(sideways_bound(radius, from, to));
        let curve = w_t * length + w_r * yaw;
        cheap.max(f64::from(f32_below(curve * (1.0 - 1e-6))))
    }

    /// A lower bound of the cost of the shot from `from` (at `pose`) to `goal`, within
    /// an `f32` step of it: kept in the goal's table `shots`.
    pub(super) fn shot_cost_below(
        &mut self,
        from: u32,
        pose: &Pose2,
        goal: &Pose2,
        shots: &ShotTable,
    ) -> f64 {
        let slot = self.shot_slot(from, shots);
        if let Some(slot) = slot {
            let bits = shots.costs[slot].load(Relaxed);
            if bits != UNKNOWN_COST {
                return f64::from(f32::from_bits(bits));
            }
        }
        self.me.counts.shot_costs += 1;
        let below = f32_below(self.sh.objective.motion_cost(pose, goal));
        if let Some(slot) = slot {
            shots.costs[slot].store(below.to_bits(), Relaxed);
        }
        f64::from(below)
    }

    /// Whether the shot from `from` (at `pose`) to `goal` is valid: kept in the goal's
    /// table `shots`.
    pub(super) fn shot_valid(
        &mut self,
        from: u32,
        pose: &Pose2,
        goal: &Pose2,
        shots: &ShotTable,
    ) -> bool {
        let slot = self.shot_slot(from, shots);
        if let Some(valid) = slot.and_then(|slot| known(&shots.valid[slot])) {
            return valid;
        }
        self.me.counts.shot_checks += 1;
        let valid = self.sh.motions.is_valid_motion_between_valid(pose, goal);
        if let Some(slot) = slot {
            record(&shots.valid[slot], valid);
        }
        valid
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn costs_are_rounded_down_to_the_nearest_f32() {
        for cost in [0.0, 1.0, 0.1, 1.0 / 3.0, 12_345.678_901_234, f64::INFINITY] {
            let below = f32_below(cost);
            assert!(f64::from(below) <= cost, "{cost}");
            assert!(
                f64::from(below.next_up()) > cost || cost.is_infinite(),
                "{cost}"
            );
        }
    }
}
