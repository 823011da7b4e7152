//! The obstacle-aware part of the lattice search's heuristic: shortest distances on a
//! 2D relaxation of the lattice. Its nodes are the lattice points where some heading is
//! valid, its edges every primitive's displacement (any heading, either gear), each
//! weighted by `w_t` times its straight length; the goals' seeds are the points a final
//! shot may start from, valued at `w_t` times their straight distance to the goal.
//! Every lattice path ending in a shot maps onto a path of this graph that costs no
//! more, so the distances are admissible and consistent; a point it cannot join to a
//! seed cannot reach a goal at all.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A point of the relaxation: (column, row).
pub type Point = (usize, usize);

/// Distances to the nearest seed on the 2D relaxation, per lattice point (`INFINITY`:
/// no seed reachable).
pub fn distances(
    nx: usize,
    ny: usize,
    displacements: &[(i32, i32, f64)],
    seeds: &[(Point, f64)],
    mut open: impl FnMut(usize, usize) -> bool,
) -> Vec<f32> {
    let mut dist = vec![f32::INFINITY; nx * ny];
    // 0: unknown, 1: open, 2: closed to the relaxation (no valid heading).
    let mut known = vec![0u8; nx * ny];
    let mut is_open = |i: usize, ix: usize, iy: usize| -> bool {
        if known[i] == 0 {
            known[i] = if open(ix, iy) { 1 } else { 2 };
        }
        known[i] == 1
    };
    let mut heap = BinaryHeap::new();
    for &((ix, iy), value) in seeds {
        let i = iy * nx + ix;
        if (value as f32) < dist[i] && is_open(i, ix, iy) {
            dist[i] = value as f32;
            heap.push(Reverse(((value as f32).to_bits(), i as u32)));
        }
    }
    while let Some(Reverse((bits, i))) = heap.pop() {
        let d = f32::from_bits(bits);
        let i = i as usize;
        if d > dist[i] {
            continue;
        }
        let (ix, iy) = ((i % nx) as i64, (i / nx) as i64);
        // The edge q → q + δ reaches this point from q = p − δ.
        for &(di, dj, w) in displacements {
            let qx = ix - di as i64;
            let qy = iy - dj as i64;
            if qx < 0 || qy < 0 || qx >= nx as i64 || qy >= ny as i64 {
                continue;
            }
            let q = qy as usize * nx + qx as usize;
            let nd = d + w as f32;
            if nd < dist[q] && is_open(q, qx as usize, qy as usize) {
                dist[q] = nd;
                heap.push(Reverse((nd.to_bits(), q as u32)));
            }
        }
    }
    dist
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wall_is_walked_around_and_a_closed_pocket_is_unreachable() {
        // 5 × 5 points, a wall at column 2 but for its top row; moves of one point.
        let moves: Vec<(i32, i32, f64)> = [(1, 0), (-1, 0), (0, 1), (0, -1)]
            .iter()
            .map(|&(a, b)| (a, b, 1.0))
            .collect();
        let d = distances(5, 5, &moves, &[((0, 0), 0.0)], |x, y| !(x == 2 && y < 4));
        assert_eq!(d[4], 4.0 + 8.0, "around the wall through the top row");
        let sealed = distances(5, 5, &moves, &[((0, 0), 0.0)], |x, _| x != 2);
        assert!(sealed[4].is_infinite());
        assert_eq!(sealed[1], 1.0);
    }
}
