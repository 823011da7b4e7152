//! `smug bench p2p`: LazyPRM* on grid maps — MovingAI's (`--data DIR` or
//! `$SMUG_DATA/movingai`) or generated ones (`--generated`, see `bench_p2p_maps`) —
//! scenarios solved, path length against the optimal octile length, time — with a disc
//! robot and yaw weight 0; and PoI-to-PoI queries on the lunar world (`bench_p2p_lunar`).

use crate::{bench_p2p_maps, Outcome};
use serde::Serialize;
use smug_core::{LoadedConfig, Mission, Pipeline, PlannerOutcome, Pose2};
use smug_worlds::map_file::load_map;
use smug_worlds::movingai::{
    convert_movingai, read_map, read_scenarios, scenario_to_world, MovingAiMap,
};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `smug bench p2p`.
#[derive(clap::Args, Debug)]
pub struct BenchP2pArgs {
    /// The MovingAI data folder (holding `mapf/`, `dao/`, `room/`); default
    /// `$SMUG_DATA/movingai`. Without either, MovingAI maps cannot run.
    #[arg(long, value_name = "DIR")]
    data: Option<PathBuf>,
    /// Also run generated maps of every family (random 10% and 20%, rooms, maze,
    /// terrain; seed 1) with scenarios from our octile Dijkstra: no download needed.
    #[arg(long)]
    generated: bool,
    /// Only these maps (file stems, comma-separated, `lunar` for the lunar world), e.g.
    /// `lunar,random-32-32-10,arena2` or `random-32x32-d10-s1`.
    #[arg(long, value_delimiter = ',')]
    maps: Vec<String>,
    /// The lunar world's config (its world, checkers and planner).
    #[arg(long, default_value = "configs/lunar.toml")]
    lunar_config: PathBuf,
    /// PoI-to-PoI queries on the lunar world.
    #[arg(long, default_value_t = 100)]
    lunar_queries: usize,
    /// Scenarios per map, spread evenly over the scenario file.
    #[arg(long, default_value_t = 50)]
    scenarios: usize,
    /// Disc radius in cells.
    #[arg(long, default_value_t = 0.25)]
    radius: f64,
    /// Override a key of `configs/p2p-grid.toml`, e.g. `planner.params.focus=0`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Write the Markdown report here.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write the raw numbers as JSON here (default: beside `--out`, as `.json`).
    #[arg(long)]
    json: Option<PathBuf>,
}

/// One map's numbers.
#[derive(Debug, Serialize)]
struct MapResult {
    map: String,
    scenarios: usize,
    solved: usize,
    /// Solved paths that touch a blocked cell (must be 0).
    unsafe_paths: usize,
    length_ratio: f64,
    time_s: f64,
    roadmap_vertices: u64,
    /// The planner's counters and time breakdown after the last query.
    planner: smug_core::PlannerStats,
    /// Every query, in order.
    queries: Vec<QueryResult>,
}

/// One scenario's numbers.
#[derive(Debug, Serialize)]
struct QueryResult {
    status: &'static str,
    /// Planned length (absent when not solved).
    cost: Option<f64>,
    /// The scenario's optimal octile length.
    optimal: f64,
    time_s: f64,
    /// Samples this query drew.
    samples: u64,
    /// True when the path touches a blocked cell.
    touches_blocked: bool,
}

/// True when the polyline through `states` passes through a blocked cell of `grid`
/// (checked every 0.005 cell, the map converted at 1 m per cell).
fn touches_blocked(grid: &MovingAiMap, states: &[Pose2]) -> bool {
    let blocked = |x: f64, y: f64| {
        if x < 0.0 || y < 0.0 {
            return true;
        }
        let (col, row_from_bottom) = (x.floor() as usize, y.floor() as usize);
        row_from_bottom >= grid.height || !grid.is_passable(col, grid.height - 1 - row_from_bottom)
    };
    states.windows(2).any(|w| {
        let steps = (w[0].xy_distance(&w[1]) / 0.005).ceil().max(1.0) as usize;
        (0..=steps).any(|k| {
            let t = k as f64 / steps as f64;
            blocked(
                w[0].x + t * (w[1].x - w[0].x),
                w[0].y + t * (w[1].y - w[0].y),
            )
        })
    })
}

