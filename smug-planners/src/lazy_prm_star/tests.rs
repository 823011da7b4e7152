//! Unit tests of LazyPRM*.

use super::query::improvement_interval;
use super::test_support::{planner_on, Free, Ring};
use super::*;

fn planner(params: LazyPrmStarParams) -> Result<LazyPrmStar> {
    planner_on(params, 7, Free)
}

#[test]
fn negative_or_non_finite_shares_and_focus_are_rejected() {
    for bad in [-0.1, f64::INFINITY, f64::NAN] {
        let share = LazyPrmStarParams {
            attempt_share: bad,
            ..LazyPrmStarParams::default()
        };
        let focus = LazyPrmStarParams {
            focus: bad,
            ..LazyPrmStarParams::default()
        };
        assert!(planner(share).is_err(), "attempt_share {bad}");
        assert!(planner(focus).is_err(), "focus {bad}");
    }
}

#[test]
fn improvement_rounds_scale_with_the_samples_the_first_path_needed() {
    let params = LazyPrmStarParams {
        attempt_share: 0.1,
        ..LazyPrmStarParams::default()
    };
    assert_eq!(
        improvement_interval(&params, 0),
        5,
        "a path on the roadmap as is"
    );
    assert_eq!(
        improvement_interval(&params, 30),
        5,
        "at least attempt_every"
    );
    assert_eq!(improvement_interval(&params, 5_000), 500);
    let reference = LazyPrmStarParams::default();
    assert_eq!(
        improvement_interval(&reference, 5_000),
        5,
        "share 0: the reference"
    );
}

#[test]
fn the_focus_alternates_with_the_bounds_and_widens_geometrically() {
    let (a, b) = (Pose2::new(0.0, 0.0, 0.0), Pose2::new(4.0, 0.0, 0.0));
    let mut focus = Focus::new(0.5, 4.0, 100.0, 3);
    let set = focus.next_set(&a, &b).expect("first sample: the focus");
    assert!((set.best_cost - 6.0).abs() < 1e-12);
    assert!(focus.next_set(&a, &b).is_none(), "then the bounds");
    assert!(
        !focus.tick() && !focus.tick() && focus.tick(),
        "due after 3"
    );
    focus.widen(3);
    let set = focus.next_set(&a, &b).unwrap();
    assert!((set.best_cost - 8.0).abs() < 1e-12, "excess 1.0");
    assert!(!focus.covers(10.0) && focus.covers(8.0));
    let small = Focus::new(0.5, 4.0, 5.0, 3);
    assert!(small.covers(1e9), "the focus holds the whole bounds");
    let mut off = Focus::new(0.0, 4.0, 100.0, 3);
    assert!(
        (0..4).all(|_| off.next_set(&a, &b).is_none()),
        "0: no focus"
    );
}

#[test]
fn a_query_in_free_space_finds_the_straight_line_with_every_option() {
    let params = LazyPrmStarParams {
        attempt_share: 0.1,
        focus: 0.5,
        smooth: true,
        ..LazyPrmStarParams::default()
    };
    let mut p = planner(params).unwrap();
    let (a, b) = (Pose2::new(1.0, 1.0, 0.0), Pose2::new(9.0, 8.0, 0.0));
    let outcome = p.plan(&a, &b).unwrap();
    let path = outcome.exact_path().expect("a path");
    assert!((path.cost - a.xy_distance(&b)).abs() < 1e-9);
    assert!(p.stats().counters["samples"] < p.params.max_samples);
}

fn ring_planner(retry_cut_off: bool) -> LazyPrmStar {
    let params = LazyPrmStarParams {
        max_samples: 1_000,
        retry_cut_off,
        ..LazyPrmStarParams::default()
    };
    planner_on(params, 7, Ring).unwrap()
}

#[test]
fn a_spent_time_budget_is_named_as_such() {
    let mut p = ring_planner(true);
    p.params.max_samples = u64::MAX;
    p.params.time_limit = Some(0.05);
    let outcome = p.plan(&Pose2::new(1.0, 1.0, 0.0), &Pose2::new(8.0, 8.0, 0.0));
    assert_eq!(
        outcome.unwrap(),
        PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::Time))
    );
}

#[test]
fn a_query_the_deadline_ends_cuts_off_no_pocket() {
    let mut p = ring_planner(false);
    let free = p.plan(&Pose2::new(1.0, 9.0, 0.0), &Pose2::new(1.0, 1.0, 0.0));
    assert!(
        free.unwrap().exact_path().is_some(),
        "a roadmap outside the ring"
    );
    p.deadline = Deadline::after(0.0);
    let cut = p.plan(&Pose2::new(1.0, 1.0, 0.0), &Pose2::new(8.0, 8.0, 0.0));
    assert_eq!(
        cut.unwrap(),
        PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::Deadline))
    );
    assert!(
        p.cut_off.is_empty(),
        "the deadline says nothing of a pocket"
    );
}

