//! Tests of the lazy loop: the settled order against the full matrix's with fixed
//! and refined leg costs, and the change hints of warm rounds.

use super::*;
use crate::matrix::full_matrix;
use crate::test_support::Exhaustive;
use proptest::prelude::*;
use smug_core::objective::PathLength;
use smug_core::path::Path;
use smug_core::pose::Pose2;
use smug_core::stages::Sequencer;
use smug_core::stages::{PlannerOutcome, PlannerStats, PointToPointPlanner, SelectionProblem};
use std::collections::HashMap;
use std::sync::Arc;

/// A straight path whose cost is the objective's cost times the pair's fixed detour
/// (≥ 1, symmetric), times `1 + inflation` of the pair on its first query only (a
/// leg planned on a sparse roadmap); `inflation` all zero: fixed leg costs.
struct FixedCosts {
    poses: Vec<Pose2>,
    detours: Vec<f64>,
    inflation: Vec<f64>,
    asked: HashMap<(usize, usize), u32>,
}

impl FixedCosts {
    fn pair(&self, a: &Pose2, b: &Pose2) -> (usize, usize) {
        let index = |p: &Pose2| self.poses.iter().position(|q| q == p).unwrap();
        let (i, j) = (index(a), index(b));
        (i.min(j), i.max(j))
    }

    /// The cost a pair settles at (its second and later answers).
    fn settled(&self, (i, j): (usize, usize)) -> f64 {
        let n = self.poses.len();
        PathLength::default().motion_cost(&self.poses[i], &self.poses[j]) * self.detours[i * n + j]
    }
}

