//! `held-karp`: exact dynamic programming over subsets (Held & Karp 1962).
//!
//! `best[S][j]` is the cheapest path that leaves node 0, visits exactly the nodes of `S`
//! (a bitset over nodes `1..n`) and ends at `j ∈ S`. The table holds `2^(n-1) · (n-1)`
//! costs; the order is recovered by recomputing each step's minimum, so no parent table
//! is stored. Time `O(2^n n²)`.

use crate::costs::{tour_of, trivial_tour, validate, Dist};
use crate::error::SequencingError;
use serde::{Deserialize, Serialize};
use smug_core::{CostMatrix, Sequencer, Tour, TourKind};

/// Parameters of [`HeldKarp`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HeldKarpParams {
    /// Largest instance accepted, in nodes (the start included).
    pub max_nodes: usize,
    /// Largest DP table allowed, in MiB (20 nodes need 76 MiB, 23 nodes 704 MiB).
    pub max_memory_mib: u64,
}

impl Default for HeldKarpParams {
    fn default() -> Self {
        Self {
            max_nodes: 20,
            max_memory_mib: 1024,
        }
    }
}

/// Hard cap on `max_nodes`: beyond it the table cannot be indexed on any real machine.
const NODE_CAP: usize = 32;

/// Exact TSP solver for small instances, closed tours and open paths, any matrix.
#[derive(Clone, Debug)]
pub struct HeldKarp {
    params: HeldKarpParams,
}

impl HeldKarp {
    /// A solver with these limits; `max_nodes` must be in `1..=32`.
    pub fn new(params: HeldKarpParams) -> smug_core::Result<Self> {
        if params.max_nodes == 0 || params.max_nodes > NODE_CAP {
            return Err(smug_core::Error::invalid_param(
                "sequencer",
                format!(
                    "held-karp: max_nodes = {} is outside 1..={NODE_CAP}",
                    params.max_nodes
                ),
            ));
        }
        Ok(Self { params })
    }

    /// Bytes of the DP table for `n` nodes.
    pub fn table_bytes(n: usize) -> u128 {
        let m = n.saturating_sub(1) as u32;
        (1u128 << m) * u128::from(m) * std::mem::size_of::<f64>() as u128
    }

    fn check_size(&self, n: usize) -> Result<(), SequencingError> {
        if n > self.params.max_nodes {
            return Err(SequencingError::TooManyNodes {
                solver: "held-karp",
                n,
                limit: self.params.max_nodes,
                hint: " (max_nodes); use local-search or auto",
            });
        }
        let needed = Self::table_bytes(n);
        let limit = u128::from(self.params.max_memory_mib) << 20;
        if needed > limit {
            return Err(SequencingError::TooMuchMemory {
                n,
                needed_mib: u64::try_from(needed.div_ceil(1 << 20)).unwrap_or(u64::MAX),
                limit_mib: self.params.max_memory_mib,
            });
        }
        Ok(())
    }
}

impl Sequencer for HeldKarp {
    fn solve(&self, costs: &CostMatrix, kind: TourKind) -> smug_core::Result<Tour> {
        validate(costs.len(), kind)?;
        if let Some(tour) = trivial_tour(costs, kind) {
            return Ok(tour);
        }
        self.check_size(costs.len())?;
        let order = Table::fill(&Dist::new(costs), kind).best_order();
        Ok(tour_of(costs, order, kind))
    }
}

/// The cheaper of two `(node, cost)` candidates, the first on a tie; any candidate
/// beats none (`usize::MAX`), so that infinite costs (no path) still give an order.
fn cheaper(acc: (usize, f64), candidate: (usize, f64)) -> (usize, f64) {
    if candidate.1 < acc.1 || acc.0 == usize::MAX {
        candidate
    } else {
        acc
    }
}

/// Iterates over the set bits of a mask, lowest first.
fn bits(mut mask: usize) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let bit = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            bit
        })
    })
}

