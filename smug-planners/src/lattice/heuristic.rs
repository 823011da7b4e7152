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
///
/// Dijkstra's search runs on the grid padded by the longest displacement, its border
/// closed: each edge is then one offset from a point's index, with no bounds to check.
pub fn distances(
    nx: usize,
    ny: usize,
    displacements: &[(i32, i32, f64)],
    seeds: &[(Point, f64)],
    mut open: impl FnMut(usize, usize) -> bool,
) -> Vec<f32> {
    let pad = displacements
        .iter()
        .map(|&(di, dj, _)| di.unsigned_abs().max(dj.unsigned_abs()) as usize)
        .max()
        .unwrap_or(0);
    let width = nx + 2 * pad;
    let padded = width * (ny + 2 * pad);
    let index = |ix: usize, iy: usize| (iy + pad) * width + ix + pad;
    // The edge q → q + δ reaches a point p from q = p − δ: `p − offset`.
    let edges: Vec<(isize, f32)> = displacements
        .iter()
        .map(|&(di, dj, w)| (dj as isize * width as isize + di as isize, w as f32))
        .collect();
    let mut dist = vec![f32::INFINITY; padded];
    // 0: unknown, 1: open, 2: closed to the relaxation (no valid heading, or the border).
    let mut known = vec![2u8; padded];
    for iy in 0..ny {
        known[index(0, iy)..index(nx, iy)].fill(0);
    }
    let mut is_open = |q: usize| -> bool {
        if known[q] == 0 {
            let (qx, qy) = (q % width - pad, q / width - pad);
            known[q] = if open(qx, qy) { 1 } else { 2 };
        }
        known[q] == 1
    };
    let mut heap = BinaryHeap::new();
    for &((ix, iy), value) in seeds {
        let i = index(ix, iy);
        if (value as f32) < dist[i] && is_open(i) {
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
        for &(offset, w) in &edges {
            let q = i.wrapping_sub(offset as usize);
            let nd = d + w;
            if nd < dist[q] && is_open(q) {
                dist[q] = nd;
                heap.push(Reverse((nd.to_bits(), q as u32)));
            }
        }
    }
    let mut out = Vec::with_capacity(nx * ny);
    for iy in 0..ny {
        out.extend_from_slice(&dist[index(0, iy)..index(nx, iy)]);
    }
    out
}

/// Lowers `dist` to `other` wherever `other` is nearer. The distances to a union of
/// seeds are the least of the distances to each part, bit for bit: `f32` addition of
/// non-negative weights is monotone, so Dijkstra's value at a point is the least, over
/// every path from a seed, of that path's sum added up from its seed; the least over a
/// union is the least of the least over each part.
pub fn least(dist: &mut [f32], other: &[f32]) {
    for (d, &o) in dist.iter_mut().zip(other) {
        if o < *d {
            *d = o;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The distances by relaxing every edge until none improves (Bellman–Ford), with
    /// bounds checked on the unpadded grid.
    fn relaxed(
        nx: usize,
        ny: usize,
        moves: &[(i32, i32, f64)],
        seeds: &[(Point, f64)],
        open: &[bool],
    ) -> Vec<f32> {
        let mut dist = vec![f32::INFINITY; nx * ny];
        for &((x, y), v) in seeds {
            let i = y * nx + x;
            if open[i] {
                dist[i] = dist[i].min(v as f32);
            }
        }
        loop {
            let mut changed = false;
            for i in 0..nx * ny {
                if !dist[i].is_finite() {
                    continue;
                }
                let (x, y) = ((i % nx) as i64, (i / nx) as i64);
                for &(di, dj, w) in moves {
                    let (qx, qy) = (x - di as i64, y - dj as i64);
                    if qx < 0 || qy < 0 || qx >= nx as i64 || qy >= ny as i64 {
                        continue;
                    }
                    let q = qy as usize * nx + qx as usize;
                    let nd = dist[i] + w as f32;
                    if open[q] && nd < dist[q] {
                        dist[q] = nd;
                        changed = true;
                    }
                }
            }
            if !changed {
                return dist;
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn distances_equal_relaxing_every_edge_to_a_fixpoint(
            nx in 1usize..14,
            ny in 1usize..14,
            closed in proptest::collection::vec(any::<bool>(), 196),
            moves in proptest::collection::vec((-3i32..=3, -3i32..=3, 0.01f64..2.0), 1..8),
            seeds in proptest::collection::vec((0usize..14, 0usize..14, 0.0f64..3.0), 1..4),
        ) {
            let open: Vec<bool> = (0..nx * ny).map(|i| !closed[i] || i % 3 == 0).collect();
            let seeds: Vec<(Point, f64)> = seeds
                .into_iter()
                .map(|(x, y, v)| ((x % nx, y % ny), v))
                .collect();
            let fast = distances(nx, ny, &moves, &seeds, |x, y| open[y * nx + x]);
            let slow = relaxed(nx, ny, &moves, &seeds, &open);
            let bits = |d: &[f32]| d.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            prop_assert_eq!(bits(&fast), bits(&slow));
        }
    }

    #[test]
    fn distances_to_a_union_of_seeds_are_the_least_of_each_bit_for_bit() {
        // 23 × 17 points with scattered closed points, moves of odd lengths.
        let moves: Vec<(i32, i32, f64)> = [(1, 0), (-1, 0), (0, 1), (0, -1), (2, 1), (-1, -2)]
            .iter()
            .map(|&(a, b)| (a, b, 0.1 * f64::from(a * a + b * b).sqrt() + 0.013))
            .collect();
        let open = |x: usize, y: usize| !(x * 7 + y * 3).is_multiple_of(11);
        let seeds = [
            ((1, 1), 0.37),
            ((20, 3), 0.011),
            ((5, 15), 0.1),
            ((12, 8), 0.0),
        ];
        let all = distances(23, 17, &moves, &seeds, open);
        let mut least_of_each = vec![f32::INFINITY; 23 * 17];
        for seed in seeds {
            least(
                &mut least_of_each,
                &distances(23, 17, &moves, &[seed], open),
            );
        }
        let bits = |d: &[f32]| d.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&all), bits(&least_of_each));
        assert!(all.iter().any(|d| d.is_infinite()) && all.iter().any(|d| d.is_finite()));
    }

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
