//! `smug bench modes`' summaries (per mission and mode; joint minus sequential per
//! seed) and its Markdown report.

use super::runs::{Mission, Mode, Polygons, Run, POLYGON_SET};
use serde::Serialize;
use std::fmt::Write as _;

/// One mission in one mode, over the seeds whose plan succeeded.
#[derive(Debug, Serialize)]
pub struct ModeRow {
    /// The mission's name.
    pub mission: String,
    /// The mode's name.
    pub mode: String,
    /// Runs (seeds).
    pub runs: usize,
    /// Runs whose planning failed.
    pub failures: usize,
    /// Mean cost.
    pub mean_cost: Option<f64>,
    /// Highest cost.
    pub worst_cost: Option<f64>,
    /// Mean paths planned.
    pub mean_paths_planned: Option<f64>,
    /// Mean planning time (without build times), seconds.
    pub mean_planning_s: Option<f64>,
}

/// One mode minus another on one mission, per seed where both planned (joint minus
/// each sequential mode, lazy minus full).
#[derive(Debug, Serialize)]
pub struct Difference {
    /// The mission's name.
    pub mission: String,
    /// The mode whose cost comes first (`joint` or `lazy`).
    pub mode: String,
    /// The mode subtracted (`full` or `lazy`).
    pub against: String,
    /// `(seed, the mode's cost − the other mode's cost)`.
    pub per_seed: Vec<(u64, f64)>,
    /// Mean difference.
    pub mean: Option<f64>,
    /// Largest difference (the mode's worst showing).
    pub worst: Option<f64>,
    /// Seeds on which the mode is strictly cheaper.
    pub cheaper: usize,
    /// Seeds on which both chose the same target order (or, on a closed tour, the same
    /// order backwards).
    pub same_order: usize,
}

/// Everything the report shows besides the failures.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// One row per mission and mode.
    pub modes: Vec<ModeRow>,
    /// Joint against each sequential mode and lazy against full, per mission (when
    /// both ran).
    pub differences: Vec<Difference>,
}

impl Summary {
    /// Summarises `runs` of `missions` in `modes`.
    pub fn of(missions: &[&Mission], modes: &[&Mode], runs: &[Run]) -> Self {
        let mut rows = Vec::new();
        let mut differences = Vec::new();
        let has = |name: &str| modes.iter().any(|m| m.name == name);
        for mission in missions {
            for mode in modes {
                rows.push(mode_row(mission.name, mode.name, runs));
            }
            for (mode, against) in [
                ("joint", "full"),
                ("joint", "lazy"),
                ("lazy", "full"),
                ("lazy-unsettled", "full"),
            ] {
                if has(mode) && has(against) {
                    differences.push(difference(mission, mode, against, runs));
                }
            }
        }
        Self {
            modes: rows,
            differences,
        }
    }
}

fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

fn max(values: &[f64]) -> Option<f64> {
    values.iter().copied().reduce(f64::max)
}

fn mode_row(mission: &str, mode: &str, runs: &[Run]) -> ModeRow {
    let all: Vec<&Run> = runs
        .iter()
        .filter(|r| r.mission == mission && r.mode == mode)
        .collect();
    let ok: Vec<&Run> = all.iter().copied().filter(|r| r.error.is_none()).collect();
    let values =
        |f: fn(&Run) -> Option<f64>| -> Vec<f64> { ok.iter().filter_map(|r| f(r)).collect() };
    let costs = values(|r| r.cost);
    ModeRow {
        mission: mission.into(),
        mode: mode.into(),
        runs: all.len(),
        failures: all.len() - ok.len(),
        mean_cost: mean(&costs),
        worst_cost: max(&costs),
        mean_paths_planned: mean(&values(|r| r.paths_planned.map(|p| p as f64))),
        mean_planning_s: mean(&values(|r| r.planning_s)),
    }
}

fn run_of<'a>(runs: &'a [Run], mission: &str, mode: &str, seed: u64) -> Option<&'a Run> {
    runs.iter()
        .find(|r| r.mission == mission && r.mode == mode && r.seed == seed && r.cost.is_some())
}

