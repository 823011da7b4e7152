//! Running a whole mission through an assembled pipeline. The sequential mode: the ToI
//! order from path costs between representative poses (sequencer), one PoI per ToI
//! (selector), then post-processing into SE(3) waypoints. Everything goes through one
//! path oracle, so every query shares the planner's roadmap. The joint mode (`joint`)
//! chooses the order and the PoIs together.

use crate::assembly::{assemble_plan, stats};
use crate::dead_ends::drop_dead_ends;
use crate::evaluation::plan_metrics;
use crate::joint::{joint_tour, JointProblem};
use crate::layout::{register_poses, Layout};
use crate::oracle::{KnownAnswers, PathOracle};
use crate::post_process::{concatenate, waypoints};
use crate::probe::{end_not_entered, probe_start_and_end};
use crate::sequential::{sequence, unreached_after_failed_legs, unreached_from_start_row};
use crate::unreachable::{fail_or_skip, unreachable_targets, Unreachable};
use smug_core::error::{Error, Result};
use smug_core::mission::Mission;
use smug_core::mission::{PlanMode, PlanOptions};
use smug_core::pipeline::Pipeline;
use smug_core::plan::{Plan, PlanStats};
use smug_core::stages::PathCosts;
use smug_core::stages::{Selection, SelectionError, SelectionProblem};
use smug_core::world::World;
use std::collections::BTreeMap;
use std::time::Instant;

/// The target (mission index) a selector found no route through, from its error.
fn unroutable_target(selected: &Result<Selection>, order: &[usize]) -> Option<usize> {
    let Err(Error::Stage { source, .. }) = selected else {
        return None;
    };
    match source.downcast_ref::<SelectionError>()? {
        SelectionError::Unreachable { group } => order.get(*group).copied(),
        SelectionError::EndUnreachable => None,
    }
}

/// Most pose pairs one sweep of the PoI selection may weigh (a count bound: beyond it a
/// sweep takes minutes and the paths between the poses far longer).
pub const MAX_POSE_PAIRS: u128 = 100_000_000;

/// Refuses missions whose PoI selection would weigh more than [`MAX_POSE_PAIRS`] pairs per
/// sweep (bounded by the largest target's PoIs times all PoIs).
fn check_selection_size(mission: &Mission) -> Result<()> {
    let Some(largest) = mission.targets.iter().max_by_key(|t| t.pois.len()) else {
        return Ok(());
    };
    let total: u128 = mission.targets.iter().map(|t| t.pois.len() as u128).sum();
    let pairs = total * largest.pois.len() as u128;
    if pairs <= MAX_POSE_PAIRS {
        return Ok(());
    }
    Err(Error::InvalidInput(format!(
        "the mission has {total} PoIs, {} of them at target `{}`: selecting among them \
         weighs up to {pairs} pose pairs per sweep, above the {MAX_POSE_PAIRS} a plan is \
         bounded by; give the targets fewer PoIs",
        largest.pois.len(),
        largest.id
    )))
}

/// What one round of the sequential mode found.
enum Step {
    /// Targets the start cannot reach (mission indices), found from its legs.
    Unreached(Vec<usize>),
    /// The order and the selector's PoIs along it (or its failure).
    Selected(Vec<usize>, Result<Selection>),
}

/// One round of the sequential mode: the targets the start cannot reach when its legs
/// show some (before ordering with full costs, after it once a leg had no path), else
/// the order (sequencer) and the PoIs along it (selector), timed (the start's legs
/// asked first count as sequencing: they are the cost matrix's first row, or with a
/// lattice on a closed tour the whole matrix).
fn order_then_select(
    pipeline: &Pipeline,
    oracle: &mut PathOracle,
    mission: &Mission,
    layout: &Layout,
    targets: &[usize],
    options: PlanOptions,
    times: &mut BTreeMap<String, f64>,
) -> Result<Step> {
    let t = Instant::now();
    pipeline.run().progress.enter("sequencing");
    let unreached = unreached_from_start_row(oracle, mission, layout, targets, options);
    *times.entry("sequencing".to_string()).or_insert(0.0) += t.elapsed().as_secs_f64();
    let unreached = unreached?;
    if !unreached.is_empty() {
        return Ok(Step::Unreached(unreached));
    }
    let order = order_targets(pipeline, oracle, mission, layout, targets, options, times)?;
    let unreached = unreached_after_failed_legs(oracle, mission, layout, targets, options)?;
    if !unreached.is_empty() {
        return Ok(Step::Unreached(unreached));
    }
    let selected = select_pois(pipeline, oracle, layout, &order, times)?;
    Ok(Step::Selected(order, selected))
}

