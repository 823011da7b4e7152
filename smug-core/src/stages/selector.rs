//! PoI selector stage: which PoI of each target, given the visiting order.

use crate::error::Result;
use crate::stages::PathCosts;

/// A selection problem over the path oracle's poses (indices into the oracle).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SelectionProblem {
    /// Oracle index of the start pose.
    pub start: usize,
    /// For each target in visiting order, the oracle indices of its PoIs.
    pub groups: Vec<Vec<usize>>,
    /// Oracle index of the end pose (the start for a closed tour).
    pub end: usize,
}

impl SelectionProblem {
    /// The cost of choosing `chosen[g]` in group `g`, from costs `cost(i, j)`:
    /// start → chosen\[0\] → … → chosen\[last\] → end.
    pub fn route_cost(
        &self,
        chosen: &[usize],
        mut cost: impl FnMut(usize, usize) -> Result<f64>,
    ) -> Result<f64> {
        let route = self.route(chosen);
        let mut total = 0.0;
        for leg in route.windows(2) {
            total += cost(leg[0], leg[1])?;
        }
        Ok(total)
    }

    /// The cheapest route start → one PoI per group → end under `cost` (the `dp` and `idp`
    /// selectors and the GTSP solvers' cluster sweep share it), by dynamic
    /// programming over the groups: `J₀(p) = c(start, p)`, `J_g(q) = min_p J_{g−1}(p) + c(p, q)`,
    /// total `min_p J_last(p) + c(p, end)`, then backtracking the argmins. Ties go to the lowest
    /// position within a group. `cost` is asked exactly once for each pair of consecutive
    /// layers. Returns the chosen oracle indices and the route's cost under `cost` (`INFINITY`
    /// when every route has an infinite leg). Groups must be non-empty.
    pub fn solve_layers(
        &self,
        mut cost: impl FnMut(usize, usize) -> Result<f64>,
    ) -> Result<(Vec<usize>, f64)> {
        let groups = &self.groups;
        let Some(first) = groups.first() else {
            return Ok((Vec::new(), cost(self.start, self.end)?));
        };
        let mut j: Vec<f64> = first
            .iter()
            .map(|&p| cost(self.start, p))
            .collect::<Result<_>>()?;
        // back[g][b] = position in group g − 1 of the best predecessor of group g's PoI b.
        let mut back: Vec<Vec<usize>> = Vec::with_capacity(groups.len());
        back.push(Vec::new());
        for pair in groups.windows(2) {
            let (prev, group) = (&pair[0], &pair[1]);
            let mut next_j = Vec::with_capacity(group.len());
            let mut next_back = Vec::with_capacity(group.len());
            for &q in group {
                let (k, best) = argmin(
                    prev.iter()
                        .enumerate()
                        .map(|(k, &p)| Ok(j[k] + cost(p, q)?)),
                )?;
                next_j.push(best);
                next_back.push(k);
            }
            j = next_j;
            back.push(next_back);
        }
        let last = &groups[groups.len() - 1];
        let (mut k, total) = argmin(
            last.iter()
                .enumerate()
                .map(|(k, &p)| Ok(j[k] + cost(p, self.end)?)),
        )?;
        let mut chosen = vec![0; groups.len()];
        for g in (0..groups.len()).rev() {
            chosen[g] = groups[g][k];
            if g > 0 {
                k = back[g][k];
            }
        }
        Ok((chosen, total))
    }

    /// The full route start, chosen…, end as oracle indices.
    pub fn route(&self, chosen: &[usize]) -> Vec<usize> {
        std::iter::once(self.start)
            .chain(chosen.iter().copied())
            .chain(std::iter::once(self.end))
            .collect()
    }
}

/// The chosen PoI per group and the route's cost (`INFINITY` when some leg has no path).
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    /// Oracle index of the chosen PoI of each group, in visiting order.
    pub chosen: Vec<usize>,
    /// Cost of start → chosen… → end with planned paths.
    pub cost: f64,
}

/// Chooses one PoI per target over a fixed visiting order, asking a [`PathCosts`] (the
/// path oracle) for paths.
pub trait PoiSelector: Send + Sync {
    /// The selection; every leg of the returned route has been planned by the oracle.
    fn select(&self, oracle: &mut dyn PathCosts, problem: &SelectionProblem) -> Result<Selection>;
}

/// Position and value of the smallest value (first among equals; position 0 when all are
/// infinite). Evaluates every item.
fn argmin(values: impl Iterator<Item = Result<f64>>) -> Result<(usize, f64)> {
    let mut best = (0, f64::INFINITY);
    for (k, v) in values.enumerate() {
        let v = v?;
        if v < best.1 {
            best = (k, v);
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(i: usize, j: usize) -> Result<f64> {
        // Poses 0 (start/end), groups {1, 2}, {3, 4}.
        let c = [
            [0.0, 1.0, 5.0, 9.0, 9.0],
            [1.0, 0.0, 9.0, 8.0, 1.0],
            [5.0, 9.0, 0.0, 1.0, 9.0],
            [9.0, 8.0, 1.0, 0.0, 9.0],
            [9.0, 1.0, 9.0, 9.0, 0.0],
        ];
        Ok(c[i][j])
    }

    #[test]
    fn finds_the_optimum_and_counts_each_pair_once() {
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 2], vec![3, 4]],
            end: 0,
        };
        let mut calls = 0;
        let (chosen, cost) = problem
            .solve_layers(|i, j| {
                calls += 1;
                table(i, j)
            })
            .unwrap();
        // 1→4 is cheap but 4→0 is 9: 0→1→4→0 = 11; 0→2→3→0 = 15; 0→1→3→0 = 18.
        assert_eq!(chosen, vec![1, 4]);
        assert_eq!(cost, 11.0);
        assert_eq!(calls, 2 + 4 + 2);
    }

    #[test]
    fn ties_go_to_the_lowest_position_and_no_groups_is_the_direct_leg() {
        let problem = SelectionProblem {
            start: 0,
            groups: vec![vec![1, 2, 3]],
            end: 0,
        };
        let (chosen, cost) = problem.solve_layers(|_, _| Ok(2.0)).unwrap();
        assert_eq!((chosen, cost), (vec![1], 4.0));
        let (chosen, cost) = problem.solve_layers(|_, _| Ok(f64::INFINITY)).unwrap();
        assert_eq!((chosen, cost), (vec![1], f64::INFINITY));
        let direct = SelectionProblem {
            start: 0,
            groups: vec![],
            end: 3,
        };
        assert_eq!(direct.solve_layers(table).unwrap(), (vec![], 9.0));
    }
}

/// Why a selector found no route.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SelectionError {
    /// No PoI of group `group` (index in visiting order) is reachable from the start
    /// through the earlier groups, or, for the last group, none of its reachable PoIs has a
    /// path to the end.
    #[error("target {group} of the sequence has no reachable PoI")]
    Unreachable {
        /// Index of the group in `SelectionProblem::groups`.
        group: usize,
    },
    /// There are no groups and the end cannot be reached from the start.
    #[error("the end pose cannot be reached from the start")]
    EndUnreachable,
}

impl SelectionError {
    /// The error as a `smug_core::Error` of the `selector` stage.
    pub fn into_error(self) -> crate::error::Error {
        crate::error::Error::stage("selector", self)
    }
}
