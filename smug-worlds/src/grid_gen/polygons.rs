//! Open ground with random convex polygons (3 to 7 vertices, any orientation), each a
//! twentieth to a sixth of the map's shorter side across, rasterised by cell centre and
//! placed until they cover the requested share of the cells: the rasterised diagonal
//! edges are staircases, as on maps made from polygon benchmarks.

use super::shapes::{block, place_until_covered};
use crate::movingai::MovingAiMap;
use rand::Rng;
use std::f64::consts::TAU;

/// Polygons placed at most (a bound for densities that overlapping shapes reach slowly).
const MAX_POLYGONS: usize = 10_000;

/// A `width` × `height` map whose blocked share first reaches `density`.
pub(super) fn generate(
    width: usize,
    height: usize,
    density: f64,
    rng: &mut impl Rng,
) -> MovingAiMap {
    let side = width.min(height) as f64;
    let (small, large) = ((side / 40.0).max(0.5), (side / 12.0).max(1.0));
    place_until_covered(width, height, density, MAX_POLYGONS, |map| {
        let radius = rng.random_range(small..=large);
        let (cx, cy) = (
            rng.random_range(0.0..width as f64),
            rng.random_range(0.0..height as f64),
        );
        let count = rng.random_range(3..=7usize);
        let mut angles: Vec<f64> = (0..count).map(|_| rng.random_range(0.0..TAU)).collect();
        angles.sort_by(f64::total_cmp);
        let vertices: Vec<[f64; 2]> = angles
            .iter()
            .map(|a| [cx + radius * a.cos(), cy + radius * a.sin()])
            .collect();
        // Counter-clockwise vertices: a point is inside when left of every edge.
        let inside = |x: f64, y: f64| {
            (0..count).all(|k| {
                let (a, b) = (vertices[k], vertices[(k + 1) % count]);
                (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]) >= 0.0
            })
        };
        let clamp = |v: f64, n: usize| (v.max(0.0) as usize).min(n);
        let mut blocked = 0;
        for y in clamp(cy - radius, height)..clamp(cy + radius + 1.0, height) {
            for x in clamp(cx - radius, width)..clamp(cx + radius + 1.0, width) {
                if inside(x as f64 + 0.5, y as f64 + 0.5) && block(map, x, y) {
                    blocked += 1;
                }
            }
        }
        blocked
    })
}