/// The filled DP table over the nodes between the start and the end: every node but
/// the start, and but the end of an open path (appended last, outside the DP, so the
/// table holds `2^(n−2)` subsets for an open path instead of `2^(n−1)`). Bit `k` of a
/// subset is node `nodes[k]` of the matrix (in increasing order, so ties break as
/// over the matrix's own numbering).
struct Table {
    /// Number of nodes in the DP.
    m: usize,
    /// The matrix node of each bit.
    nodes: Vec<usize>,
    /// `best[S * m + j]`: cheapest path 0 → … → node of bit j through exactly `S`.
    best: Vec<f64>,
    /// `into[j * m + k]` = cost from the node of bit k to that of bit j (rows read
    /// contiguously).
    into: Vec<f64>,
    /// Cost from the node of bit k back to the start (closed) or to the end (open).
    finish: Vec<f64>,
    /// The open path's end node.
    end: Option<usize>,
}

impl Table {
    fn fill(dist: &Dist, kind: TourKind) -> Self {
        let end = match kind {
            TourKind::Closed => None,
            TourKind::OpenTo(end) => Some(end),
        };
        let nodes: Vec<usize> = (1..dist.len()).filter(|&v| Some(v) != end).collect();
        let m = nodes.len();
        let target = end.unwrap_or(0);
        let mut table = Self {
            m,
            best: vec![f64::INFINITY; (1usize << m) * m],
            into: (0..m * m)
                .map(|k| dist.d(nodes[k % m], nodes[k / m]))
                .collect(),
            finish: nodes.iter().map(|&v| dist.d(v, target)).collect(),
            nodes,
            end,
        };
        for j in 0..m {
            table.best[(1 << j) * m + j] = dist.d(0, table.nodes[j]);
        }
        table.relax_all();
        table
    }

    /// Fills every subset in increasing order, so each `S \ {j}` is final before `S`.
    fn relax_all(&mut self) {
        let m = self.m;
        for set in 1usize..(1 << m) {
            if set.count_ones() < 2 {
                continue;
            }
            for j in bits(set) {
                self.best[set * m + j] = self.cheapest_value(set, j);
            }
        }
    }

    /// The cost of [`cheapest_step`](Self::cheapest_step) without its predecessor (the
    /// same minimum: a value does not depend on which of equal candidates is kept).
    fn cheapest_value(&self, set: usize, j: usize) -> f64 {
        let m = self.m;
        let rest = set & !(1 << j);
        let row = &self.into[j * m..(j + 1) * m];
        let previous = &self.best[rest * m..(rest + 1) * m];
        let mut value = f64::INFINITY;
        for k in bits(rest) {
            let candidate = previous[k] + row[k];
            if candidate < value {
                value = candidate;
            }
        }
        value
    }

    /// The predecessor of `j` on the best path through `set`, and that path's cost.
    fn cheapest_step(&self, set: usize, j: usize) -> (usize, f64) {
        let m = self.m;
        let rest = set & !(1 << j);
        let row = &self.into[j * m..(j + 1) * m];
        let base = rest * m;
        bits(rest)
            .map(|k| (k, self.best[base + k] + row[k]))
            .fold((usize::MAX, f64::INFINITY), cheaper)
    }

    /// The optimal visiting order, start first (and end last for an open path).
    fn best_order(&self) -> Vec<usize> {
        let m = self.m;
        let full = (1usize << m) - 1;
        let mut order = Vec::with_capacity(m + 2);
        order.extend(self.end);
        if full != 0 {
            let mut last = bits(full)
                .map(|j| (j, self.best[full * m + j] + self.finish[j]))
                .fold((usize::MAX, f64::INFINITY), cheaper)
                .0;
            let mut set = full;
            while set.count_ones() > 1 {
                order.push(self.nodes[last]);
                let (previous, _) = self.cheapest_step(set, last);
                set &= !(1 << last);
                last = previous;
            }
            order.push(self.nodes[last]);
        }
        order.push(0);
        order.reverse();
        order
    }
}

