//! `smug bench validity`: state checks per second and distance-field queries of the
//! volumetric, hierarchical and exact checkers on the same sampled states.

use rand::{Rng, SeedableRng};
use serde::Serialize;
use smug_core::registry::ValidityStage;
use smug_core::rng::StageRng;
use smug_core::{LoadedConfig, Pipeline, PluginSection, Pose2, StateValidityChecker};
use smug_validity::CountingChecker;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

/// Arguments of `smug bench validity`.
#[derive(clap::Args, Debug)]
pub struct BenchValidityArgs {
    /// Pipeline config whose world (and traversability) to use.
    #[arg(long, default_value = "configs/lunar.toml")]
    config: PathBuf,
    /// Override a config key.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Number of sampled states.
    #[arg(long, default_value_t = 20_000)]
    states: usize,
    /// Fraction of the states also checked by the (slow) exact checker.
    #[arg(long, default_value_t = 0.05)]
    exact_fraction: f64,
    /// Seed of the sampled states.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Write the Markdown report here (else stdout only).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write the raw numbers as JSON here (default: beside `--out`, as `.json`).
    #[arg(long)]
    json: Option<PathBuf>,
}

/// One checker's numbers.
#[derive(Debug, Serialize)]
struct Row {
    checker: String,
    states: u64,
    valid: u64,
    seconds: f64,
    checks_per_second: f64,
    esdf_queries: u64,
    queries_per_state: f64,
    traversability_decided: u64,
}

fn checker_section(kind: &str, params: &str) -> crate::Result<PluginSection> {
    let mut section = PluginSection::new("validity", kind);
    section.params = params.parse::<toml::Table>()?;
    Ok(section)
}

fn measure(name: &str, checker: Arc<dyn StateValidityChecker>, states: &[Pose2]) -> Row {
    let counting = CountingChecker::new(checker);
    let started = Instant::now();
    for s in states {
        counting.is_valid(s);
    }
    let seconds = started.elapsed().as_secs_f64();
    let c = counting.counters();
    let get = |k: &str| c.get(k).copied().unwrap_or(0);
    Row {
        checker: name.to_string(),
        states: states.len() as u64,
        valid: get("valid"),
        seconds,
        checks_per_second: states.len() as f64 / seconds.max(1e-12),
        esdf_queries: get("esdf_queries"),
        queries_per_state: get("esdf_queries") as f64 / states.len().max(1) as f64,
        traversability_decided: get("traversability_decided"),
    }
}

/// Runs `smug bench validity`.
pub fn run(args: BenchValidityArgs) -> crate::Result<()> {
    let loaded = LoadedConfig::from_file(&args.config, &args.set)?;
    let pipeline = Pipeline::assemble(&loaded)?;
    let world = pipeline
        .world
        .clone()
        .ok_or_else(|| crate::error::invalid!("{}: no [world]", args.config.display()))?;
    let ctx = pipeline.context();
    let mut rng = StageRng::seed_from_u64(args.seed);
    let b = world.bounds();
    let states: Vec<Pose2> = (0..args.states)
        .map(|_| {
            Pose2::new(
                rng.random_range(b.min[0]..b.max[0]),
                rng.random_range(b.min[1]..b.max[1]),
                rng.random_range(-std::f64::consts::PI..std::f64::consts::PI),
            )
        })
        .collect();
    let mut candidates = vec![
        ("volumetric (full collision)", "volumetric", ""),
        (
            "hierarchical 0.3/0.3",
            "hierarchical",
            "t_low = 0.3\nt_high = 0.3",
        ),
        (
            "hierarchical 0.3/0.8",
            "hierarchical",
            "t_low = 0.3\nt_high = 0.8",
        ),
    ];
    if world.traversability.is_none() {
        candidates.truncate(1);
    }
    let mut rows = Vec::new();
    for (name, kind, params) in candidates {
        let checker: Arc<dyn StateValidityChecker> = ctx
            .build::<ValidityStage>(&checker_section(kind, params)?)?
            .object
            .into();
        rows.push(measure(name, checker, &states));
    }
    let exact_count = ((args.states as f64 * args.exact_fraction) as usize).clamp(1, args.states);
    let exact: Arc<dyn StateValidityChecker> = ctx
        .build::<ValidityStage>(&checker_section("exact", "")?)?
        .object
        .into();
    rows.push(measure(
        "exact (parry3d, subset)",
        exact,
        &states[..exact_count],
    ));

    let report = markdown(&args, &world.name, &rows);
    crate::output::write_report(&report, &rows, args.out.as_deref(), args.json.as_deref())?;
    Ok(())
}

fn markdown(args: &BenchValidityArgs, world: &str, rows: &[Row]) -> String {
    let mut out = format!(
        "# Validity benchmark\n\nWorld `{world}` from `{}`, {} uniformly sampled states (seed {}).\n\n\
         | checker | states | valid | checks/s | ESDF queries/state | decided by traversability | queries vs volumetric |\n\
         |---|---:|---:|---:|---:|---:|---:|\n",
        args.config.display(),
        args.states,
        args.seed
    );
    let baseline = rows.first().map_or(0.0, |r| r.queries_per_state);
    for r in rows {
        let ratio = if baseline > 0.0 {
            format!("{:+.0}%", 100.0 * (r.queries_per_state / baseline - 1.0))
        } else {
            "–".into()
        };
        out += &format!(
            "| {} | {} | {:.1}% | {:.0} | {:.2} | {:.1}% | {} |\n",
            r.checker,
            r.states,
            100.0 * r.valid as f64 / r.states.max(1) as f64,
            r.checks_per_second,
            r.queries_per_state,
            100.0 * r.traversability_decided as f64 / r.states.max(1) as f64,
            ratio
        );
    }
    out
}
