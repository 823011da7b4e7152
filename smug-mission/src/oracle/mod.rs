//! The path oracle: lower bounds and lazily planned, cached paths between poses.
//!
//! Sequencing and PoI selection only talk to the oracle. It owns the point-to-point
//! planner, so every query of a mission shares one roadmap.

use smug_core::deadline::Deadline;
use smug_core::error::{Error, Result};
use smug_core::objective::Objective;
use smug_core::path::Path;
use smug_core::pipeline::Pipeline;
use smug_core::pose::Pose2;
use smug_core::run_context::RunContext;
use smug_core::stages::{PathCosts, PlannerOutcome, PointToPointPlanner};
use std::collections::HashMap;
use std::sync::Arc;

mod answers;
mod layers;
mod proofs;
#[cfg(test)]
mod tests;

pub use answers::{KnownAnswers, OracleStats, PlannedPath};

/// Lower bounds and lazily planned paths between registered poses.
pub struct PathOracle {
    poses: Vec<Pose2>,
    objective: Arc<dyn Objective>,
    planner: Box<dyn PointToPointPlanner>,
    cache: HashMap<(usize, usize), Arc<PlannedPath>>,
    /// Every pair whose cached answer was set, in order (a pair refined is listed again).
    stored: Vec<(usize, usize)>,
    symmetric: bool,
    stats: OracleStats,
    known: KnownAnswers,
    run: RunContext,
    /// The planner's own lower bounds of pairs ([`tighten_bounds`](Self::tighten_bounds)).
    bounds: HashMap<(usize, usize), f64>,
}

impl PathOracle {
    /// An oracle over `planner`, with costs and bounds of `objective` (symmetric when
    /// the objective is: a path i→j reversed serves j→i).
    pub fn new(objective: Arc<dyn Objective>, planner: Box<dyn PointToPointPlanner>) -> Self {
        Self {
            poses: Vec::new(),
            symmetric: objective.is_symmetric(),
            objective,
            planner,
            cache: HashMap::new(),
            stored: Vec::new(),
            stats: OracleStats::default(),
            known: KnownAnswers::default(),
            run: RunContext::default(),
            bounds: HashMap::new(),
        }
    }

    /// An oracle over the planner taken out of `pipeline` (an error naming `stage` if it
    /// has none), with its objective, the symmetry of its space and objective, and its
    /// run context. Give the planner back with [`into_planner`](Self::into_planner).
    pub fn of_pipeline(pipeline: &mut Pipeline, stage: &str) -> Result<Self> {
        let planner = pipeline.planner.take().ok_or(Error::MissingStage {
            stage: stage.into(),
            needed: "planner",
        })?;
        Ok(Self::new(pipeline.objective.clone(), planner)
            .with_symmetry(pipeline.space.is_symmetric() && pipeline.objective.is_symmetric())
            .with_run(pipeline.run().clone()))
    }

    /// Runs within `run`: plans nothing more once its deadline's hard stop has passed,
    /// builds cost matrices within its memory limit, counts the legs it asks and gets
    /// answered in its progress (default: a deadline that is never armed, the default
    /// limit, a progress nobody reads).
    pub fn with_run(mut self, run: RunContext) -> Self {
        self.run = run;
        self
    }

    /// The run context the oracle plans within.
    pub fn run(&self) -> &RunContext {
        &self.run
    }

    /// Serves the pairs `known` holds without planning (counted as `known_hits`).
    pub fn with_known(mut self, known: KnownAnswers) -> Self {
        self.known = known;
        self
    }

    /// The known answers given with [`with_known`](Self::with_known), with every exact
    /// path this oracle planned or served added (by the poses' bits); they are moved out
    /// (the oracle keeps none after).
    pub fn take_known_answers(&mut self) -> KnownAnswers {
        let mut known = std::mem::take(&mut self.known);
        for (&(i, j), planned) in &self.cache {
            if i != j {
                known.insert(&self.poses[i], &self.poses[j], planned.clone());
            }
        }
        known
    }

    /// The known answer for `i → j`, if any.
    fn known_pair(&self, i: usize, j: usize) -> Option<&Arc<PlannedPath>> {
        if self.known.is_empty() {
            return None;
        }
        self.known.get(&self.poses[i], &self.poses[j])
    }

