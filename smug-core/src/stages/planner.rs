//! Point-to-point planner stage (multi-query: keeps its roadmap between queries).

use crate::error::Result;
use crate::path::Path;
use crate::pipeline::BuildContext;
use crate::pose::Pose2;
use crate::stages::roadmap::ChangedDisc;
use crate::timing::TimeBreakdown;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// How a query ended. Errors (bad input, bad config) are `Err`, not outcomes.
#[derive(Clone, Debug, PartialEq)]
pub enum PlannerOutcome {
    /// A valid path from start to goal.
    Exact(Path),
    /// A valid path that ends `goal_distance` (metric) short of the goal.
    Approximate {
        /// The path.
        path: Path,
        /// Metric distance from its end to the goal.
        goal_distance: f64,
    },
    /// No path: proved that none exists, or the budget ran out (see [`NoPathReason`]).
    NoPath(NoPathReason),
    /// The start state is invalid.
    InvalidStart,
    /// The goal state is invalid.
    InvalidGoal,
}

impl PlannerOutcome {
    /// The exact path, if any.
    pub fn exact_path(&self) -> Option<&Path> {
        match self {
            PlannerOutcome::Exact(path) => Some(path),
            _ => None,
        }
    }

    /// Why there is no path, for a query between valid endpoints that found none.
    pub fn no_path_reason(&self) -> Option<NoPathReason> {
        match self {
            PlannerOutcome::NoPath(reason) => Some(*reason),
            _ => None,
        }
    }

    /// Short machine-readable status: `exact`, `approximate`, `no_path`, `invalid_start`, `invalid_goal`.
    pub fn status(&self) -> &'static str {
        match self {
            PlannerOutcome::Exact(_) => "exact",
            PlannerOutcome::Approximate { .. } => "approximate",
            PlannerOutcome::NoPath(_) => "no_path",
            PlannerOutcome::InvalidStart => "invalid_start",
            PlannerOutcome::InvalidGoal => "invalid_goal",
        }
    }
}

/// Why a query between valid endpoints ended without a path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NoPathReason {
    /// No path exists: the planner proved it.
    Proved(Proof),
    /// The planner's budget ran out first: a path may exist.
    BudgetSpent(Budget),
}

/// How a planner proved that no path exists.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Proof {
    /// The goal lies outside the start's free region (another connected component of
    /// the free space: an exact search covered everything the start reaches, or a
    /// flood fill of the free cells does not join them).
    Disconnected,
    /// A search of the planner's discretisation (a lattice of poses and motion
    /// primitives) reached everything the start reaches, the goal not among it: no path
    /// exists at the planner's resolution.
    Exhausted,
}

/// Which budget ran out.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Budget {
    /// The sample (iteration) budget, e.g. LazyPRM*'s `max_samples`.
    Samples,
    /// The query's time budget, e.g. LazyPRM*'s `time_limit`.
    Time,
    /// The run's deadline (`smug plan --deadline`).
    Deadline,
    /// An endpoint was cut off after an earlier query between the same regions spent
    /// its budget (LazyPRM*'s pocket rule, see `retry_cut_off`).
    EarlierQuery,
    /// The search's expansion budget, e.g. the lattice planner's `max_expansions`.
    Expansions,
    /// The planner does not say which.
    Unspecified,
}

impl NoPathReason {
    /// Every reason (the names [`kind`](Self::kind) and [`why`](Self::why) give are
    /// theirs).
    pub const ALL: [NoPathReason; 8] = [
        NoPathReason::Proved(Proof::Disconnected),
        NoPathReason::Proved(Proof::Exhausted),
        NoPathReason::BudgetSpent(Budget::Samples),
        NoPathReason::BudgetSpent(Budget::Time),
        NoPathReason::BudgetSpent(Budget::Deadline),
        NoPathReason::BudgetSpent(Budget::EarlierQuery),
        NoPathReason::BudgetSpent(Budget::Expansions),
        NoPathReason::BudgetSpent(Budget::Unspecified),
    ];

    /// True when no path exists (proved), false when the budget ran out.
    pub fn is_proved(&self) -> bool {
        matches!(self, NoPathReason::Proved(_))
    }

