//! `smug sweep`: configs × seeds × a grid of overrides, each run in a process of its
//! own (this binary's hidden `sweep-run`), at most `--jobs` at once, one JSON row per
//! run appended to `--out` as it finishes; runs already there are skipped.

use crate::Outcome;
use anyhow::Context;
use smug_app::sweep::jsonl::{done_runs, RowWriter};
use smug_app::sweep::{parse_grid, parse_seeds, run_one, RunSpec, RunStatus, Sweep, SweepRow};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Mutex};
use std::time::Instant;

/// Arguments of `smug sweep`.
#[derive(clap::Args, Debug)]
pub struct SweepArgs {
    /// The pipeline configs (TOML) to sweep.
    #[arg(required = true, value_name = "CONFIG")]
    configs: Vec<PathBuf>,
    /// The seeds: `1..10` (both ends included), `1,4,9`, or one number.
    #[arg(long, default_value = "1")]
    seeds: String,
    /// A grid axis: a config key and its values, `KEY=V1,V2,…` (values as for
    /// `smug plan --set`; commas inside `[…]`, `{…}` or quotes belong to the value).
    /// Runs cover every combination of the axes; one value fixes a key for every run.
    #[arg(long = "grid", value_name = "KEY=V1,V2")]
    grid: Vec<String>,
    /// How many runs at once, each a process planning on one thread.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..))]
    jobs: u16,
    /// The rows file (JSON lines), appended to as runs finish; runs whose id it already
    /// holds are skipped, so a sweep stopped half-way goes on where it stopped.
    #[arg(long, default_value = "runs.jsonl")]
    out: PathBuf,
}

/// Arguments of the hidden `smug sweep-run` (one run of a sweep, its row on stdout).
#[derive(clap::Args, Debug)]
pub struct SweepRunArgs {
    /// The pipeline config.
    config: PathBuf,
    /// The seed.
    #[arg(long)]
    seed: u64,
    /// The run's overrides, `KEY=VALUE` each.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
}

/// Runs `smug sweep-run`: plans one run on one thread and prints its row.
pub fn run_one_row(args: SweepRunArgs) -> anyhow::Result<Outcome> {
    let spec = RunSpec::new(&args.config, &args.set, args.seed)?;
    println!("{}", run_one(&spec, Some(1)).to_json_line());
    Ok(Outcome::Ok)
}

/// Runs `smug sweep`.
pub fn run(args: SweepArgs) -> anyhow::Result<Outcome> {
    let sweep = Sweep {
        configs: args.configs.clone(),
        seeds: parse_seeds(&args.seeds)?,
        grid: args
            .grid
            .iter()
            .map(String::as_str)
            .map(parse_grid)
            .collect::<Result<_, _>>()?,
    };
    let runs = sweep.runs()?;
    refuse_a_config_as_out(&args.out, &args.configs)?;
    let done = done_runs(&args.out)?;
    if done.unreadable_lines > 0 {
        eprintln!(
            "smug sweep: {}: {} lines are not rows (a sweep stopped while writing?); their runs run again",
            args.out.display(),
            done.unreadable_lines
        );
    }
    let (skipped, todo): (Vec<RunSpec>, Vec<RunSpec>) = runs
        .into_iter()
        .partition(|run| done.ids.contains(&run.run_id));
    eprintln!(
        "smug sweep: {} runs: {} already in {} (skipped), {} to run, {} at once",
        skipped.len() + todo.len(),
        skipped.len(),
        args.out.display(),
        todo.len(),
        usize::from(args.jobs).min(todo.len())
    );
    let mut writer = RowWriter::append_to(&args.out)?;
    let exe = std::env::current_exe().context("cannot find the smug executable to run sweeps")?;
    let started = Instant::now();
    let mut tally = BTreeMap::<&'static str, usize>::new();
    let total = todo.len();
    run_in_processes(&exe, todo, usize::from(args.jobs), |row| {
        writer.write(&row)?;
        *tally.entry(row.status.name()).or_default() += 1;
        let finished: usize = tally.values().sum();
        let width = total.to_string().len();
        eprintln!("[{finished:>width$}/{total}] {}", progress_line(&row));
        Ok(())
    })?;
    let counts: Vec<String> = tally.iter().map(|(s, n)| format!("{n} {s}")).collect();
    eprintln!(
        "smug sweep: {total} runs in {:.1} s{}{}; {} skipped; rows in {}",
        started.elapsed().as_secs_f64(),
        if counts.is_empty() { "" } else { ": " },
        counts.join(", "),
        skipped.len(),
        args.out.display()
    );
    Ok(Outcome::Ok)
}

