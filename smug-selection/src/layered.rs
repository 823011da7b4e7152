//! The DP selector on an oracle that answers a whole layer with one search
//! ([`PathCosts::plan_layer`]): every pose of a layer is a source at its DP value, and
//! one search gives each pose of the next layer its best predecessor.

use crate::error::unreachable_error;
use smug_core::{PathCosts, Result, Selection, SelectionProblem};

/// The DP over `layers` (the start, the groups in order, the end) by layer searches:
/// `J(q) = min_p J(p) + c(p, q)` with the predecessor the planner's search chose
/// (by its own costs), each value then `J(p)` plus the planned leg's cost.
pub(crate) fn dp_by_layers(
    oracle: &mut dyn PathCosts,
    problem: &SelectionProblem,
    layers: &[Vec<usize>],
) -> Result<Selection> {
    let mut values: Vec<f64> = vec![0.0];
    // back[l][b]: the position in layer l − 1 of the best predecessor of layer l's b.
    let mut back: Vec<Vec<usize>> = vec![Vec::new()];
    for (l, pair) in layers.windows(2).enumerate() {
        let (from, to) = (&pair[0], &pair[1]);
        let after = layers.get(l + 2).map_or(&[][..], Vec::as_slice);
        let sources: Vec<(usize, f64)> = from
            .iter()
            .zip(&values)
            .filter(|(_, v)| v.is_finite())
            .map(|(&p, &v)| (p, v))
            .collect();
        if sources.is_empty() {
            return Err(unreachable_error(oracle, problem));
        }
        let best = oracle.plan_layer(&sources, to, after)?;
        let mut next = Vec::with_capacity(to.len());
        let mut links = Vec::with_capacity(to.len());
        for (&q, source) in to.iter().zip(best) {
            let position = source.and_then(|p| from.iter().position(|&x| x == p));
            match position {
                Some(k) => {
                    next.push(values[k] + oracle.cost(from[k], q)?);
                    links.push(k);
                }
                None => {
                    next.push(f64::INFINITY);
                    links.push(0);
                }
            }
        }
        values = next;
        back.push(links);
    }
    if !values[0].is_finite() {
        return Err(unreachable_error(oracle, problem));
    }
    let mut chosen = vec![0; problem.groups.len()];
    let mut at = 0;
    for g in (0..problem.groups.len()).rev() {
        at = back[g + 2][at];
        chosen[g] = problem.groups[g][at];
    }
    let cost = problem.route_cost(&chosen, |i, j| oracle.cost(i, j))?;
    Ok(Selection { chosen, cost })
}
