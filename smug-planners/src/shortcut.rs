//! Greedy shortcutting: from each kept state, jump to the farthest later state that
//! the motion validator accepts. Under a metric objective the cost never rises
//! (triangle inequality); under others the planner keeps the cheaper of the path and
//! its shortcut. Every new segment is checked, so the path stays valid.
//!
//! [`shortcut_galloping`] finds a far jump by galloping instead (try 1, 2, 4… states
//! ahead until a segment is invalid), then bisecting between the last valid and the
//! first invalid jump: a handful of checks per kept state, each about as long as the
//! shortcut itself, where trying every later state from the farthest down costs a
//! check of every long segment (a long path through clutter has many, all invalid).
//!
//! [`smooth`] goes further: it alternates greedy shortcutting with corner cutting —
//! each interior state `v` between `a` and `b` is replaced by two states on its
//! segments, `p` on `v → a` and `q` on `v → b` at the largest fraction (found by
//! bisection) whose segments `a → p → q → b` are all valid — which pulls the path taut
//! around the obstacles' corners, in its homotopy class: a roadmap path's zigzag
//! through a door or along a wall becomes nearly the shortest path through it. Both
//! steps only replace a part of the path by a cheaper one whose segments the motion
//! validator accepts, so the cost never rises and the path stays valid.
//!
//! The input is a valid path (its segments were checked, so its states are valid),
//! and every state these steps add ends a segment checked valid: a segment between
//! two such states is asked with
//! [`is_valid_motion_between_valid`](MotionValidator::is_valid_motion_between_valid),
//! which may skip the ends' checks (the same verdict, two state checks fewer).

use smug_core::{MotionValidator, Objective, Pose2, StateSpace};

/// Rounds of [`smooth`] at most (each: one shortcut pass and one corner-cutting pass).
const SMOOTH_ROUNDS: usize = 8;
/// [`smooth`] stops once a round saves less than this share of the path's cost.
const SMOOTH_TOLERANCE: f64 = 1e-3;
/// Bisection steps of a corner cut (the cut's fraction is found to `2⁻⁶`).
const CUT_BISECTIONS: u32 = 6;

/// The shortcut path through the valid path `states` (same endpoints): from each kept
/// state, the farthest later state with a valid segment.
pub fn shortcut(states: &[Pose2], motions: &dyn MotionValidator) -> Vec<Pose2> {
    if states.len() <= 2 {
        return states.to_vec();
    }
    let mut kept = vec![states[0]];
    let mut i = 0;
    while i + 1 < states.len() {
        let mut j = states.len() - 1;
        while j > i + 1 && !motions.is_valid_motion_between_valid(&states[i], &states[j]) {
            j -= 1;
        }
        kept.push(states[j]);
        i = j;
    }
    kept
}

/// The shortcut path through the valid path `states` (same endpoints), each jump found
/// by galloping and bisection (far, not always the farthest; few checks on long paths).
pub fn shortcut_galloping(states: &[Pose2], motions: &dyn MotionValidator) -> Vec<Pose2> {
    if states.len() <= 2 {
        return states.to_vec();
    }
    let mut kept = vec![states[0]];
    let mut i = 0;
    while i + 1 < states.len() {
        i = farthest_jump(states, i, motions);
        kept.push(states[i]);
    }
    kept
}

/// A later state `j > i` with a valid segment `i → j`, found by galloping then
/// bisecting; `i + 1` when no farther one is found (consecutive states are joined
/// by the path's own valid segments).
fn farthest_jump(states: &[Pose2], i: usize, motions: &dyn MotionValidator) -> usize {
    let last = states.len() - 1;
    let reaches = |j: usize| motions.is_valid_motion_between_valid(&states[i], &states[j]);
    let (mut valid, mut step) = (i + 1, 1);
    let invalid = loop {
        if valid == last {
            return last;
        }
        let j = (valid + step).min(last);
        if !reaches(j) {
            break j;
        }
        valid = j;
        step *= 2;
    };
    bisect_jump(valid, invalid, reaches)
}

/// The last valid jump found by bisecting between a valid and an invalid one.
fn bisect_jump(mut valid: usize, mut invalid: usize, reaches: impl Fn(usize) -> bool) -> usize {
    while invalid - valid > 1 {
        let mid = valid + (invalid - valid) / 2;
        if reaches(mid) {
            valid = mid;
        } else {
            invalid = mid;
        }
    }
    valid
}

/// The valid path through `states` shortened by rounds of greedy shortcutting and corner
/// cutting (same endpoints, cost never higher, every new segment checked).
pub fn smooth(
    states: &[Pose2],
    motions: &dyn MotionValidator,
    space: &dyn StateSpace,
    objective: &dyn Objective,
) -> Vec<Pose2> {
    let mut path = shortcut_galloping(states, motions);
    let mut cost = objective.path_cost(&path);
    for _ in 0..SMOOTH_ROUNDS {
        let next = shortcut_galloping(&cut_corners(&path, motions, space, objective), motions);
        let next_cost = objective.path_cost(&next);
        if next_cost >= cost {
            break;
        }
        let saved = cost - next_cost;
        path = next;
        cost = next_cost;
        if saved < SMOOTH_TOLERANCE * cost {
            break;
        }
    }
    path
}

