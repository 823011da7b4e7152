//! `brute-force`: tries every order (for tests; at most 9 nodes).

use crate::costs::{tour_of, trivial_tour, validate};
use crate::error::SequencingError;
use serde::{Deserialize, Serialize};
use smug_core::{CostMatrix, Sequencer, Tour, TourKind};

/// Largest instance [`BruteForce`] accepts (8! = 40 320 orders).
pub const BRUTE_FORCE_MAX_NODES: usize = 9;

/// Parameters of [`BruteForce`] (none).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BruteForceParams {}

/// Exhaustive search over all orders of at most [`BRUTE_FORCE_MAX_NODES`] nodes: the
/// reference the other solvers are tested against. Costs are summed exactly as
/// [`CostMatrix::tour_cost`] does; ties keep the lexicographically first order.
#[derive(Clone, Copy, Debug, Default)]
pub struct BruteForce;

impl Sequencer for BruteForce {
    fn solve(&self, costs: &CostMatrix, kind: TourKind) -> smug_core::Result<Tour> {
        let n = costs.len();
        validate(n, kind)?;
        if let Some(tour) = trivial_tour(costs, kind) {
            return Ok(tour);
        }
        if n > BRUTE_FORCE_MAX_NODES {
            return Err(SequencingError::TooManyNodes {
                solver: "brute-force",
                n,
                limit: BRUTE_FORCE_MAX_NODES,
                hint: " (it is meant for tests); use held-karp or auto",
            }
            .into());
        }
        let (middle, last): (Vec<usize>, Option<usize>) = match kind {
            TourKind::Closed => ((1..n).collect(), None),
            TourKind::OpenTo(end) => ((1..n).filter(|&v| v != end).collect(), Some(end)),
        };
        let mut best: Option<Tour> = None;
        let mut middle = middle;
        loop {
            let order: Vec<usize> = std::iter::once(0)
                .chain(middle.iter().copied())
                .chain(last)
                .collect();
            let tour = tour_of(costs, order, kind);
            if best.as_ref().is_none_or(|b| tour.cost < b.cost) {
                best = Some(tour);
            }
            if !next_permutation(&mut middle) {
                break;
            }
        }
        // `middle` always yields at least one order, so `best` is set.
        best.ok_or_else(|| smug_core::Error::InvalidInput("brute-force: no order".into()))
    }
}

/// Advances `items` to the next lexicographic permutation; false after the last one.
fn next_permutation(items: &mut [usize]) -> bool {
    let Some(pivot) = items.windows(2).rposition(|w| w[0] < w[1]) else {
        return false;
    };
    let successor = items
        .iter()
        .rposition(|&v| v > items[pivot])
        .unwrap_or(pivot + 1);
    items.swap(pivot, successor);
    items[pivot + 1..].reverse();
    true
}

smug_core::register_plugin!(
    smug_core::registry::SequencerStage,
    name = "brute-force",
    summary = "every order (tests only; n ≤ 9)",
    params = BruteForceParams,
    build = |_params, _ctx| Ok(Box::new(BruteForce)),
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permutations_are_all_visited() {
        let mut items = vec![1, 2, 3, 4];
        let mut count = 1;
        while next_permutation(&mut items) {
            count += 1;
        }
        assert_eq!(count, 24);
        assert_eq!(items, vec![4, 3, 2, 1]);
    }

    #[test]
    fn refuses_ten_nodes() {
        let m = CostMatrix::from_fn(10, |i, j| (i * j) as f64).unwrap();
        let err = BruteForce
            .solve(&m, TourKind::Closed)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("10 nodes") && err.contains("limit of 9"),
            "{err}"
        );
    }
}