/// The sequential mode's order of `targets` (sequencer), timed.
fn order_targets(
    pipeline: &Pipeline,
    oracle: &mut PathOracle,
    mission: &Mission,
    layout: &Layout,
    targets: &[usize],
    options: PlanOptions,
    times: &mut BTreeMap<String, f64>,
) -> Result<Vec<usize>> {
    let t = Instant::now();
    pipeline.run().progress.enter("sequencing");
    let order = sequence(
        pipeline,
        oracle,
        mission,
        layout,
        targets,
        options.representative,
        options.sequencing_costs,
        options.refine_legs,
    )?;
    *times.entry("sequencing".to_string()).or_insert(0.0) += t.elapsed().as_secs_f64();
    Ok(order)
}

/// The sequential mode's PoIs along `order` (selector), timed; the selector's own
/// failure is the inner result.
fn select_pois(
    pipeline: &Pipeline,
    oracle: &mut PathOracle,
    layout: &Layout,
    order: &[usize],
    times: &mut BTreeMap<String, f64>,
) -> Result<Result<Selection>> {
    let t = Instant::now();
    pipeline.run().progress.enter("selection");
    let selector = pipeline.selector.as_ref().ok_or(Error::MissingStage {
        stage: "plan".into(),
        needed: "selector",
    })?;
    let problem = SelectionProblem {
        start: layout.start,
        groups: order.iter().map(|&t| layout.pois[t].clone()).collect(),
        end: layout.end,
    };
    let selected = selector.select(oracle, &problem);
    *times.entry("selection".to_string()).or_insert(0.0) += t.elapsed().as_secs_f64();
    Ok(selected)
}

/// Plans the pipeline's mission: sequencing, PoI selection, post-processing, within
/// the options' deadline when they set one (armed on the pipeline's own
/// [`Deadline`](smug_core::deadline::Deadline), which its stages hold).
pub fn plan_mission(pipeline: &mut Pipeline, options: PlanOptions) -> Result<Plan> {
    plan_mission_keeping(pipeline, options, None)
}

/// A mission that ended without a plan: the error, and the counters and timings of the
/// run up to then (paths planned, legs without a path, the planner's counters).
#[derive(Debug)]
pub struct MissionFailed {
    /// Why there is no plan.
    pub error: Error,
    /// The run's statistics when it ended (only `total` and the build stages in
    /// `stage_times_s`; empty when it failed before planning any path).
    pub stats: Box<PlanStats>,
}

/// [`plan_mission`] that, when it fails, also says what the run did up to then.
pub fn plan_mission_reporting(
    pipeline: &mut Pipeline,
    options: PlanOptions,
) -> std::result::Result<Plan, MissionFailed> {
    plan_mission_keeping_reporting(pipeline, options, None)
}

/// [`plan_mission`] serving the pose pairs found in `answers` (paths kept from earlier
/// missions) without planning, and adding to it every exact path it planned (what a
/// [`MissionSession`](crate::MissionSession) remembers between replans).
pub(crate) fn plan_mission_keeping(
    pipeline: &mut Pipeline,
    options: PlanOptions,
    answers: Option<&mut KnownAnswers>,
) -> Result<Plan> {
    plan_mission_keeping_reporting(pipeline, options, answers).map_err(|failed| failed.error)
}

/// [`plan_mission_keeping`] that, when it fails, also says what the run did up to then.
pub(crate) fn plan_mission_keeping_reporting(
    pipeline: &mut Pipeline,
    options: PlanOptions,
    answers: Option<&mut KnownAnswers>,
) -> std::result::Result<Plan, MissionFailed> {
    let Some(seconds) = options.deadline else {
        return plan_unbounded(pipeline, options, answers);
    };
    let built_s: f64 = pipeline.build_times_s.values().sum();
    let deadline = pipeline.run().deadline.clone();
    let _armed = deadline.arm(Some(seconds - built_s));
    match plan_unbounded(pipeline, options, answers) {
        Ok(mut plan) => {
            plan.deadline_reached = deadline.reached();
            Ok(plan)
        }
        Err(MissionFailed { error, stats }) => {
            let error = match error {
                Error::DeadlinePassed { during, .. } => Error::DeadlinePassed { seconds, during },
                // An anytime search cut short can look like a missing path: say what
                // happened.
                _ if deadline.reached() => Error::DeadlinePassed {
                    seconds,
                    during: "path planning".into(),
                },
                other => other,
            };
            Err(MissionFailed { error, stats })
        }
    }
}

