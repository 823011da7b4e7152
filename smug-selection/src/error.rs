//! Selection errors and the diagnosis of unreachable targets.

use smug_core::{Error, PathCosts, Result, SelectionProblem};

pub use smug_core::SelectionError;

/// The first group (in visiting order) with no PoI reachable from the start through the
/// earlier groups, or the last group when none of its reachable PoIs reaches the end.
///
/// Plans legs between consecutive groups as needed (already planned legs first), so it
/// answers from true path costs. `None` when a finite route exists or there are no groups.
pub fn unreachable_group(
    oracle: &mut dyn PathCosts,
    problem: &SelectionProblem,
) -> Result<Option<usize>> {
    let mut reachable = vec![problem.start];
    for (g, group) in problem.groups.iter().enumerate() {
        let mut next = Vec::with_capacity(group.len());
        for &q in group {
            if reaches_from(oracle, &reachable, q)? {
                next.push(q);
            }
        }
        if next.is_empty() {
            return Ok(Some(g));
        }
        reachable = next;
    }
    if problem.groups.is_empty() || reaches_from(oracle, &reachable, problem.end)? {
        Ok(None)
    } else {
        Ok(Some(problem.groups.len() - 1))
    }
}

/// The error to return when the best route found is infinite.
pub(crate) fn unreachable_error(oracle: &mut dyn PathCosts, problem: &SelectionProblem) -> Error {
    let diagnosis = match unreachable_group(oracle, problem) {
        Ok(d) => d,
        Err(e) => return e,
    };
    match diagnosis {
        Some(group) => SelectionError::Unreachable { group },
        None if problem.groups.is_empty() => SelectionError::EndUnreachable,
        // A finite route exists but the selector did not find one (cannot happen for the
        // exact selectors): blame the last group's departure.
        None => SelectionError::Unreachable {
            group: problem.groups.len() - 1,
        },
    }
    .into_error()
}

/// Whether some pose of `from` has a path to `to`, trying planned legs first.
fn reaches_from(oracle: &mut dyn PathCosts, from: &[usize], to: usize) -> Result<bool> {
    if from
        .iter()
        .any(|&p| oracle.planned_cost(p, to).is_some_and(f64::is_finite))
    {
        return Ok(true);
    }
    for &p in from {
        if !oracle.is_planned(p, to) && oracle.cost(p, to)?.is_finite() {
            return Ok(true);
        }
    }
    Ok(false)
}

/// Rejects problems with an empty group.
pub(crate) fn check_groups(problem: &SelectionProblem) -> Result<()> {
    match problem.groups.iter().position(Vec::is_empty) {
        Some(g) => Err(Error::InvalidInput(format!(
            "target {g} of the sequence has no PoI"
        ))),
        None => Ok(()),
    }
}
