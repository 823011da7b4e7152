//! Optimal 8-connected path lengths by MovingAI's rules: straight moves cost 1,
//! diagonal moves √2 and need both cells beside the diagonal to be passable (no corner
//! cutting).

use super::MovingAiMap;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// The cost of a diagonal move.
pub const SQRT_2: f64 = std::f64::consts::SQRT_2;

/// The optimal octile length from `start` to every cell (index `y · width + x`);
/// `f64::INFINITY` for unreachable or blocked cells, and for every cell when `start`
/// is blocked or outside the map.
pub fn octile_distances(map: &MovingAiMap, start: [usize; 2]) -> Vec<f64> {
    let mut distance = vec![f64::INFINITY; map.passable.len()];
    run_dijkstra(map, start, None, &mut distance);
    distance
}

/// The optimal octile length from `start` to `goal`, `None` when no path joins them
/// (or either is blocked or outside the map).
pub fn octile_length(map: &MovingAiMap, start: [usize; 2], goal: [usize; 2]) -> Option<f64> {
    if !map.is_passable(goal[0], goal[1]) {
        return None;
    }
    let goal_index = goal[1] * map.width + goal[0];
    let mut distance = vec![f64::INFINITY; map.passable.len()];
    run_dijkstra(map, start, Some(goal_index), &mut distance);
    Some(distance[goal_index]).filter(|d| d.is_finite())
}

/// A heap entry: a tentative distance and its cell, smallest distance first.
#[derive(PartialEq)]
struct Entry(f64, usize);

impl Eq for Entry {}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Dijkstra from `start` into `distance`, stopping once `goal` is settled.
fn run_dijkstra(map: &MovingAiMap, start: [usize; 2], goal: Option<usize>, distance: &mut [f64]) {
    if !map.is_passable(start[0], start[1]) {
        return;
    }
    let start_index = start[1] * map.width + start[0];
    distance[start_index] = 0.0;
    let mut heap = BinaryHeap::from([Entry(0.0, start_index)]);
    while let Some(Entry(d, cell)) = heap.pop() {
        if d > distance[cell] {
            continue;
        }
        if Some(cell) == goal {
            return;
        }
        for (next, step) in moves(map, cell) {
            let candidate = d + step;
            if candidate < distance[next] {
                distance[next] = candidate;
                heap.push(Entry(candidate, next));
            }
        }
    }
}

/// The legal moves out of passable cell `cell`: (target cell, cost).
fn moves(map: &MovingAiMap, cell: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
    let (x, y) = ((cell % map.width) as isize, (cell / map.width) as isize);
    let free = move |dx: isize, dy: isize| {
        let (nx, ny) = (x + dx, y + dy);
        nx >= 0 && ny >= 0 && map.is_passable(nx as usize, ny as usize)
    };
    const STEPS: [(isize, isize); 8] = [
        (1, 0),
        (-1, 0),
        (0, 1),
        (0, -1),
        (1, 1),
        (1, -1),
        (-1, 1),
        (-1, -1),
    ];
    STEPS.into_iter().filter_map(move |(dx, dy)| {
        let diagonal = dx != 0 && dy != 0;
        let legal = free(dx, dy) && (!diagonal || (free(dx, 0) && free(0, dy)));
        legal.then(|| {
            let target = (y + dy) as usize * map.width + (x + dx) as usize;
            (target, if diagonal { SQRT_2 } else { 1.0 })
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::movingai::parse_map;
    use std::path::Path;

    fn map(rows: &[&str]) -> MovingAiMap {
        let text = format!(
            "type octile\nheight {}\nwidth {}\nmap\n{}\n",
            rows.len(),
            rows[0].len(),
            rows.join("\n")
        );
        parse_map(&text, Path::new("t.map")).unwrap()
    }

    #[test]
    fn blocked_or_outside_endpoints_have_no_length() {
        let m = map(&[".@", ".."]);
        assert_eq!(octile_length(&m, [1, 0], [0, 0]), None);
        assert_eq!(octile_length(&m, [0, 0], [1, 0]), None);
        assert_eq!(octile_length(&m, [5, 0], [0, 0]), None);
        assert!(octile_distances(&m, [1, 0]).iter().all(|d| d.is_infinite()));
        assert_eq!(octile_length(&m, [0, 0], [0, 0]), Some(0.0));
    }
}
