//! What a PoI selector asks of the paths between a mission's poses: costs planned on
//! demand, admissible bounds of the ones not planned, and batches planned together.
//!
//! The path oracle of `smug-mission` implements it; the selectors of `smug-selection`
//! see only this trait, so the core keeps no orchestration.

use crate::error::Result;

/// Path costs between registered poses (indices), planned lazily and cached.
pub trait PathCosts {
    /// The planned cost from `i` to `j`, planned on first request (`INFINITY` when no
    /// path exists).
    fn cost(&mut self, i: usize, j: usize) -> Result<f64>;
    /// An admissible bound of any path's cost from `i` to `j`.
    fn lower_bound(&self, i: usize, j: usize) -> f64;
    /// True when the pair has been planned.
    fn is_planned(&self, i: usize, j: usize) -> bool;
    /// The planned cost if the pair has been planned (`INFINITY` for no path).
    fn planned_cost(&self, i: usize, j: usize) -> Option<f64>;
    /// The planned cost if planned, else the lower bound.
    fn cost_or_bound(&self, i: usize, j: usize) -> f64 {
        self.planned_cost(i, j)
            .unwrap_or_else(|| self.lower_bound(i, j))
    }
    /// True when one start and many goals are answered in one call: callers that need
    /// many pairs from one pose then ask [`plan_rows`](Self::plan_rows) first.
    fn answers_many(&self) -> bool;
    /// Plans every pair `i → j` of every row `(i, js)` not planned yet, in one call
    /// (rows possibly side by side); their costs are then served by [`cost`](Self::cost).
    fn plan_rows(&mut self, rows: &[(usize, Vec<usize>)]) -> Result<()>;
    /// Plans every pair of `pairs` not planned yet (side by side where the planner can).
    fn plan_pairs(&mut self, pairs: &[(usize, usize)]) -> Result<()>;
    /// True when [`plan_layer`](Self::plan_layer) answers a DP layer with one search
    /// (default false).
    fn answers_layers(&self) -> bool {
        false
    }
    /// For each of `goals`: the `i` of `sources` (each `(i, offset)`, the cost already
    /// paid to be at `i`) from which the offset plus the path's cost is least, the pair
    /// `i → goal` then planned (its cost served by [`cost`](Self::cost)); `None` when
    /// no source reaches the goal. `next`: the goals of the layer after this one
    /// (empty for the last), which the planner may start on early; the answers do not
    /// depend on it. The default plans every pair and compares the costs (ties to the
    /// first source).
    fn plan_layer(
        &mut self,
        sources: &[(usize, f64)],
        goals: &[usize],
        next: &[usize],
    ) -> Result<Vec<Option<usize>>> {
        let _ = next;
        let rows: Vec<(usize, Vec<usize>)> =
            sources.iter().map(|&(i, _)| (i, goals.to_vec())).collect();
        self.plan_rows(&rows)?;
        let mut best = Vec::with_capacity(goals.len());
        for &j in goals {
            let mut least: Option<(f64, usize)> = None;
            for &(i, offset) in sources {
                let total = offset + self.cost(i, j)?;
                if total.is_finite() && least.is_none_or(|(l, _)| total < l) {
                    least = Some((total, i));
                }
            }
            best.push(least.map(|(_, i)| i));
        }
        Ok(best)
    }
}
