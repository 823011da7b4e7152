//! The report of `smug bench team`: means per objective, each robot's load, the two
//! checks seed by seed.

use super::runs::Run;
use smug_core::TeamObjective;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Slack of the checks (relative): costs equal up to rounding count as equal.
const SLACK: f64 = 1e-9;

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let values: Vec<f64> = values.collect();
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

fn find<'a>(
    runs: &'a [Run],
    config: &str,
    seed: u64,
    how: &str,
    o: TeamObjective,
) -> Option<&'a Run> {
    runs.iter()
        .find(|r| r.config == config && r.seed == seed && r.how == how && r.objective == o)
}

fn loads(run: &Run) -> String {
    run.robots
        .iter()
        .map(|r| r.targets.to_string())
        .collect::<Vec<_>>()
        .join("/")
}

/// The Markdown report.
pub(super) fn report(configs: &[PathBuf], seeds: u64, runs: &[Run]) -> String {
    let mut out = String::from("# Teams: the sum of the robots' times against the makespan\n\n");
    let _ = writeln!(
        out,
        "Each team config planned with seeds 1 to {seeds} (new roadmaps and team-sequencer \
         runs per seed; the world of seed 1 unless `--vary-world`) for both team objectives. `shared`: both objectives on the same robots' \
         oracles, the makespan's routes seeding the sum's again (both plans rest on the same \
         planned costs; the makespan plan's makespan and the sum plan's sum are then each \
         at least as good as the other plan's by construction of the seeding, so the checks \
         test the team sequencer only through the warm starts); `alone`: each objective \
         planned by itself, as `smug plan` does (its own roadmaps: the checks can fail by \
         the noise of the planned costs). Costs and times in seconds (the team unit \
         `time`: every robot at its own speed). Loads: targets per robot in the config's \
         order.\n"
    );
    for config in configs {
        let config = config.display().to_string();
        let robots: Vec<String> = runs
            .iter()
            .find(|r| r.config == config)
            .map(|r| r.robots.iter().map(|x| x.name.clone()).collect())
            .unwrap_or_default();
        let _ = writeln!(out, "## {config} ({})\n", robots.join(", "));
        means(&mut out, runs, &config, &robots);
        checks(&mut out, runs, &config, seeds);
        per_seed(&mut out, runs, &config, seeds);
    }
    out
}

fn means(out: &mut String, runs: &[Run], config: &str, robots: &[String]) {
    out.push_str("| planned | objective | sum s | makespan s |");
    for name in robots {
        let _ = write!(out, " {name}: targets, time s |");
    }
    out.push_str(" paths | rounds | wall s |\n|---|---|---:|---:|");
    out.push_str(&"---:|".repeat(robots.len()));
    out.push_str("---:|---:|---:|\n");
    for how in ["shared", "alone"] {
        for objective in [TeamObjective::Sum, TeamObjective::Makespan] {
            let rows: Vec<&Run> = runs
                .iter()
                .filter(|r| r.config == config && r.how == how && r.objective == objective)
                .collect();
            if rows.is_empty() {
                continue;
            }
            let _ = write!(
                out,
                "| {how} | {objective:?} | {:.2} | {:.2} |",
                mean(rows.iter().map(|r| r.total)),
                mean(rows.iter().map(|r| r.makespan))
            );
            for k in 0..robots.len() {
                let _ = write!(
                    out,
                    " {:.1}, {:.1} |",
                    mean(rows.iter().map(|r| r.robots[k].targets as f64)),
                    mean(rows.iter().map(|r| r.robots[k].time_s))
                );
            }
            let _ = writeln!(
                out,
                " {:.0} | {:.1} | {:.2} |",
                mean(rows.iter().map(|r| r.paths_planned as f64)),
                mean(rows.iter().map(|r| r.rounds as f64)),
                mean(rows.iter().map(|r| r.wall_s))
            );
        }
    }
    out.push('\n');
}

fn checks(out: &mut String, runs: &[Run], config: &str, seeds: u64) {
    for how in ["shared", "alone"] {
        let mut makespan_ok = 0;
        let mut total_ok = 0;
        let mut both = 0;
        for seed in 1..=seeds {
            let (Some(s), Some(m)) = (
                find(runs, config, seed, how, TeamObjective::Sum),
                find(runs, config, seed, how, TeamObjective::Makespan),
            ) else {
                continue;
            };
            both += 1;
            makespan_ok += usize::from(m.makespan <= s.makespan * (1.0 + SLACK));
            total_ok += usize::from(s.total <= m.total * (1.0 + SLACK));
        }
        if both > 0 {
            let _ = writeln!(
                out,
                "- {how}: makespan plan's makespan ≤ sum plan's makespan on {makespan_ok}/{both} \
                 seeds; sum plan's sum ≤ makespan plan's sum on {total_ok}/{both} seeds."
            );
        }
    }
    out.push('\n');
}

fn per_seed(out: &mut String, runs: &[Run], config: &str, seeds: u64) {
    out.push_str("| seed | planned | sum plan: sum, makespan, loads | makespan plan: sum, makespan, loads |\n");
    out.push_str("|---:|---|---|---|\n");
    for seed in 1..=seeds {
        for how in ["shared", "alone"] {
            let (Some(s), Some(m)) = (
                find(runs, config, seed, how, TeamObjective::Sum),
                find(runs, config, seed, how, TeamObjective::Makespan),
            ) else {
                continue;
            };
            let _ = writeln!(
                out,
                "| {seed} | {how} | {:.2}, {:.2}, {} | {:.2}, {:.2}, {} |",
                s.total,
                s.makespan,
                loads(s),
                m.total,
                m.makespan,
                loads(m)
            );
        }
    }
    out.push('\n');
}