/// Refuses a rows file that is one of the configs (rows would be appended to it).
fn refuse_a_config_as_out(out: &Path, configs: &[PathBuf]) -> anyhow::Result<()> {
    let Ok(out_real) = out.canonicalize() else {
        return Ok(());
    };
    match configs
        .iter()
        .find(|c| c.canonicalize().is_ok_and(|c| c == out_real))
    {
        Some(config) => anyhow::bail!(
            "{}: is a config of this sweep; choose another --out",
            config.display()
        ),
        None => Ok(()),
    }
}

/// One line of progress: status, id, config, seed, overrides, and the cost or the error.
fn progress_line(row: &SweepRow) -> String {
    let outcome = match (&row.cost, &row.error) {
        (Some(cost), _) => format!("cost {cost:.3}"),
        (None, Some(why)) => why.clone(),
        (None, None) => String::new(),
    };
    format!(
        "{:<11} {} {} seed {} {}: {outcome} ({:.2} s)",
        row.status.name(),
        row.run_id,
        row.config,
        row.seed,
        row.overrides.join(" "),
        row.total_time_s
    )
}

/// Runs `runs` as child processes of `exe`, at most `jobs` at once, handing each row
/// to `take` as its run finishes; an error of `take` stops starting runs and is
/// returned once the running ones end.
fn run_in_processes(
    exe: &Path,
    runs: Vec<RunSpec>,
    jobs: usize,
    mut take: impl FnMut(SweepRow) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let queue = Mutex::new(runs.into_iter());
    let stop = AtomicBool::new(false);
    let (rows, finished) = mpsc::channel::<SweepRow>();
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            let rows = rows.clone();
            let (queue, stop) = (&queue, &stop);
            scope.spawn(move || {
                while !stop.load(Ordering::Relaxed) {
                    let next = queue.lock().unwrap_or_else(|e| e.into_inner()).next();
                    let Some(run) = next else { break };
                    if rows.send(run_in_a_process(exe, &run)).is_err() {
                        break;
                    }
                }
            });
        }
        drop(rows);
        let mut outcome = Ok(());
        for row in finished {
            if outcome.is_ok() {
                outcome = take(row);
                if outcome.is_err() {
                    stop.store(true, Ordering::Relaxed);
                }
            }
        }
        outcome
    })
}

/// Runs `run` as `exe sweep-run …` on one thread and reads its row; a child that
/// fails to start, dies, or prints no row makes an `error` row saying so.
fn run_in_a_process(exe: &Path, run: &RunSpec) -> SweepRow {
    let started = Instant::now();
    let mut command = Command::new(exe);
    command
        .arg("sweep-run")
        .arg(&run.config)
        .arg("--seed")
        .arg(run.seed.to_string())
        .env("RAYON_NUM_THREADS", "1")
        .stdin(Stdio::null());
    for set in &run.overrides {
        command.arg(format!("--set={set}"));
    }
    let failed =
        |why: String| SweepRow::failed(run, RunStatus::Error, why, started.elapsed().as_secs_f64());
    let output = match command.output() {
        Ok(output) => output,
        Err(err) => return failed(format!("cannot start {}: {err}", exe.display())),
    };
    let stdout = String::from_utf8_lossy(&output.stdout);
    match serde_json::from_str::<SweepRow>(stdout.trim()) {
        Ok(row) if output.status.success() => row,
        _ => {
            let stderr = String::from_utf8_lossy(&output.stderr);
            let last = stderr.lines().rev().find(|l| !l.trim().is_empty());
            failed(format!(
                "the run's process ended with {}: {}",
                output.status,
                last.unwrap_or("(nothing on stderr)").trim()
            ))
        }
    }
}
