//! `smug bench team`: team missions (issue 32) planned for the sum of the robots'
//! times and for the makespan, N seeds each: per robot the targets it serves, its cost
//! and time; the team's sum and makespan; and the checks that the makespan plan
//! finishes no later than the sum plan and the sum plan costs no more in total.
//!
//! Both objectives are planned twice: on the same robots' oracles (`shared`: the
//! second objective's routes seed the first's again, so both plans rest on the same
//! planned costs), and each alone as `smug plan` plans it (`alone`: its own roadmaps).

mod report;
mod runs;

use runs::{RobotRun, Run};

use crate::output::ReportArgs;
use smug_app::team::{assemble_team, plan_assembled, TeamPlanned};
use smug_core::{LoadedConfig, TeamObjective, TeamPlan};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `smug bench team`.
#[derive(clap::Args, Debug)]
pub struct BenchTeamArgs {
    /// Team configs to plan.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "configs/lunar-team.toml,configs/indoor-team.toml"
    )]
    configs: Vec<PathBuf>,
    /// Seeds per config (1..=N): new roadmaps (and new LNS runs) per seed.
    #[arg(long, default_value_t = 10)]
    runs: u64,
    /// A new world per seed (default: the world of seed 1 for every run).
    #[arg(long)]
    vary_world: bool,
    /// Plan only on shared oracles (skip the objectives planned alone).
    #[arg(long)]
    shared_only: bool,
    /// `--set`, `--out`, `--json`.
    #[command(flatten)]
    report: ReportArgs,
}

/// Runs `smug bench team`.
pub fn run(args: BenchTeamArgs) -> crate::Result<()> {
    let both = [TeamObjective::Sum, TeamObjective::Makespan];
    let mut set = args.report.set.clone();
    if !args.vary_world {
        set.insert(0, "world.params.seed=1".to_string());
    }
    let mut runs = Vec::new();
    let mut failures = Vec::new();
    for config in &args.configs {
        for seed in 1..=args.runs {
            let mut asked: Vec<(&'static str, Vec<TeamObjective>)> =
                vec![("shared", both.to_vec())];
            if !args.shared_only {
                asked.extend(both.map(|o| ("alone", vec![o])));
            }
            for (how, objectives) in asked {
                match plan_once(config, seed, &set, how, &objectives) {
                    Ok(planned) => runs.extend(planned),
                    Err(err) => failures.push(format!(
                        "{} seed {seed} ({how}): {}",
                        config.display(),
                        smug_app::one_line(&err)
                    )),
                }
            }
        }
    }
    let mut report = report::report(&args.configs, args.runs, &runs);
    if !failures.is_empty() {
        report.push_str("## Runs without a plan\n\n");
        for failure in &failures {
            report.push_str(&format!("- {failure}\n"));
        }
        report.push('\n');
    }
    report.push_str(&format!(
        "Command: `smug bench team --runs {}{}{}`\n",
        args.runs,
        if args.vary_world { " --vary-world" } else { "" },
        if args.shared_only {
            " --shared-only"
        } else {
            ""
        }
    ));
    args.report.write(&report, &runs)?;
    Ok(())
}

/// The team of `config` with `seed` planned for `objectives` on one set of oracles.
fn plan_once(
    config: &std::path::Path,
    seed: u64,
    set: &[String],
    how: &'static str,
    objectives: &[TeamObjective],
) -> crate::Result<Vec<Run>> {
    let context = |e: smug_app::AppError| {
        crate::BenchError::context(format!("{} seed {seed}", config.display()), e)
    };
    let mut overrides = vec![format!("seed={seed}")];
    overrides.extend(set.iter().cloned());
    let loaded = LoadedConfig::from_file(config, &overrides)?;
    let started = Instant::now();
    let team = assemble_team(&loaded).map_err(context)?;
    let outcome = plan_assembled(team, objectives).map_err(context)?;
    let wall_s = started.elapsed().as_secs_f64();
    let Some(TeamPlanned { plans, .. }) = outcome.solved() else {
        return Err(crate::BenchError::invalid(format!(
            "{} seed {seed}: no solution",
            config.display()
        )));
    };
    Ok(plans
        .iter()
        .map(|plan| measure(config, seed, how, plan, wall_s))
        .collect())
}

fn measure(
    config: &std::path::Path,
    seed: u64,
    how: &'static str,
    plan: &TeamPlan,
    wall_s: f64,
) -> Run {
    Run {
        config: config.display().to_string(),
        seed,
        how,
        objective: plan.objective,
        total: plan.total,
        makespan: plan.makespan,
        robots: plan
            .robots
            .iter()
            .map(|r| RobotRun {
                name: r.name.clone(),
                targets: r.plan.sequence.len(),
                cost: r.plan.cost,
                time_s: r.time,
                length_m: r.plan.metrics.length_m,
            })
            .collect(),
        paths_planned: plan.stats.paths_planned,
        rounds: plan.stats.counters.get("team_rounds").copied().unwrap_or(0),
        wall_s,
    }
}
