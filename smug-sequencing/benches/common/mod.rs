//! What the sequencing benches share: seeded random Euclidean matrices.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smug_core::CostMatrix;

/// Euclidean distances between `n` seeded random points in a `width × height` box.
pub fn random_matrix(n: usize, seed: u64, [width, height]: [f64; 2]) -> CostMatrix {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let points: Vec<(f64, f64)> = (0..n)
        .map(|_| (rng.random_range(0.0..width), rng.random_range(0.0..height)))
        .collect();
    CostMatrix::from_fn(n, |i, j| {
        (points[i].0 - points[j].0).hypot(points[i].1 - points[j].1)
    })
    .expect("finite costs")
}