/// `selection` with each leg of its route that costs more than its lower bound planned
/// again on the roadmap as grown since (a leg planned early saw a sparser roadmap),
/// cheaper paths kept, and its cost summed anew.
fn refine_route(
    oracle: &mut PathOracle,
    problem: &SelectionProblem,
    selection: Selection,
) -> Result<Selection> {
    let cost = problem.route_cost(&selection.chosen, |a, b| {
        let bound = oracle.lower_bound(a, b);
        if oracle.cost_or_bound(a, b) > bound + 1e-9 * bound.abs().max(1.0) {
            oracle.refine(a, b)?;
        }
        oracle.cost(a, b)
    })?;
    Ok(Selection { cost, ..selection })
}

/// The mission in the options' mode (sequential or joint), without a deadline.
fn plan_unbounded(
    pipeline: &mut Pipeline,
    options: PlanOptions,
    mut answers: Option<&mut KnownAnswers>,
) -> std::result::Result<Plan, MissionFailed> {
    let started = Instant::now();
    let failed = |error| MissionFailed {
        error,
        stats: Box::default(),
    };
    let missing = || Error::MissingStage {
        stage: "plan".into(),
        needed: "world",
    };
    let mission = pipeline.mission.clone().ok_or_else(|| failed(missing()))?;
    let world = pipeline.world.clone().ok_or_else(|| failed(missing()))?;
    let oracle = PathOracle::of_pipeline(pipeline, "plan").map_err(failed)?;
    let known = answers.as_deref_mut().map(std::mem::take);
    let mut oracle = oracle.with_known(known.unwrap_or_default());
    let planned = plan_on_oracle(pipeline, &mut oracle, &mission, &world, options, started)
        .map_err(|error| MissionFailed {
            error,
            stats: Box::new(stats(&oracle, pipeline, run_times(pipeline, started))),
        });
    if let Some(answers) = answers {
        *answers = oracle.take_known_answers();
    }
    // The planner goes back to the pipeline with its roadmap (`--save-roadmap`, a
    // session's next replan), whatever the outcome.
    pipeline.planner = Some(oracle.into_planner());
    planned
}

/// The run's `total` time (planning since `started` and building the stages) and each
/// stage's build time, as `stage_times_s` has them.
fn run_times(pipeline: &Pipeline, started: Instant) -> BTreeMap<String, f64> {
    let mut times = BTreeMap::new();
    times.insert(
        "total".into(),
        started.elapsed().as_secs_f64() + pipeline.build_times_s.values().sum::<f64>(),
    );
    for (stage, s) in &pipeline.build_times_s {
        times.insert(format!("build:{stage}"), *s);
    }
    times
}

