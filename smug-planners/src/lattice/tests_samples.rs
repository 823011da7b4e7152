//! Tests of the primitives' states computed once ([`samples::PrimitiveStates`]): on a
//! rover's lattice (Reeds–Shepp curves, a box robot on terrain), translated to lattice
//! poses they are the states the motion validator checks there, and get its verdict.

use super::primitives::Layout;
use super::*;
use rand::{Rng, SeedableRng};
use smug_core::{Bounds2, Mission, World};
use smug_spaces::ReedsSheppSpace;
use smug_validity::DiscreteMotionValidator;
use smug_worlds::flat::{flat_world, BoxObstacle, FlatParams};

/// A 1.2 × 0.8 m box on the terrain: valid when its centre and corners stand lower
/// than 0.2 m (so its heading matters).
struct LowBox(Arc<World>);

impl StateValidityChecker for LowBox {
    fn is_valid(&self, s: &Pose2) -> bool {
        let (sin, cos) = s.yaw.sin_cos();
        [
            (0.0, 0.0),
            (0.6, 0.4),
            (0.6, -0.4),
            (-0.6, 0.4),
            (-0.6, -0.4),
        ]
        .iter()
        .all(|&(u, v)| {
            let (x, y) = (s.x + u * cos - v * sin, s.y + u * sin + v * cos);
            self.0.height_at(x, y).is_some_and(|z| z < 0.2)
        })
    }
}

/// A 20 × 20 m world with its lower left corner at `origin`, with tall boxes
/// (obstacles) and low ones (too steep to climb).
fn terrain(origin: [f64; 2]) -> Arc<World> {
    let mission: Mission = smug_core::toml::from_str("start = { x = 1.0, y = 4.0 }").unwrap();
    let boxes = [
        ([0.0, 5.0], [3.0, 7.0], 1.0),
        ([8.0, 3.0], [9.0, 12.0], 1.0),
        ([3.0, 15.0], [14.0, 16.0], 1.0),
        ([11.0, 6.0], [15.0, 10.0], 0.15),
        ([1.0, 10.0], [5.0, 12.5], 0.15),
    ];
    let params = FlatParams {
        size: [20.0, 20.0],
        origin,
        obstacles: boxes
            .iter()
            .map(
                |&(min, max, height): &([f64; 2], [f64; 2], f64)| BoxObstacle {
                    min: [min[0] + origin[0], min[1] + origin[1]],
                    max: [max[0] + origin[0], max[1] + origin[1]],
                    height,
                },
            )
            .collect(),
        ..FlatParams::default()
    };
    Arc::new(flat_world(&params, mission).unwrap().world)
}

/// The rover's lattice on [`terrain`] at `origin`, its primitives and motion
/// validator.
fn rover(origin: [f64; 2]) -> (Lattice, Primitives, DiscreteMotionValidator) {
    let world = terrain(origin);
    let space = Arc::new(ReedsSheppSpace::new(1.5).unwrap());
    let bounds = Bounds2 {
        min: origin,
        max: [origin[0] + 20.0, origin[1] + 20.0],
    };
    let lattice = Lattice::new(bounds, default_resolution(1.5), 64);
    let layout = Layout {
        space: space.as_ref(),
        radius: 1.5,
        reverse: true,
    };
    let primitives = layout.primitives(&lattice);
    let states = Arc::new(LowBox(world.clone()));
    let motions = DiscreteMotionValidator::new(states, space, Some((world, 0.27)), 0.25).unwrap();
    (lattice, primitives, motions)
}

/// Random primitives from random lattice poses, their states translated where they
/// can be and checked against the validator's own: (translated, checked as asked).
/// Translated states are the validator's own bit for bit, and its verdict on them is
/// its verdict on the motion; valid and invalid primitives both turn up.
fn translate_random_primitives(origin: [f64; 2]) -> (usize, usize) {
    let (lattice, primitives, motions) = rover(origin);
    let table = samples::PrimitiveStates::new(&lattice, &primitives, &motions)
        .expect("a box robot's motions are checked by their states");
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let (mut out, mut valid, mut invalid) = (Vec::new(), 0, 0);
    let (mut translated, mut asked) = (0, 0);
    while valid + invalid < 3000 {
        let (ix, iy) = (
            rng.random_range(0..lattice.nx),
            rng.random_range(0..lattice.ny),
        );
        let k = rng.random_range(0..lattice.headings);
        let p = rng.random_range(0..primitives.by_heading[k].len());
        let prim = primitives.by_heading[k][p];
        let Some((jx, jy)) = lattice.offset(ix, iy, prim.di, prim.dj) else {
            continue;
        };
        let a = lattice.pose(lattice.id(ix, iy, k));
        let b = lattice.pose(lattice.id(jx, jy, prim.to_heading));
        if !table.translated(k, p, (&a, &b), &mut out) {
            asked += 1;
            continue;
        }
        translated += 1;
        assert_eq!(out, motions.check_states(&a, &b).unwrap(), "{a:?} → {b:?}");
        if !(ends_valid(&motions, &a) && ends_valid(&motions, &b)) {
            continue;
        }
        let verdict = motions.states_valid_between_valid(&out);
        assert_eq!(
            verdict,
            motions.is_valid_motion_between_valid(&a, &b),
            "{a:?} → {b:?}"
        );
        if verdict {
            valid += 1;
        } else {
            invalid += 1;
        }
    }
    assert!(
        valid > 300 && invalid > 100,
        "{valid} valid, {invalid} invalid"
    );
    (translated, asked)
}

/// Lattice positions exact in binary (a round corner, a cell of 1/4 m): every
/// primitive is translated.
#[test]
fn on_exact_positions_every_primitive_is_translated() {
    let (_, asked) = translate_random_primitives([-3.0, 2.0]);
    assert_eq!(asked, 0);
}

/// Lattice positions rounded in binary: a primitive whose ends are not exactly its
/// offset apart is checked as asked (its curve may be another of the same length:
/// without that, the comparison fails on this map for this seed).
#[test]
fn on_rounded_positions_only_exact_offsets_are_translated() {
    let (translated, asked) = translate_random_primitives([-3.3, 1.7]);
    assert!(
        translated > 0 && asked > 0,
        "{translated} translated, {asked} not"
    );
}

/// Whether the validator's checker finds the pose valid (a motion's end).
fn ends_valid(motions: &DiscreteMotionValidator, pose: &Pose2) -> bool {
    // The validator checks a motion's ends when not told they are valid: a motion to
    // itself is valid when its pose is.
    motions.is_valid_motion(pose, pose)
}
