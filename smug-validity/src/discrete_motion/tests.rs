//! Tests of the discrete motion validator.

use super::*;
use proptest::prelude::*;
use smug_core::{Mission, Se2Space};
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
        Arc::new(Se2Space::default()),
        terrain,
        resolution,
    )
    .unwrap()
}

/// The disc obstacle of [`DiscObstacle`] with its clearance (a point robot).
struct ClearDisc;

impl StateValidityChecker for ClearDisc {
    fn is_valid(&self, s: &Pose2) -> bool {
        DiscObstacle.is_valid(s)
    }

    fn clearance(&self, s: &Pose2) -> Option<f64> {
        Some((s.x - 5.0).hypot(s.y - 5.0) - 1.0)
    }
}

/// A curved, one-way model: `a → b` drives the half circle on the left of the
/// segment `a b` (its planar length `π/2 · |ab|`).
#[derive(Debug)]
struct HalfCircle;

impl StateSpace for HalfCircle {
    fn distance(&self, a: &Pose2, b: &Pose2) -> f64 {
        std::f64::consts::FRAC_PI_2 * a.xy_distance(b)
    }

    fn interpolate(&self, a: &Pose2, b: &Pose2, t: f64) -> Pose2 {
        let (cx, cy) = (0.5 * (a.x + b.x), 0.5 * (a.y + b.y));
        let r = 0.5 * a.xy_distance(b);
        let start = (a.y - cy).atan2(a.x - cx);
        let angle = start - std::f64::consts::PI * t;
        Pose2::new(cx + r * angle.cos(), cy + r * angle.sin(), 0.0)
    }

    fn lower_bound_weights(&self) -> (f64, f64) {
        (1.0, 0.0)
    }

    fn is_symmetric(&self) -> bool {
        false
    }

    fn motion_extent(&self, a: &Pose2, b: &Pose2) -> smug_core::MotionExtent {
        smug_core::MotionExtent {
            length: self.distance(a, b),
            turning: std::f64::consts::PI,
        }
    }

    fn is_holonomic(&self) -> bool {
        false
    }
}

#[test]
fn motions_between_valid_ends_get_the_same_verdict_with_two_checks_fewer() {
    let v = validator(0.5, None);
    let checked = |v: &DiscreteMotionValidator| v.states_checked.total();
    for (a, b) in [
        (Pose2::new(1.0, 5.0, 0.0), Pose2::new(9.0, 5.0, 0.0)),
        (Pose2::new(1.0, 1.0, 0.0), Pose2::new(9.0, 1.0, 0.3)),
        (Pose2::new(3.0, 3.0, 0.0), Pose2::new(5.0, 7.0, 2.0)),
    ] {
        assert!(DiscObstacle.is_valid(&a) && DiscObstacle.is_valid(&b));
        let before = checked(&v);
        let full = v.is_valid_motion(&a, &b);
        let with_ends = checked(&v) - before;
        let between = v.is_valid_motion_between_valid(&a, &b);
        let without_ends = checked(&v) - before - with_ends;
        assert_eq!(full, between, "{a:?} → {b:?}");
        if full {
            assert_eq!(without_ends + 2, with_ends, "{a:?} → {b:?}");
        }
    }
}

#[test]
fn a_curved_motion_is_traced_along_its_curve_not_its_chord() {
    let v = DiscreteMotionValidator::new(Arc::new(ClearDisc), Arc::new(HalfCircle), None, 0.05)
        .unwrap();
    // The chord y = 8 is clear of the disc around (5, 5); the half circle from
    // (9, 8) to (1, 8) bulges down through it (lowest point (5, 4)).
    let (a, b) = (Pose2::new(9.0, 8.0, 0.0), Pose2::new(1.0, 8.0, 0.0));
    assert!(!v.is_valid_motion(&a, &b));
    assert!(!v.check_motion(&a, &b).is_valid());
    // The other way, the half circle bulges up, away from the disc.
    assert!(v.is_valid_motion(&b, &a));
    assert!(v.check_motion(&b, &a).is_valid());
}

/// The bisection order as a queue of intervals (midpoint first, then the halves'
/// midpoints, breadth first): the reference for the allocation-free walk.
fn queued_bisection_order(n: usize) -> Vec<usize> {
    let mut queue = std::collections::VecDeque::from([(0usize, n)]);
    let mut order = Vec::new();
    while let Some((lo, hi)) = queue.pop_front() {
        if hi - lo >= 2 {
            let mid = lo + (hi - lo) / 2;
            queue.push_back((lo, mid));
            queue.push_back((mid, hi));
            order.push(mid);
        }
    }
    order
}

#[test]
fn bisection_visits_every_interior_state_once_in_breadth_first_order() {
    for n in 1..300 {
        let mut seen = Vec::new();
        assert!(all_in_bisection_order(n, |k| {
            seen.push(k);
            true
        }));
        assert_eq!(seen, queued_bisection_order(n), "n = {n}");
        seen.sort();
        assert_eq!(seen, (1..n).collect::<Vec<_>>());
    }
}

