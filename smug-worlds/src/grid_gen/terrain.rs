//! Open terrain with a few large obstacles: discs and axis-aligned rectangles, each a
//! sixth to a third of the map's shorter side across, placed at random until they
//! cover the requested share of the cells.

use super::shapes::{block, place_until_covered};
use crate::movingai::MovingAiMap;
use rand::Rng;

/// Obstacles placed at most (a bound for densities that overlapping shapes reach
/// slowly).
const MAX_OBSTACLES: usize = 10_000;

/// A `width` × `height` map whose blocked share first reaches `density`.
pub(super) fn generate(
    width: usize,
    height: usize,
    density: f64,
    rng: &mut impl Rng,
) -> MovingAiMap {
    let side = width.min(height);
    let (small, large) = ((side / 6).max(1), (side / 3).max(1));
    place_until_covered(width, height, density, MAX_OBSTACLES, |map| {
        let size = rng.random_range(small..=large);
        let (cx, cy) = (rng.random_range(0..width), rng.random_range(0..height));
        let disc = rng.random_bool(0.5);
        let aspect = rng.random_range(0.5..=1.0);
        let (half_w, half_h) = (size as f64 / 2.0, (size as f64 * aspect) / 2.0);
        let mut blocked = 0;
        for y in cy.saturating_sub(size)..(cy + size + 1).min(height) {
            for x in cx.saturating_sub(size)..(cx + size + 1).min(width) {
                let (dx, dy) = (x as f64 - cx as f64, y as f64 - cy as f64);
                let inside = if disc {
                    dx * dx + dy * dy <= half_w * half_w
                } else {
                    dx.abs() <= half_w && dy.abs() <= half_h
                };
                if inside && block(map, x, y) {
                    blocked += 1;
                }
            }
        }
        blocked
    })
}
