//! Prints seeded random pose pairs and their `dubins` and `reeds-shepp` distances, for
//! the OMPL cross-check (`tools/ompl-peer/spaces_compare.py`, `SPACES.md`).
//!
//! Usage: `spaces_check RADIUS PAIRS SEED` → lines `x1 y1 yaw1 x2 y2 yaw2 dubins rs class`,
//! class `far`, `near` or `tangent`.
//! Eight pairs in ten have positions in `[-10, 10]²`; one in ten lies within one turning
//! radius (the short CCC, CCCC and CCSCC words); yaws are uniform in `[-π, π)`. One in
//! ten is a tangent case: `b` is `a` driven along a single arc or straight piece
//! (forwards or in reverse), where the words meet and rounding decides.

use smug_core::pose::Pose2;
use smug_core::space::StateSpace;
use smug_spaces::{Curve, DubinsSpace, ReedsSheppSpace, Steer};
use std::f64::consts::PI;

/// SplitMix64: a seeded stream of uniform numbers in `[0, 1)`.
struct SplitMix(u64);

impl SplitMix {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or(default.to_string());
    let radius: f64 = arg(0, "1").parse().expect("RADIUS");
    let pairs: usize = arg(1, "10000").parse().expect("PAIRS");
    let seed: u64 = arg(2, "1").parse().expect("SEED");
    let dubins = DubinsSpace::new(radius).expect("radius");
    let rs = ReedsSheppSpace::new(radius).expect("radius");
    let mut rng = SplitMix(seed);
    for i in 0..pairs {
        let half = if i % 10 == 9 { radius } else { 10.0 };
        let a = Pose2::new(
            rng.range(-half, half),
            rng.range(-half, half),
            rng.range(-PI, PI),
        );
        let b = if i % 10 == 8 {
            let steer =
                [Steer::Left, Steer::Straight, Steer::Right][(rng.uniform() * 3.0) as usize];
            let piece = Curve::from_word(&[steer], &[rng.range(-1.9 * PI, 1.9 * PI)]);
            piece.sample(&a, radius, 1.0)
        } else {
            Pose2::new(
                rng.range(-half, half),
                rng.range(-half, half),
                rng.range(-PI, PI),
            )
        };
        println!(
            "{:.17e} {:.17e} {:.17e} {:.17e} {:.17e} {:.17e} {:.17e} {:.17e} {}",
            a.x,
            a.y,
            a.yaw,
            b.x,
            b.y,
            b.yaw,
            dubins.distance(&a, &b),
            rs.distance(&a, &b),
            ["far", "near", "tangent"][usize::from(i % 10 == 9) + 2 * usize::from(i % 10 == 8)]
        );
    }
}
