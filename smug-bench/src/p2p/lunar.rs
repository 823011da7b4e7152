//! The lunar part of `smug bench p2p`: seeded PoI-to-PoI queries on the lunar world,
//! in order, on one shared roadmap — time per query, cost, and the planner's breakdown.

use rand::{Rng, SeedableRng};
use serde::Serialize;
use smug_core::{LoadedConfig, Pipeline, PlannerOutcome, PlannerStats, Pose2};
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

/// The lunar benchmark's numbers.
#[derive(Debug, Serialize)]
pub struct LunarResult {
    /// The config the world and planner came from.
    pub config: String,
    /// Queries planned.
    pub queries: usize,
    /// Queries with an exact solution.
    pub solved: usize,
    /// Mean wall time per query, seconds.
    pub mean_time_s: f64,
    /// Median wall time per query, seconds.
    pub median_time_s: f64,
    /// Slowest query, seconds.
    pub max_time_s: f64,
    /// Mean cost of the solved queries.
    pub mean_cost: f64,
    /// Mean straight-line (metric) lower bound of the solved queries.
    pub mean_lower_bound: f64,
    /// Each query's time, seconds, in order.
    pub times_s: Vec<f64>,
    /// The planner's statistics after all queries (breakdown, counters, roadmap size).
    pub planner: PlannerStats,
}

/// `count` seeded PoI pairs from different targets (PoIs the checkers accept).
fn poi_pairs(pipeline: &Pipeline, count: usize, seed: u64) -> crate::Result<Vec<(Pose2, Pose2)>> {
    let mission = pipeline
        .mission
        .as_ref()
        .ok_or_else(|| crate::error::invalid!("the config has no world with a mission"))?;
    let pois: Vec<(usize, Pose2)> = mission
        .targets
        .iter()
        .enumerate()
        .flat_map(|(t, target)| target.pois.iter().map(move |p| (t, *p)))
        .collect();
    if mission.targets.len() < 2 {
        crate::error::bail!("the lunar benchmark needs at least two targets");
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut pairs = Vec::with_capacity(count);
    while pairs.len() < count {
        let a = pois[rng.random_range(0..pois.len())];
        let b = pois[rng.random_range(0..pois.len())];
        if a.0 != b.0 {
            pairs.push((a.1, b.1));
        }
    }
    Ok(pairs)
}

/// Plans `count` PoI-to-PoI queries on the world of `config`, on one shared roadmap.
pub fn run(config: &Path, set: &[String], count: usize) -> crate::Result<LunarResult> {
    let loaded = LoadedConfig::from_file(config, set)?;
    let mut pipeline = Pipeline::assemble(&loaded)?;
    let pairs = poi_pairs(&pipeline, count, loaded.config.seed)?;
    let objective = pipeline.objective.clone();
    let planner = pipeline
        .planner
        .as_mut()
        .ok_or_else(|| crate::error::invalid!("{}: no planner", config.display()))?;
    let (mut times, mut solved, mut cost, mut bound) = (Vec::new(), 0, 0.0, 0.0);
    for (start, goal) in &pairs {
        let t = Instant::now();
        let outcome = planner.plan(start, goal)?;
        times.push(t.elapsed().as_secs_f64());
        if let PlannerOutcome::Exact(path) = outcome {
            solved += 1;
            cost += path.cost;
            bound += objective.cost_bound(start, goal);
        }
    }
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    Ok(LunarResult {
        config: config.display().to_string(),
        queries: pairs.len(),
        solved,
        mean_time_s: times.iter().sum::<f64>() / times.len().max(1) as f64,
        median_time_s: sorted.get(sorted.len() / 2).copied().unwrap_or(0.0),
        max_time_s: sorted.last().copied().unwrap_or(0.0),
        mean_cost: cost / solved.max(1) as f64,
        mean_lower_bound: bound / solved.max(1) as f64,
        times_s: times,
        planner: planner.stats(),
    })
}

/// The lunar section of the report.
pub fn markdown(r: &LunarResult) -> String {
    let b = &r.planner.breakdown;
    let per_query = |s: f64| 1e3 * s / r.queries.max(1) as f64;
    let mut md = format!(
        "## Lunar world: {} PoI-to-PoI queries on one roadmap ({})\n\n\
         | solved | mean time / query (ms) | median (ms) | max (ms) | mean cost | mean lower bound | roadmap vertices |\n\
         |---:|---:|---:|---:|---:|---:|---:|\n\
         | {}/{} | {:.2} | {:.2} | {:.1} | {:.3} | {:.3} | {} |\n\n",
        r.queries,
        r.config,
        r.solved,
        r.queries,
        1e3 * r.mean_time_s,
        1e3 * r.median_time_s,
        1e3 * r.max_time_s,
        r.mean_cost,
        r.mean_lower_bound,
        r.planner.vertices
    );
    let _ = writeln!(
        md,
        "Breakdown per query (ms): A* {:.2}, sampling {:.2}, edge checking {:.2}, vertex checking {:.2}, misc {:.2}.\n",
        per_query(b.astar_s),
        per_query(b.sampling_s),
        per_query(b.edge_checking_s),
        per_query(b.vertex_checking_s),
        per_query(b.misc_s)
    );
    md
}