fn difference(mission: &Mission, mode: &str, against: &str, runs: &[Run]) -> Difference {
    let closed = !matches!(mission.polygons, Some(Polygons::Data { open: true }));
    let pairs: Vec<(&Run, &Run)> = runs
        .iter()
        .filter(|r| r.mission == mission.name && r.mode == mode && r.cost.is_some())
        .filter_map(|r| Some((r, run_of(runs, mission.name, against, r.seed)?)))
        .collect();
    let per_seed: Vec<(u64, f64)> = pairs
        .iter()
        .filter_map(|(r, o)| Some((r.seed, r.cost? - o.cost?)))
        .collect();
    let same = |a: &[String], b: &[String]| a == b || (closed && a.iter().eq(b.iter().rev()));
    let diffs: Vec<f64> = per_seed.iter().map(|&(_, d)| d).collect();
    Difference {
        mission: mission.name.into(),
        mode: mode.into(),
        against: against.into(),
        mean: mean(&diffs),
        worst: max(&diffs),
        cheaper: diffs.iter().filter(|&&d| d < 0.0).count(),
        same_order: pairs
            .iter()
            .filter(|(r, o)| same(&r.order, &o.order))
            .count(),
        per_seed,
    }
}

fn cell(value: Option<f64>, digits: usize) -> String {
    value.map_or("–".into(), |v| format!("{v:.digits$}"))
}

fn signed(value: Option<f64>) -> String {
    value.map_or("–".into(), |v| format!("{v:+.2}"))
}

fn label<'a>(missions: &[&'a Mission], name: &str) -> &'a str {
    missions
        .iter()
        .find(|m| m.name == name)
        .map_or("?", |m| m.label)
}

/// The Markdown report.
pub fn report(
    missions: &[&Mission],
    modes: &[&Mode],
    seeds: u64,
    set: &[String],
    summary: &Summary,
    runs: &[Run],
) -> String {
    let mut md = intro(missions, modes, seeds, set);
    md.push_str(
        "| mission | mode | runs | failures | mean cost | worst cost | paths planned | planning (s) |\n\
         |---|---|---:|---:|---:|---:|---:|---:|\n",
    );
    for row in &summary.modes {
        let mode = mode_label(modes, &row.mode);
        let _ = writeln!(
            md,
            "| {} | {mode} | {} | {} | {} | {} | {} | {} |",
            label(missions, &row.mission),
            row.runs,
            row.failures,
            cell(row.mean_cost, 2),
            cell(row.worst_cost, 2),
            cell(row.mean_paths_planned, 1),
            cell(row.mean_planning_s, 3),
        );
    }
    differences(&mut md, missions, summary);
    failures(&mut md, runs);
    md
}

fn mode_label<'a>(modes: &[&'a Mode], name: &str) -> &'a str {
    modes
        .iter()
        .find(|m| m.name == name)
        .map_or("?", |m| m.label)
}

fn intro(missions: &[&Mission], modes: &[&Mode], seeds: u64, set: &[String]) -> String {
    let mut md = format!(
        "# Planning modes (`smug bench modes`, seeds 1..={seeds})\n\n\
         Each mission planned in each mode with seeds 1 to {seeds} (the seed sets the world \
         and the planner). Cost: the plan's cost; paths planned: the plan's \
         `stats.paths_planned`; planning: the plan's `total` time minus the pipeline's \
         build times, seconds. Means and worst (highest) cost over the runs that planned; \
         failed runs are counted and listed below.\n\n"
    );
    md.push_str("Missions (`--missions`) and modes (`--modes`), with their overrides:\n\n");
    for mission in missions {
        if let Some(polygons) = mission.polygons {
            let source = match polygons {
                Polygons::Generated(_) => {
                    "a map generated for each seed (28 star-shaped \
                                           polygons of 5–8 corners, 60–180 cells across; \
                                           cities ≥ 4 cells from them; the first city is \
                                           the start)"
                }
                Polygons::Data { .. } => "the `--data` file",
            };
            let _ = writeln!(
                md,
                "- `{}`: {}: {source}, rasterised to 2000 × 2000 cells (of 1 m on a generated map), one PoI \
                 per city; `configs/p2p-grid.toml` with the `auto` sequencer, the `idp` \
                 selector and `{}`",
                mission.name,
                mission.label,
                POLYGON_SET.join("`, `")
            );
            continue;
        }
        let set = if mission.set.is_empty() {
            String::new()
        } else {
            format!(" with `{}`", mission.set.join("`, `"))
        };
        let _ = writeln!(
            md,
            "- `{}`: {}: `{}`{set}",
            mission.name, mission.label, mission.config
        );
    }
    for mode in modes {
        let _ = writeln!(
            md,
            "- `{}`: {}: `{}`",
            mode.name,
            mode.label,
            mode.set.join("`, `")
        );
    }
    if !set.is_empty() {
        let _ = writeln!(md, "- every run: `{}`", set.join("`, `"));
    }
    md.push('\n');
    md
}

