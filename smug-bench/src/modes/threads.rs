//! `smug bench modes --threads 1,2`: each run again on pools of each thread count; the
//! whole time (building included: the traversability and terrain grids are filled
//! side by side too), the speed-up against the first count, and whether every plan is
//! the first count's (same order, same cost bits).

use super::runs::{Mission, Mode, Run};
use serde::Serialize;

/// One mission × mode at one thread count.
#[derive(Debug, Serialize)]
pub struct ThreadRow {
    /// Mission name.
    pub mission: String,
    /// Mode name.
    pub mode: String,
    /// Threads in the pool.
    pub threads: usize,
    /// Runs that planned.
    pub planned: usize,
    /// Mean whole time (build and planning), seconds.
    pub mean_total_s: f64,
    /// Mean planning time, seconds.
    pub mean_planning_s: f64,
    /// Mean CPU time of the process's threads per run, seconds.
    pub mean_cpu_s: f64,
    /// Mean time the threads waited for a core per run (the machine shared), seconds.
    pub mean_waited_s: f64,
    /// The first count's mean whole time over this one's.
    pub speed_up: f64,
    /// Seeds whose plan (order and cost bits) equals the first count's.
    pub same_plan: usize,
    /// Seeds compared.
    pub seeds: usize,
}

/// The rows of every mission × mode × thread count.
pub fn rows(
    missions: &[&Mission],
    modes: &[&Mode],
    threads: &[usize],
    runs: &[Run],
) -> Vec<ThreadRow> {
    let mut rows = Vec::new();
    for mission in missions {
        for mode in modes {
            let of = |t: usize| -> Vec<&Run> {
                runs.iter()
                    .filter(|r| {
                        r.mission == mission.name && r.mode == mode.name && r.threads == Some(t)
                    })
                    .collect()
            };
            let first = of(threads[0]);
            let base = mean(first.iter().filter_map(|r| r.total_s));
            for &t in threads {
                let these = of(t);
                let same_plan = these
                    .iter()
                    .filter(|r| {
                        first.iter().any(|f| {
                            f.seed == r.seed
                                && f.cost.map(f64::to_bits) == r.cost.map(f64::to_bits)
                                && f.order == r.order
                        })
                    })
                    .count();
                let total = mean(these.iter().filter_map(|r| r.total_s));
                rows.push(ThreadRow {
                    mission: mission.name.into(),
                    mode: mode.name.into(),
                    threads: t,
                    planned: these.iter().filter(|r| r.cost.is_some()).count(),
                    mean_total_s: total,
                    mean_planning_s: mean(these.iter().filter_map(|r| r.planning_s)),
                    mean_cpu_s: mean(these.iter().filter_map(|r| r.cpu_s)),
                    mean_waited_s: mean(these.iter().filter_map(|r| r.waited_s)),
                    speed_up: base / total,
                    same_plan,
                    seeds: these.len(),
                });
            }
        }
    }
    rows
}

/// The report's section.
pub fn section(rows: &[ThreadRow], labels: impl Fn(&str, &str) -> (String, String)) -> String {
    let mut out = String::from(
        "\n## Threads\n\nEach run again on a pool of each thread count (`--threads`), one after another \
         in one process. Whole: the plan's `total` time (building the pipeline included: \
         the traversability and terrain grids are filled side by side too); speed-up: the \
         first count's mean whole time over this one's; CPU: the time the process's \
         threads ran during the run, all threads summed (more than whole: the threads ran \
         side by side); waited: the time they were ready to run while every core was busy \
         with other jobs on the machine (Linux; `–` elsewhere): a speed-up is the cores' \
         only where it is small; same plan: seeds whose order and cost (bit for bit) are \
         the first count's.\n\n\
         | mission | mode | threads | planned | whole (s) | planning (s) | CPU (s) | waited (s) | speed-up | same plan |\n\
         |---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for row in rows {
        let (mission, mode) = labels(&row.mission, &row.mode);
        out.push_str(&format!(
            "| {mission} | {mode} | {} | {} | {:.3} | {:.3} | {} | {} | {:.2}× | {}/{} |\n",
            row.threads,
            row.planned,
            row.mean_total_s,
            row.mean_planning_s,
            seconds_or_dash(row.mean_cpu_s),
            seconds_or_dash(row.mean_waited_s),
            row.speed_up,
            row.same_plan,
            row.seeds
        ));
    }
    out
}

/// Seconds to 3 decimals, `–` when unknown (NaN).
fn seconds_or_dash(s: f64) -> String {
    if s.is_nan() {
        "–".into()
    } else {
        format!("{s:.3}")
    }
}

/// The mean (NaN for none).
fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if n == 0 {
        f64::NAN
    } else {
        sum / n as f64
    }
}
