//! Running a whole mission through an assembled pipeline: the ToI order from path
//! costs between representative poses (sequencer), one PoI per ToI (selector), then
//! post-processing into SE(3) waypoints. Everything goes through one path oracle, so
//! every query shares the planner's roadmap.

use crate::error::{Error, Result};
use crate::evaluation::plan_metrics;
use crate::mission::Mission;
use crate::oracle::PathOracle;
use crate::pipeline::Pipeline;
use crate::plan::{ChosenPoi, Plan, PlanStats, Segment};
use crate::pose::Pose2;
use crate::post_process::{concatenate, waypoints};
use crate::stages::{CostMatrix, SelectionProblem, Sequencer, Tour, TourKind};
use crate::world::World;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Which pose stands in for a target when the visiting order is computed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Representative {
    /// The PoI nearest the target's centre.
    #[default]
    NearestPoi,
    /// The target's first PoI.
    FirstPoi,
}

/// How the sequencer's ToI cost matrix is filled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SequencingCosts {
    /// Plan only the legs the tour uses: solve on lower bounds (straight-line metric
    /// costs) where no path is planned yet, plan the tour's unplanned legs, repeat until
    /// the tour uses planned legs only. With an exact solver the order is optimal for
    /// the planned costs, as with the full matrix, from far fewer paths (IDP's idea
    /// applied to sequencing).
    Lazy,
    /// Plan a path between every pair of representatives (the paper's way).
    #[default]
    Full,
}

/// How the mission is run (the config's `[plan]` section).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlanOptions {
    /// The pose that stands in for each target when sequencing.
    pub representative: Representative,
    /// Leave out targets none of whose PoIs can be reached (and say so) instead of failing.
    pub skip_unreachable: bool,
    /// Keep the roadmap's headings instead of aligning waypoints with the direction of travel.
    pub keep_headings: bool,
    /// How the sequencer's cost matrix is filled: `"full"` (default) or `"lazy"`.
    pub sequencing_costs: SequencingCosts,
}

/// Targets that cannot be reached: the plan fails and names them.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("no safe path reaches target(s) {}", .targets.iter().map(|t| format!("`{t}`")).collect::<Vec<_>>().join(", "))]
pub struct Unreachable {
    /// Ids of the unreachable targets.
    pub targets: Vec<String>,
}

/// Where the mission's poses sit in the oracle.
struct Layout {
    start: usize,
    end: usize,
    /// For each target of the mission, the oracle indices of its PoIs.
    pois: Vec<Vec<usize>>,
}

fn register_poses(oracle: &mut PathOracle, mission: &Mission) -> Layout {
    let start = oracle.add_pose(mission.start);
    let end = match mission.end {
        Some(end) => oracle.add_pose(end),
        None => start,
    };
    let pois = mission
        .targets
        .iter()
        .map(|t| t.pois.iter().map(|p| oracle.add_pose(*p)).collect())
        .collect();
    Layout { start, end, pois }
}

/// The target's stand-in for sequencing.
fn representative(
    mission: &Mission,
    layout: &Layout,
    target: usize,
    rule: Representative,
) -> usize {
    let t = &mission.targets[target];
    if rule == Representative::FirstPoi {
        return layout.pois[target][0];
    }
    let d = |p: &Pose2| (p.x - t.position.x).hypot(p.y - t.position.y);
    let best = (0..t.pois.len())
        .min_by(|&a, &b| d(&t.pois[a]).total_cmp(&d(&t.pois[b])).then(a.cmp(&b)))
        .unwrap_or(0);
    layout.pois[target][best]
}

/// The visiting order of `targets` (indices into the mission).
fn sequence(
    pipeline: &Pipeline,
    oracle: &mut PathOracle,
    mission: &Mission,
    layout: &Layout,
    targets: &[usize],
    rule: Representative,
    costs: SequencingCosts,
) -> Result<Vec<usize>> {
    let sequencer = pipeline.sequencer.as_ref().ok_or(Error::MissingStage {
        stage: "smug plan".into(),
        needed: "sequencer",
    })?;
    let open = mission.end.is_some();
    let mut nodes = vec![layout.start];
    nodes.extend(
        targets
            .iter()
            .map(|&t| representative(mission, layout, t, rule)),
    );
    if open {
        nodes.push(layout.end);
    }
    let n = nodes.len();
    let kind = if open {
        TourKind::OpenTo(n - 1)
    } else {
        TourKind::Closed
    };
    let tour = match costs {
        SequencingCosts::Full => sequencer.solve(&full_matrix(oracle, &nodes)?, kind)?,
        SequencingCosts::Lazy => lazy_tour(sequencer.as_ref(), oracle, &nodes, kind)?,
    };
    Ok(tour
        .order
        .iter()
        .filter(|&&v| v != 0 && !(open && v == n - 1))
        .map(|&v| targets[v - 1])
        .collect())
}