#[test]
fn an_endpoint_in_a_pocket_is_cut_off_after_one_failed_budget() {
    let pocket = Pose2::new(8.0, 8.0, 0.0);
    let mut p = ring_planner(false);
    let first = p.plan(&Pose2::new(1.0, 1.0, 0.0), &pocket).unwrap();
    assert_eq!(
        first,
        PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::Samples))
    );
    let spent = p.stats().counters["samples"];
    assert!(spent >= 1_000, "the whole budget: {spent}");
    let second = p.plan(&pocket, &Pose2::new(1.0, 9.0, 0.0)).unwrap();
    assert_eq!(
        second,
        PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::EarlierQuery))
    );
    assert_eq!(
        p.stats().counters["samples"],
        spent,
        "no budget spent again"
    );
    assert_eq!(p.stats().counters["cut_off_queries"], 1);
    let free = p.plan(&Pose2::new(1.0, 9.0, 0.0), &Pose2::new(1.0, 1.0, 0.0));
    assert!(
        free.unwrap().exact_path().is_some(),
        "the other end is not cut off"
    );

    let beside = Pose2::new(8.5, 7.5, 0.0);
    let spent = p.stats().counters["samples"];
    let third = p.plan(&beside, &Pose2::new(9.0, 1.0, 0.0)).unwrap();
    assert_eq!(
        third,
        PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::EarlierQuery)),
        "another pose in the same pocket is cut off with it"
    );
    assert_eq!(p.stats().counters["samples"], spent);
    let inside = p.plan(&beside, &pocket).unwrap();
    assert!(
        inside.exact_path().is_some(),
        "a query inside the pocket is not cut off"
    );

    let mut retried = ring_planner(true);
    retried.plan(&Pose2::new(1.0, 1.0, 0.0), &pocket).unwrap();
    retried.plan(&pocket, &Pose2::new(1.0, 9.0, 0.0)).unwrap();
    assert!(
        retried.stats().counters["samples"] >= 2_000,
        "a second budget"
    );
    assert_eq!(retried.stats().counters["cut_off_queries"], 0);
}

/// Free space that says it is a disc of radius 0.1 on a 10 × 10 grid of 1 m cells
/// with every other cell of every other row blocked (many corners).
struct Dotted;

impl StateValidityChecker for Dotted {
    fn is_valid(&self, _: &Pose2) -> bool {
        true
    }

    fn disc_on_grid(&self) -> Option<smug_core::DiscOnGrid> {
        Some(smug_core::DiscOnGrid {
            radius: 0.1,
            geometry: smug_core::GridGeometry::new([0.0, 0.0], 1.0, [10, 10]).unwrap(),
            blocked: (0..100).map(|k| (k / 10) % 2 == 1 && k % 2 == 1).collect(),
        })
    }
}

impl MotionValidator for Dotted {
    fn is_valid_motion(&self, _: &Pose2, _: &Pose2) -> bool {
        true
    }

    fn check_motion(&self, _: &Pose2, _: &Pose2) -> smug_core::MotionCheck {
        smug_core::MotionCheck::Valid
    }
}

#[test]
fn corner_vertices_have_their_own_budget_not_the_queries_samples() {
    let waypoints = {
        let disc = Dotted.disc_on_grid().unwrap();
        let mut w = crate::grid_disc::corner_waypoints(&disc);
        w.extend(crate::grid_disc::corridor_waypoints(&disc));
        w.len() as u64
    };
    assert!(waypoints > 50, "{waypoints} waypoints");
    let (s, g) = (Pose2::new(0.5, 0.5, 0.0), Pose2::new(9.5, 0.5, 0.0));
    // A sample budget far below the corners: every corner still joins the roadmap.
    let params = LazyPrmStarParams {
        max_samples: 10,
        ..Default::default()
    };
    let mut p = planner_on(params, 1, Dotted).unwrap();
    p.plan(&s, &g).unwrap();
    let vertices = p.stats().vertices;
    assert!(
        vertices >= waypoints,
        "{vertices} vertices < {waypoints} waypoints"
    );
    // Their own budget thins them.
    let params = LazyPrmStarParams {
        max_samples: 10,
        max_corner_vertices: 20,
        ..Default::default()
    };
    let mut p = planner_on(params, 1, Dotted).unwrap();
    p.plan(&s, &g).unwrap();
    let vertices = p.stats().vertices;
    assert!(vertices <= 20 + 10 + 2, "{vertices} vertices");
}
