//! Maps of shapes placed at random until they cover a share of the cells (the
//! terrain and polygons families).

use crate::movingai::MovingAiMap;

/// A `width` × `height` map with shapes from `place` until `round(density · cells)`
/// cells are blocked or `max` shapes were placed. `place` blocks the cells of one shape
/// (with [`block`]) and returns how many it blocked that were passable.
pub(super) fn place_until_covered(
    width: usize,
    height: usize,
    density: f64,
    max: usize,
    mut place: impl FnMut(&mut MovingAiMap) -> usize,
) -> MovingAiMap {
    let mut map = MovingAiMap::filled(width, height, true);
    let target = (density * (width * height) as f64).round() as usize;
    let mut blocked = 0;
    for _ in 0..max {
        if blocked >= target {
            break;
        }
        blocked += place(&mut map);
    }
    map
}

/// Blocks cell `(x, y)`; true when it was passable.
pub(super) fn block(map: &mut MovingAiMap, x: usize, y: usize) -> bool {
    let was = map.is_passable(x, y);
    if was {
        map.set_passable(x, y, false);
    }
    was
}
