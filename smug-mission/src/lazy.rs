//! The lazy loop of both modes: solve on planned costs where known and admissible lower
//! bounds elsewhere, plan the legs the tour uses, re-solve until the tour uses planned
//! legs only. With `settle`, legs planned on a sparser roadmap than today's are planned
//! again where they decide the order, until the order is optimal even if each leg not
//! planned twice fell to its lower bound.

use crate::oracle::PathOracle;
use smug_core::error::Result;
use smug_core::stages::PathCosts;
use smug_core::stages::{Clusters, CostMatrix, Tour, TourKind};
use std::collections::{HashMap, HashSet};

/// Relative slack of the cost comparisons (rounding in sums of floating-point legs).
const SLACK: f64 = 1e-9;

/// A round's warm start: the previous round's tour, and when it was found on the
/// same matrix as this round's but for the legs planned since, the positions whose
/// legs (in or out) changed ([`Sequencer::solve_from_changed`](smug_core::Sequencer)).
#[derive(Clone, Copy)]
pub(super) struct Warm<'a> {
    /// The previous round's tour.
    pub(super) tour: &'a Tour,
    /// The positions whose legs changed since it was found, if known.
    pub(super) changed: Option<&'a [usize]>,
}

/// The lazy loop shared by the sequential and joint modes: `solve` the matrix of
/// planned costs where known and lower bounds elsewhere, plan the tour's unplanned
/// legs, repeat until the tour uses planned legs only (or one of them has no path; for
/// a directed model, until the solver finds no tour round the legs without a path).
///
/// With `warm`, each round is given the previous round's tour to start from (and the
/// positions whose legs were planned since, when it was found on the same matrix); a
/// warm round that ends on planned legs only is checked by one solve from scratch of
/// the same matrix, whose tour is taken (and the loop goes on) when it is cheaper.
///
/// With `settle`, a planned leg is final only once it has been planned again
/// ([`PathOracle::refine`], on the roadmap as grown since: a leg planned on a sparser
/// roadmap can cost more than planning it again gives) or when it costs its lower
/// bound. Once the tour uses planned legs only, its own legs are refined, and the
/// matrix with final legs at their cost and every other leg at its lower bound is
/// solved: if that tour is cheaper, its planned legs are refined and its unplanned
/// legs planned, and the loop goes on; else the tour is optimal (with an exact solver)
/// for any costs that refining or planning the other legs could give. Each leg is
/// planned at most twice, so the loop ends.
///
/// `clusters` groups the positions of `nodes` (the joint mode's targets; singletons
/// otherwise): with a planner that answers many goals with one search, a round plans
/// each unplanned leg's start to every pose of its end's cluster, as the next rounds
/// would try them one by one.
pub(super) fn lazy_solve(
    oracle: &mut PathOracle,
    nodes: &[usize],
    clusters: &Clusters,
    kind: TourKind,
    warm: bool,
    settle: bool,
    mut solve: impl FnMut(&CostMatrix, Option<Warm<'_>>) -> Result<Tour>,
) -> Result<Tour> {
    let mut previous: Option<Tour> = None;
    let mut refined = Refined::new(oracle.is_symmetric());
    let mut matrix = LazyMatrix::new(oracle, nodes)?;
    loop {
        let on = Nodes {
            indices: nodes,
            clusters,
        };
        let (tour, dead_end) = converge(
            oracle,
            on,
            &mut matrix,
            kind,
            previous.take(),
            warm,
            &mut solve,
        )?;
        if dead_end || !settle {
            return Ok(tour);
        }
        for (a, b) in tour_legs(&tour, kind) {
            refined.refine(oracle, nodes, a, b)?;
        }
        let cost = matrix.refresh(oracle)?.tour_cost(&tour.order, kind);
        let optimistic = CostMatrix::from_fn_within(nodes.len(), oracle.run().memory, |i, j| {
            if i == j {
                0.0
            } else if refined.is_final(oracle, nodes, i, j) {
                oracle.cost_or_bound(nodes[i], nodes[j])
            } else {
                oracle.lower_bound(nodes[i], nodes[j])
            }
        })?;
        let rival = solve(
            &optimistic,
            Some(Warm {
                tour: &tour,
                changed: None,
            }),
        )?;
        if optimistic.tour_cost(&rival.order, kind) >= cost * (1.0 - SLACK) {
            return Ok(tour);
        }
        let doubtful: Vec<(usize, usize)> = tour_legs(&rival, kind)
            .filter(|&(a, b)| !refined.is_final(oracle, nodes, a, b))
            .collect();
        if doubtful.is_empty() {
            // Cheaper on final costs alone (a heuristic solver missed it before).
            return Ok(rival);
        }
        for (a, b) in doubtful {
            if oracle.is_planned(nodes[a], nodes[b]) {
                refined.refine(oracle, nodes, a, b)?;
            } else {
                oracle.cost(nodes[a], nodes[b])?;
            }
        }
        previous = warm.then_some(rival);
    }
}

/// The lazy loop's nodes: their oracle indices, and the clusters their positions form.
#[derive(Clone, Copy)]
struct Nodes<'a> {
    indices: &'a [usize],
    clusters: &'a Clusters,
}

