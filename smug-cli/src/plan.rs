//! `smug plan`: the whole mission, from a config to plan.json, plan.csv, plan.svg and plan.mcap.

use crate::progress::Progress;
use crate::Outcome;
use smug_app::outputs::{plan_json, refuse_overwriting_inputs, write_no_plan, write_outputs};
use smug_app::plan_mcap::WriteMode;
use smug_app::Planned;
use smug_core::{Pipeline, Plan};
use std::path::{Path, PathBuf};

/// Arguments of `smug plan`.
#[derive(clap::Args, Debug)]
pub struct PlanArgs {
    /// The pipeline config (TOML).
    config: PathBuf,
    /// Override a config key (see `smug check --help`).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Override the config's seed.
    #[arg(long)]
    seed: Option<u64>,
    /// Seconds after which searches stop with their best result and no new path is
    /// planned (sets `plan.deadline`): a complete plan found by then is written and
    /// marked `deadline_reached`, else smug exits 1 saying so.
    #[arg(long, value_name = "SECONDS")]
    deadline: Option<String>,
    /// Output directory for plan.json, plan.csv, plan.svg and plan.mcap (default: the config's
    /// `output.dir`, else `out`).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print plan.json to stdout instead of a summary.
    #[arg(long)]
    json: bool,
    /// After the mission, save the planner's roadmap (vertices, edges, check status,
    /// costs, answered queries) to FILE, for `smug replan --roadmap FILE`.
    #[arg(long, value_name = "FILE")]
    save_roadmap: Option<PathBuf>,
}

/// Runs `smug plan`.
pub fn run(args: PlanArgs) -> anyhow::Result<Outcome> {
    let mut set = args.set.clone();
    if let Some(seconds) = &args.deadline {
        set.push(format!("plan.deadline={seconds}"));
    }
    let loaded = smug_app::load_config(&args.config, &set, args.seed)?;
    let out = args
        .out
        .clone()
        .or_else(|| loaded.config.output.dir.clone())
        .unwrap_or_else(|| PathBuf::from("out"));
    refuse_overwriting_inputs(&out, &loaded, &[])?;
    if smug_app::team::is_team(&loaded) {
        return crate::team::run(&loaded, &out, args.json, args.save_roadmap.as_ref());
    }
    let progress = Progress::start("building the world and the checkers");
    let pipeline = smug_app::plan::assemble(&loaded, None, None)?;
    progress.stage("planning");
    progress.follow(&pipeline.run().progress);
    let planned = smug_app::plan::plan_config_pipeline(&loaded, pipeline);
    progress.finish();
    let Planned {
        plan,
        pipeline,
        world,
    } = match planned? {
        smug_app::Outcome::Solved(planned) => planned,
        smug_app::Outcome::NoSolution { why } => {
            write_no_plan(&why.report, &loaded.config.output, &out, WriteMode::Replace)?;
            return Ok(crate::no_solution(why.why));
        }
    };
    if plan.deadline_reached {
        eprintln!(
            "smug: the deadline cut a search short: the plan is complete and valid, the best \
             found by then (marked `deadline_reached` in plan.json)"
        );
    }
    write_outputs(&plan, &pipeline, &out, WriteMode::Replace)?;
    if let Some(file) = &args.save_roadmap {
        smug_app::save_roadmap(&pipeline, &loaded, &world, file)?;
    }
    if args.json {
        println!("{}", plan_json(&plan)?);
    } else {
        print_summary(&plan, &pipeline, &out);
    }
    Ok(Outcome::Ok)
}

pub(crate) fn print_summary(plan: &Plan, pipeline: &Pipeline, out: &Path) {
    let s = &plan.stats;
    let b = &s.breakdown;
    println!(
        "planned {} targets, cost {:.3}, {} waypoints; {} paths planned, {} validity queries",
        plan.sequence.len(),
        plan.cost,
        plan.waypoints.len(),
        s.paths_planned,
        s.validity_queries
    );
    let stage = |name: &str| s.stage_times_s.get(name).copied().unwrap_or(0.0);
    // The joint mode has one stage where the sequential mode has two.
    let mut stages = match s.stage_times_s.get("joint") {
        Some(joint) => format!("joint {joint:.3}"),
        None => format!(
            "sequencing {:.3}, selection {:.3}",
            stage("sequencing"),
            stage("selection")
        ),
    };
    if let Some(refine) = s.stage_times_s.get("refine") {
        stages.push_str(&format!(", refine {refine:.3}"));
    }
    println!(
        "time {:.3} s ({stages}); planner: A* {:.3}, sampling {:.3}, edge checking {:.3}, vertex checking {:.3}, misc {:.3}",
        stage("total"),
        b.astar_s,
        b.sampling_s,
        b.edge_checking_s,
        b.vertex_checking_s,
        b.misc_s
    );
    if !plan.skipped.is_empty() {
        println!("skipped unreachable targets: {}", plan.skipped.join(", "));
    }
    if !pipeline.dropped_pois.is_empty() {
        println!(
            "{} PoIs were not valid for the robot and were left out",
            pipeline.dropped_pois.len()
        );
    }
    if !plan.dead_ends.is_empty() {
        eprintln!(
            "{} PoIs are dead ends for the robot and were left out (plan.json `dead_ends`):",
            plan.dead_ends.len()
        );
        for d in &plan.dead_ends {
            eprintln!("  target `{}` PoI {}: {}", d.target, d.index, d.why);
        }
    }
    if !s.legs_without_path.is_empty() {
        let counts: Vec<String> = s
            .legs_without_path
            .iter()
            .map(|(why, n)| format!("{n} {why}"))
            .collect();
        eprintln!("pose pairs without a path: {}", counts.join(", "));
    }
    println!("order: {}", plan.sequence.join(" → "));
    println!(
        "wrote {}/plan.json, plan.csv, plan.svg, plan.mcap",
        out.display()
    );
}
