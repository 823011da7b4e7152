//! The exact planner against independent brute force on small random grids.

use super::geometry::{circle_tangents, point_tangents, Grid, Pt};
use super::*;
use proptest::prelude::*;
use smug_core::PathLength;
use std::collections::BinaryHeap;

/// A disc of radius `r` on a grid at 1 m per cell, checked by brute force.
struct DiscCheck {
    nx: usize,
    ny: usize,
    blocked: Vec<bool>,
    r: f64,
}

impl DiscCheck {
    fn is_blocked(&self, i: i64, j: i64) -> bool {
        i < 0
            || j < 0
            || i >= self.nx as i64
            || j >= self.ny as i64
            || self.blocked[j as usize * self.nx + i as usize]
    }

    /// Distance from `(x, y)` to the nearest blocked cell or the outside, every cell.
    fn distance(&self, x: f64, y: f64) -> f64 {
        let mut best = x.min(y).min(self.nx as f64 - x).min(self.ny as f64 - y);
        for j in 0..self.ny as i64 {
            for i in 0..self.nx as i64 {
                if self.is_blocked(i, j) {
                    let dx = (i as f64 - x).max(0.0).max(x - i as f64 - 1.0);
                    let dy = (j as f64 - y).max(0.0).max(y - j as f64 - 1.0);
                    best = best.min(dx.hypot(dy));
                }
            }
        }
        best
    }
}

impl StateValidityChecker for DiscCheck {
    fn is_valid(&self, s: &Pose2) -> bool {
        let d = self.distance(s.x, s.y);
        d >= self.r && d > 0.0
    }
}

fn disc(nx: usize, ny: usize, blocked: &[bool], r: f64) -> DiscOnGrid {
    DiscOnGrid {
        radius: r,
        geometry: GridGeometry::new([0.0, 0.0], 1.0, [nx, ny]).unwrap(),
        blocked: blocked.to_vec(),
    }
}

fn planner(nx: usize, ny: usize, blocked: &[bool], r: f64) -> Visibility {
    planner_with(nx, ny, blocked, r, VisibilityParams::default())
}

fn planner_with(
    nx: usize,
    ny: usize,
    blocked: &[bool],
    r: f64,
    params: VisibilityParams,
) -> Visibility {
    let check = DiscCheck {
        nx,
        ny,
        blocked: blocked.to_vec(),
        r,
    };
    Visibility::new(
        params,
        disc(nx, ny, blocked, r),
        Arc::new(check),
        Arc::new(PathLength::new(1.0, 0.0).unwrap()),
    )
    .unwrap()
}

/// Dijkstra on an explicit graph.
fn dijkstra(n: usize, edges: &[(usize, usize, f64)], s: usize, g: usize) -> Option<f64> {
    let mut adj = vec![Vec::new(); n];
    for &(a, b, w) in edges {
        adj[a].push((b, w));
        adj[b].push((a, w));
    }
    let mut best = vec![f64::INFINITY; n];
    let mut heap = BinaryHeap::new();
    best[s] = 0.0;
    heap.push((std::cmp::Reverse(OrdF(0.0)), s));
    while let Some((std::cmp::Reverse(OrdF(d)), v)) = heap.pop() {
        if d > best[v] {
            continue;
        }
        for &(w, c) in &adj[v] {
            if d + c < best[w] {
                best[w] = d + c;
                heap.push((std::cmp::Reverse(OrdF(d + c)), w));
            }
        }
    }
    best[g].is_finite().then_some(best[g])
}

#[derive(PartialEq)]
struct OrdF(f64);
impl Eq for OrdF {}
impl Ord for OrdF {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&o.0)
    }
}
impl PartialOrd for OrdF {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}

// ---- A point robot (the limit r → 0) with exact rational line of sight ----

/// A rational `n / d`, `d > 0`.
#[derive(Clone, Copy, Debug)]
struct Q(i128, i128);

impl Q {
    fn eq(self, o: Q) -> bool {
        self.0 * o.1 == o.0 * self.1
    }
    fn floor(self) -> i128 {
        self.0.div_euclid(self.1)
    }
    fn is_int(self) -> bool {
        self.0.rem_euclid(self.1) == 0
    }
}

