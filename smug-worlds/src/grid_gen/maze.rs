//! Perfect mazes with one-cell corridors: a randomised depth-first search over the
//! cells at even coordinates, opening the wall cell between two visited neighbours.

use crate::movingai::MovingAiMap;
use rand::Rng;

/// A `width` × `height` maze. Corridor junctions lie at even `(x, y)`; the cells between
/// two junctions open when the search passes between them. With an even width (height)
/// the last column (row) stays blocked.
pub(super) fn generate(width: usize, height: usize, rng: &mut impl Rng) -> MovingAiMap {
    let mut map = MovingAiMap::filled(width, height, false);
    let (nx, ny) = (width.div_ceil(2), height.div_ceil(2));
    let mut visited = vec![false; nx * ny];
    let mut stack = vec![(0usize, 0usize)];
    visited[0] = true;
    map.set_passable(0, 0, true);
    while let Some(&(x, y)) = stack.last() {
        let options: Vec<(usize, usize)> = neighbours(x, y, nx, ny)
            .filter(|&(a, b)| !visited[b * nx + a])
            .collect();
        if options.is_empty() {
            stack.pop();
            continue;
        }
        let (a, b) = options[rng.random_range(0..options.len())];
        visited[b * nx + a] = true;
        map.set_passable(x + a, y + b, true); // the wall cell between (2x, 2y) and (2a, 2b)
        map.set_passable(2 * a, 2 * b, true);
        stack.push((a, b));
    }
    map
}

/// The junctions beside junction `(x, y)` on an `nx` × `ny` lattice.
fn neighbours(x: usize, y: usize, nx: usize, ny: usize) -> impl Iterator<Item = (usize, usize)> {
    [
        (x + 1 < nx).then(|| (x + 1, y)),
        (x > 0).then(|| (x.wrapping_sub(1), y)),
        (y + 1 < ny).then(|| (x, y + 1)),
        (y > 0).then(|| (x, y.wrapping_sub(1))),
    ]
    .into_iter()
    .flatten()
}