    /// Short machine-readable kind: `proved` or `budget_spent`.
    pub fn kind(&self) -> &'static str {
        match self {
            NoPathReason::Proved(_) => "proved",
            NoPathReason::BudgetSpent(_) => "budget_spent",
        }
    }

    /// Short machine-readable cause: `disconnected`, `exhausted`, `samples`, `time`, `deadline`,
    /// `expansions`, `earlier_query`, `unspecified`.
    pub fn why(&self) -> &'static str {
        match self {
            NoPathReason::Proved(Proof::Disconnected) => "disconnected",
            NoPathReason::Proved(Proof::Exhausted) => "exhausted",
            NoPathReason::BudgetSpent(Budget::Samples) => "samples",
            NoPathReason::BudgetSpent(Budget::Time) => "time",
            NoPathReason::BudgetSpent(Budget::Deadline) => "deadline",
            NoPathReason::BudgetSpent(Budget::EarlierQuery) => "earlier_query",
            NoPathReason::BudgetSpent(Budget::Expansions) => "expansions",
            NoPathReason::BudgetSpent(Budget::Unspecified) => "unspecified",
        }
    }
}

impl std::fmt::Display for NoPathReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            NoPathReason::Proved(Proof::Disconnected) => {
                "no path exists: the goal lies outside the start's free region"
            }
            NoPathReason::Proved(Proof::Exhausted) => {
                "no path exists at the planner's resolution: its search reached everything the start reaches"
            }
            NoPathReason::BudgetSpent(Budget::Samples) => {
                "no path found before the sample budget ran out (max_samples); one may exist"
            }
            NoPathReason::BudgetSpent(Budget::Time) => {
                "no path found before the time budget ran out (time_limit); one may exist"
            }
            NoPathReason::BudgetSpent(Budget::Deadline) => {
                "no path found before the run's deadline; one may exist"
            }
            NoPathReason::BudgetSpent(Budget::EarlierQuery) => {
                "no path searched: an endpoint was cut off after an earlier query spent its budget; one may exist"
            }
            NoPathReason::BudgetSpent(Budget::Expansions) => {
                "no path found before the expansion budget ran out (max_expansions); one may exist"
            }
            NoPathReason::BudgetSpent(Budget::Unspecified) => {
                "no path found within the planner's budget; one may exist"
            }
        })
    }
}

/// A DP layer answered by one [`plan_many`](PointToPointPlanner::plan_many) per
/// source, keeping for each goal the source with the least offset plus path cost (ties
/// to the lowest index): what [`PointToPointPlanner::plan_layer`] does by default.
pub fn plan_layer_by_sources<P: PointToPointPlanner + ?Sized>(
    planner: &mut P,
    sources: &[(Pose2, f64)],
    goals: &[Pose2],
) -> Result<Vec<LayerOutcome>> {
    let mut best: Vec<Option<(f64, LayerOutcome)>> = vec![None; goals.len()];
    for (s, (pose, offset)) in sources.iter().enumerate() {
        for (slot, outcome) in best.iter_mut().zip(planner.plan_many(pose, goals)?) {
            let total = outcome
                .exact_path()
                .map_or(f64::INFINITY, |p| offset + p.cost);
            if slot.as_ref().is_none_or(|(least, _)| total < *least) {
                *slot = Some((total, LayerOutcome { source: s, outcome }));
            }
        }
    }
    let no_source = || LayerOutcome {
        source: 0,
        outcome: PlannerOutcome::InvalidStart,
    };
    Ok(best
        .into_iter()
        .map(|slot| slot.map_or_else(no_source, |(_, answer)| answer))
        .collect())
}

/// A goal's answer in a DP layer ([`PointToPointPlanner::plan_layer`]).
#[derive(Clone, Debug, PartialEq)]
pub struct LayerOutcome {
    /// The index of the source the path leaves from.
    pub source: usize,
    /// The path from that source (or why there is none).
    pub outcome: PlannerOutcome,
}

/// A planner's cumulative statistics over all its queries.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PlannerStats {
    /// Queries answered.
    pub queries: u64,
    /// Roadmap vertices.
    pub vertices: u64,
    /// Roadmap edges.
    pub edges: u64,
    /// Where the time went.
    pub breakdown: TimeBreakdown,
    /// Other counters (state checks, edge checks, samples, …).
    pub counters: BTreeMap<String, u64>,
}

