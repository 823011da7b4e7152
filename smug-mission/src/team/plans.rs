//! A team solution turned into one plan per robot: its legs from its own oracle (the
//! paths planned for the matrix), its waypoints from its own model, its metrics and time.

use super::member::TeamMember;
use super::robots::{Nodes, RobotOracle};
use crate::assembly::{assemble_plan, stats};
use crate::evaluation::plan_metrics;
use crate::post_process::{concatenate, waypoints};
use smug_core::error::Result;
use smug_core::mission::Mission;
use smug_core::plan::{Plan, RobotPlan};
use smug_core::pose::Waypoint;
use smug_core::stages::Visit;
use smug_core::world::World;
use std::collections::BTreeMap;

/// What every robot's plan is made from.
pub(super) struct PlanInputs<'a> {
    /// The shared nodes.
    pub(super) nodes: &'a Nodes,
    /// The shared mission (as given).
    pub(super) mission: &'a Mission,
    /// The world.
    pub(super) world: &'a World,
    /// Keep the roadmap's headings (`[plan] keep_headings`).
    pub(super) keep_headings: bool,
}

/// Robot `member`'s plan along `route` at `cost` (its route's cost in the team problem).
pub(super) fn robot_plan(
    robot: &mut RobotOracle,
    member: &TeamMember,
    route: &[Visit],
    cost: f64,
    inputs: &PlanInputs<'_>,
) -> Result<RobotPlan> {
    let PlanInputs {
        nodes,
        mission,
        world,
        keep_headings,
    } = *inputs;
    let own = Mission {
        start: member.start,
        end: member.end,
        targets: mission.targets.clone(),
    };
    let order: Vec<usize> = route
        .iter()
        .map(|v| nodes.poi_of(v.node).map_or(v.target, |(t, _)| t))
        .collect();
    let local = |node: usize| robot.local[node].expect("a route uses its robot's nodes");
    let chosen: Vec<usize> = route.iter().map(|v| local(v.node)).collect();
    let mut stops = vec![local(robot.start)];
    stops.extend(&chosen);
    stops.push(local(robot.end));
    let mut plan = if route.is_empty() && robot.start == robot.end {
        Plan {
            waypoints: vec![Waypoint::from_pose(
                &member.start,
                world
                    .height_at(member.start.x, member.start.y)
                    .unwrap_or(f64::NAN),
            )],
            ..Plan::default()
        }
    } else {
        assemble_plan(&mut robot.oracle, &own, mission, &order, &chosen, &stops)?
    };
    let pipeline = &member.pipeline;
    let objective = pipeline
        .config
        .objective
        .as_ref()
        .map_or("path-length", |section| section.kind.as_str());
    let states = concatenate(&plan).0;
    plan.metrics = plan_metrics(&pipeline.context(), world, objective, &states);
    if plan.segments.is_empty() {
        // A robot that stays (an empty sum is -0.0).
        plan.metrics.length_m = 0.0;
        plan.metrics.climb_m = 0.0;
    } else {
        (plan.waypoints, plan.reversing) = waypoints(&plan, pipeline, world, keep_headings);
    }
    plan.cost = cost;
    plan.stats = stats(&robot.oracle, pipeline, BTreeMap::new());
    let time = match &member.time {
        Some(time) if states.len() > 1 => time.path_cost(&states),
        Some(_) => 0.0,
        None => cost,
    };
    Ok(RobotPlan {
        name: member.name.clone(),
        time,
        plan,
    })
}
