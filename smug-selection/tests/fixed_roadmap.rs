//! The selectors on a shared, fixed roadmap: IDP returns exactly DP's cost with no more
//! paths, DP equals brute force, and IRBA is never below DP.

use proptest::prelude::*;
use smug_core::{
    Error, Path, PathLength, PlannerOutcome, PlannerStats, PoiSelector, PointToPointPlanner, Pose2,
    Result, Selection, SelectionProblem,
};
use smug_mission::PathOracle;
use smug_selection::{BruteForceSelector, DpSelector, IdpSelector, IrbaSelector, SelectionError};
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::sync::Arc;

const SIDE: usize = 12;

fn objective() -> PathLength {
    PathLength::new(1.0, 0.0).expect("valid weights")
}

/// A wall at x = 6 with a gap at the top, and a walled-in island vertex at (2, 9).
fn blocked(x: usize, y: usize) -> bool {
    let wall = x == 6 && y <= 9;
    let island_ring = (1..=3).contains(&x) && (8..=10).contains(&y) && !(x == 2 && y == 9);
    wall || island_ring
}

fn free_vertices() -> Vec<(usize, usize)> {
    (0..SIDE)
        .flat_map(|x| (0..SIDE).map(move |y| (x, y)))
        .filter(|&(x, y)| !blocked(x, y))
        .collect()
}

/// Exact shortest paths on a fixed 8-connected grid graph: each pose snaps to its nearest
/// vertex; the path is start → grid vertices → goal, costed as a polyline under the metric
/// (so never below the straight line).
struct GridPlanner {
    queries: u64,
}

impl GridPlanner {
    fn snap(p: &Pose2) -> Option<usize> {
        let (x, y) = (p.x.round(), p.y.round());
        if !(0.0..SIDE as f64).contains(&x) || !(0.0..SIDE as f64).contains(&y) {
            return None;
        }
        let (x, y) = (x as usize, y as usize);
        (!blocked(x, y)).then_some(x * SIDE + y)
    }

    fn dijkstra(from: usize, to: usize) -> Option<Vec<usize>> {
        let mut dist = vec![f64::INFINITY; SIDE * SIDE];
        let mut parent = vec![usize::MAX; SIDE * SIDE];
        let mut heap = BinaryHeap::new();
        dist[from] = 0.0;
        heap.push((Reverse(0u64), from));
        while let Some((Reverse(d), v)) = heap.pop() {
            let d = f64::from_bits(d);
            if d > dist[v] {
                continue;
            }
            if v == to {
                break;
            }
            let (x, y) = ((v / SIDE) as i64, (v % SIDE) as i64);
            for dx in -1..=1i64 {
                for dy in -1..=1i64 {
                    let (nx, ny) = (x + dx, y + dy);
                    if (dx, dy) == (0, 0)
                        || !(0..SIDE as i64).contains(&nx)
                        || !(0..SIDE as i64).contains(&ny)
                        || blocked(nx as usize, ny as usize)
                    {
                        continue;
                    }
                    let w = ((dx * dx + dy * dy) as f64).sqrt();
                    let u = nx as usize * SIDE + ny as usize;
                    if d + w < dist[u] {
                        dist[u] = d + w;
                        parent[u] = v;
                        // Non-negative floats order like their bits.
                        heap.push((Reverse((d + w).to_bits()), u));
                    }
                }
            }
        }
        if !dist[to].is_finite() {
            return None;
        }
        let mut path = vec![to];
        while *path.last()? != from {
            path.push(parent[*path.last()?]);
        }
        path.reverse();
        Some(path)
    }
}

impl PointToPointPlanner for GridPlanner {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        self.queries += 1;
        let Some(s) = Self::snap(start) else {
            return Ok(PlannerOutcome::InvalidStart);
        };
        let Some(g) = Self::snap(goal) else {
            return Ok(PlannerOutcome::InvalidGoal);
        };
        let Some(vertices) = Self::dijkstra(s, g) else {
            return Ok(PlannerOutcome::NoPath(smug_core::NoPathReason::Proved(
                smug_core::Proof::Disconnected,
            )));
        };
        let states: Vec<Pose2> = std::iter::once(*start)
            .chain(
                vertices
                    .iter()
                    .map(|&v| Pose2::new((v / SIDE) as f64, (v % SIDE) as f64, 0.0)),
            )
            .chain(std::iter::once(*goal))
            .collect();
        Ok(PlannerOutcome::Exact(Path::new(states, &objective())))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats {
            queries: self.queries,
            ..Default::default()
        }
    }
}

/// A random mission: poses as (free vertex, offset x, offset y, yaw).
type PoseSpec = (usize, f64, f64, f64);

fn pose(free: &[(usize, usize)], &(v, dx, dy, yaw): &PoseSpec) -> Pose2 {
    let (x, y) = free[v % free.len()];
    Pose2::new(x as f64 + dx, y as f64 + dy, yaw)
}

fn arb_pose() -> impl Strategy<Value = PoseSpec> {
    (
        0usize..1000,
        -0.45f64..0.45,
        -0.45f64..0.45,
        -std::f64::consts::PI..std::f64::consts::PI,
    )
}

fn arb_mission() -> impl Strategy<Value = (PoseSpec, Vec<Vec<PoseSpec>>, Option<PoseSpec>)> {
    (
        arb_pose(),
        prop::collection::vec(prop::collection::vec(arb_pose(), 1..=5), 2..=7),
        prop::option::of(arb_pose()),
    )
}

