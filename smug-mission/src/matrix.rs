//! The full cost matrix over a set of the oracle's poses (every pair planned).

use crate::oracle::PathOracle;
use smug_core::error::Result;
use smug_core::stages::CostMatrix;

/// Path costs between every pair of `nodes` (each pair planned once when the oracle is
/// symmetric, both ways otherwise).
pub(crate) fn full_matrix(oracle: &mut PathOracle, nodes: &[usize]) -> Result<CostMatrix> {
    let n = nodes.len();
    let mut costs = vec![0.0; n * n];
    if oracle.answers_many() {
        plan_matrix_rows(oracle, nodes)?;
    }
    for i in 0..n {
        for j in i + 1..n {
            let c = oracle.cost(nodes[i], nodes[j])?;
            costs[i * n + j] = c;
            costs[j * n + i] = if oracle.is_symmetric() {
                c
            } else {
                oracle.cost(nodes[j], nodes[i])?
            };
        }
    }
    CostMatrix::from_rows(n, costs)
}

/// Plans the full matrix's rows over `nodes` with one call to the oracle's
/// [`plan_order_rows`](PathOracle::plan_order_rows): one search per row (the rest of
/// the row for a symmetric oracle), side by side where the planner can. Pairs planned
/// already are not asked again.
pub(crate) fn plan_matrix_rows(oracle: &mut PathOracle, nodes: &[usize]) -> Result<()> {
    let rows: Vec<(usize, Vec<usize>)> = (0..nodes.len())
        .map(|i| {
            let from = if oracle.is_symmetric() { i + 1 } else { 0 };
            (nodes[i], nodes[from..].to_vec())
        })
        .collect();
    oracle.plan_order_rows(&rows)
}
