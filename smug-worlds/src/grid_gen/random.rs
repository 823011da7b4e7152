//! Random obstacles: an exact number of cells, chosen uniformly.

use crate::movingai::MovingAiMap;
use rand::Rng;

/// A `width` × `height` map with `round(density · cells)` blocked cells drawn without
/// replacement (a partial Fisher–Yates shuffle).
pub(super) fn generate(
    width: usize,
    height: usize,
    density: f64,
    rng: &mut impl Rng,
) -> MovingAiMap {
    let mut map = MovingAiMap::filled(width, height, true);
    let cells = width * height;
    let blocked = ((density * cells as f64).round() as usize).min(cells);
    let mut order: Vec<usize> = (0..cells).collect();
    for i in 0..blocked {
        let j = rng.random_range(i..cells);
        order.swap(i, j);
        map.passable[order[i]] = false;
    }
    map
}