fn differences(md: &mut String, missions: &[&Mission], summary: &Summary) {
    if summary.differences.is_empty() {
        return;
    }
    md.push_str(
        "\nOne mode minus another, per seed where both planned: mean, worst (largest) \
         difference, the seeds on which the first is cheaper, and the seeds on which both \
         chose the same target order (on a closed tour, or the same order backwards).\n\n\
         | mission | difference | seeds | mean | worst | cheaper | same order |\n\
         |---|---|---:|---:|---:|---:|---:|\n",
    );
    for d in &summary.differences {
        let _ = writeln!(
            md,
            "| {} | {} − {} | {} | {} | {} | {}/{} | {}/{} |",
            label(missions, &d.mission),
            d.mode,
            d.against,
            d.per_seed.len(),
            signed(d.mean),
            signed(d.worst),
            d.cheaper,
            d.per_seed.len(),
            d.same_order,
            d.per_seed.len(),
        );
    }
}

fn failures(md: &mut String, runs: &[Run]) {
    let failed: Vec<&Run> = runs.iter().filter(|r| r.error.is_some()).collect();
    if failed.is_empty() {
        return;
    }
    md.push_str("\nFailures:\n\n");
    for r in failed {
        let _ = writeln!(
            md,
            "- {} / {} / seed {}: {}",
            r.mission,
            r.mode,
            r.seed,
            r.error.as_deref().unwrap_or_default()
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modes::runs::{MISSIONS, MODES};

    fn run(mode: &str, seed: u64, cost: Option<f64>) -> Run {
        Run {
            mission: "lunar".into(),
            mode: mode.into(),
            seed,
            cost,
            paths_planned: cost.map(|_| 10),
            planning_s: cost.map(|_| 0.5),
            order: vec!["a".into(), "b".into()],
            error: cost.is_none().then(|| "no safe path".into()),
            total_s: cost.map(|_| 0.6),
            threads: None,
            cpu_s: None,
            waited_s: None,
        }
    }

    #[test]
    fn a_failed_run_is_counted_listed_and_left_out_of_the_differences() {
        let runs = [
            run("full", 1, Some(10.0)),
            run("full", 2, None),
            run("joint", 1, Some(9.0)),
            run("joint", 2, Some(12.0)),
        ];
        let missions = [&MISSIONS[0]];
        let modes = [&MODES[0], &MODES[3]];
        let summary = Summary::of(&missions, &modes, &runs);
        let full = &summary.modes[0];
        assert_eq!((full.runs, full.failures), (2, 1));
        assert_eq!(full.mean_cost, Some(10.0));
        let joint = &summary.modes[1];
        assert_eq!(
            (joint.mean_cost, joint.worst_cost),
            (Some(10.5), Some(12.0))
        );
        assert_eq!(summary.differences.len(), 1);
        let d = &summary.differences[0];
        assert_eq!(d.per_seed, [(1, -1.0)]);
        assert_eq!((d.cheaper, d.same_order), (1, 1));
        let md = report(&missions, &modes, 2, &[], &summary, &runs);
        assert!(
            md.contains("| lunar 13×10 | sequential, full matrix | 2 | 1 | 10.00 |"),
            "{md}"
        );
        assert!(md.contains("- lunar / full / seed 2: no safe path"), "{md}");
    }
}