    /// Moves a known answer for `i → j` (if any) into the cache; true if one was found.
    fn take_known(&mut self, i: usize, j: usize) -> bool {
        let Some(found) = self.known_pair(i, j).cloned() else {
            return false;
        };
        self.stats.known_hits += 1;
        if self.symmetric && !self.cache.contains_key(&(j, i)) {
            self.store(j, i, Arc::new(found.reversed()));
        }
        self.store(i, j, found);
        true
    }

    /// True when the oracle serves answers kept from earlier missions
    /// ([`with_known`](Self::with_known)): a [`MissionSession`](crate::MissionSession)'s replans.
    pub fn has_known_answers(&self) -> bool {
        !self.known.is_empty()
    }

    /// Whether a path i→j reversed may serve j→i (true for undirected roadmaps,
    /// symmetric spaces and symmetric objectives; default: the objective's symmetry).
    pub fn with_symmetry(mut self, symmetric: bool) -> Self {
        self.symmetric = symmetric;
        self
    }

    /// Registers a pose; returns its index.
    pub fn add_pose(&mut self, pose: Pose2) -> usize {
        self.poses.push(pose);
        self.poses.len() - 1
    }

    /// The pose at index `i`.
    pub fn pose(&self, i: usize) -> &Pose2 {
        &self.poses[i]
    }

    /// Number of registered poses.
    pub fn len(&self) -> usize {
        self.poses.len()
    }

    /// True when no pose is registered.
    pub fn is_empty(&self) -> bool {
        self.poses.is_empty()
    }

    /// The objective.
    pub fn objective(&self) -> &dyn Objective {
        self.objective.as_ref()
    }

    /// Whether a path i→j reversed serves j→i.
    pub fn is_symmetric(&self) -> bool {
        self.symmetric
    }

    /// A lower bound of the cost of the planner's path from `i` to `j`: the objective's
    /// (of any path), or the planner's own where [`tighten_bounds`](Self::tighten_bounds)
    /// asked for it, whichever is larger.
    pub fn lower_bound(&self, i: usize, j: usize) -> f64 {
        let bound = self.objective.cost_bound(&self.poses[i], &self.poses[j]);
        self.bounds.get(&(i, j)).map_or(bound, |b| b.max(bound))
    }

    /// Asks the planner for its own lower bounds between every two of `nodes`
    /// ([`PointToPointPlanner::cost_bounds`]), kept for [`lower_bound`](Self::lower_bound);
    /// for a symmetric oracle a pair's bound is the larger of its two ways'.
    pub fn tighten_bounds(&mut self, nodes: &[usize]) -> Result<()> {
        let poses: Vec<Pose2> = nodes.iter().map(|&i| self.poses[i]).collect();
        let Some(rows) = self.planner.cost_bounds(&poses, &poses)? else {
            return Ok(());
        };
        for (a, &i) in nodes.iter().enumerate() {
            for (b, &j) in nodes.iter().enumerate() {
                if i == j {
                    continue;
                }
                let back = if self.symmetric { rows[b][a] } else { 0.0 };
                let bound = rows[a][b].max(back);
                let known = self.bounds.get(&(i, j)).copied().unwrap_or(0.0);
                self.bounds.insert((i, j), bound.max(known));
            }
        }
        Ok(())
    }

    /// True when the pair has been planned (in either direction if symmetric).
    pub fn is_planned(&self, i: usize, j: usize) -> bool {
        i == j || self.cache.contains_key(&(i, j)) || self.known_pair(i, j).is_some()
    }

    /// The planned cost if the pair has been planned (`INFINITY` for no path).
    pub fn planned_cost(&self, i: usize, j: usize) -> Option<f64> {
        if i == j {
            return Some(0.0);
        }
        self.cache
            .get(&(i, j))
            .or_else(|| self.known_pair(i, j))
            .map(|p| p.cost)
    }

    /// Caches `planned` as the answer for `i → j` and logs the pair (see
    /// [`stored_since`](Self::stored_since)).
    fn store(&mut self, i: usize, j: usize, planned: Arc<PlannedPath>) {
        self.cache.insert((i, j), planned);
        self.stored.push((i, j));
    }