/// Plans collision-free paths between two poses; successive queries share the
/// planner's data structures (roadmap), which is what makes multi-goal planning fast.
pub trait PointToPointPlanner: Send + Sync {
    /// Plans from `start` to `goal` within the planner's configured budget.
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome>;

    /// Plans from `start` to each of `goals` (one-to-many), in order. The default
    /// plans each pair with [`plan`](Self::plan), in order; a planner that answers a
    /// whole set of goals with one search (an exact graph search) overrides it.
    fn plan_many(&mut self, start: &Pose2, goals: &[Pose2]) -> Result<Vec<PlannerOutcome>> {
        goals.iter().map(|goal| self.plan(start, goal)).collect()
    }

    /// Plans every row `(start, goals)` as [`plan_many`](Self::plan_many) would, the
    /// answers in the rows' order. The default plans the rows one after another; a
    /// planner whose searches can run side by side (on threads) overrides it, with
    /// answers that must not depend on how many run at once.
    fn plan_rows(&mut self, rows: &[(Pose2, Vec<Pose2>)]) -> Result<Vec<Vec<PlannerOutcome>>> {
        rows.iter()
            .map(|(start, goals)| self.plan_many(start, goals))
            .collect()
    }

    /// [`plan_rows`](Self::plan_rows) for the rows of a cost matrix that only orders
    /// targets (the sequencer's): a planner may answer them with fewer expansions and
    /// dearer paths (the lattice's `order_heuristic_weight`). The default is
    /// `plan_rows`.
    fn plan_order_rows(
        &mut self,
        rows: &[(Pose2, Vec<Pose2>)],
    ) -> Result<Vec<Vec<PlannerOutcome>>> {
        self.plan_rows(rows)
    }

    /// Lower bounds of the costs of the paths this planner finds from each of `starts`
    /// to each of `goals` (a row per start), where it knows more than the objective's
    /// contract bound (the lattice: around obstacles); `None` (the default) where it
    /// does not. A sequencer's lazy cost matrix orders targets by them before planning
    /// the legs.
    fn cost_bounds(&mut self, starts: &[Pose2], goals: &[Pose2]) -> Result<Option<Vec<Vec<f64>>>> {
        let _ = (starts, goals);
        Ok(None)
    }

    /// True when [`plan_rows`](Self::plan_rows) searches rows side by side: the path
    /// oracle then hands it independent pairs (a route's legs) together (default
    /// false: they are planned one by one with [`plan`](Self::plan)).
    fn plans_rows_side_by_side(&self) -> bool {
        false
    }

    /// True when [`plan_many`](Self::plan_many) is cheaper than one query per goal:
    /// the path oracle then plans a cost-matrix row or a DP layer in one call
    /// (default false: pairs are planned one by one, in the order they are asked).
    fn answers_many(&self) -> bool {
        false
    }

    /// True when [`plan_layer`](Self::plan_layer) answers a whole DP layer with one
    /// search, cheaper than a search per source (default false).
    fn answers_layers(&self) -> bool {
        false
    }

    /// For each of `goals`, the cheapest way there from any of `sources`, each a pose
    /// and the cost already paid to be there (a DP value): the source's index and the
    /// path from it. The source is the one whose offset plus the planner's own cost is
    /// least (ties to the lowest index); a planner that shortcuts its paths after
    /// choosing may return a path cheaper than it chose by. A goal no source reaches
    /// gets source 0 and the first source's answer (`InvalidStart` when there are no
    /// sources). `next`: the layer after this one's goals (empty for the last), which
    /// a planner may start on early (the lattice warms its caches with it beside this
    /// search); the answers must not depend on it. The default plans from each source
    /// with [`plan_many`](Self::plan_many) and compares the paths' costs.
    fn plan_layer(
        &mut self,
        sources: &[(Pose2, f64)],
        goals: &[Pose2],
        next: &[Pose2],
    ) -> Result<Vec<LayerOutcome>> {
        let _ = next;
        plan_layer_by_sources(self, sources, goals)
    }

    /// Statistics accumulated over all queries so far.
    fn stats(&self) -> PlannerStats;

    /// True when [`prove_unreachable`](Self::prove_unreachable) can prove anything and
    /// a proved "no path" is cheap (an exhaustive search of a bounded lattice): the
    /// mission then drops the PoIs a directed model cannot use before sequencing.
    /// Default false: nothing is asked, nothing changes.
    fn proves_dead_ends(&self) -> bool {
        false
    }