/// Path costs between every pair of `nodes` (each pair planned once when the oracle is
/// symmetric, both ways otherwise).
fn full_matrix(oracle: &mut PathOracle, nodes: &[usize]) -> Result<CostMatrix> {
    let n = nodes.len();
    let mut costs = vec![0.0; n * n];
    if oracle.answers_many() {
        // One call per row (the rest of the row for a symmetric oracle).
        for i in 0..n {
            let from = if oracle.is_symmetric() { i + 1 } else { 0 };
            oracle.plan_from(nodes[i], &nodes[from..])?;
        }
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

/// The tour over `nodes` on planned costs where known and lower bounds elsewhere,
/// re-solved after planning its unplanned legs until it uses planned legs only (or a
/// planned leg has no path: then the selection finds out which target is unreachable).
fn lazy_tour(
    sequencer: &dyn Sequencer,
    oracle: &mut PathOracle,
    nodes: &[usize],
    kind: TourKind,
) -> Result<Tour> {
    let n = nodes.len();
    loop {
        let matrix = CostMatrix::from_fn(n, |i, j| {
            if i == j {
                0.0
            } else {
                oracle.cost_or_bound(nodes[i], nodes[j])
            }
        })?;
        let tour = sequencer.solve(&matrix, kind)?;
        let unplanned: Vec<(usize, usize)> = tour_legs(&tour, kind)
            .map(|(a, b)| (nodes[a], nodes[b]))
            .filter(|&(a, b)| !oracle.is_planned(a, b))
            .collect();
        if unplanned.is_empty() {
            return Ok(tour);
        }
        let mut dead_end = false;
        for (a, b) in unplanned {
            dead_end |= !oracle.cost(a, b)?.is_finite();
        }
        if dead_end {
            return Ok(tour);
        }
    }
}

/// The legs `(from, to)` of a tour, the return leg of a closed tour included.
fn tour_legs(tour: &Tour, kind: TourKind) -> impl Iterator<Item = (usize, usize)> + '_ {
    let closing = match kind {
        TourKind::Closed => tour.order.last().map(|&last| (last, tour.order[0])),
        TourKind::OpenTo(_) => None,
    };
    tour.order.windows(2).map(|w| (w[0], w[1])).chain(closing)
}

/// Targets none of whose PoIs the start reaches.
fn unreachable_targets(
    oracle: &mut PathOracle,
    layout: &Layout,
    targets: &[usize],
) -> Result<Vec<usize>> {
    let mut unreachable = Vec::new();
    for &t in targets {
        let mut reached = false;
        for &p in &layout.pois[t] {
            if oracle.cost(layout.start, p)?.is_finite() {
                reached = true;
                break;
            }
        }
        if !reached {
            unreachable.push(t);
        }
    }
    Ok(unreachable)
}

/// Plans the pipeline's mission: sequencing, PoI selection, post-processing.
pub fn plan_mission(pipeline: &mut Pipeline, options: PlanOptions) -> Result<Plan> {
    let started = Instant::now();
    let mission = pipeline.mission.clone().ok_or(Error::MissingStage {
        stage: "smug plan".into(),
        needed: "world",
    })?;
    let world = pipeline.world.clone().ok_or(Error::MissingStage {
        stage: "smug plan".into(),
        needed: "world",
    })?;
    let planner = pipeline.planner.take().ok_or(Error::MissingStage {
        stage: "smug plan".into(),
        needed: "planner",
    })?;
    let mut oracle = PathOracle::new(pipeline.objective.clone(), planner)
        .with_symmetry(pipeline.space.is_symmetric() && pipeline.objective.is_symmetric());
    let layout = register_poses(&mut oracle, &mission);
    let mut targets: Vec<usize> = (0..mission.targets.len()).collect();
    let mut skipped = Vec::new();
    let mut times = std::collections::BTreeMap::new();
    let (order, problem, selection) = loop {
        let t = Instant::now();
        let order = sequence(
            pipeline,
            &mut oracle,
            &mission,
            &layout,
            &targets,
            options.representative,
            options.sequencing_costs,
        )?;
        *times.entry("sequencing".to_string()).or_insert(0.0) += t.elapsed().as_secs_f64();
        let t = Instant::now();
        let selector = pipeline.selector.as_ref().ok_or(Error::MissingStage {
            stage: "smug plan".into(),
            needed: "selector",
        })?;
        let problem = SelectionProblem {
            start: layout.start,
            groups: order.iter().map(|&t| layout.pois[t].clone()).collect(),
            end: layout.end,
        };
        let selected = selector.select(&mut oracle, &problem);
        *times.entry("selection".to_string()).or_insert(0.0) += t.elapsed().as_secs_f64();
        let selection = match selected {
            Ok(s) if s.cost.is_finite() => s,
            other => {
                let unreachable = unreachable_targets(&mut oracle, &layout, &targets)?;
                if unreachable.is_empty() {
                    other?;
                    return Err(Error::stage(
                        "smug plan",
                        Unreachable {
                            targets: vec!["(the end pose)".into()],
                        },
                    ));
                }
                let ids: Vec<String> = unreachable
                    .iter()
                    .map(|&t| mission.targets[t].id.clone())
                    .collect();
                if !options.skip_unreachable {
                    return Err(Error::stage("smug plan", Unreachable { targets: ids }));
                }
                skipped.extend(ids);
                targets.retain(|t| !unreachable.contains(t));
                continue;
            }
        };
        break (order, problem, selection);
    };
    let t = Instant::now();
    let route = problem.route(&selection.chosen);
    let mut plan = assemble_plan(
        &mut oracle,
        &mission,
        &world,
        &order,
        &selection.chosen,
        &route,
    )?;
    let objective = pipeline
        .config
        .objective
        .as_ref()
        .map_or("path-length", |section| section.kind.as_str());
    plan.metrics = plan_metrics(pipeline.context(), &world, objective, &concatenate(&plan).0);
    (plan.waypoints, plan.reversing) = waypoints(&plan, pipeline, &world, options.keep_headings);
    plan.cost = selection.cost;
    plan.skipped = skipped;
    times.insert("post-processing".into(), t.elapsed().as_secs_f64());
    times.insert(
        "total".into(),
        started.elapsed().as_secs_f64() + pipeline.build_times_s.values().sum::<f64>(),
    );
    for (stage, s) in &pipeline.build_times_s {
        times.insert(format!("build:{stage}"), *s);
    }
    plan.stats = stats(&oracle, pipeline, times);
    Ok(plan)
}

/// The index of `pose` among the world's original PoIs of target `id`.
fn original_index(world: &World, id: &str, pose: &Pose2) -> usize {
    world
        .mission
        .targets
        .iter()
        .find(|t| t.id == id)
        .and_then(|t| t.pois.iter().position(|p| p == pose))
        .unwrap_or(0)
}

fn assemble_plan(
    oracle: &mut PathOracle,
    mission: &Mission,
    world: &World,
    order: &[usize],
    chosen: &[usize],
    route: &[usize],
) -> Result<Plan> {
    let name = |k: usize| -> String {
        if k == 0 {
            "start".into()
        } else if k == route.len() - 1 {
            if mission.end.is_some() {
                "end".into()
            } else {
                "start".into()
            }
        } else {
            mission.targets[order[k - 1]].id.clone()
        }
    };
    let mut segments = Vec::new();
    for k in 0..route.len() - 1 {
        let planned = oracle.path(route[k], route[k + 1])?;
        let path = planned.path().cloned().ok_or_else(|| {
            Error::InvalidInput(format!("no path from {} to {}", name(k), name(k + 1)))
        })?;
        segments.push(Segment {
            from: name(k),
            to: name(k + 1),
            path,
        });
    }
    let pois = order
        .iter()
        .zip(chosen)
        .map(|(&t, &p)| {
            let pose = *oracle.pose(p);
            let id = mission.targets[t].id.clone();
            ChosenPoi {
                index: original_index(world, &id, &pose),
                target: id,
                pose,
            }
        })
        .collect();
    Ok(Plan {
        sequence: order
            .iter()
            .map(|&t| mission.targets[t].id.clone())
            .collect(),
        pois,
        segments,
        ..Plan::default()
    })
}

fn stats(
    oracle: &PathOracle,
    pipeline: &Pipeline,
    times: std::collections::BTreeMap<String, f64>,
) -> PlanStats {
    let planner = oracle.planner().stats();
    let validity = pipeline
        .state_validity
        .as_ref()
        .map(|c| c.counters())
        .unwrap_or_default();
    let mut counters = planner.counters.clone();
    counters.insert("roadmap_vertices".into(), planner.vertices);
    counters.insert("roadmap_edges".into(), planner.edges);
    counters.insert("oracle_cache_hits".into(), oracle.stats().cache_hits);
    for (k, v) in &validity {
        counters.insert(format!("validity_{k}"), *v);
    }
    PlanStats {
        paths_planned: oracle.stats().paths_planned,
        validity_queries: validity.get("checks").copied().unwrap_or(0),
        stage_times_s: times,
        breakdown: planner.breakdown,
        counters,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::objective::PathLength;
    use crate::path::Path;
    use crate::stages::{PlannerOutcome, PlannerStats, PointToPointPlanner};
    use proptest::prelude::*;
    use std::sync::Arc;

    /// Answers every query with a straight path whose cost is the objective's cost
    /// times a fixed detour factor of the pair (≥ 1, symmetric).
    struct DetourPlanner {
        poses: Vec<Pose2>,
        detours: Vec<f64>,
        objective: PathLength,
    }

    impl DetourPlanner {
        fn index(&self, pose: &Pose2) -> usize {
            self.poses.iter().position(|p| p == pose).unwrap()
        }
    }

    impl PointToPointPlanner for DetourPlanner {
        fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
            let (i, j) = (self.index(start), self.index(goal));
            let n = self.poses.len();
            let factor = self.detours[i.min(j) * n + i.max(j)];
            let mut path = Path::new(vec![*start, *goal], &self.objective);
            path.cost *= factor;
            Ok(PlannerOutcome::Exact(path))
        }

        fn stats(&self) -> PlannerStats {
            PlannerStats::default()
        }
    }

    /// The best tour by trying every order (small n only).
    struct Exhaustive;

    impl Sequencer for Exhaustive {
        fn solve(&self, costs: &CostMatrix, kind: TourKind) -> Result<Tour> {
            let n = costs.len();
            let mut rest: Vec<usize> = (1..n).collect();
            let mut best = Tour {
                order: vec![],
                cost: f64::INFINITY,
            };
            permute(&mut rest, 0, &mut |p| {
                let order: Vec<usize> = std::iter::once(0).chain(p.iter().copied()).collect();
                let cost = costs.tour_cost(&order, kind);
                if cost < best.cost {
                    best = Tour { order, cost };
                }
            });
            Ok(best)
        }
    }

    fn permute(items: &mut [usize], k: usize, visit: &mut impl FnMut(&[usize])) {
        if k == items.len() {
            return visit(items);
        }
        for i in k..items.len() {
            items.swap(k, i);
            permute(items, k + 1, visit);
            items.swap(k, i);
        }
    }

    fn oracle(poses: &[Pose2], detours: Vec<f64>) -> (PathOracle, Vec<usize>) {
        let objective = PathLength::default();
        let planner = DetourPlanner {
            poses: poses.to_vec(),
            detours,
            objective: objective.clone(),
        };
        let mut oracle = PathOracle::new(Arc::new(objective), Box::new(planner));
        let nodes = poses.iter().map(|p| oracle.add_pose(*p)).collect();
        (oracle, nodes)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]
        /// With an exact solver and admissible lower bounds, the lazy tour costs what
        /// the full matrix's tour costs, from no more planned paths.
        #[test]
        fn lazy_sequencing_is_exact_with_an_exact_solver(
            points in prop::collection::vec((0.0..20.0f64, 0.0..20.0f64, -3.0..3.0f64), 3..7),
            detours in prop::collection::vec(1.0..2.0f64, 49),
            open in any::<bool>(),
        ) {
            let poses: Vec<Pose2> = points.iter().map(|&(x, y, yaw)| Pose2::new(x, y, yaw)).collect();
            let n = poses.len();
            let kind = if open { TourKind::OpenTo(n - 1) } else { TourKind::Closed };
            let (mut full_oracle, nodes) = oracle(&poses, detours.clone());
            let full = Exhaustive.solve(&full_matrix(&mut full_oracle, &nodes).unwrap(), kind).unwrap();
            let (mut lazy_oracle, nodes) = oracle(&poses, detours);
            let lazy = lazy_tour(&Exhaustive, &mut lazy_oracle, &nodes, kind).unwrap();
            let true_cost = full_matrix(&mut full_oracle, &nodes).unwrap().tour_cost(&lazy.order, kind);
            prop_assert!((true_cost - full.cost).abs() < 1e-9, "lazy {true_cost} vs full {}", full.cost);
            prop_assert!((lazy.cost - true_cost).abs() < 1e-9, "the lazy tour's legs are all planned");
            prop_assert!(lazy_oracle.stats().paths_planned <= full_oracle.stats().paths_planned);
        }
    }
}