    /// [`store`](Self::store)s `planned` for `i → j`, after its reverse for `j → i`
    /// when the oracle is symmetric and `i ≠ j`.
    fn store_both_ways(&mut self, i: usize, j: usize, planned: Arc<PlannedPath>) {
        if self.symmetric && i != j {
            self.store(j, i, Arc::new(planned.reversed()));
        }
        self.store(i, j, planned);
    }

    /// The pairs whose answer was set (planned, served from known answers, or refined)
    /// since the log held `mark` entries, in order; `stored_since(0).len()` is the
    /// mark to pass next time. A matrix of planned costs updates from these alone.
    pub fn stored_since(&self, mark: usize) -> &[(usize, usize)] {
        &self.stored[mark.min(self.stored.len())..]
    }

    /// The path from `i` to `j`, planned on first request and cached.
    pub fn path(&mut self, i: usize, j: usize) -> Result<Arc<PlannedPath>> {
        if let Some(hit) = self.cache.get(&(i, j)) {
            self.stats.cache_hits += 1;
            return Ok(hit.clone());
        }
        if self.take_known(i, j) {
            return Ok(self.cache[&(i, j)].clone());
        }
        let planned = Arc::new(if i == j {
            PlannedPath {
                outcome: PlannerOutcome::Exact(Path {
                    states: vec![self.poses[i]],
                    cost: 0.0,
                }),
                cost: 0.0,
            }
        } else {
            self.plan_pair(i, j)?
        });
        self.store_both_ways(i, j, planned.clone());
        Ok(planned)
    }

    /// True when the planner answers one start and many goals in one call (see
    /// [`PointToPointPlanner::answers_many`]): callers that need many pairs from one
    /// pose then ask [`plan_from`](Self::plan_from) first.
    pub fn answers_many(&self) -> bool {
        self.planner.answers_many()
    }

    /// True when the planner answers many goals at once and searches rows side by
    /// side (on threads): rows asked together then share the machine's cores.
    pub fn plans_rows_side_by_side(&self) -> bool {
        self.planner.answers_many() && self.planner.plans_rows_side_by_side()
    }

    /// Plans the pairs `i → j` for every `j` of `js` not planned yet, with one call to
    /// the planner's `plan_many`, and caches them (served by [`path`](Self::path) and
    /// [`cost`](Self::cost) afterwards, as cache hits).
    pub fn plan_from(&mut self, i: usize, js: &[usize]) -> Result<()> {
        self.plan_rows(&[(i, js.to_vec())])
    }

    /// [`plan_from`](Self::plan_from) for every row `(i, js)`, with one call to the
    /// planner's `plan_rows` (which may search the rows side by side).
    pub fn plan_rows(&mut self, rows: &[(usize, Vec<usize>)]) -> Result<()> {
        self.plan_rows_for(rows, false)
    }

    /// [`plan_rows`](Self::plan_rows) for the rows of a matrix that only orders
    /// targets ([`PointToPointPlanner::plan_order_rows`]).
    pub fn plan_order_rows(&mut self, rows: &[(usize, Vec<usize>)]) -> Result<()> {
        self.plan_rows_for(rows, true)
    }

    /// The rows' pairs not planned yet, planned with one call to the planner
    /// (`for_order`: as rows of a matrix that only orders targets).
    fn plan_rows_for(&mut self, rows: &[(usize, Vec<usize>)], for_order: bool) -> Result<()> {
        let mut asked: Vec<(usize, Vec<usize>)> = Vec::new();
        for (i, js) in rows {
            let mut wanted: Vec<usize> = Vec::new();
            for &j in js {
                let earlier = asked.iter().any(|(a, w)| {
                    (*a == *i && w.contains(&j)) || (self.symmetric && *a == j && w.contains(i))
                });
                if j != *i
                    && !earlier
                    && !self.cache.contains_key(&(*i, j))
                    && !wanted.contains(&j)
                    && !self.take_known(*i, j)
                {
                    wanted.push(j);
                }
            }
            if !wanted.is_empty() {
                asked.push((*i, wanted));
            }
        }
        if asked.is_empty() {
            return Ok(());
        }
        refuse_after_deadline(&self.run.deadline)?;
        let queries: Vec<(Pose2, Vec<Pose2>)> = asked
            .iter()
            .map(|(i, js)| (self.poses[*i], js.iter().map(|&j| self.poses[j]).collect()))
            .collect();
        let legs: usize = asked.iter().map(|(_, js)| js.len()).sum();
        let asked_so_far = self.run.progress.ask(legs as u64);
        let answers = if for_order {
            self.planner.plan_order_rows(&queries)
        } else {
            self.planner.plan_rows(&queries)
        };
        self.run.progress.answered_up_to(asked_so_far);
        let answers = answers?;
        for ((i, wanted), outcomes) in asked.into_iter().zip(answers) {
            self.stats.paths_planned += wanted.len() as u64;
            for (j, outcome) in wanted.into_iter().zip(outcomes) {
                if self.cache.contains_key(&(i, j)) {
                    continue;
                }
                self.store_both_ways(i, j, Arc::new(PlannedPath::new(outcome)));
            }
        }
        Ok(())
    }