    /// Tries, within `effort` units of work (a search's expansions), to prove that no
    /// path leads from `start` to `goal`: `Some(reason)` when proved (a forward-only
    /// car facing a stone up close exhausts its few reachable poses at once), `None`
    /// when a path exists or the effort ran out first. The default proves nothing.
    fn prove_unreachable(
        &mut self,
        start: &Pose2,
        goal: &Pose2,
        effort: u64,
    ) -> Result<Option<NoPathReason>> {
        let _ = (start, goal, effort);
        Ok(None)
    }

    /// [`prove_unreachable`](Self::prove_unreachable) for each `(start, goal)` of
    /// `pairs`, the answers in order. The default asks one after another; a planner
    /// whose searches can run side by side overrides it, with answers that must not
    /// depend on how many run at once.
    fn prove_each_unreachable(
        &mut self,
        pairs: &[(Pose2, Pose2)],
        effort: u64,
    ) -> Result<Vec<Option<NoPathReason>>> {
        pairs
            .iter()
            .map(|(start, goal)| self.prove_unreachable(start, goal, effort))
            .collect()
    }

    /// Tries, within `effort` units of work, to prove for each of `goals` that no path
    /// leads from `start` to it (one search for all: a boxed-in start exhausts its few
    /// reachable poses at once, whatever the goals). One entry per goal, as
    /// [`prove_unreachable`](Self::prove_unreachable). The default proves nothing.
    fn prove_unreachable_from(
        &mut self,
        start: &Pose2,
        goals: &[Pose2],
        effort: u64,
    ) -> Result<Vec<Option<NoPathReason>>> {
        let _ = (start, effort);
        Ok(vec![None; goals.len()])
    }

    /// Tries, within `effort` units of work, to prove for each of `starts` that no path
    /// leads from it to `goal` (an end pose that cannot be entered, its only ways in
    /// blocked, say). One entry per start. The default proves nothing.
    fn prove_unenterable(
        &mut self,
        goal: &Pose2,
        starts: &[Pose2],
        effort: u64,
    ) -> Result<Vec<Option<NoPathReason>>> {
        let _ = (goal, effort);
        Ok(vec![None; starts.len()])
    }

    /// The planner's roadmap and answered queries, to save after a mission: bytes in
    /// the planner's own format, opaque to the caller, who stores them with a
    /// [`Fingerprint`](crate::stages::Fingerprint) of what they were built for
    /// (default: `None`, the planner keeps no roadmap).
    fn save_roadmap(&self) -> Option<Vec<u8>> {
        None
    }

    /// Loads a roadmap saved by [`save_roadmap`](Self::save_roadmap) (its bytes) before
    /// any query; the world changed in `changed` since (vertices there are checked
    /// again, edges that may pass there are unchecked again, answers through there
    /// are dropped). The default refuses: the planner keeps no roadmap.
    fn load_roadmap(&mut self, saved: &[u8], changed: &[ChangedDisc]) -> Result<()> {
        let _ = (saved, changed);
        Err(crate::error::Error::stage("planner", NoRoadmap))
    }

    /// Carries on after obstacles were added to the world in `changed`: the validity
    /// checker, the motion validator and the objective of `ctx` (rebuilt for the updated
    /// world) replace the planner's, and what reaches into `changed` is checked again as
    /// after [`load_roadmap`](Self::load_roadmap) (vertices there checked again, edges
    /// that may pass there unchecked again, answers through there dropped); the rest
    /// of the roadmap is kept. The default refuses ([`refuse_world_update`]): the planner
    /// keeps no roadmap, callers build a new one.
    fn update_world(&mut self, ctx: &BuildContext, changed: &[ChangedDisc]) -> Result<()> {
        let _ = (ctx, changed);
        Err(refuse_world_update())
    }
}

/// The planner keeps no roadmap to carry on with after a world change; callers build
/// a new planner instead.
pub fn refuse_world_update() -> crate::error::Error {
    crate::error::Error::stage("planner", NoRoadmap)
}

/// The planner keeps no roadmap to save or load.
#[derive(Debug, thiserror::Error)]
#[error("this planner keeps no roadmap to save or load")]
pub struct NoRoadmap;
