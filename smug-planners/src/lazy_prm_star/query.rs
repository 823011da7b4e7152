//! One query: grow, search and improve until the stall rule, the budget or optimality
//! stops; "no path" proved or named by the budget that ran out.

use super::*;

/// Samples between improvement attempts once a query has its first path:
/// `attempt_every`, or `attempt_share` × the samples it drew to find that path if more.
pub(super) fn improvement_interval(params: &LazyPrmStarParams, samples_to_first_path: u64) -> u32 {
    let scaled = (params.attempt_share * samples_to_first_path as f64).ceil();
    (scaled.min(f64::from(u32::MAX)) as u32).max(params.attempt_every)
}

impl LazyPrmStar {
    /// Grows the roadmap and searches until the stall rule, the budget or optimality stops.
    pub(super) fn solve(
        &mut self,
        start: &Pose2,
        goal: &Pose2,
        s: u32,
        g: u32,
    ) -> Option<GraphPath> {
        let budget =
            Termination::from_budgets(self.params.time_limit, Some(self.params.max_samples));
        let deadline = self.deadline.clone();
        let mut clock = budget.start_within(&deadline);
        let mut best = if self.roadmap.maybe_connected(s, g) {
            self.attempt(s, g, f64::INFINITY, 0)
        } else {
            None
        };
        let (mut stall, mut since_attempt) = (0u32, 0u32);
        // Before the first solution, wait longer after each failed attempt (the roadmap
        // must grow by a share of its size), so cluttered maps do not search per sample.
        let mut wait = 1u32;
        // Once a path is known, samples between attempts (see `attempt_share`).
        let mut interval = self.params.attempt_every;
        let mut focus = Focus::new(
            self.params.focus,
            self.objective.cost_bound(start, goal),
            self.whole_bounds_cost(start, goal),
            self.focus_period(),
        );
        let max_stall = self.params.max_stall;
        let stalled = |best: &Option<GraphPath>, stall: u32| best.is_some() && stall >= max_stall;
        self.expansion.begin(start, goal);
        while !clock.is_done() && !stalled(&best, stall) {
            // `best` changes only at the end of an iteration.
            let best_cost = best.as_ref().map_or(f64::INFINITY, |b| b.cost);
            let focusing = !focus.covers(best_cost);
            let expanding = best.is_none()
                && clock.iterations() >= self.params.expand_after
                && self.expansion.is_due();
            let (inserted, widened) = if expanding {
                clock.tick();
                (self.insert_expansion_sample(), false)
            } else {
                let focused = if focusing {
                    focus.next_set(start, goal)
                } else {
                    None
                };
                let from_focus = focused.is_some();
                let informed = focused.or_else(|| {
                    best.as_ref().map(|b| InformedSet {
                        start: *start,
                        goal: *goal,
                        best_cost: b.cost,
                    })
                });
                clock.tick();
                let Some(sample) = self.draw_sample(informed.as_ref()) else {
                    if from_focus {
                        focus.widen(self.focus_period());
                        continue; // the focus fell outside the bounds: widen it
                    }
                    break; // the informed set is empty: nothing can improve the path
                };
                let widened = focusing && focus.tick();
                if widened {
                    focus.widen(self.focus_period());
                }
                let bridging = best.is_none() && clock.iterations() >= self.params.expand_after;
                let inserted = if bridging {
                    self.insert_or_bridge(sample)
                } else {
                    self.insert_sample(sample)
                };
                (inserted, widened)
            };
            if !inserted && !widened {
                continue;
            }
            since_attempt += 1;
            let due = match &best {
                None => since_attempt >= wait && self.roadmap.maybe_connected(s, g),
                // While focusing, once per focus period: the roadmap grows by a share
                // of its size between searches, as before the first path.
                Some(_) if focusing => widened,
                Some(_) => since_attempt >= interval,
            };
            if !due {
                continue;
            }
            since_attempt = 0;
            let repaired = match best {
                Some(_) => self.repair(s, g),
                None => Repair::NoBase,
            };
            let found = match repaired {
                Repair::NoCheaper => {
                    // As a searched attempt: a stall only once the focus covers the
                    // informed set.
                    if focus.covers(best_cost) {
                        stall += 1;
                    }
                    continue;
                }
                // The repair was this attempt's first search round.
                Repair::Cheaper(path) if self.validate(&path) => Some(path),
                Repair::Cheaper(_) => self.attempt(s, g, best_cost, 1),
                Repair::NoBase => self.attempt(s, g, best_cost, 0),
            };
            if found.is_none() && best.is_none() {
                wait = ((self.roadmap.live_vertex_count() / 20) as u32).max(1);
            }
            if found.is_none() && best.is_some() && focus.covers(best_cost) {
                // No cheaper path: a stalled attempt, as a repair that finds none.
                stall += 1;
            }
            if let Some(path) = found {
                if best.is_none() {
                    interval = improvement_interval(&self.params, clock.iterations());
                }
                // A round counts as stalled only once the focus covers the informed
                // set: until then the samples have not yet reached all of it.
                if path.cost > best_cost * (1.0 - self.params.improvement)
                    && focus.covers(best_cost)
                {
                    stall += 1;
                } else {
                    stall = 0;
                }
                if path.cost < best_cost {
                    best = Some(path);
                }
            }
        }
        if best.is_none() && since_attempt > 0 && self.roadmap.maybe_connected(s, g) {
            // The samples since the last attempt may have connected the endpoints.
            best = self.attempt(s, g, f64::INFINITY, 0);
        }
        if best.is_none() {
            self.last_budget = if deadline.passed() {
                Budget::Deadline
            } else if self
                .params
                .time_limit
                .is_some_and(|t| clock.elapsed().as_secs_f64() >= t)
            {
                Budget::Time
            } else {
                Budget::Samples
            };
            // A passed deadline ends every query alike: it says nothing of a pocket.
            if self.last_budget != Budget::Deadline {
                self.cut_off_pocket(s, g);
            }
        }
        best
    }

