//! Greedy shortcutting: from each kept state, jump to the farthest later state that
//! the motion validator accepts. Under a metric the cost never rises (triangle
//! inequality), and every new segment is checked, so the path stays valid.

use smug_core::{MotionValidator, Pose2};

/// The shortcut path through `states` (same endpoints).
pub fn shortcut(states: &[Pose2], motions: &dyn MotionValidator) -> Vec<Pose2> {
    if states.len() <= 2 {
        return states.to_vec();
    }
    let mut kept = vec![states[0]];
    let mut i = 0;
    while i + 1 < states.len() {
        let mut j = states.len() - 1;
        while j > i + 1 && !motions.is_valid_motion(&states[i], &states[j]) {
            j -= 1;
        }
        kept.push(states[j]);
        i = j;
    }
    kept
}
