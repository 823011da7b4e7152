//! `smug plan` and `smug replan` on a team config: one plan per robot, a per-robot
//! summary.

use crate::progress::Progress;
use crate::Outcome;
use smug_app::outputs::{config_run_info, write_no_plan};
use smug_app::plan_mcap::WriteMode;
use smug_app::team::{plan_team_config_with, Team, TeamPlanned};
use smug_app::team_outputs::write_team_outputs;
use smug_app::team_replan::replan_team;
use smug_app::NoPlan;
use smug_core::mission::TeamState;
use smug_core::{LoadedConfig, TeamPlan};
use std::path::{Path, PathBuf};

/// Plans the team of `loaded`, writes its files into `out`, prints plan.json (`json`)
/// or a summary.
pub fn run(
    loaded: &LoadedConfig,
    out: &Path,
    json: bool,
    save_roadmap: Option<&PathBuf>,
) -> anyhow::Result<Outcome> {
    if save_roadmap.is_some() {
        anyhow::bail!("--save-roadmap: a team has one roadmap per robot; not supported yet");
    }
    let progress = Progress::start("assembling the team");
    let outcome = plan_team_config_with(loaded, &mut |team| {
        progress.stage("planning the team");
        progress.follow_team(robot_progress(team));
    });
    progress.finish();
    finish(outcome?, loaded, out, (json, WriteMode::Replace))
}

/// Each robot's name and run progress.
fn robot_progress(team: &Team) -> Vec<(String, smug_core::RunProgress)> {
    team.members
        .iter()
        .map(|m| (m.name.clone(), m.pipeline.run().progress.clone()))
        .collect()
}

/// `smug replan` on a team config: the team state in `state`, the plan written to `out`.
pub fn replan(
    loaded: &LoadedConfig,
    state: &Path,
    out: &Path,
    json: bool,
    roadmap: Option<&PathBuf>,
) -> anyhow::Result<Outcome> {
    if roadmap.is_some() {
        anyhow::bail!("--roadmap: a team has one roadmap per robot; not supported yet");
    }
    let text = std::fs::read_to_string(state)
        .map_err(|e| anyhow::anyhow!("{}: cannot read: {e}", state.display()))?;
    let name = state.display().to_string();
    let state = TeamState::from_toml(&text, &name)?;
    let outcome = replan_team(loaded, &state, Some(&name))?;
    finish(outcome, loaded, out, (json, WriteMode::Append))
}

/// Writes a team plan's files into `out` (plan.mcap as `mode` says) and prints it
/// (`json`) or its summary; no solution is exit 1, with a plan.json that says why (and
/// no other file of an earlier plan left beside it).
fn finish(
    outcome: smug_app::Outcome<TeamPlanned, NoPlan>,
    loaded: &LoadedConfig,
    out: &Path,
    (json, mode): (bool, WriteMode),
) -> anyhow::Result<Outcome> {
    let TeamPlanned { plans, team } = match outcome {
        smug_app::Outcome::Solved(planned) => planned,
        smug_app::Outcome::NoSolution { why } => {
            write_no_plan(&why.report, &loaded.config.output, out, mode)?;
            return Ok(crate::no_solution(why.why));
        }
    };
    let plan = &plans[0];
    if plan.robots.iter().any(|r| r.plan.deadline_reached) {
        eprintln!(
            "smug: the deadline cut a search short: the team plan is complete and valid, the \
             best found by then (each robot marked `deadline_reached` in plan.json)"
        );
    }
    let written = write_team_outputs(
        plan,
        &team.world,
        &team.mission.mission,
        &loaded.config.output,
        out,
        (&config_run_info(&loaded.config, mode), mode),
    )?;
    if json {
        println!("{}", serde_json::to_string_pretty(plan)?);
    } else {
        print_team_summary(plan);
        println!("wrote {}/{}", out.display(), written.join(", "));
    }
    Ok(Outcome::Ok)
}

/// The team's sum and makespan, then one line per robot.
fn print_team_summary(plan: &TeamPlan) {
    let s = &plan.stats;
    println!(
        "team of {} robots, objective {:?} ({}): sum {:.3}, makespan {:.3}; {} paths planned, \
         {} rounds, {:.3} s",
        plan.robots.len(),
        plan.objective,
        plan.unit,
        plan.total,
        plan.makespan,
        s.paths_planned,
        s.counters.get("team_rounds").copied().unwrap_or(0),
        s.stage_times_s.get("total").copied().unwrap_or(0.0),
    );
    if let Some(replan) = &plan.replan {
        if !replan.lost.is_empty() {
            println!(
                "  lost: {} (their targets shared among the others)",
                replan.lost.join(", ")
            );
        }
        for skipped in &replan.skipped {
            println!("  skipped `{}`: {}", skipped.target, skipped.reason);
        }
    }
    let width = plan.robots.iter().map(|r| r.name.len()).max().unwrap_or(0);
    for robot in &plan.robots {
        let p = &robot.plan;
        println!(
            "  {:width$}  {:2} targets, cost {:8.3}, time {:8.3} s, {:.1} m, {} waypoints: {}",
            robot.name,
            p.sequence.len(),
            p.cost,
            robot.time,
            p.metrics.length_m,
            p.waypoints.len(),
            if p.sequence.is_empty() {
                "(stays)".to_string()
            } else {
                p.sequence.join(" → ")
            }
        );
    }
}

/// `smug check` on a team config: the team assembled, each robot's pipeline resolved.
pub fn check(config: &Path, loaded: &LoadedConfig) -> anyhow::Result<Outcome> {
    let team = smug_app::team::assemble_team(loaded)?;
    println!("# {}: configuration is valid", config.display());
    let m = &team.mission.mission;
    println!(
        "# team of {} robots, objective {:?} ({}); world `{}`: {} targets, {} poses of interest",
        team.members.len(),
        team.objective,
        team.mission.unit,
        team.world.name,
        m.targets.len(),
        m.poi_count()
    );
    for member in &team.members {
        println!("\n# robot `{}`", member.name);
        print!("{}", member.pipeline.resolved_toml());
    }
    Ok(Outcome::Ok)
}