/// The cells (in unit-cell indices) whose closure holds the point `(x, y)` given in
/// half-cells; empty unless the point lies on no vertex.
fn cells_at(x: Q, y: Q) -> Vec<(i64, i64)> {
    let axis = |v: Q| -> Vec<i64> {
        // v in half-cells: cell k covers [2k, 2k + 2].
        let half = Q(v.0, v.1 * 2);
        if half.is_int() {
            let k = half.floor() as i64;
            vec![k - 1, k]
        } else {
            vec![half.floor() as i64]
        }
    };
    let (xs, ys) = (axis(x), axis(y));
    ys.iter()
        .flat_map(|&j| xs.iter().map(move |&i| (i, j)))
        .collect()
}

/// Exact line of sight of a point robot between half-cell points `p` and `q`: every
/// piece of the segment lies in (or on the edge of) a free cell, and at every grid
/// vertex it passes, the free cells before and after are joined around the vertex.
fn los0(check: &DiscCheck, p: [i64; 2], q: [i64; 2]) -> bool {
    let d = [q[0] - p[0], q[1] - p[1]];
    let mut ts = vec![Q(0, 1), Q(1, 1)];
    for k in 0..2 {
        if d[k] == 0 {
            continue;
        }
        let (lo, hi) = (p[k].min(q[k]), p[k].max(q[k]));
        for line in (lo..=hi).filter(|v| v % 2 == 0) {
            let (mut n, mut den) = ((line - p[k]) as i128, d[k] as i128);
            if den < 0 {
                n = -n;
                den = -den;
            }
            if n > 0 && n < den {
                ts.push(Q(n, den));
            }
        }
    }
    ts.sort_by(|a, b| (a.0 * b.1).cmp(&(b.0 * a.1)));
    ts.dedup_by(|a, b| a.eq(*b));
    let at = |t: Q| {
        (
            Q(p[0] as i128 * t.1 + t.0 * d[0] as i128, t.1),
            Q(p[1] as i128 * t.1 + t.0 * d[1] as i128, t.1),
        )
    };
    let mid = |a: Q, b: Q| Q(a.0 * b.1 + b.0 * a.1, 2 * a.1 * b.1);
    let pieces: Vec<Vec<(i64, i64)>> = ts
        .windows(2)
        .map(|w| {
            let (x, y) = at(mid(w[0], w[1]));
            cells_at(x, y)
        })
        .collect();
    let free = |c: &(i64, i64)| !check.is_blocked(c.0, c.1);
    if !pieces.iter().all(|cells| cells.iter().any(free)) {
        return false;
    }
    for (k, t) in ts
        .iter()
        .enumerate()
        .skip(1)
        .take(ts.len().saturating_sub(2))
    {
        let (x, y) = at(*t);
        let (hx, hy) = (Q(x.0, x.1 * 2), Q(y.0, y.1 * 2));
        if !(hx.is_int() && hy.is_int()) {
            continue;
        }
        let (vx, vy) = (hx.floor() as i64, hy.floor() as i64);
        // Quadrants around the vertex in cyclic order.
        let ring = [(vx - 1, vy - 1), (vx, vy - 1), (vx, vy), (vx - 1, vy)];
        let joined = |a: usize, b: usize| -> bool {
            for dir in [1usize, 3] {
                let mut i = a;
                loop {
                    if !free(&ring[i]) {
                        break;
                    }
                    if i == b {
                        return true;
                    }
                    i = (i + dir) % 4;
                    if i == a {
                        break;
                    }
                }
            }
            false
        };
        let ids = |cells: &Vec<(i64, i64)>| -> Vec<usize> {
            cells
                .iter()
                .filter_map(|c| ring.iter().position(|r| r == c))
                .collect()
        };
        let (before, after) = (ids(&pieces[k - 1]), ids(&pieces[k]));
        if !before.iter().any(|&a| after.iter().any(|&b| joined(a, b))) {
            return false;
        }
    }
    true
}

