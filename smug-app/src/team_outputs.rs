//! The files of a team plan: plan.json (one entry per robot, the team's sum and
//! makespan), plan.csv (a `robot` column) and plan.svg (one colour per robot), as the
//! config's `[output]` asks, and plan.mcap (each robot on topics of its own).

use crate::outputs::{file_writer, push_waypoint_rows};
use crate::plan_mcap::{write_team_plan_mcap, RunInfo, TeamScene, WriteMode};
use crate::Result;
use smug_core::config::OutputConfig;
use smug_core::{Mission, TeamPlan, World};
use smug_worlds::render::{render_svg, RenderOptions};
use std::path::Path;

/// The colours of the robots' paths in plan.svg, in the team's order (then again).
pub const ROBOT_COLOURS: [&str; 6] = [
    "#1f77b4", "#d62728", "#9467bd", "#ff7f0e", "#17becf", "#e377c2",
];

/// Writes `plan` into `dir` (plan.json, plan.csv, plan.svg, plan.mcap, as `output`
/// asks; `run` for plan.mcap's metadata, a replan appended as `mode` says), each file
/// whole or not at all.
pub fn write_team_outputs(
    plan: &TeamPlan,
    world: &World,
    mission: &Mission,
    output: &OutputConfig,
    dir: &Path,
    (run, mode): (&RunInfo, WriteMode),
) -> Result<Vec<&'static str>> {
    let write = file_writer(dir)?;
    let mut written = Vec::new();
    if output.json {
        write("plan.json", serde_json::to_string_pretty(plan)?)?;
        written.push("plan.json");
    }
    if output.csv {
        write("plan.csv", team_csv(plan))?;
        written.push("plan.csv");
    }
    if output.svg {
        let options = team_render_options(plan, world, mission);
        write("plan.svg", render_svg(world, Some(mission), &options))?;
        written.push("plan.svg");
    }
    if output.mcap {
        let scene = TeamScene {
            plan,
            world,
            mission,
        };
        write_team_plan_mcap(&dir.join("plan.mcap"), &scene, run, mode)?;
        written.push("plan.mcap");
    }
    Ok(written)
}

/// `plan.csv` of a team: `robot,x,y,z,yaw` per waypoint, robot after robot, and a
/// `reversing` column (0/1) when some robot ever drives backwards.
pub fn team_csv(plan: &TeamPlan) -> String {
    let gears = plan.robots.iter().any(|r| !r.plan.reversing.is_empty());
    let mut csv = String::from(if gears {
        "robot,x,y,z,yaw,reversing\n"
    } else {
        "robot,x,y,z,yaw\n"
    });
    for robot in &plan.robots {
        push_waypoint_rows(&mut csv, &format!("{},", robot.name), &robot.plan, gears);
    }
    csv
}

/// How plan.svg draws a team plan: one path per robot in its colour, the chosen PoIs,
/// a title with the team's sum and makespan.
pub fn team_render_options(plan: &TeamPlan, world: &World, mission: &Mission) -> RenderOptions {
    let highlighted = plan
        .robots
        .iter()
        .flat_map(|r| &r.plan.pois)
        .filter_map(|c| {
            let t = mission.targets.iter().position(|t| t.id == c.target)?;
            Some((t, c.index))
        })
        .collect();
    let names: Vec<String> = plan
        .robots
        .iter()
        .enumerate()
        .map(|(r, robot)| {
            format!(
                "{} ({}, {})",
                robot.name,
                ROBOT_COLOURS[r % ROBOT_COLOURS.len()],
                robot.plan.sequence.len()
            )
        })
        .collect();
    RenderOptions {
        title: Some(format!(
            "{}: team {:?}, sum {:.2}, makespan {:.2} ({}); {}",
            world.name,
            plan.objective,
            plan.total,
            plan.makespan,
            plan.unit,
            names.join(", ")
        )),
        paths: plan
            .robots
            .iter()
            .map(|r| r.plan.waypoints.iter().map(|w| [w.x, w.y]).collect())
            .collect(),
        path_colours: (0..plan.robots.len())
            .map(|r| ROBOT_COLOURS[r % ROBOT_COLOURS.len()].to_string())
            .collect(),
        highlighted_pois: highlighted,
        ..RenderOptions::default()
    }
}