#[test]
fn bisection_stops_at_the_first_failing_state() {
    for n in 2..100 {
        let order = queued_bisection_order(n);
        for (stop, &bad) in order.iter().enumerate() {
            let mut asked = 0;
            assert!(!all_in_bisection_order(n, |k| {
                asked += 1;
                k != bad
            }));
            assert_eq!(asked, stop + 1, "n = {n}, bad = {bad}");
        }
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
    let world = Arc::new(flat_world(&params, mission).unwrap().world);
    let v = validator(0.1, Some((world.clone(), 0.58)));
    // A 0.3 m step crossed within 0.1 m is far steeper than 0.58.
    assert!(!v.is_valid_motion(&Pose2::new(1.0, 7.0, 0.0), &Pose2::new(1.0, 9.0, 0.0)));
    assert!(v.is_valid_motion(&Pose2::new(1.0, 2.0, 0.0), &Pose2::new(1.0, 4.0, 0.0)));
    let lenient = validator(0.1, Some((world, 10.0)));
    assert!(lenient.is_valid_motion(&Pose2::new(1.0, 7.0, 0.0), &Pose2::new(1.0, 9.0, 0.0)));
}

/// Every position of a motion the continuous trace accepts is valid for the disc
/// (checked every millimetre), and the trace rejects a motion whose disc clips a
/// corner between the resolution's states.
mod continuous {
    use super::*;
    use crate::clearance_2d::{Clearance2dChecker, Clearance2dParams};
    use smug_core::{GridGeometry, GridLayer};

    fn disc_world() -> World {
        let g = GridGeometry::new([0.0, 0.0], 1.0, [10, 10]).unwrap();
        let blocked = [(3, 3), (4, 3), (7, 8), (5, 6)];
        let elevation =
            GridLayer::from_fn(g, |i, j| if blocked.contains(&(i, j)) { 2.0 } else { 0.0 });
        World::new("grid", elevation)
    }

    fn disc_validator(resolution: f64) -> DiscreteMotionValidator {
        let params = Clearance2dParams {
            radius: 0.25,
            obstacle_height: 1.0,
        };
        let states = Arc::new(Clearance2dChecker::new(&disc_world(), params).unwrap());
        DiscreteMotionValidator::new(states, Arc::new(Se2Space::default()), None, resolution)
            .unwrap()
    }

    proptest! {
        #[test]
        fn accepted_motions_are_valid_everywhere(
            a in (0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0),
            b in (0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0),
        ) {
            let v = disc_validator(0.05);
            let (a, b) = (Pose2::new(a.0, a.1, a.2), Pose2::new(b.0, b.1, b.2));
            let valid = v.is_valid_motion(&a, &b);
            prop_assert_eq!(valid, v.check_motion(&a, &b).is_valid());
            prop_assert_eq!(valid, v.is_valid_motion(&b, &a), "the reverse motion");
            prop_assert_eq!(valid, v.check_motion(&b, &a).is_valid());
            if valid {
                let steps = (a.xy_distance(&b) / 0.001).ceil().max(1.0) as usize;
                for k in 0..=steps {
                    let t = k as f64 / steps as f64;
                    let p = Pose2::new(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, 0.0);
                    prop_assert!(v.states.is_valid(&p), "{:?} on {:?} → {:?}", p, a, b);
                }
            }
            if let MotionCheck::Invalid { last_valid: Some((s, _)) } = v.check_motion(&a, &b) {
                prop_assert!(v.states.is_valid(&s));
            }
        }
    }

    #[test]
    fn a_corner_between_coarse_steps_is_caught() {
        // Passing the blocked square (5, 6)..(6, 7) with the disc overlapping its
        // corner by 5 mm, between states 1 m apart.
        let v = disc_validator(1.0);
        let y = 6.0 - 0.25 + 0.005;
        let (a, b) = (Pose2::new(4.0, y - 1.0, 0.0), Pose2::new(6.0, y + 1.0, 0.0));
        let corner_gap = {
            // Distance from the segment to the corner (5, 6), less the radius.
            let (dx, dy) = (b.x - a.x, b.y - a.y);
            let t = ((5.0 - a.x) * dx + (6.0 - a.y) * dy) / (dx * dx + dy * dy);
            let (px, py) = (a.x + t * dx, a.y + t * dy);
            (px - 5.0).hypot(py - 6.0) - 0.25
        };
        assert!(corner_gap < 0.0, "the test motion must clip the corner");
        assert!(!v.is_valid_motion(&a, &b));
    }
}

/// The states the validator checks, given back by `check_states`, get the verdict of
/// `is_valid_motion_between_valid` through `states_valid_between_valid`.
mod given_states {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// A 0.6 × 0.4 m box on the terrain: valid when its centre and corners stand
    /// lower than 0.2 m (so its heading matters).
    struct LowBox(Arc<World>);

    impl StateValidityChecker for LowBox {
        fn is_valid(&self, s: &Pose2) -> bool {
            let (sin, cos) = s.yaw.sin_cos();
            [
                (0.0, 0.0),
                (0.3, 0.2),
                (0.3, -0.2),
                (-0.3, 0.2),
                (-0.3, -0.2),
            ]
            .iter()
            .all(|&(u, v)| {
                let (x, y) = (s.x + u * cos - v * sin, s.y + u * sin + v * cos);
                self.0.height_at(x, y).is_some_and(|z| z < 0.2)
            })
        }
    }

    /// A 10 × 10 m world with tall boxes (obstacles) and low ones (too steep to
    /// climb at the inclination limit, not too tall to stand on).
    fn terrain() -> Arc<World> {
        let mission: Mission = smug_core::toml::from_str("start = { x = 1.0, y = 1.0 }").unwrap();
        let boxes = [
            ([2.0, 2.0], [3.0, 4.0], 1.0),
            ([6.0, 1.0], [7.5, 2.0], 1.0),
            ([4.0, 6.0], [8.0, 6.5], 1.0),
            ([1.0, 6.5], [3.0, 8.5], 0.15),
            ([5.0, 3.0], [6.5, 4.5], 0.15),
        ];
        let params = FlatParams {
            obstacles: boxes
                .iter()
                .map(|&(min, max, height)| BoxObstacle { min, max, height })
                .collect(),
            ..FlatParams::default()
        };
        Arc::new(flat_world(&params, mission).unwrap().world)
    }

    fn box_validator(space: Arc<dyn StateSpace>, world: &Arc<World>) -> DiscreteMotionValidator {
        let states = Arc::new(LowBox(world.clone()));
        DiscreteMotionValidator::new(states, space, Some((world.clone(), 0.3)), 0.25).unwrap()
    }

    fn counts(v: &DiscreteMotionValidator) -> (u64, u64) {
        (v.motions_checked.total(), v.states_checked.total())
    }

    /// Random motions between valid poses up to 4 m apart: the same verdicts and
    /// counts both ways, for a straight and a curved model; every kind of verdict
    /// (valid, a blocked state, only too steep) turns up.
    #[test]
    fn the_given_states_get_the_motions_verdict_and_counts() {
        let world = terrain();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let spaces: [Arc<dyn StateSpace>; 2] =
            [Arc::new(Se2Space::default()), Arc::new(HalfCircle)];
        for space in spaces {
            let v = box_validator(space.clone(), &world);
            let pose = |rng: &mut rand_chacha::ChaCha8Rng| {
                Pose2::new(
                    rng.random_range(0.5..9.5),
                    rng.random_range(0.5..9.5),
                    rng.random_range(-3.1..3.1),
                )
            };
            let (mut valid, mut blocked, mut steep) = (0, 0, 0);
            while valid + blocked + steep < 2000 {
                let a = pose(&mut rng);
                let mut b = pose(&mut rng);
                (b.x, b.y) = (a.x + (b.x - a.x) * 0.4, a.y + (b.y - a.y) * 0.4);
                if !(v.states.is_valid(&a) && v.states.is_valid(&b)) {
                    continue;
                }
                let states = v.check_states(&a, &b).expect("a box robot's states decide");
                let n = v.segment_count(&a, &b);
                assert_eq!(states.len(), n + 1);
                assert_eq!(states[0], a);
                assert_eq!(states[n], space.interpolate(&a, &b, 1.0));
                let before = counts(&v);
                let given = v.states_valid_between_valid(&states);
                let between = counts(&v);
                let direct = v.is_valid_motion_between_valid(&a, &b);
                let after = counts(&v);
                assert_eq!(given, direct, "{a:?} → {b:?}");
                assert_eq!(
                    (between.0 - before.0, between.1 - before.1),
                    (after.0 - between.0, after.1 - between.1),
                    "{a:?} → {b:?}"
                );
                let states_ok = states.iter().all(|s| v.states.is_valid(s));
                match (direct, states_ok) {
                    (true, _) => valid += 1,
                    (false, false) => blocked += 1,
                    (false, true) => steep += 1,
                }
            }
            assert!(
                valid > 200 && blocked > 200 && steep > 50,
                "{valid} {blocked} {steep}"
            );
        }
    }

    /// A checker with a clearance traces motions: no fixed states, and states given
    /// anyway are judged by the motion between the first and the last.
    #[test]
    fn a_traced_motion_has_no_fixed_states() {
        let v = DiscreteMotionValidator::new(
            Arc::new(ClearDisc),
            Arc::new(Se2Space::default()),
            None,
            0.5,
        )
        .unwrap();
        let (a, b) = (Pose2::new(1.0, 5.0, 0.0), Pose2::new(9.0, 5.0, 0.0));
        assert_eq!(v.check_states(&a, &b), None);
        assert!(!v.states_valid_between_valid(&[a, b]));
        let (c, d) = (Pose2::new(1.0, 1.0, 0.0), Pose2::new(9.0, 1.0, 0.0));
        assert!(v.states_valid_between_valid(&[c, d]));
    }
}