/// The shortest path of a point robot from `s` to `g` (half-cell coordinates): Dijkstra
/// on the visibility graph of every convex corner, exact line of sight.
fn brute_force_point(check: &DiscCheck, s: [i64; 2], g: [i64; 2]) -> Option<f64> {
    let mut nodes = vec![s, g];
    for y in 0..=check.ny as i64 {
        for x in 0..=check.nx as i64 {
            let around = [(x - 1, y - 1), (x, y - 1), (x - 1, y), (x, y)];
            if around.iter().filter(|c| check.is_blocked(c.0, c.1)).count() == 1 {
                nodes.push([2 * x, 2 * y]);
            }
        }
    }
    let mut edges = Vec::new();
    for a in 0..nodes.len() {
        for b in a + 1..nodes.len() {
            if los0(check, nodes[a], nodes[b]) {
                let (dx, dy) = (nodes[b][0] - nodes[a][0], nodes[b][1] - nodes[a][1]);
                edges.push((a, b, (dx as f64).hypot(dy as f64) / 2.0));
            }
        }
    }
    dijkstra(nodes.len(), &edges, 0, 1)
}

// ---- A disc: every tangent between every pair of corner circles ----

/// The shortest path of a disc of radius `r` from `s` to `g` on the explicit graph of
/// all tangent points (every corner pair, no visibility pruning) joined by arcs.
fn brute_force_disc(check: &DiscCheck, s: Pt, g: Pt, r: f64) -> Option<f64> {
    let grid = Grid::new(check.nx, check.ny, check.blocked.clone());
    let (rc, need) = (r + 2e-7, r + 1e-7);
    let mut points: Vec<(Option<usize>, f64)> = vec![(None, 0.0), (None, 0.0)];
    let mut edges = Vec::new();
    let clear = |p: Pt, q: Pt, need: f64| grid.segment_clear(p, q, need);
    let cs = check.distance(s[0], s[1]).min(need);
    let cg = check.distance(g[0], g[1]).min(need);
    if clear(s, g, cs.min(cg)) {
        edges.push((0, 1, super::geometry::dist(s, g)));
    }
    let corners = grid.corners.clone();
    for (a, ca) in corners.iter().enumerate() {
        for (end, pt, c_end) in [(0usize, s, cs), (1, g, cg)] {
            for n in point_tangents(pt, ca.at, rc) {
                if let Some(rel) = ca.relative_angle(n) {
                    let p = ca.point(rc, rel);
                    if clear(p, pt, c_end) {
                        points.push((Some(a), rel));
                        edges.push((end, points.len() - 1, super::geometry::dist(p, pt)));
                    }
                }
            }
        }
        for (b, cb) in corners.iter().enumerate().skip(a + 1) {
            for (na, nb) in circle_tangents(ca.at, cb.at, rc) {
                let (Some(ra), Some(rb)) = (ca.relative_angle(na), cb.relative_angle(nb)) else {
                    continue;
                };
                let (pa, pb) = (ca.point(rc, ra), cb.point(rc, rb));
                if clear(pa, pb, need) {
                    points.push((Some(a), ra));
                    points.push((Some(b), rb));
                    let n = points.len();
                    edges.push((n - 2, n - 1, super::geometry::dist(pa, pb)));
                }
            }
        }
    }
    for (a, corner) in corners.iter().enumerate() {
        let mut on: Vec<(f64, usize)> = points
            .iter()
            .enumerate()
            .filter(|(_, p)| p.0 == Some(a))
            .map(|(i, p)| (p.1, i))
            .collect();
        on.sort_by(|x, y| x.0.total_cmp(&y.0));
        for w in on.windows(2) {
            if grid.arc_clear(corner, rc, w[0].0, w[1].0, need) {
                edges.push((w[0].1, w[1].1, rc * (w[1].0 - w[0].0)));
            }
        }
    }
    dijkstra(points.len(), &edges, 0, 1)
}

/// A random grid of `nx × ny` with about `density` blocked, and two free cells.
fn arb_grid() -> impl Strategy<Value = (usize, usize, Vec<bool>, usize, usize)> {
    (3usize..9, 3usize..9, 0.0f64..0.45).prop_flat_map(|(nx, ny, density)| {
        (
            Just(nx),
            Just(ny),
            proptest::collection::vec(proptest::bool::weighted(density), nx * ny),
            0..nx * ny,
            0..nx * ny,
        )
    })
}