/// A fresh oracle over the grid with the mission's poses registered in a fixed order.
fn setup(
    (start, groups, end): &(PoseSpec, Vec<Vec<PoseSpec>>, Option<PoseSpec>),
) -> (PathOracle, SelectionProblem) {
    let free = free_vertices();
    let mut oracle = PathOracle::new(Arc::new(objective()), Box::new(GridPlanner { queries: 0 }));
    let start = oracle.add_pose(pose(&free, start));
    let groups = groups
        .iter()
        .map(|g| g.iter().map(|p| oracle.add_pose(pose(&free, p))).collect())
        .collect();
    let end = end
        .as_ref()
        .map_or(start, |p| oracle.add_pose(pose(&free, p)));
    (oracle, SelectionProblem { start, groups, end })
}

/// Runs `selector` on a fresh oracle; checks that every leg of its route is planned and
/// costed as reported. Returns the selection (or error) and the paths planned.
fn run(
    selector: &dyn PoiSelector,
    mission: &(PoseSpec, Vec<Vec<PoseSpec>>, Option<PoseSpec>),
) -> (std::result::Result<Selection, Error>, u64) {
    let (mut oracle, problem) = setup(mission);
    let result = selector.select(&mut oracle, &problem);
    if let Ok(s) = &result {
        assert_eq!(s.chosen.len(), problem.groups.len());
        for (c, g) in s.chosen.iter().zip(&problem.groups) {
            assert!(g.contains(c));
        }
        let planned = problem
            .route_cost(&s.chosen, |i, j| {
                Ok(oracle.planned_cost(i, j).expect("every leg is planned"))
            })
            .unwrap();
        assert_eq!(planned, s.cost);
    }
    (result, oracle.stats().paths_planned)
}

fn selection_error(err: &Error) -> SelectionError {
    match err {
        Error::Stage { stage, source } if stage == "selector" => *source
            .downcast_ref::<SelectionError>()
            .expect("a selection error"),
        other => panic!("unexpected error: {other}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn idp_matches_dp_and_brute_force_with_fewer_paths(mission in arb_mission()) {
        let (dp, dp_planned) = run(&DpSelector::default(), &mission);
        let (idp, idp_planned) = run(&IdpSelector::default(), &mission);
        let (irba, _) = run(&IrbaSelector::default(), &mission);
        let (brute, _) = run(&BruteForceSelector::default(), &mission);
        let brute = brute.unwrap();
        prop_assert!(idp_planned <= dp_planned, "idp {idp_planned} > dp {dp_planned}");
        match dp {
            Ok(dp) => {
                let (idp, irba) = (idp.unwrap(), irba.unwrap());
                prop_assert!(dp.cost.is_finite());
                prop_assert!((dp.cost - brute.cost).abs() <= 1e-9, "dp {dp:?} brute {brute:?}");
                prop_assert!((idp.cost - dp.cost).abs() <= 1e-9, "idp {idp:?} dp {dp:?}");
                prop_assert!(irba.cost >= dp.cost - 1e-9, "irba {irba:?} dp {dp:?}");
            }
            Err(e) => {
                prop_assert_eq!(brute.cost, f64::INFINITY);
                let expected = selection_error(&e);
                prop_assert_eq!(selection_error(&idp.unwrap_err()), expected);
                prop_assert_eq!(selection_error(&irba.unwrap_err()), expected);
            }
        }
    }
}

#[test]
fn a_walled_in_group_is_reported_by_index() {
    let free = free_vertices();
    let island = free.iter().position(|&v| v == (2, 9)).unwrap();
    let corner = free.iter().position(|&v| v == (0, 0)).unwrap();
    let far = free.iter().position(|&v| v == (11, 0)).unwrap();
    let at = |v: usize| (v, 0.0, 0.0, 0.0);
    // Group 1's only PoI is on the island; group 0 is reachable.
    let mission = (
        at(corner),
        vec![vec![at(far)], vec![at(island)], vec![at(corner)]],
        None,
    );
    for selector in [
        &DpSelector::default() as &dyn PoiSelector,
        &IdpSelector::default(),
        &IrbaSelector::default(),
    ] {
        let (result, _) = run(selector, &mission);
        assert_eq!(
            selection_error(&result.unwrap_err()),
            SelectionError::Unreachable { group: 1 }
        );
    }
}

#[test]
fn idp_and_irba_plan_far_fewer_paths_than_dp_overall() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let (mut dp_total, mut idp_total, mut irba_total, mut failures) = (0, 0, 0, 0);
    let mut irba_excess = 0.0;
    for _ in 0..200 {
        let mission = arb_mission().new_tree(&mut runner).unwrap().current();
        let (dp, dp_planned) = run(&DpSelector::default(), &mission);
        let (_, idp_planned) = run(&IdpSelector::default(), &mission);
        let (irba, irba_planned) = run(&IrbaSelector::default(), &mission);
        dp_total += dp_planned;
        idp_total += idp_planned;
        irba_total += irba_planned;
        match (dp, irba) {
            (Ok(dp), Ok(irba)) => irba_excess += irba.cost / dp.cost - 1.0,
            _ => failures += 1,
        }
    }
    eprintln!(
        "paths planned over 200 missions: dp {dp_total}, idp {idp_total}, irba {irba_total}; \
         {failures} unreachable; irba mean excess {:.3}%",
        100.0 * irba_excess / f64::from(200 - failures)
    );
    assert!(idp_total * 2 < dp_total);
    assert!(irba_total * 2 < dp_total);
}
