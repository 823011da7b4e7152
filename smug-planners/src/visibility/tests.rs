//! The exact planner against independent brute force on small random grids.

mod brute;
mod staircases;

use super::geometry::Grid;
use super::*;
use brute::{brute_force_disc, brute_force_point, DiscCheck};
use proptest::prelude::*;
use smug_core::PathLength;

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
    let mut built = planner_with(
        nx,
        ny,
        &blocked,
        r,
        VisibilityParams {
            build_all: true,
            ..Default::default()
        },
    );
    prop_assert_eq!(&built.plan(&sp, &gp).unwrap(), &outcome);
    let expected = brute_force_disc(&check, s, g, r);
    // The flood fill LazyPRM* proves "no path" with never contradicts a path.
    let regions = crate::grid_disc::FreeRegions::new(&disc(nx, ny, &blocked, r));
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

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// The run-by-run shadowcast finds every corner beside a cell the cell-by-cell
    /// shadowcast lights (so every corner a clear segment reaches).
    #[test]
    fn run_shadowcast_finds_every_corner_the_cell_shadowcast_finds(
        (nx, ny, density) in (2usize..140, 2usize..40, 0.0f64..0.5),
        seed in proptest::collection::vec(any::<u32>(), 140 * 40),
        s in (0.0f64..1.0, 0.0f64..1.0), snap in 0u8..4,
    ) {
        let blocked: Vec<bool> = (0..nx * ny).map(|k| (seed[k] as f64 / u32::MAX as f64) < density).collect();
        let grid = Grid::new(nx, ny, blocked);
        let mut s = [s.0 * nx as f64, s.1 * ny as f64];
        // Sources on grid lines and vertices too (corners are sources).
        if snap & 1 == 1 { s[0] = s[0].round(); }
        if snap & 2 == 2 { s[1] = s[1].round(); }
        let lines = shadow::Lines::new(&grid);
        let mut fast = std::collections::HashSet::new();
        lines.visible_corners(s, |c| { fast.insert(c); });
        let mut missed = Vec::new();
        grid.visible_cells(s, |i, j| {
            for (x, y) in [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)] {
                if let Some(c) = grid.corner_at(x, y) {
                    if !fast.contains(&c) { missed.push((x, y)); }
                }
            }
        });
        prop_assert!(missed.is_empty(), "from {:?}: missed corners {:?}", s, missed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// The segment check that jumps over open ground answers as the cell-by-cell one.
    #[test]
    fn jumping_segment_check_equals_the_exact_one(
        (nx, ny, density) in (2usize..90, 2usize..90, 0.0f64..0.05),
        seed in proptest::collection::vec(any::<u32>(), 90 * 90),
        s in (-0.05f64..1.05, -0.05f64..1.05), t in (-0.05f64..1.05, -0.05f64..1.05),
        r in 0.0f64..3.0,
    ) {
        let blocked: Vec<bool> = (0..nx * ny).map(|k| (seed[k] as f64 / u32::MAX as f64) < density).collect();
        let grid = Grid::new(nx, ny, blocked);
        let (s, t) = ([s.0 * nx as f64, s.1 * ny as f64], [t.0 * nx as f64, t.1 * ny as f64]);
        prop_assert_eq!(grid.segment_clear(s, t, r), grid.segment_clear_exact(s, t, r));
    }
}