fn run_map(
    args: &BenchP2pArgs,
    map: &Path,
    scen: &Path,
    scratch: &Path,
) -> anyhow::Result<MapResult> {
    let grid = read_map(map)?;
    let scenarios = read_scenarios(scen)?;
    let stem = smug_worlds::map_file::file_stem(map);
    let yaml = scratch.join(format!("{stem}.yaml"));
    convert_movingai(map, &yaml, 1.0)?;
    let to_pose = |cell: [usize; 2]| {
        let [x, y] = scenario_to_world(cell, grid.height, 1.0);
        Pose2::new(x, y, 0.0)
    };
    let count = args.scenarios.min(scenarios.len());
    let picked: Vec<_> = (0..count)
        .map(|i| &scenarios[i * scenarios.len() / count.max(1)])
        .collect();
    let start = picked
        .first()
        .map_or(Pose2::new(0.5, 0.5, 0.0), |s| to_pose(s.start));
    let world = load_map(&yaml, 2.0)?.into_world(
        stem.clone(),
        Mission {
            start,
            end: None,
            targets: vec![],
        },
        &yaml,
    )?;
    // The `smug p2p` disc robot, without the yaw term (grid paths have no heading).
    let mut set = vec![
        "space.type=se2".to_string(),
        "space.params.rotation_weight=0".to_string(),
        "objective.type=path-length".to_string(),
        "objective.params.rotation_weight=0".to_string(),
    ];
    set.extend(args.set.iter().cloned());
    set.push(format!("validity.params.radius={}", args.radius));
    let loaded = LoadedConfig::from_text(
        crate::p2p::DEFAULT_CONFIG,
        "<bench p2p>",
        Path::new("."),
        &set,
    )?;
    let mut pipeline = Pipeline::assemble_with_world(&loaded, world)?;
    let planner = pipeline
        .planner
        .as_mut()
        .ok_or_else(|| anyhow::anyhow!("no planner"))?;
    let started = Instant::now();
    let (mut solved, mut planned, mut optimal) = (0, 0.0, 0.0);
    let mut queries = Vec::with_capacity(picked.len());
    let samples = |p: &dyn smug_core::PointToPointPlanner| {
        p.stats().counters.get("samples").copied().unwrap_or(0)
    };
    for s in &picked {
        let (query_started, samples_before) = (Instant::now(), samples(planner.as_ref()));
        let outcome = planner.plan(&to_pose(s.start), &to_pose(s.goal))?;
        let mut query = QueryResult {
            status: outcome.status(),
            cost: None,
            optimal: s.optimal_length,
            time_s: query_started.elapsed().as_secs_f64(),
            samples: samples(planner.as_ref()) - samples_before,
            touches_blocked: false,
        };
        if let PlannerOutcome::Exact(path) = &outcome {
            solved += 1;
            planned += path.cost;
            optimal += s.optimal_length;
            query.cost = Some(path.cost);
            query.touches_blocked = touches_blocked(&grid, &path.states);
        }
        queries.push(query);
        eprint!("\r{stem}: {solved}/{} solved", picked.len());
    }
    eprintln!();
    Ok(MapResult {
        map: stem,
        scenarios: picked.len(),
        solved,
        unsafe_paths: queries.iter().filter(|q| q.touches_blocked).count(),
        length_ratio: if optimal > 0.0 {
            planned / optimal
        } else {
            f64::NAN
        },
        time_s: started.elapsed().as_secs_f64(),
        roadmap_vertices: planner.stats().vertices,
        planner: planner.stats(),
        queries,
    })
}

/// Runs `smug bench p2p`.
pub fn run(args: BenchP2pArgs) -> anyhow::Result<Outcome> {
    let wants = |name: &str| args.maps.is_empty() || args.maps.iter().any(|m| m == name);
    let movingai = movingai_folder(&args)?;
    let lunar = if wants("lunar") {
        eprintln!("lunar: {} queries", args.lunar_queries);
        Some(crate::bench_p2p_lunar::run(
            &args.lunar_config,
            &[],
            args.lunar_queries,
        )?)
    } else {
        None
    };
    let scratch = std::env::temp_dir().join(format!("smug-bench-p2p-{}", std::process::id()));
    std::fs::create_dir_all(&scratch)?;
    let mut maps = match &movingai {
        Some(dir) => bench_p2p_maps::movingai_maps(dir, wants),
        None => Vec::new(),
    };
    if args.generated {
        maps.extend(bench_p2p_maps::generated_maps(
            &scratch,
            args.scenarios,
            wants,
        )?);
    }
    let mut results = Vec::new();
    for map in &maps {
        results.push(run_map(&args, &map.map, &map.scen, &scratch)?);
    }
    std::fs::remove_dir_all(&scratch).ok();
    let mut report = String::from("# Point-to-point benchmark\n\n");
    if let Some(lunar) = &lunar {
        report += &crate::bench_p2p_lunar::markdown(lunar);
    }
    if !results.is_empty() {
        report += &movingai_markdown(&args, &results);
    }
    let raw = serde_json::json!({ "lunar": lunar, "movingai": results });
    crate::bench_output::write_report(&report, &raw, args.out.as_deref(), args.json.as_deref())?;
    Ok(Outcome::Ok)
}

/// The MovingAI data folder when MovingAI maps are to run: named maps need one; with
/// no `--maps`, one is needed unless `--generated` is given.
fn movingai_folder(args: &BenchP2pArgs) -> anyhow::Result<Option<PathBuf>> {
    let named = args.maps.iter().any(|m| bench_p2p_maps::is_movingai(m));
    match bench_p2p_maps::movingai_dir(args.data.as_deref()) {
        Ok(dir) if named || args.maps.is_empty() => Ok(Some(dir)),
        Ok(_) => Ok(None),
        Err(err) if named || (args.maps.is_empty() && !args.generated) => Err(err),
        Err(_) => Ok(None),
    }
}

fn movingai_markdown(args: &BenchP2pArgs, results: &[MapResult]) -> String {
    let mut md = format!(
        "## Grid maps\n\nLazyPRM* with `configs/p2p-grid.toml`{}, disc radius {} cell, yaw weight 0, \
         {} scenarios per map.\n\n\
         | map | solved | paths touching a blocked cell | mean length / optimal octile | \
         worst length / optimal | time (s) | ms per query | roadmap vertices |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|\n",
        if args.set.is_empty() {
            String::new()
        } else {
            format!(" and `{}`", args.set.join(" "))
        },
        args.radius,
        args.scenarios
    );
    for r in results {
        let worst = r
            .queries
            .iter()
            .filter_map(|q| q.cost.map(|c| c / q.optimal))
            .fold(f64::NAN, f64::max);
        md += &format!(
            "| {} | {}/{} | {} | {:.4} | {:.2} | {:.2} | {:.1} | {} |\n",
            r.map,
            r.solved,
            r.scenarios,
            r.unsafe_paths,
            r.length_ratio,
            worst,
            r.time_s,
            1e3 * r.time_s / r.scenarios.max(1) as f64,
            r.roadmap_vertices
        );
    }
    md
}