/// One pass of corner cutting: every interior state `v` (between the last kept state
/// `a` and the next state `b`) becomes `p = v + t(a − v)`, `q = v + t(b − v)` with the
/// largest `t` found by bisection for which `a → p`, `p → q` and `q → b` are valid and
/// cheaper than `a → v → b` under `objective` (`p`, `q` on the space's motions); it
/// stays when no such `t` is found. `p → q` is checked first, with its ends; `a` and
/// `b` are valid (the path's), so `a → p` and `q → b` are then between valid states.
fn cut_corners(
    states: &[Pose2],
    motions: &dyn MotionValidator,
    space: &dyn StateSpace,
    objective: &dyn Objective,
) -> Vec<Pose2> {
    if states.len() <= 2 {
        return states.to_vec();
    }
    let mut out = vec![states[0]];
    for i in 1..states.len() - 1 {
        let (a, v, b) = (out[out.len() - 1], states[i], states[i + 1]);
        let cost = |x: &Pose2, y: &Pose2| objective.motion_cost(x, y);
        let corner = cost(&a, &v) + cost(&v, &b);
        let cut = |t: f64| {
            let (p, q) = (space.interpolate(&v, &a, t), space.interpolate(&v, &b, t));
            let cost = cost(&a, &p) + cost(&p, &q) + cost(&q, &b);
            (cost < corner
                && motions.is_valid_motion(&p, &q)
                && motions.is_valid_motion_between_valid(&a, &p)
                && motions.is_valid_motion_between_valid(&q, &b))
            .then_some((p, q))
        };
        let (mut lo, mut hi, mut best) = (0.0, 1.0, None);
        for _ in 0..CUT_BISECTIONS {
            let mid = 0.5 * (lo + hi);
            match cut(mid) {
                Some(pq) => {
                    best = Some(pq);
                    lo = mid;
                }
                None => hi = mid,
            }
        }
        match best {
            Some((p, q)) => {
                out.push(p);
                out.push(q);
            }
            None => out.push(v),
        }
    }
    out.push(states[states.len() - 1]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::objective::PathLengthParams;
    use smug_core::{MotionCheck, PathLength};

    /// The path length objective with yaw weight `w_r`.
    fn length(w_r: f64) -> PathLength {
        PathLength::from_params(PathLengthParams {
            translation_weight: 1.0,
            rotation_weight: w_r,
        })
        .unwrap()
    }

    /// Motions are valid unless they cross the wall `x = 5` above `y = 1`.
    struct Wall;

    impl MotionValidator for Wall {
        fn is_valid_motion(&self, a: &Pose2, b: &Pose2) -> bool {
            if (a.x - 5.0) * (b.x - 5.0) > 0.0 {
                return true;
            }
            let t = (5.0 - a.x) / (b.x - a.x);
            a.y + t * (b.y - a.y) < 1.0
        }

        fn check_motion(&self, a: &Pose2, b: &Pose2) -> MotionCheck {
            if self.is_valid_motion(a, b) {
                MotionCheck::Valid
            } else {
                MotionCheck::Invalid { last_valid: None }
            }
        }
    }

    #[test]
    fn a_detour_around_the_wall_keeps_only_its_corner() {
        // Up the left side, around the wall's foot, up the right side.
        let mut states: Vec<Pose2> = (0..=8)
            .map(|k| Pose2::new(1.0, 8.0 - k as f64, 0.0))
            .collect();
        states.push(Pose2::new(5.0, 0.0, 0.0));
        states.extend((0..=8).map(|k| Pose2::new(9.0, k as f64, 0.0)));
        let short = shortcut_galloping(&states, &Wall);
        assert_eq!(short.first(), states.first());
        assert_eq!(short.last(), states.last());
        assert!(short.len() <= 4, "{short:?}");
        assert!(short.windows(2).all(|w| Wall.is_valid_motion(&w[0], &w[1])));
    }

    /// [`Wall`], counting the checks asked without the ends known valid.
    #[derive(Default)]
    struct EndsCounted {
        with_ends: std::sync::atomic::AtomicUsize,
        between_valid: std::sync::atomic::AtomicUsize,
    }

    impl MotionValidator for EndsCounted {
        fn is_valid_motion(&self, a: &Pose2, b: &Pose2) -> bool {
            self.with_ends
                .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            Wall.is_valid_motion(a, b)
        }

        fn is_valid_motion_between_valid(&self, a: &Pose2, b: &Pose2) -> bool {
            self.between_valid
                .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            Wall.is_valid_motion(a, b)
        }

        fn check_motion(&self, a: &Pose2, b: &Pose2) -> MotionCheck {
            Wall.check_motion(a, b)
        }
    }

    #[test]
    fn segments_between_the_paths_states_skip_the_ends_checks() {
        use std::sync::atomic::Ordering::Relaxed;
        let mut states: Vec<Pose2> = (0..=8)
            .map(|k| Pose2::new(1.0, 8.0 - k as f64, 0.0))
            .collect();
        states.push(Pose2::new(5.0, 0.0, 0.0));
        states.extend((0..=8).map(|k| Pose2::new(9.0, k as f64, 0.0)));
        for f in [shortcut, shortcut_galloping] {
            let motions = EndsCounted::default();
            f(&states, &motions);
            assert_eq!(motions.with_ends.load(Relaxed), 0);
            assert!(motions.between_valid.load(Relaxed) > 0);
        }
        // Corner cutting checks each new `p → q` with its ends; its shortcut passes and
        // the cuts' `a → p`, `q → b` go between valid states.
        let space = smug_core::Se2Space::new(1.0, 0.0).unwrap();
        let motions = EndsCounted::default();
        smooth(&states, &motions, &space, &length(0.0));
        assert!(motions.with_ends.load(Relaxed) > 0);
        assert!(motions.between_valid.load(Relaxed) > 0);
    }

    #[test]
    fn a_free_path_becomes_one_segment() {
        let states: Vec<Pose2> = (0..20)
            .map(|k| Pose2::new(6.0 + 0.1 * k as f64, (k % 3) as f64, 0.0))
            .collect();
        assert_eq!(
            shortcut_galloping(&states, &Wall),
            vec![states[0], states[19]]
        );
        assert_eq!(shortcut(&states, &Wall), vec![states[0], states[19]]);
    }

    #[test]
    fn smoothing_pulls_the_detour_taut_around_the_wall_foot() {
        let space = smug_core::Se2Space::new(1.0, 0.0).unwrap();
        let metric = length(0.0);
        let mut states: Vec<Pose2> = (0..=8)
            .map(|k| Pose2::new(1.0, 8.0 - k as f64, 0.0))
            .collect();
        states.push(Pose2::new(5.0, 0.0, 0.0));
        states.extend((0..=8).map(|k| Pose2::new(9.0, k as f64, 0.0)));
        let smooth = smooth(&states, &Wall, &space, &metric);
        let taut = 2.0 * (4.0f64).hypot(7.0); // through the wall's foot (5, 1)
        let cost = metric.path_cost(&smooth);
        assert!(
            cost >= taut - 1e-9 && cost <= 1.01 * taut,
            "{cost} vs {taut}"
        );
        assert!(smooth
            .windows(2)
            .all(|w| Wall.is_valid_motion(&w[0], &w[1])));
    }

    /// Motions are valid when they keep out of the discs (centre, radius).
    struct Discs(Vec<([f64; 2], f64)>);

    impl MotionValidator for Discs {
        fn is_valid_motion(&self, a: &Pose2, b: &Pose2) -> bool {
            self.0.iter().all(|&([cx, cy], r)| {
                let (dx, dy) = (b.x - a.x, b.y - a.y);
                let len2 = dx * dx + dy * dy;
                let t = if len2 > 0.0 {
                    (((cx - a.x) * dx + (cy - a.y) * dy) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (a.x + t * dx - cx).hypot(a.y + t * dy - cy) > r
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

    proptest::proptest! {
        #[test]
        fn smoothing_keeps_the_endpoints_and_validity_and_never_raises_cost(
            discs in proptest::collection::vec(((1.0..9.0f64, 1.0..9.0f64), 0.2..1.5f64), 0..6),
            walk in proptest::collection::vec((0.0..10.0f64, 0.0..10.0f64, -3.0..3.0f64), 2..30),
            yaw_weight in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.0..1.0f64],
        ) {
            let motions = Discs(discs.into_iter().map(|((x, y), r)| ([x, y], r)).collect());
            let space = smug_core::Se2Space::new(1.0, yaw_weight).unwrap();
            let metric = length(yaw_weight);
            // A valid input path: the random walk's states, keeping only valid segments.
            let mut states = vec![Pose2::new(walk[0].0, walk[0].1, walk[0].2)];
            for &(x, y, yaw) in &walk[1..] {
                let p = Pose2::new(x, y, yaw);
                if motions.is_valid_motion(states.last().unwrap(), &p) {
                    states.push(p);
                }
            }
            for f in [shortcut, shortcut_galloping] {
                let short = f(&states, &motions);
                proptest::prop_assert_eq!(short.first(), states.first());
                proptest::prop_assert_eq!(short.last(), states.last());
                proptest::prop_assert!(metric.path_cost(&short) <= metric.path_cost(&states) + 1e-9);
            }
            let smooth = smooth(&states, &motions, &space, &metric);
            proptest::prop_assert_eq!(smooth.first(), states.first());
            proptest::prop_assert_eq!(smooth.last(), states.last());
            proptest::prop_assert!(smooth.windows(2).all(|w| motions.is_valid_motion(&w[0], &w[1])));
            proptest::prop_assert!(metric.path_cost(&smooth) <= metric.path_cost(&states) + 1e-9);
        }
    }
}