/// The loop without settling: the tour, and whether one of its planned legs has no path.
fn converge(
    oracle: &mut PathOracle,
    on: Nodes<'_>,
    lazy: &mut LazyMatrix,
    kind: TourKind,
    mut previous: Option<Tour>,
    warm: bool,
    solve: &mut impl FnMut(&CostMatrix, Option<Warm<'_>>) -> Result<Tour>,
) -> Result<(Tour, bool)> {
    let nodes = on.indices;
    // Whether `previous` was found on the lazy matrix (not on the settling step's).
    let mut on_lazy_matrix = false;
    loop {
        lazy.refresh(oracle)?;
        let changed = lazy.take_changed();
        let matrix = &lazy.matrix;
        let start = previous.as_ref().map(|tour| Warm {
            tour,
            changed: on_lazy_matrix.then_some(changed.as_slice()),
        });
        let mut tour = solve(matrix, start)?;
        if previous.is_some() && unplanned_legs(oracle, nodes, &tour, kind).is_empty() {
            let cold = solve(matrix, None)?;
            let cost = |t: &Tour| matrix.tour_cost(&t.order, kind);
            if cost(&cold) >= cost(&tour) * (1.0 - SLACK) {
                return Ok((tour, false));
            }
            tour = cold;
        }
        // Only planned legs are infinite: the solver found no tour around them.
        if !matrix.tour_cost(&tour.order, kind).is_finite() {
            return Ok((tour, true));
        }
        let unplanned = unplanned_legs(oracle, nodes, &tour, kind);
        if unplanned.is_empty() {
            return Ok((tour, false));
        }
        oracle.plan_pairs(&round_legs(oracle, on, &tour, kind))?;
        let mut dead_end = false;
        let mut unproved = false;
        for (a, b) in unplanned {
            let planned = oracle.path(a, b)?;
            if !planned.cost.is_finite() {
                dead_end = true;
                unproved |= !planned
                    .outcome
                    .no_path_reason()
                    .is_some_and(|reason| reason.is_proved());
            }
        }
        if dead_end && oracle.is_symmetric() && unproved {
            return Ok((tour, true));
        }
        // A directed model's leg without a path (a PoI a car can enter but not leave
        // towards the end, say) may have a way round in another order, and so may a
        // leg a lattice proved impossible at its resolution between two PoIs both
        // reached from the start (the lattice joins a start and enters a goal
        // differently, so such a proof need not hold the other way round): solve
        // again with it infinite (each round plans a leg more, so the loop ends). A
        // leg whose budget ran out ends the loop instead, so that a robot that cannot
        // leave its room does not spend one budget per PoI.
        previous = warm.then_some(tour);
        on_lazy_matrix = true;
    }
}

/// The legs (positions in `nodes`) planned again since the loop began.
struct Refined {
    legs: HashSet<(usize, usize)>,
    symmetric: bool,
}

impl Refined {
    fn new(symmetric: bool) -> Self {
        Self {
            legs: HashSet::new(),
            symmetric,
        }
    }

    fn key(&self, i: usize, j: usize) -> (usize, usize) {
        if self.symmetric {
            (i.min(j), i.max(j))
        } else {
            (i, j)
        }
    }

    /// True when the leg `i → j` is planned and planning it again would not be
    /// cheaper: refined already, at its lower bound, or without a path.
    fn is_final(&self, oracle: &PathOracle, nodes: &[usize], i: usize, j: usize) -> bool {
        oracle.is_planned(nodes[i], nodes[j])
            && (self.legs.contains(&self.key(i, j)) || !above_bound(oracle, nodes[i], nodes[j]))
    }

    /// Plans the planned leg `i → j` again, keeping the cheaper path, unless it is
    /// final already.
    fn refine(
        &mut self,
        oracle: &mut PathOracle,
        nodes: &[usize],
        i: usize,
        j: usize,
    ) -> Result<()> {
        if !self.is_final(oracle, nodes, i, j) && self.legs.insert(self.key(i, j)) {
            oracle.refine(nodes[i], nodes[j])?;
        }
        Ok(())
    }
}

/// True when the pair is planned at a finite cost above its lower bound (planning it
/// again may find it cheaper).
fn above_bound(oracle: &PathOracle, a: usize, b: usize) -> bool {
    let Some(cost) = oracle.planned_cost(a, b) else {
        return false;
    };
    let bound = oracle.lower_bound(a, b);
    cost.is_finite() && cost > bound + SLACK * bound.abs().max(1.0)
}

/// The matrix of planned costs where known and lower bounds elsewhere, kept up to
/// date from the oracle's log of stored answers ([`PathOracle::stored_since`]) instead
/// of built again every round (a million entries for a thousand targets): the same
/// entries as [`lazy_matrix`] gives.
struct LazyMatrix {
    matrix: CostMatrix,
    /// Whether each position's legs changed since [`take_changed`](Self::take_changed).
    changed: Vec<bool>,
    /// The matrix positions of each oracle index among the nodes.
    positions: HashMap<usize, Vec<usize>>,
    /// The oracle's log length the matrix is up to date with.
    mark: usize,
}

impl LazyMatrix {
    fn new(oracle: &PathOracle, nodes: &[usize]) -> Result<Self> {
        let mut positions: HashMap<usize, Vec<usize>> = HashMap::new();
        for (position, &node) in nodes.iter().enumerate() {
            positions.entry(node).or_default().push(position);
        }
        Ok(Self {
            matrix: lazy_matrix(oracle, nodes)?,
            changed: vec![false; nodes.len()],
            positions,
            mark: oracle.stored_since(0).len(),
        })
    }

    /// The matrix with every answer stored since the last refresh.
    fn refresh(&mut self, oracle: &PathOracle) -> Result<&CostMatrix> {
        let stored = oracle.stored_since(self.mark);
        for &(a, b) in stored {
            let (Some(rows), Some(columns)) = (self.positions.get(&a), self.positions.get(&b))
            else {
                continue;
            };
            let cost = oracle.cost_or_bound(a, b);
            for &i in rows {
                for &j in columns.iter().filter(|&&j| j != i) {
                    if self.matrix.get(i, j).to_bits() != cost.to_bits() {
                        self.matrix.set(i, j, cost)?;
                        self.changed[i] = true;
                        self.changed[j] = true;
                    }
                }
            }
        }
        self.mark += stored.len();
        Ok(&self.matrix)
    }

    /// The positions whose legs changed since the last call, in order; forgets them.
    fn take_changed(&mut self) -> Vec<usize> {
        let changed = (0..self.changed.len())
            .filter(|&i| self.changed[i])
            .collect();
        self.changed.fill(false);
        changed
    }
}

/// The matrix of planned costs where known and lower bounds elsewhere.
pub(super) fn lazy_matrix(oracle: &PathOracle, nodes: &[usize]) -> Result<CostMatrix> {
    CostMatrix::from_fn_within(nodes.len(), oracle.run().memory, |i, j| {
        if i == j {
            0.0
        } else {
            oracle.cost_or_bound(nodes[i], nodes[j])
        }
    })
}

/// The legs of `tour` (as oracle index pairs) not planned yet.
fn unplanned_legs(
    oracle: &PathOracle,
    nodes: &[usize],
    tour: &Tour,
    kind: TourKind,
) -> Vec<(usize, usize)> {
    tour_legs(tour, kind)
        .map(|(a, b)| (nodes[a], nodes[b]))
        .filter(|&(a, b)| !oracle.is_planned(a, b))
        .collect()
}

/// The legs (oracle indices) a round plans for the tour's unplanned legs, in one
/// batch: each leg, or with a planner that answers many goals with one search, the
/// leg's start to every pose of its end's cluster not planned yet.
fn round_legs(
    oracle: &PathOracle,
    on: Nodes<'_>,
    tour: &Tour,
    kind: TourKind,
) -> Vec<(usize, usize)> {
    let (nodes, clusters) = (on.indices, on.clusters);
    let mut legs = Vec::new();
    for (a, b) in tour_legs(tour, kind) {
        if oracle.is_planned(nodes[a], nodes[b]) {
            continue;
        }
        let ends = if oracle.answers_many() {
            clusters.members(clusters.of(b))
        } else {
            std::slice::from_ref(&b)
        };
        for &end in ends {
            let leg = (nodes[a], nodes[end]);
            if !oracle.is_planned(leg.0, leg.1) && !legs.contains(&leg) {
                legs.push(leg);
            }
        }
    }
    legs
}

/// The legs `(from, to)` of a tour, the return leg of a closed tour included.
pub(super) fn tour_legs(tour: &Tour, kind: TourKind) -> impl Iterator<Item = (usize, usize)> + '_ {
    let closing = match kind {
        TourKind::Closed => tour.order.last().map(|&last| (last, tour.order[0])),
        TourKind::OpenTo(_) => None,
    };
    tour.order.windows(2).map(|w| (w[0], w[1])).chain(closing)
}

#[cfg(test)]
mod tests {
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
            PathLength::default().motion_cost(&self.poses[i], &self.poses[j])
                * self.detours[i * n + j]
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
                    .prop_map(|(points, detours, inflation, sizes, open)| {
                        Generated {
                            poses: points
                                .iter()
                                .map(|&(x, y, yaw)| Pose2::new(x, y, yaw))
                                .collect(),
                            sizes,
                            open,
                            detours,
                            inflation,
                        }
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
                false,
                true,
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
            true,
            settle,
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
            let tour = lazy_solve(&mut lazy, &nodes, &Clusters::singletons(nodes.len()), kind, false, true, |m, _| Exhaustive.solve(m, kind)).unwrap();
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
}
