//! One solution attempt: searches on the optimistic roadmap (LazySP) or Lazy Weighted
//! A*, the candidate path's checks, and the repair of the previous search.

use super::*;

/// LazySP rounds an `auto` attempt tries before switching to Lazy Weighted A*.
pub(super) const AUTO_LAZY_SP_ROUNDS: u32 = 4;

impl LazyPrmStar {
    /// Checks the unknown vertices, then the unknown edges, of `path`, and removes
    /// every invalid one found (all of them, so that one search discards as many bad
    /// edges as possible). True when the whole path is valid.
    pub(super) fn validate(&mut self, path: &GraphPath) -> bool {
        let mut checks = Checks {
            states: self.states.as_ref(),
            motions: self.motions.as_ref(),
            counts: &mut self.counts,
        };
        let mut valid = true;
        for &v in &path.vertices {
            valid &= checks.vertex(&mut self.roadmap, v);
        }
        if valid {
            for &e in &path.edges {
                valid &= checks.edge(&mut self.roadmap, e);
            }
        }
        valid
    }

    /// One A* search on the optimistic roadmap (no checks), within `bound`.
    pub(super) fn optimistic_search(&mut self, s: u32, g: u32, bound: f64) -> Option<GraphPath> {
        let started = Instant::now();
        let found = self
            .astar
            .search(&self.roadmap, s, g, self.objective.as_ref(), bound);
        self.counts.searches += 1;
        self.counts.breakdown.astar_s += started.elapsed().as_secs_f64();
        found
    }

    /// One Lazy Weighted A* search within `bound`; its checking time is booked as
    /// checking, not search.
    pub(super) fn lazy_weighted_search(&mut self, s: u32, g: u32, bound: f64) -> Option<GraphPath> {
        self.timed_lazy_search(|astar, roadmap, objective, checks| {
            astar.search_lazy(roadmap, s, g, objective, checks, bound)
        })
    }

    /// Runs `search`, which checks lazily through the planner's counted checks, as one
    /// search: its time less the checking it did is booked as A*, the checking as
    /// checking.
    pub(super) fn timed_lazy_search<T>(
        &mut self,
        search: impl FnOnce(&mut AStar, &mut Roadmap, &dyn Objective, &mut Checks<'_>) -> T,
    ) -> T {
        let started = Instant::now();
        let checking_before =
            self.counts.breakdown.edge_checking_s + self.counts.breakdown.vertex_checking_s;
        let mut checks = Checks {
            states: self.states.as_ref(),
            motions: self.motions.as_ref(),
            counts: &mut self.counts,
        };
        let found = search(
            &mut self.astar,
            &mut self.roadmap,
            self.objective.as_ref(),
            &mut checks,
        );
        self.counts.searches += 1;
        let checking = self.counts.breakdown.edge_checking_s
            + self.counts.breakdown.vertex_checking_s
            - checking_before;
        self.counts.breakdown.astar_s += (started.elapsed().as_secs_f64() - checking).max(0.0);
        found
    }

    /// The latest search of this query repaired for the vertices added since (see
    /// [`AStar::repair`]), timed as A*; [`Repair::NoBase`] when that cannot be done.
    pub(super) fn repair(&mut self, s: u32, g: u32) -> Repair {
        if !self.params.incremental_attempts {
            return Repair::NoBase;
        }
        let started = Instant::now();
        let fresh_from = self.fresh_from;
        let repaired = self
            .astar
            .repair(&self.roadmap, s, g, fresh_from, self.objective.as_ref());
        if repaired != Repair::NoBase {
            self.fresh_from = self.roadmap.vertex_count() as u32;
            self.counts.repairs += 1;
        }
        self.counts.breakdown.astar_s += started.elapsed().as_secs_f64();
        repaired
    }

    /// Searches and validates until a valid path is found or `s` and `g` are disconnected.
    /// `best_cost` is the cost of a valid path known to be in the roadmap (valid edges
    /// are never removed), so no search needs to open a vertex estimated above it;
    /// `rounds_done` LazySP rounds of this attempt were already spent (by a repair).
    pub(super) fn attempt(
        &mut self,
        s: u32,
        g: u32,
        best_cost: f64,
        rounds_done: u32,
    ) -> Option<GraphPath> {
        // Slack for sums of the same edges in another order.
        let bound = best_cost * (1.0 + 1e-9);
        self.fresh_from = self.roadmap.vertex_count() as u32;
        let lazy_sp_rounds = match self.params.search {
            SearchMode::LazySp => u32::MAX,
            SearchMode::LazyWeighted => 0,
            SearchMode::Auto => AUTO_LAZY_SP_ROUNDS,
        };
        let mut rounds = rounds_done;
        let found = loop {
            if rounds >= lazy_sp_rounds {
                break self.lazy_weighted_search(s, g, bound);
            }
            rounds += 1;
            match self.optimistic_search(s, g, bound) {
                None => break None,
                Some(path) if self.validate(&path) => break Some(path),
                Some(_) => {}
            }
        };
        if found.is_none() {
            self.roadmap.refresh_components();
        }
        found
    }
}