impl PointToPointPlanner for FixedCosts {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        let key = self.pair(start, goal);
        let asked = self.asked.entry(key).or_insert(0);
        *asked += 1;
        let factor = if *asked == 1 {
            1.0 + self.inflation[key.0 * self.poses.len() + key.1]
        } else {
            1.0
        };
        let mut path = Path::new(vec![*start, *goal], &PathLength::default());
        path.cost = self.settled(key) * factor;
        Ok(PlannerOutcome::Exact(path))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

use smug_core::objective::Objective as _;

/// An oracle over `FixedCosts` and the oracle indices of `poses`.
fn oracle(poses: &[Pose2], detours: &[f64], inflation: &[f64]) -> (PathOracle, Vec<usize>) {
    let planner = FixedCosts {
        poses: poses.to_vec(),
        detours: detours.to_vec(),
        inflation: inflation.to_vec(),
        asked: HashMap::new(),
    };
    let mut oracle = PathOracle::new(Arc::new(PathLength::default()), Box::new(planner));
    let nodes = poses.iter().map(|p| oracle.add_pose(*p)).collect();
    (oracle, nodes)
}

/// A generated mission: the start, groups of PoIs, the end of an open one.
#[derive(Clone, Debug)]
struct Generated {
    poses: Vec<Pose2>,
    sizes: Vec<usize>,
    open: bool,
    detours: Vec<f64>,
    inflation: Vec<f64>,
}

fn generated(max_pois: usize) -> impl Strategy<Value = Generated> {
    (
        prop::collection::vec(1usize..=max_pois, 2..=6),
        any::<bool>(),
    )
        .prop_flat_map(|(sizes, open)| {
            let total = sizes.iter().sum::<usize>() + 1 + usize::from(open);
            (
                prop::collection::vec((0.0..20.0f64, 0.0..20.0f64, -3.0..3.0f64), total),
                prop::collection::vec(1.0..2.0f64, total * total),
                prop::collection::vec(0.0..0.5f64, total * total),
                Just(sizes),
                Just(open),
            )
                .prop_map(|(points, detours, inflation, sizes, open)| Generated {
                    poses: points
                        .iter()
                        .map(|&(x, y, yaw)| Pose2::new(x, y, yaw))
                        .collect(),
                    sizes,
                    open,
                    detours,
                    inflation,
                })
        })
}

/// The sequential mode on `mission`: the order of the targets (from their first PoIs,
/// exhaustive solver; the lazy matrix when `lazy`, settled) and the exact selection's
/// cost along it.
fn plan(mission: &Generated, lazy: bool, inflation: &[f64]) -> (Vec<usize>, f64, PathOracle) {
    let (mut oracle, nodes) = oracle(&mission.poses, &mission.detours, inflation);
    let mut groups = Vec::new();
    let mut next = 1;
    for &size in &mission.sizes {
        groups.push(nodes[next..next + size].to_vec());
        next += size;
    }
    let end = if mission.open { nodes[next] } else { nodes[0] };
    let mut reps = vec![nodes[0]];
    reps.extend(groups.iter().map(|g| g[0]));
    let kind = if mission.open {
        reps.push(end);
        TourKind::OpenTo(reps.len() - 1)
    } else {
        TourKind::Closed
    };
    let tour = if lazy {
        lazy_solve(
            &mut oracle,
            &reps,
            &Clusters::singletons(reps.len()),
            kind,
            LazyRules {
                warm: false,
                settle: true,
                order_only: false,
            },
            |m, _| Exhaustive.solve(m, kind),
        )
        .unwrap()
    } else {
        Exhaustive
            .solve(&full_matrix(&mut oracle, &reps).unwrap(), kind)
            .unwrap()
    };
    let order: Vec<usize> = tour
        .order
        .iter()
        .copied()
        .filter(|&v| v != 0 && v <= groups.len())
        .map(|v| v - 1)
        .collect();
    let problem = SelectionProblem {
        start: nodes[0],
        groups: order.iter().map(|&g| groups[g].clone()).collect(),
        end,
    };
    let (_, cost) = problem.solve_layers(|i, j| oracle.cost(i, j)).unwrap();
    (order, cost, oracle)
}

/// Runs the warm lazy loop (settled or not) on `mission`'s representatives and
/// checks every warm round told what changed against the matrices the solver saw:
/// the positions named are exactly those with a leg (in or out) that differs from
/// the matrix the previous tour was found on. The number of such rounds.
fn check_change_hints(mission: &Generated, settle: bool) -> std::result::Result<usize, String> {
    let (mut oracle, nodes) = oracle(&mission.poses, &mission.detours, &mission.inflation);
    let mut reps = vec![nodes[0]];
    let mut next = 1;
    for &size in &mission.sizes {
        reps.push(nodes[next]);
        next += size;
    }
    let kind = if mission.open {
        reps.push(nodes[next]);
        TourKind::OpenTo(reps.len() - 1)
    } else {
        TourKind::Closed
    };
    let n = reps.len();
    let mut last: Option<CostMatrix> = None;
    let mut hints = 0;
    let mut wrong = None;
    lazy_solve(
        &mut oracle,
        &reps,
        &Clusters::singletons(n),
        kind,
        LazyRules {
            warm: true,
            settle,
            order_only: false,
        },
        |m, warm| {
            if let (
                Some(Warm {
                    changed: Some(changed),
                    ..
                }),
                Some(before),
            ) = (warm, &last)
            {
                hints += 1;
                let differs = |i: usize| {
                    (0..n).any(|j| {
                        m.get(i, j).to_bits() != before.get(i, j).to_bits()
                            || m.get(j, i).to_bits() != before.get(j, i).to_bits()
                    })
                };
                let expected: Vec<usize> = (0..n).filter(|&i| differs(i)).collect();
                if changed != expected.as_slice() {
                    wrong = Some(format!("told {changed:?}, changed {expected:?}"));
                }
            }
            last = Some(m.clone());
            Exhaustive.solve(m, kind)
        },
    )
    .map_err(|e| e.to_string())?;
    match wrong {
        Some(message) => Err(message),
        None => Ok(hints),
    }
}

/// The hints are given at all: over generated missions some warm rounds are told
/// what changed (else the property below would hold vacuously).
#[test]
fn warm_rounds_are_told_what_changed() {
    use proptest::strategy::ValueTree;
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let strategy = generated(3);
    let mut hints = 0;
    for case in 0..64 {
        let mission = strategy.new_tree(&mut runner).unwrap().current();
        hints += check_change_hints(&mission, case % 2 == 0).unwrap();
    }
    assert!(hints > 0, "no warm round was told what changed");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// A warm round told what changed is told exactly the positions whose legs
    /// changed since its tour was found.
    #[test]
    fn warm_rounds_are_told_exactly_what_changed(mission in generated(3), settle: bool) {
        prop_assert!(check_change_hints(&mission, settle).is_ok(), "{:?}", check_change_hints(&mission, settle));
    }

    /// Exact sequencing and selection with fixed leg costs: the settled lazy matrix
    /// gives the full matrix's order (or, on a closed tour of symmetric costs, the
    /// same order backwards, which costs the same) and the full matrix's cost.
    #[test]
    fn settled_lazy_order_and_cost_equal_the_full_matrix(mission in generated(3)) {
        let none = vec![0.0; mission.detours.len()];
        let (full_order, full_cost, _) = plan(&mission, false, &none);
        let (lazy_order, lazy_cost, _) = plan(&mission, true, &none);
        let backwards: Vec<usize> = full_order.iter().rev().copied().collect();
        prop_assert!(
            lazy_order == full_order || (!mission.open && lazy_order == backwards),
            "lazy order {lazy_order:?}, full order {full_order:?}"
        );
        prop_assert!((lazy_cost - full_cost).abs() <= 1e-9 * full_cost, "lazy {lazy_cost} vs full {full_cost}");
    }

    /// A leg's first answer dearer than its later ones (a sparse roadmap): the
    /// settled lazy tour is optimal for the later answers, since every leg that
    /// could decide the order was planned again.
    #[test]
    fn settled_lazy_order_is_optimal_for_refined_costs(mission in generated(1)) {
        let n = mission.sizes.len() + 1 + usize::from(mission.open);
        let kind = if mission.open { TourKind::OpenTo(n - 1) } else { TourKind::Closed };
        let (mut lazy, nodes) = oracle(&mission.poses, &mission.detours, &mission.inflation);
        let tour = lazy_solve(&mut lazy, &nodes, &Clusters::singletons(nodes.len()), kind, LazyRules { warm: false, settle: true, order_only: false }, |m, _| Exhaustive.solve(m, kind)).unwrap();
        let none = vec![0.0; mission.detours.len()];
        let (mut settled, nodes) = oracle(&mission.poses, &mission.detours, &none);
        let truth = full_matrix(&mut settled, &nodes).unwrap();
        let best = Exhaustive.solve(&truth, kind).unwrap();
        let cost = truth.tour_cost(&tour.order, kind);
        prop_assert!((cost - best.cost).abs() <= 1e-9 * best.cost, "lazy {cost} vs optimum {}", best.cost);
        let known = lazy_matrix(&lazy, &nodes).unwrap().tour_cost(&tour.order, kind);
        prop_assert!((known - cost).abs() <= 1e-9 * cost, "every leg of the tour refined");
    }
}