/// The mission in the options' mode on `oracle`, its poses not registered yet.
fn plan_on_oracle(
    pipeline: &Pipeline,
    oracle: &mut PathOracle,
    mission: &Mission,
    world: &World,
    options: PlanOptions,
    started: Instant,
) -> Result<Plan> {
    check_selection_size(mission)?;
    let given = pipeline.given_mission.as_ref().unwrap_or(mission);
    let mut layout = register_poses(oracle, mission);
    let mut targets: Vec<usize> = (0..mission.targets.len()).collect();
    let mut skipped = Vec::new();
    let mut times = BTreeMap::new();
    let t = Instant::now();
    pipeline.run().progress.enter("dead ends");
    probe_start_and_end(oracle, &layout, &targets)?;
    let dead_ends = drop_dead_ends(oracle, mission, given, &mut layout, &targets)?;
    if !dead_ends.is_empty() {
        times.insert("dead-ends".to_string(), t.elapsed().as_secs_f64());
        let emptied: Vec<usize> = targets
            .iter()
            .copied()
            .filter(|&t| layout.pois[t].is_empty())
            .collect();
        if !emptied.is_empty() {
            let ids: Vec<String> = emptied
                .iter()
                .map(|&t| mission.targets[t].id.clone())
                .collect();
            if !options.skip_unreachable {
                let why = dead_ends
                    .iter()
                    .filter(|d| ids.contains(&d.target))
                    .map(|d| format!("target `{}` PoI {}: {}", d.target, d.index, d.why))
                    .collect();
                return Err(Error::stage(
                    "plan",
                    Unreachable {
                        targets: ids,
                        why,
                        legs: Vec::new(),
                    },
                ));
            }
            skipped.extend(ids);
            targets.retain(|t| !emptied.contains(t));
        }
    }
    let (order, problem, selection) = loop {
        let (order, selected) = match options.mode {
            PlanMode::Sequential => match order_then_select(
                pipeline, oracle, mission, &layout, &targets, options, &mut times,
            )? {
                Step::Selected(order, selected) => (order, selected),
                Step::Unreached(unreached) => {
                    fail_or_skip(
                        oracle,
                        mission,
                        &layout,
                        &mut targets,
                        &unreached,
                        options.skip_unreachable,
                        &mut skipped,
                    )?;
                    continue;
                }
            },
            PlanMode::Joint => {
                let t = Instant::now();
                pipeline.run().progress.enter("joint order and PoIs");
                let sequencer = pipeline.sequencer.as_ref().ok_or(Error::MissingStage {
                    stage: "plan".into(),
                    needed: "sequencer",
                })?;
                let joint = JointProblem {
                    start: layout.start,
                    groups: targets.iter().map(|&t| layout.pois[t].clone()).collect(),
                    end: mission.end.is_some().then_some(layout.end),
                };
                let (positions, selection) = joint_tour(sequencer.as_ref(), oracle, &joint)?;
                *times.entry("joint".to_string()).or_insert(0.0) += t.elapsed().as_secs_f64();
                let order: Vec<usize> = positions.iter().map(|&k| targets[k]).collect();
                (order, Ok(selection))
            }
        };
        let problem = SelectionProblem {
            start: layout.start,
            groups: order.iter().map(|&t| layout.pois[t].clone()).collect(),
            end: layout.end,
        };
        let selection = match selected {
            Ok(s) if s.cost.is_finite() => s,
            other => {
                let unreachable = unreachable_targets(oracle, &layout, &targets)?;
                if unreachable.is_empty() {
                    if let Some(cut) = end_not_entered(oracle, &layout, &targets)? {
                        return Err(Error::stage("plan", cut));
                    }
                    if let Some(target) = unroutable_target(&other, &order) {
                        return Err(Error::stage(
                            "plan",
                            Unreachable {
                                targets: vec![mission.targets[target].id.clone()],
                                why: vec![format!(
                                    "target `{}`: the start reaches its PoIs, but none of them continues the route in the order chosen (a directed model: a PoI it can enter but not leave, or reach only from some targets)",
                                    mission.targets[target].id
                                )],
                                legs: Vec::new(),
                            },
                        ));
                    }
                    other?;
                    return Err(Error::stage(
                        "plan",
                        Unreachable {
                            targets: vec!["(the end pose)".into()],
                            why: Vec::new(),
                            legs: Vec::new(),
                        },
                    ));
                }
                fail_or_skip(
                    oracle,
                    mission,
                    &layout,
                    &mut targets,
                    &unreachable,
                    options.skip_unreachable,
                    &mut skipped,
                )?;
                continue;
            }
        };
        break (order, problem, selection);
    };
    let selection = if options.refine_legs {
        let t = Instant::now();
        pipeline.run().progress.enter("refining legs");
        let refined = refine_route(oracle, &problem, selection)?;
        times.insert("refine".to_string(), t.elapsed().as_secs_f64());
        refined
    } else {
        selection
    };
    let t = Instant::now();
    pipeline.run().progress.enter("post-processing");
    let route = problem.route(&selection.chosen);
    let mut plan = assemble_plan(oracle, mission, given, &order, &selection.chosen, &route)?;
    let objective = pipeline
        .config
        .objective
        .as_ref()
        .map_or("path-length", |section| section.kind.as_str());
    plan.metrics = plan_metrics(&pipeline.context(), world, objective, &concatenate(&plan).0);
    (plan.waypoints, plan.reversing) = waypoints(&plan, pipeline, world, options.keep_headings);
    plan.cost = selection.cost;
    plan.skipped = skipped;
    plan.dead_ends = dead_ends;
    times.insert("post-processing".into(), t.elapsed().as_secs_f64());
    times.extend(run_times(pipeline, started));
    plan.stats = stats(oracle, pipeline, times);
    Ok(plan)
}
