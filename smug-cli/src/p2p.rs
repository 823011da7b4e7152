//! `smug p2p`: point-to-point queries, in order, on one shared roadmap.

use crate::Outcome;
use smug_app::p2p::{P2pPlanner, P2pRequest, P2pWorld};
use std::path::PathBuf;

/// Arguments of `smug p2p`.
#[derive(clap::Args, Debug)]
pub struct P2pArgs {
    /// The map (ROS map_server-style YAML); absent: the config's world.
    #[arg(long)]
    map: Option<PathBuf>,
    /// Queries, one `sx,sy,syaw,gx,gy,gyaw` per row (a header row is allowed).
    #[arg(long)]
    queries: PathBuf,
    /// Pipeline config for the planner and validity checker (default:
    /// `configs/p2p-grid.toml`, a disc robot on an occupancy grid).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Override a config key.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Use this validity checker (e.g. `clearance-2d`).
    #[arg(long)]
    validity: Option<String>,
    /// Disc radius for `--validity clearance-2d`, metres.
    #[arg(long)]
    radius: Option<f64>,
    /// Obstacle height of imported maps, metres.
    #[arg(long, default_value_t = 2.0)]
    obstacle_height: f64,
    /// Where to write results.json.
    #[arg(long)]
    out: Option<PathBuf>,
}

fn overrides(args: &P2pArgs) -> Vec<String> {
    let mut set = args.set.clone();
    if let Some(kind) = &args.validity {
        set.push(format!("validity.type={kind}"));
    }
    if let Some(r) = args.radius {
        set.push(format!("validity.params.radius={r}"));
    }
    set
}

/// Runs `smug p2p`.
pub fn run(args: P2pArgs) -> anyhow::Result<Outcome> {
    let queries = smug_core::queries::read_queries(&args.queries)?;
    let request = P2pRequest {
        config: args.config.clone(),
        set: overrides(&args),
        world: match &args.map {
            Some(path) => P2pWorld::Map {
                path: path.clone(),
                obstacle_height: args.obstacle_height,
            },
            None => P2pWorld::Config,
        },
        prefer_exact: true,
    };
    let (mut planner, fallback) = P2pPlanner::assemble(&request)?;
    if let Some(why) = fallback {
        eprintln!("smug p2p: {why}; planning with lazy-prm-star");
    }
    let planner_type = planner.planner_type().to_string();
    let results = planner.run(&queries, |k, row| {
        if let Some(reason) = &row.reason {
            eprintln!("query {}: {}: {reason}", k + 1, row.status);
        }
    })?;
    let exact = results.exact();
    let mean_cost = match exact {
        0 => "—".to_string(),
        n => format!(
            "{:.3}",
            results.queries.iter().filter_map(|q| q.cost).sum::<f64>() / n as f64
        ),
    };
    let count = |kind: &str| {
        results
            .queries
            .iter()
            .filter(|q| q.no_path == Some(kind))
            .count()
    };
    println!(
        "{} queries ({planner_type}): {exact} exact, {} without a path ({} proved none exists, {} budget spent), {} invalid endpoints; mean cost {mean_cost}; {:.3} s; roadmap {} vertices",
        results.queries.len(),
        count("proved") + count("budget_spent"),
        count("proved"),
        count("budget_spent"),
        results.queries.iter().filter(|q| q.status.starts_with("invalid")).count(),
        results.total_time_s,
        results.planner.vertices
    );
    if let Some(out) = &args.out {
        smug_core::output::write_atomic(out, serde_json::to_string_pretty(&results)?.as_bytes())
            .map_err(|e| anyhow::anyhow!("{}: {e}", out.display()))?;
    }
    if let Some(first) = results.first_bad_query() {
        anyhow::bail!("bad query: {first}");
    }
    Ok(if exact == results.queries.len() {
        Outcome::Ok
    } else {
        Outcome::NoSolution
    })
}