    /// Plans every pair of `pairs` not planned yet: when the planner searches rows side
    /// by side, as rows (with [`plan_rows`](Self::plan_rows)): one search per pose the
    /// pairs share (see `rows_of`) if it answers many goals at once,
    /// else one per pair; otherwise one after another as [`path`](Self::path) would.
    /// (Grouped rows were measured for the lattice only: LazyPRM*'s one-to-many
    /// searches change its plans, dearer on lunar, cheaper on the imported map.)
    pub fn plan_pairs(&mut self, pairs: &[(usize, usize)]) -> Result<()> {
        self.plan_pairs_for(pairs, false)
    }

    /// [`plan_pairs`](Self::plan_pairs) for legs that only order targets (a lazy cost
    /// matrix's): rows are asked with [`plan_order_rows`](Self::plan_order_rows).
    pub fn plan_order_pairs(&mut self, pairs: &[(usize, usize)]) -> Result<()> {
        self.plan_pairs_for(pairs, true)
    }

    /// [`plan_pairs`](Self::plan_pairs), the rows asked as rows of a matrix that only
    /// orders targets when `for_order`.
    fn plan_pairs_for(&mut self, pairs: &[(usize, usize)], for_order: bool) -> Result<()> {
        if !self.planner.plans_rows_side_by_side() {
            for &(i, j) in pairs {
                self.path(i, j)?;
            }
            return Ok(());
        }
        let rows: Vec<(usize, Vec<usize>)> = if self.planner.answers_many() {
            self.rows_of(pairs)
        } else {
            pairs.iter().map(|&(i, j)| (i, vec![j])).collect()
        };
        self.plan_rows_for(&rows, for_order)
    }

    /// `pairs` grouped into rows by their source, in the order the sources first
    /// appear; with a symmetric planner each pair is searched from whichever of its
    /// poses more pairs share (the lower index on a tie), so a PoI's legs to every PoI
    /// of the next target are one search, not one each.
    fn rows_of(&self, pairs: &[(usize, usize)]) -> Vec<(usize, Vec<usize>)> {
        let mut shares: HashMap<usize, usize> = HashMap::new();
        for &(i, j) in pairs {
            *shares.entry(i).or_default() += 1;
            *shares.entry(j).or_default() += 1;
        }
        let hub = |k: usize| (shares[&k], std::cmp::Reverse(k));
        let mut rows: Vec<(usize, Vec<usize>)> = Vec::new();
        for &(i, j) in pairs {
            let (from, to) = if self.symmetric && hub(j) > hub(i) {
                (j, i)
            } else {
                (i, j)
            };
            match rows.iter_mut().find(|(source, _)| *source == from) {
                Some((_, goals)) => goals.push(to),
                None => rows.push((from, vec![to])),
            }
        }
        rows
    }

    /// Plans the cached pair `i → j` again on the roadmap as it is now (grown by every
    /// query since the pair was planned) and keeps the new path when it is cheaper.
    /// True when the cost went down; an unplanned pair is planned as by
    /// [`path`](Self::path) (and reported as not improved).
    pub fn refine(&mut self, i: usize, j: usize) -> Result<bool> {
        let Some(old) = self.planned_cost(i, j) else {
            self.path(i, j)?;
            return Ok(false);
        };
        if i == j || !old.is_finite() {
            return Ok(false);
        }
        let planned = self.plan_pair(i, j)?;
        if planned.cost >= old {
            return Ok(false);
        }
        self.store_both_ways(i, j, Arc::new(planned));
        Ok(true)
    }