    /// True when no path joins `start` and `goal`, proved cheaply: for a disc on a
    /// grid, they lie in different components of the free cells (see [`FreeRegions`]).
    pub(super) fn proved_disconnected(&mut self, start: &Pose2, goal: &Pose2) -> bool {
        let states = &self.states;
        let regions = self
            .regions
            .get_or_insert_with(|| states.disc_on_grid().map(|disc| FreeRegions::new(&disc)));
        let proved = regions
            .as_ref()
            .is_some_and(|r| r.disconnected(start, goal));
        if proved {
            self.counts.proved_no_path += 1;
        }
        proved
    }

    /// A query between the valid endpoint vertices `s ≠ g` of `start` and `goal`:
    /// "no path" at once when one is cut off, else solved and post-processed.
    pub(super) fn solve_query(
        &mut self,
        start: &Pose2,
        goal: &Pose2,
        s: u32,
        g: u32,
    ) -> PlannerOutcome {
        if self.proved_disconnected(start, goal) {
            return PlannerOutcome::NoPath(NoPathReason::Proved(Proof::Disconnected));
        }
        if self.cut_off_from(s, g) || self.cut_off_from(g, s) {
            self.counts.cut_off_queries += 1;
            return PlannerOutcome::NoPath(NoPathReason::BudgetSpent(Budget::EarlierQuery));
        }
        match self.solve(start, goal, s, g) {
            Some(path) => PlannerOutcome::Exact(self.post_processed(&path)),
            None => PlannerOutcome::NoPath(NoPathReason::BudgetSpent(self.last_budget)),
        }
    }

    /// True when `v` lies in a pocket an earlier query was cut off in, apart from
    /// `other`: `v`'s component holds a cut-off vertex and less than half the roadmap,
    /// and `other` is not in it. A pocket is the component as it grows (every PoI of a
    /// room a car cannot leave, not only the endpoint that failed); one that joins the
    /// rest of the roadmap (more than half of it) is a pocket no more.
    pub(super) fn cut_off_from(&mut self, v: u32, other: u32) -> bool {
        if self.cut_off.is_empty() || self.roadmap.maybe_connected(v, other) {
            return false;
        }
        self.roadmap.refresh_components();
        if self.roadmap.maybe_connected(v, other)
            || self.roadmap.component_size(v) >= self.roadmap.live_vertex_count() / 2
        {
            return false;
        }
        let roadmap = &mut self.roadmap;
        self.cut_off.iter().any(|&c| roadmap.maybe_connected(c, v))
    }

    /// After a failed query: cuts off the endpoint whose component is the smaller one
    /// if it holds less than half the roadmap (both on a tie), unless retried.
    pub(super) fn cut_off_pocket(&mut self, s: u32, g: u32) {
        if self.params.retry_cut_off {
            return;
        }
        self.roadmap.refresh_components();
        let half = self.roadmap.live_vertex_count() / 2;
        let (size_s, size_g) = (
            self.roadmap.component_size(s),
            self.roadmap.component_size(g),
        );
        for (v, size, other) in [(s, size_s, size_g), (g, size_g, size_s)] {
            if size <= other && size < half {
                self.cut_off.insert(v);
            }
        }
    }

    /// A cost whose informed set holds the whole bounds: every corner's sum of
    /// distances to the foci, weighted, plus the rotational lower bound.
    pub(super) fn whole_bounds_cost(&self, start: &Pose2, goal: &Pose2) -> f64 {
        let (w_t, w_r) = self.objective.bound_weights();
        let [x0, y0] = self.bounds.min;
        let [x1, y1] = self.bounds.max;
        let farthest = [[x0, y0], [x0, y1], [x1, y0], [x1, y1]]
            .iter()
            .map(|&[x, y]| (x - start.x).hypot(y - start.y) + (x - goal.x).hypot(y - goal.y))
            .fold(0.0, f64::max);
        w_t * farthest + w_r * angle_distance(start.yaw, goal.yaw)
    }

    /// Samples the focus gets before it widens: a share of the roadmap (as the wait
    /// between failed attempts), at least [`MIN_FOCUS_PERIOD`].
    pub(super) fn focus_period(&self) -> u64 {
        ((self.roadmap.live_vertex_count() / 20) as u64).max(MIN_FOCUS_PERIOD)
    }
}
