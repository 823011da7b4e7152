//! PoI selector stage: which PoI of each target, given the visiting order.

use crate::error::Result;
use crate::oracle::PathOracle;

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

/// Chooses one PoI per target over a fixed visiting order, asking the oracle for paths.
pub trait PoiSelector: Send + Sync {
    /// The selection; every leg of the returned route has been planned by the oracle.
    fn select(&self, oracle: &mut PathOracle, problem: &SelectionProblem) -> Result<Selection>;
}
