//! Staircase corners left out of the graph (see `staircase`) against the graph of
//! every corner and brute force, on maps of rasterised polygons: the same lengths,
//! endpoints in pockets included, over queries sharing one graph.

use super::brute::{brute_force_disc, DiscCheck};
use super::*;

/// A `n × n` grid with rasterised convex polygons (cell blocked when its centre is
/// inside): diagonal edges become staircases.
fn polygons(n: usize, shapes: &[(f64, f64, f64, Vec<f64>)]) -> Vec<bool> {
    let mut blocked = vec![false; n * n];
    for (cx, cy, radius, angles) in shapes {
        let mut angles = angles.clone();
        angles.sort_by(f64::total_cmp);
        let v: Vec<Pt> = angles
            .iter()
            .map(|a| [cx + radius * a.cos(), cy + radius * a.sin()])
            .collect();
        for y in 0..n {
            for x in 0..n {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                let inside = (0..v.len()).all(|k| {
                    let (a, b) = (v[k], v[(k + 1) % v.len()]);
                    (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]) >= 0.0
                });
                blocked[y * n + x] |= inside;
            }
        }
    }
    blocked
}

fn arb_shapes(n: usize) -> impl Strategy<Value = Vec<(f64, f64, f64, Vec<f64>)>> {
    let nf = n as f64;
    proptest::collection::vec(
        (
            0.0..nf,
            0.0..nf,
            2.0..nf / 2.5,
            proptest::collection::vec(0.0..std::f64::consts::TAU, 3..7),
        ),
        1..4,
    )
}

/// Points near corners (in their pockets, often) and anywhere.
fn endpoint(grid: &Grid, pick: (usize, f64, f64, bool)) -> Pt {
    let (k, dx, dy, near) = pick;
    if near && !grid.corners.is_empty() {
        let c = grid.corners[k % grid.corners.len()].at;
        [c[0] + dx, c[1] + dy]
    } else {
        let fx = (k % 997) as f64 / 997.0;
        let fy = (k / 997 % 991) as f64 / 991.0;
        [fx * grid.nx as f64, fy * grid.ny as f64]
    }
}

fn pose(p: Pt) -> Pose2 {
    Pose2::new(p[0], p[1], 0.0)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(150))]

    /// Leaving hidden staircase corners out changes no length: several queries (one
    /// start, three goals each) on one planner, against the graph of every corner.
    #[test]
    fn hidden_staircase_corners_change_no_length(
        n in 16usize..48,
        shapes in arb_shapes(48),
        r in prop_oneof![Just(0.0), 0.0f64..0.3, 0.3f64..0.8],
        picks in proptest::collection::vec(
            (any::<usize>(), -1.2f64..1.2, -1.2f64..1.2, any::<bool>()), 16),
    ) {
        let shapes: Vec<_> = shapes.into_iter().map(|(x, y, rad, a)| (x * n as f64 / 48.0, y * n as f64 / 48.0, rad * n as f64 / 48.0, a)).collect();
        let blocked = polygons(n, &shapes);
        let grid = Grid::new(n, n, blocked.clone());
        let mut collapsed = planner(n, n, &blocked, r);
        let mut every = planner_with(n, n, &blocked, r, VisibilityParams { all_corners: true, ..Default::default() });
        for q in picks.chunks(4) {
            let s = pose(endpoint(&grid, q[0]));
            let goals: Vec<Pose2> = q[1..].iter().map(|&p| pose(endpoint(&grid, p))).collect();
            let a = collapsed.plan_many(&s, &goals).unwrap();
            let b = every.plan_many(&s, &goals).unwrap();
            for (k, (x, y)) in a.iter().zip(&b).enumerate() {
                prop_assert_eq!(x.status(), y.status(), "goal {}", k);
            }
            for (x, y) in collapsed.last_optimum().iter().zip(every.last_optimum()) {
                match (x, y) {
                    (Some(x), Some(y)) => prop_assert!((x - y).abs() < 1e-7, "{} vs {}", x, y),
                    (x, y) => prop_assert_eq!(x, y),
                }
            }
        }
    }
}

/// A staircase of slope 2/5 (runs of 3 and 2 cells): its corners below the chord of
/// their neighbours are hidden, and a query from inside a pocket still gets the exact
/// length (against brute force), as do queries hugging the staircase.
#[test]
fn a_pocket_start_is_planned_exactly_on_a_hidden_corner() {
    let n = 30;
    let mut blocked = vec![false; n * n];
    // Blocked below the staircase y ≤ 2 + 0.4 x (rows counted from 0), by columns.
    for x in 0..n {
        let top = 2 + (2 * x) / 5;
        for y in 0..top.min(n) {
            blocked[y * n + x] = true;
        }
    }
    let r = 0.05;
    let p = planner(n, n, &blocked, r);
    let hidden = p.stats().counters["corners_hidden"];
    assert!(hidden >= 4, "{hidden} hidden corners");
    let check = DiscCheck {
        nx: n,
        ny: n,
        blocked: blocked.clone(),
        r,
    };
    let grid = Grid::new(n, n, blocked.clone());
    let mut tried = 0;
    // From just above every corner (in its pocket when it is hidden) to a point far
    // along the staircase, and back, on one planner.
    let mut p = planner(n, n, &blocked, r);
    for c in grid
        .corners
        .iter()
        .filter(|c| c.at[0] > 0.0 && c.at[1] > 0.0 && c.at[0] < 25.0)
    {
        let s = [c.at[0] - 0.3, c.at[1] + 0.08];
        let g = [28.0, 14.5];
        for (a, b) in [(s, g), (g, s), (s, [1.0, 4.0])] {
            if !check.is_valid(&pose(a)) || !check.is_valid(&pose(b)) {
                continue;
            }
            tried += 1;
            p.plan(&pose(a), &pose(b)).unwrap();
            let got = p.last_optimum()[0].expect("a path");
            let expected = brute_force_disc(&check, a, b, r).expect("brute path");
            assert!(
                (got - expected).abs() < 1e-7,
                "{a:?} → {b:?}: {got} vs {expected}"
            );
        }
    }
    assert!(tried >= 10, "{tried} queries");
}
