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

/// How [`lazy_solve`] runs.
#[derive(Clone, Copy, Debug)]
pub(super) struct LazyRules {
    /// Each round starts from the previous round's tour.
    pub(super) warm: bool,
    /// Legs planned on a sparser roadmap are planned again where they decide the order.
    pub(super) settle: bool,
    /// The legs only order targets (the sequential mode's): planned as the rows of a
    /// matrix that only orders ([`PathOracle::plan_order_pairs`]), not as legs of the
    /// route (the joint mode's).
    pub(super) order_only: bool,
}

/// The lazy loop shared by the sequential and joint modes: `solve` the matrix of
/// planned costs where known and lower bounds elsewhere, plan the tour's unplanned
/// legs, repeat until the tour uses planned legs only (or one of them has no path; for
/// a directed model, until the solver finds no tour round the legs without a path).
///
/// With `rules.warm`, each round is given the previous round's tour to start from (and the
/// positions whose legs were planned since, when it was found on the same matrix); a
/// warm round that ends on planned legs only is checked by one solve from scratch of
/// the same matrix, whose tour is taken (and the loop goes on) when it is cheaper.
///
/// With `rules.settle`, a planned leg is final only once it has been planned again
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
    rules: LazyRules,
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
            rules,
            &mut solve,
        )?;
        if dead_end || !rules.settle {
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
        previous = rules.warm.then_some(rival);
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
    rules: LazyRules,
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
        let legs = round_legs(oracle, on, &tour, kind);
        if rules.order_only {
            oracle.plan_order_pairs(&legs)?;
        } else {
            oracle.plan_pairs(&legs)?;
        }
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
        previous = rules.warm.then_some(tour);
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
#[path = "lazy_tests.rs"]
mod tests;