/// True when every millimetre of the path keeps the disc's clearance.
fn valid_everywhere(check: &DiscCheck, path: &Path) -> bool {
    path.states.windows(2).all(|w| {
        let n = (w[0].xy_distance(&w[1]) / 1e-3).ceil().max(1.0) as usize;
        (0..=n).all(|k| {
            let t = k as f64 / n as f64;
            check.is_valid(&Pose2::new(
                w[0].x + t * (w[1].x - w[0].x),
                w[0].y + t * (w[1].y - w[0].y),
                0.0,
            ))
        })
    })
}

/// One query of a disc against the brute-force tangent graph (see the property tests).
fn disc_case(
    nx: usize,
    ny: usize,
    mut blocked: Vec<bool>,
    (a, b): (usize, usize),
    r: f64,
    ds: (f64, f64, f64, f64),
) -> Result<(), TestCaseError> {
    blocked[a] = false;
    blocked[b] = false;
    let check = DiscCheck {
        nx,
        ny,
        blocked: blocked.clone(),
        r,
    };
    let s = [(a % nx) as f64 + 0.5 + ds.0, (a / nx) as f64 + 0.5 + ds.1];
    let g = [(b % nx) as f64 + 0.5 + ds.2, (b / nx) as f64 + 0.5 + ds.3];
    let (sp, gp) = (Pose2::new(s[0], s[1], 0.3), Pose2::new(g[0], g[1], -2.0));
    let mut p = planner(nx, ny, &blocked, r);
    let outcome = p.plan(&sp, &gp).unwrap();
    if !check.is_valid(&sp) {
        prop_assert_eq!(outcome.status(), "invalid_start");
        return Ok(());
    }
    if !check.is_valid(&gp) {
        prop_assert_eq!(outcome.status(), "invalid_goal");
        return Ok(());
    }
    // The whole graph built first (preprocessing) answers the same.
    let mut built = planner_with(nx, ny, &blocked, r, VisibilityParams { build_all: true });
    prop_assert_eq!(&built.plan(&sp, &gp).unwrap(), &outcome);
    let expected = brute_force_disc(&check, s, g, r);
    // The flood fill LazyPRM* proves "no path" with never contradicts a path.
    let regions = smug_core::FreeRegions::new(&disc(nx, ny, &blocked, r));
    prop_assert!(
        expected.is_none() || !regions.disconnected(&sp, &gp),
        "free-cell components separate a connected pair"
    );
    match (expected, &outcome) {
        (None, PlannerOutcome::NoPath(NoPathReason::Proved(Proof::Disconnected))) => {}
        (Some(len), PlannerOutcome::Exact(path)) => {
            let optimum = p.last_optimum()[0].unwrap();
            prop_assert!(
                (optimum - len).abs() < 1e-7,
                "optimum {optimum} vs brute force {len}"
            );
            prop_assert!(
                path.cost >= optimum - 1e-9 && path.cost <= optimum * 1.001 + 1e-9,
                "{} vs {optimum}",
                path.cost
            );
            prop_assert!(valid_everywhere(&check, path));
            prop_assert_eq!(path.states[0], sp);
            prop_assert_eq!(*path.states.last().unwrap(), gp);
        }
        (e, o) => prop_assert!(false, "brute force {e:?}, planner {}", o.status()),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]

    /// Discs wider than half a cell on sparser, bigger grids, where arcs pass near
    /// other cells.
    #[test]
    fn wide_discs_match_brute_force_on_sparse_grids(
        (nx, ny, blocked, a, b) in (10usize..16, 10usize..16, 0.03f64..0.15).prop_flat_map(|(nx, ny, d)| (
            Just(nx), Just(ny),
            proptest::collection::vec(proptest::bool::weighted(d), nx * ny),
            0..nx * ny, 0..nx * ny)),
        r in 0.5f64..1.4,
        ds in (-0.3f64..0.3, -0.3f64..0.3, -0.3f64..0.3, -0.3f64..0.3),
    ) {
        disc_case(nx, ny, blocked, (a, b), r, ds)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// A radius-0 disc (the planner's limit of a point) matches the exact point
    /// visibility graph with rational line of sight on 300 random grids.
    #[test]
    fn point_robot_matches_exact_visibility_graph((nx, ny, mut blocked, a, b) in arb_grid()) {
        blocked[a] = false;
        blocked[b] = false;
        let check = DiscCheck { nx, ny, blocked: blocked.clone(), r: 0.0 };
        let (s, g) = ([2 * (a % nx) as i64 + 1, 2 * (a / nx) as i64 + 1], [2 * (b % nx) as i64 + 1, 2 * (b / nx) as i64 + 1]);
        let expected = brute_force_point(&check, s, g);
        let mut p = planner(nx, ny, &blocked, 0.0);
        let (sp, gp) = (Pose2::new(s[0] as f64 / 2.0, s[1] as f64 / 2.0, 0.0), Pose2::new(g[0] as f64 / 2.0, g[1] as f64 / 2.0, 0.0));
        let outcome = p.plan(&sp, &gp).unwrap();
        match (expected, &outcome) {
            (None, PlannerOutcome::NoPath(NoPathReason::Proved(Proof::Disconnected))) => {}
            (Some(len), PlannerOutcome::Exact(path)) => {
                let optimum = p.last_optimum()[0].unwrap();
                prop_assert!((optimum - len).abs() < 1e-5, "optimum {optimum} vs brute force {len}");
                prop_assert!(path.cost >= optimum - 1e-9 && path.cost <= optimum * 1.001 + 1e-9);
                prop_assert!(valid_everywhere(&check, path));
            }
            (e, o) => prop_assert!(false, "brute force {e:?}, planner {}", o.status()),
        }
    }

    /// Discs of several radii match the graph of every tangent between every pair of
    /// corner circles; the returned path is valid at every millimetre and at most
    /// 0.1 % above the exact length.
    #[test]
    fn disc_matches_brute_force_tangent_graph((nx, ny, blocked, a, b) in arb_grid(), r in prop_oneof![Just(0.1), Just(0.25), Just(0.4), Just(0.5), 0.01f64..0.48, 0.48f64..1.6], ds in (-0.3f64..0.3, -0.3f64..0.3, -0.3f64..0.3, -0.3f64..0.3)) {
        disc_case(nx, ny, blocked, (a, b), r, ds)?;
    }

    /// One start to many goals gives what one query per goal gives.
    #[test]
    fn one_to_many_equals_one_to_one((nx, ny, blocked, a, _b) in arb_grid(), goals in proptest::collection::vec(0usize..64, 1..6), r in 0.05f64..0.45) {
        let cell = |k: usize| Pose2::new((k % nx) as f64 + 0.5, (k / nx) as f64 + 0.5, 0.0);
        let goals: Vec<Pose2> = goals.iter().map(|&k| cell(k % (nx * ny))).collect();
        let mut many = planner(nx, ny, &blocked, r);
        let all = many.plan_many(&cell(a), &goals).unwrap();
        let optima = many.last_optimum().to_vec();
        let mut one = planner(nx, ny, &blocked, r);
        for (k, goal) in goals.iter().enumerate() {
            let single = one.plan(&cell(a), goal).unwrap();
            prop_assert_eq!(single.status(), all[k].status());
            if let (Some(x), Some(y)) = (optima[k], one.last_optimum()[0]) {
                prop_assert!((x - y).abs() < 1e-9, "{x} vs {y}");
            }
        }
    }
}

#[test]
fn straight_line_on_an_empty_map_and_around_one_corner() {
    let mut p = planner(4, 4, &[false; 16], 0.0);
    let path = p
        .plan(&Pose2::new(0.5, 0.5, 0.0), &Pose2::new(3.5, 2.5, 0.0))
        .unwrap();
    let len = p.last_optimum()[0].unwrap();
    assert!((len - 3.0f64.hypot(2.0)).abs() < 1e-12, "{len}");
    assert_eq!(path.exact_path().unwrap().states.len(), 2);
    // One blocked cell (1, 1) on a 3×3 map, from (0.5, 1.5) to (2.5, 1.5), r → 0:
    // over the corners (1, 2) and (2, 2) (or under, as long).
    let mut blocked = [false; 9];
    blocked[4] = true;
    let mut p = planner(3, 3, &blocked, 0.0);
    p.plan(&Pose2::new(0.5, 1.5, 0.0), &Pose2::new(2.5, 1.5, 0.0))
        .unwrap();
    let expected = 2.0 * 0.5f64.hypot(0.5) + 1.0;
    assert!((p.last_optimum()[0].unwrap() - expected).abs() < 1e-5);
    // With r = 0.25: tangent, arc around (1, 2), the inflated top edge, mirrored.
    let mut p = planner(3, 3, &blocked, 0.25);
    p.plan(&Pose2::new(0.5, 1.5, 0.0), &Pose2::new(2.5, 1.5, 0.0))
        .unwrap();
    // Tangent from (0.5, 1.5) to the circle of radius 0.25 at (1, 2): length
    // sqrt(d² − r²) with d = √0.5; arc between the tangent's normal and straight up;
    // then the straight top edge of length 1, mirrored.
    let d = 0.5f64.hypot(0.5);
    let t = (d * d - 0.0625).sqrt();
    // Normal of the tangent point: angle of (p − c) = direction from c to s rotated.
    let alpha = (0.25 / d).acos(); // angle between c→s and the normal
    let to_s = (-0.5f64).atan2(-0.5); // direction from c = (1, 2) to s = (0.5, 1.5)
    let normal = to_s - alpha + std::f64::consts::TAU; // the upper-left tangent point
    let arc = 0.25 * (normal - std::f64::consts::FRAC_PI_2).abs();
    let expected = 2.0 * (t + arc) + 1.0;
    assert!(
        (p.last_optimum()[0].unwrap() - expected).abs() < 1e-5,
        "{} vs {expected}",
        p.last_optimum()[0].unwrap()
    );
}

#[test]
fn a_goal_at_the_start_turns_on_the_spot() {
    let mut p = planner(3, 3, &[false; 9], 0.25);
    let outcome = p
        .plan(&Pose2::new(1.5, 1.5, 0.0), &Pose2::new(1.5, 1.5, 1.0))
        .unwrap();
    let path = outcome.exact_path().unwrap();
    assert_eq!(
        path.states,
        vec![Pose2::new(1.5, 1.5, 0.0), Pose2::new(1.5, 1.5, 1.0)]
    );
    assert_eq!(p.last_optimum()[0], Some(0.0));
}

#[test]
fn invalid_endpoints_and_unreachable_goals_are_named() {
    // A wall across the middle column of a 3×3 map.
    let blocked = [false, true, false, false, true, false, false, true, false];
    let mut p = planner(3, 3, &blocked, 0.25);
    let left = Pose2::new(0.5, 1.5, 0.0);
    assert_eq!(
        p.plan(&left, &Pose2::new(2.5, 1.5, 0.0)).unwrap(),
        PlannerOutcome::NoPath(NoPathReason::Proved(Proof::Disconnected))
    );
    assert_eq!(
        p.plan(&Pose2::new(1.5, 1.5, 0.0), &left).unwrap().status(),
        "invalid_start"
    );
    assert_eq!(
        p.plan(&left, &Pose2::new(0.9, 1.5, 0.0)).unwrap().status(),
        "invalid_goal"
    );
}

#[test]
fn refuses_a_negative_radius_naming_the_key() {
    let check = Arc::new(DiscCheck {
        nx: 2,
        ny: 2,
        blocked: vec![false; 4],
        r: 0.0,
    });
    let err = Visibility::new(
        VisibilityParams::default(),
        disc(2, 2, &[false; 4], -0.6),
        check,
        Arc::new(PathLength::default()),
    )
    .err()
    .unwrap()
    .to_string();
    assert!(err.contains("validity.params.radius"), "{err}");
}

#[test]
fn a_disc_wider_than_a_cell_turns_in_a_three_cell_corridor() {
    // A U-turn around a wall: r = 1.2 cells, corridors 3 cells wide (2.4 needed).
    let (nx, ny) = (9, 9);
    let mut blocked = vec![false; nx * ny];
    for j in 0..6 {
        blocked[j * nx + 4] = true; // the wall x ∈ [4, 5], y ∈ [0, 6]
    }
    let check = DiscCheck {
        nx,
        ny,
        blocked: blocked.clone(),
        r: 1.2,
    };
    let mut p = planner(nx, ny, &blocked, 1.2);
    let (s, g) = (Pose2::new(2.0, 1.5, 0.0), Pose2::new(7.0, 1.5, 0.0));
    let PlannerOutcome::Exact(path) = p.plan(&s, &g).unwrap() else {
        panic!("no path");
    };
    assert!(valid_everywhere(&check, &path));
    let optimum = p.last_optimum()[0].unwrap();
    let expected = brute_force_disc(&check, [2.0, 1.5], [7.0, 1.5], 1.2).unwrap();
    assert!((optimum - expected).abs() < 1e-7, "{optimum} vs {expected}");
    // At least up and down the wall's side plus the wall's width.
    assert!(optimum > 2.0 * 4.5 + 1.0, "{optimum}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// The shadowcast never misses a cell a clear segment reaches (the planner's
    /// candidate corners are a superset of the visible ones).
    #[test]
    fn shadowcast_finds_every_cell_a_clear_segment_reaches(
        (nx, ny, density) in (5usize..40, 5usize..40, 0.0f64..0.2),
        seed in proptest::collection::vec(any::<u32>(), 1600),
        s in (0.0f64..1.0, 0.0f64..1.0), t in (0.0f64..1.0, 0.0f64..1.0),
    ) {
        let blocked: Vec<bool> = (0..nx * ny).map(|k| (seed[k] as f64 / u32::MAX as f64) < density).collect();
        let grid = Grid::new(nx, ny, blocked);
        let (s, t) = ([s.0 * nx as f64, s.1 * ny as f64], [t.0 * nx as f64, t.1 * ny as f64]);
        prop_assume!(grid.segment_clear(s, t, 1e-9));
        let target = (t[0].floor() as i64, t[1].floor() as i64);
        let mut seen = false;
        grid.visible_cells(s, |i, j| seen |= (i, j) == target);
        prop_assert!(seen, "cell {:?} of {:?} not found from {:?}", target, t, s);
    }
}

#[test]
fn an_arc_through_a_closed_diagonal_gap_is_refused() {
    // An L-shaped wall (column 5 and row 5, up to the corner cell (5, 5)) and a cell
    // (7, 7): the gap between (5, 5) and (7, 7) (√2) is closed for r = 0.9, yet the
    // circle around the corner (6, 6) is clear at both ends of its quarter: only the
    // arc check keeps the path from hugging the corner through the gap.
    let (nx, ny, r) = (14, 14, 0.9);
    let mut blocked = vec![false; nx * ny];
    for k in 0..6 {
        blocked[k * nx + 5] = true;
        blocked[5 * nx + k] = true;
    }
    blocked[7 * nx + 7] = true;
    let check = DiscCheck {
        nx,
        ny,
        blocked: blocked.clone(),
        r,
    };
    let mut p = planner(nx, ny, &blocked, r);
    let (s, g) = ([6.95, 1.0], [1.0, 6.95]);
    let PlannerOutcome::Exact(path) = p
        .plan(&Pose2::new(s[0], s[1], 0.0), &Pose2::new(g[0], g[1], 0.0))
        .unwrap()
    else {
        panic!("no path");
    };
    assert!(valid_everywhere(&check, &path));
    let expected = brute_force_disc(&check, s, g, r).unwrap();
    let optimum = p.last_optimum()[0].unwrap();
    assert!((optimum - expected).abs() < 1e-7, "{optimum} vs {expected}");
    // Around the far side of (7, 7), well beyond the corner hug (≈ 11.4).
    assert!(optimum > 13.0, "{optimum}");
}