smug_core::register_plugin!(
    smug_core::registry::SequencerStage,
    name = "held-karp",
    summary = "exact dynamic programming over subsets (n ≤ ~20; closed or open, asymmetric ok)",
    params = HeldKarpParams,
    build = |params, _ctx| Ok(Box::new(HeldKarp::new(params)?)),
);

#[cfg(test)]
mod tests {
    use super::*;

    fn solve(costs: &CostMatrix, kind: TourKind) -> Tour {
        HeldKarp::new(HeldKarpParams::default())
            .unwrap()
            .solve(costs, kind)
            .unwrap()
    }

    #[test]
    fn tiny_instances() {
        let one = CostMatrix::from_rows(1, vec![7.0]).unwrap();
        assert_eq!(solve(&one, TourKind::Closed).order, vec![0]);
        assert_eq!(solve(&one, TourKind::Closed).cost, 0.0);
        let two = CostMatrix::from_rows(2, vec![0.0, 3.0, 4.0, 0.0]).unwrap();
        assert_eq!(solve(&two, TourKind::Closed).cost, 7.0);
        assert_eq!(solve(&two, TourKind::OpenTo(1)).cost, 3.0);
        let three = CostMatrix::from_fn(3, |i, j| (10 * i + j) as f64).unwrap();
        assert_eq!(solve(&three, TourKind::OpenTo(1)).order, vec![0, 2, 1]);
    }

    /// Open paths to any end (the end left out of the table) and closed tours cost
    /// what trying every order costs, on asymmetric matrices with ties.
    #[test]
    fn every_end_and_closed_tours_match_brute_force() {
        let mut state = 7u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 33) % 7
        };
        for n in 3..=8 {
            let m = CostMatrix::from_rows(n, (0..n * n).map(|_| next() as f64).collect()).unwrap();
            let kinds = (1..n).map(TourKind::OpenTo).chain([TourKind::Closed]);
            for kind in kinds {
                let exact = crate::BruteForce.solve(&m, kind).unwrap().cost;
                let tour = solve(&m, kind);
                assert!(tour.is_valid_for(n, kind), "{n} {kind:?}");
                assert_eq!(tour.cost, exact, "{n} {kind:?}");
            }
        }
    }

    #[test]
    fn asymmetric_cycle_direction_matters() {
        // 0→1→2→3→0 costs 4; the reverse costs 40.
        let m = CostMatrix::from_fn(4, |i, j| if j == (i + 1) % 4 { 1.0 } else { 10.0 }).unwrap();
        let tour = solve(&m, TourKind::Closed);
        assert_eq!(tour.order, vec![0, 1, 2, 3]);
        assert_eq!(tour.cost, 4.0);
    }

    #[test]
    fn no_finite_tour_still_gives_a_permutation() {
        let m = CostMatrix::from_fn(5, |i, j| if i == j { 0.0 } else { f64::INFINITY }).unwrap();
        for kind in [TourKind::OpenTo(3), TourKind::Closed] {
            let tour = solve(&m, kind);
            assert!(tour.is_valid_for(5, kind), "{kind:?}");
            assert_eq!(tour.cost, f64::INFINITY);
        }
    }

    #[test]
    fn refuses_large_instances_with_a_clear_message() {
        let m = CostMatrix::from_fn(22, |i, j| (i + j) as f64).unwrap();
        let err = HeldKarp::new(HeldKarpParams::default())
            .unwrap()
            .solve(&m, TourKind::Closed)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("22 nodes") && err.contains("limit of 20"),
            "{err}"
        );
        let tight = HeldKarp::new(HeldKarpParams {
            max_nodes: 30,
            max_memory_mib: 16,
        })
        .unwrap();
        let err = tight.solve(&m, TourKind::Closed).unwrap_err().to_string();
        assert!(err.contains("MiB") && err.contains("22 nodes"), "{err}");
        assert!(HeldKarp::new(HeldKarpParams {
            max_nodes: 40,
            max_memory_mib: 1
        })
        .is_err());
    }
}