    /// The planned cost from `i` to `j` (`INFINITY` when unreachable).
    pub fn cost(&mut self, i: usize, j: usize) -> Result<f64> {
        Ok(self.path(i, j)?.cost)
    }

    /// Counters.
    pub fn stats(&self) -> OracleStats {
        self.stats
    }

    /// The planner back, with the roadmap it grew (to save it after a mission).
    pub fn into_planner(self) -> Box<dyn PointToPointPlanner> {
        self.planner
    }

    /// The planner (for its statistics).
    pub fn planner(&self) -> &dyn PointToPointPlanner {
        self.planner.as_ref()
    }

    /// Pairs asked so far that have no path, by `kind:why` of the planner's reason
    /// (`proved:exhausted`, `budget_spent:samples`, …).
    pub fn no_path_counts(&self) -> std::collections::BTreeMap<String, u64> {
        let mut counts = std::collections::BTreeMap::new();
        for planned in self.cache.values() {
            if let Some(reason) = planned.outcome.no_path_reason() {
                *counts
                    .entry(format!("{}:{}", reason.kind(), reason.why()))
                    .or_insert(0) += 1;
            }
        }
        counts
    }

    /// True when some pair asked so far has no path.
    pub fn has_legs_without_path(&self) -> bool {
        self.cache
            .values()
            .any(|planned| planned.outcome.no_path_reason().is_some())
    }

    fn plan_pair(&mut self, i: usize, j: usize) -> Result<PlannedPath> {
        refuse_after_deadline(&self.run.deadline)?;
        self.stats.paths_planned += 1;
        let asked_so_far = self.run.progress.ask(1);
        let outcome = self.planner.plan(&self.poses[i], &self.poses[j]);
        self.run.progress.answered_up_to(asked_so_far);
        let outcome = outcome?;
        Ok(PlannedPath::new(outcome))
    }
}

/// No new path is planned once the run's hard stop has passed (the deadline's seconds
/// are filled in by whoever armed it).
fn refuse_after_deadline(deadline: &Deadline) -> Result<()> {
    if deadline.hard_stop_passed() {
        return Err(Error::DeadlinePassed {
            seconds: f64::NAN,
            during: "path planning".into(),
        });
    }
    Ok(())
}

/// What the PoI selectors ask of the oracle.
impl PathCosts for PathOracle {
    fn cost(&mut self, i: usize, j: usize) -> Result<f64> {
        PathOracle::cost(self, i, j)
    }

    fn lower_bound(&self, i: usize, j: usize) -> f64 {
        PathOracle::lower_bound(self, i, j)
    }

    fn is_planned(&self, i: usize, j: usize) -> bool {
        PathOracle::is_planned(self, i, j)
    }

    fn planned_cost(&self, i: usize, j: usize) -> Option<f64> {
        PathOracle::planned_cost(self, i, j)
    }

    fn answers_many(&self) -> bool {
        PathOracle::answers_many(self)
    }

    fn plan_rows(&mut self, rows: &[(usize, Vec<usize>)]) -> Result<()> {
        PathOracle::plan_rows(self, rows)
    }

    fn plan_pairs(&mut self, pairs: &[(usize, usize)]) -> Result<()> {
        PathOracle::plan_pairs(self, pairs)
    }

    fn answers_layers(&self) -> bool {
        PathOracle::answers_layers(self)
    }

    fn plan_layer(
        &mut self,
        sources: &[(usize, f64)],
        goals: &[usize],
        next: &[usize],
    ) -> Result<Vec<Option<usize>>> {
        PathOracle::plan_layer(self, sources, goals, next)
    }
}

impl std::fmt::Debug for PathOracle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PathOracle")
            .field("poses", &self.poses.len())
            .field("cached", &self.cache.len())
            .field("symmetric", &self.symmetric)
            .field("stats", &self.stats)
            .finish()
    }
}
