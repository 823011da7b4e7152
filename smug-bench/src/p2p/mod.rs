//! `smug bench p2p`: LazyPRM* and the exact `visibility` planner side by side on grid
//! maps — MovingAI's (`--data DIR` or `$SMUG_DATA/movingai`) or generated ones
//! (`--generated`, see `maps`) — scenarios solved, path length against the
//! exact optimum of the disc (from `visibility`, arcs exact) and against the optimal
//! octile length, time per query — with a disc robot and yaw weight 0; and PoI-to-PoI
//! queries on the lunar world (`lunar`).

mod lunar;
pub mod maps;

use serde::Serialize;
use smug_core::{LoadedConfig, Pipeline, PlannerOutcome, PointToPointPlanner, Pose2};
use smug_planners::{Visibility, VisibilityParams};
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
    /// The planners to bench on grid maps: `lazy-prm-star` (the config's planner, with
    /// `--set`, yaw weight 0), `lazy-prm-star-default-metric` (the same with the
    /// config's own metric, yaw weight 0.5) and `visibility` (exact; its grid, clearance
    /// bounds and staircase corners are preprocessing, timed apart; its graph is built
    /// lazily by the queries, timed with them). The exact optimum of every scenario
    /// comes from `visibility` whichever planners are benched.
    #[arg(long, value_delimiter = ',', default_values_t = [
        "lazy-prm-star".to_string(),
        "lazy-prm-star-default-metric".to_string(),
        "visibility".to_string(),
    ])]
    planners: Vec<String>,
    /// Write the Markdown report here.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write the raw numbers as JSON here (default: beside `--out`, as `.json`).
    #[arg(long)]
    json: Option<PathBuf>,
}

/// One map's numbers for one planner.
#[derive(Debug, Serialize)]
struct MapResult {
    map: String,
    /// `lazy-prm-star` or `visibility`.
    planner_type: String,
    scenarios: usize,
    solved: usize,
    /// Solved paths that touch a blocked cell (must be 0).
    unsafe_paths: usize,
    /// Σ planned length / Σ optimal octile length over the solved scenarios.
    length_ratio: f64,
    /// Mean over the solved scenarios of planned length / exact optimum.
    exact_ratio_mean: f64,
    /// Largest planned length / exact optimum.
    exact_ratio_worst: f64,
    /// Seconds for all queries (after preprocessing).
    time_s: f64,
    /// Seconds of preprocessing before the first query (`visibility`: the grid, its
    /// clearance bounds and staircase corners; the graph is built by the queries).
    preprocessing_s: f64,
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
    /// The exact optimum of the disc (arcs exact), when a path exists.
    exact_optimum: Option<f64>,
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

/// A map with its scenarios, loaded once for every planner.
struct LoadedMap {
    stem: String,
    grid: MovingAiMap,
    queries: Vec<(Pose2, Pose2, f64)>,
    world: smug_core::World,
}

fn load_bench_map(
    args: &BenchP2pArgs,
    map: &Path,
    scen: &Path,
    scratch: &Path,
) -> crate::Result<LoadedMap> {
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
    let queries: Vec<_> = (0..count)
        .map(|i| &scenarios[i * scenarios.len() / count.max(1)])
        .map(|s| (to_pose(s.start), to_pose(s.goal), s.optimal_length))
        .collect();
    let world = load_map(&yaml, 2.0)?.into_world(stem.clone());
    Ok(LoadedMap {
        stem,
        grid,
        queries,
        world,
    })
}

/// The bench pipeline: `configs/p2p-grid.toml` with the disc robot, yaw weight 0 (or
/// the config's own metric with `default_metric`).
fn bench_pipeline(
    args: &BenchP2pArgs,
    world: smug_core::World,
    default_metric: bool,
) -> crate::Result<Pipeline> {
    // The `smug p2p` disc robot, without the yaw term (grid paths have no heading).
    let mut set = vec![
        "space.type=se2".to_string(),
        "objective.type=path-length".to_string(),
    ];
    if !default_metric {
        set.push("space.params.rotation_weight=0".to_string());
        set.push("objective.params.rotation_weight=0".to_string());
    }
    set.extend(args.set.iter().cloned());
    set.push(format!("validity.params.radius={}", args.radius));
    let loaded = LoadedConfig::from_text(
        smug_app::p2p::DEFAULT_CONFIG,
        "<bench p2p>",
        Path::new("."),
        &set,
    )?;
    Ok(Pipeline::assemble_with_world(&loaded, world)?)
}

/// The exact planner of the bench pipeline and its preprocessing time (its graph is
/// built lazily by the queries).
fn exact_planner(pipeline: &Pipeline) -> crate::Result<(Visibility, f64)> {
    let states = pipeline
        .state_validity
        .clone()
        .ok_or_else(|| crate::error::invalid!("no validity checker"))?;
    let disc = states
        .disc_on_grid()
        .ok_or_else(|| crate::error::invalid!("the bench's checker is not a disc on a grid"))?;
    let started = Instant::now();
    let planner = Visibility::new(
        VisibilityParams::default(),
        disc,
        states,
        pipeline.objective.clone(),
    )?;
    Ok((planner, started.elapsed().as_secs_f64()))
}

/// Runs every scenario of `map` with `planner`, against the exact optima `optima`.
fn run_planner(
    name: &str,
    map: &LoadedMap,
    planner: &mut dyn PointToPointPlanner,
    optima: &[Option<f64>],
    preprocessing_s: f64,
) -> crate::Result<MapResult> {
    let (mut solved, mut planned, mut optimal) = (0, 0.0, 0.0);
    let (mut ratio_sum, mut ratio_worst, mut ratio_count) = (0.0, f64::NAN, 0usize);
    let mut queries = Vec::with_capacity(map.queries.len());
    let samples =
        |p: &dyn PointToPointPlanner| p.stats().counters.get("samples").copied().unwrap_or(0);
    let mut query_time = 0.0;
    for (k, (start, goal, octile)) in map.queries.iter().enumerate() {
        let (query_started, samples_before) = (Instant::now(), samples(planner));
        let outcome = planner.plan(start, goal)?;
        let time_s = query_started.elapsed().as_secs_f64();
        query_time += time_s;
        let mut query = QueryResult {
            status: outcome.status(),
            cost: None,
            optimal: *octile,
            exact_optimum: optima[k],
            time_s,
            samples: samples(planner) - samples_before,
            touches_blocked: false,
        };
        if let PlannerOutcome::Exact(path) = &outcome {
            solved += 1;
            planned += path.cost;
            optimal += octile;
            query.cost = Some(path.cost);
            query.touches_blocked = touches_blocked(&map.grid, &path.states);
            if let Some(best) = optima[k].filter(|&b| b > 0.0) {
                let ratio = path.cost / best;
                ratio_sum += ratio;
                ratio_count += 1;
                ratio_worst = ratio_worst.max(ratio);
            }
        }
        queries.push(query);
        eprint!("\r{} ({name}): {solved}/{} solved", map.stem, k + 1);
    }
    eprintln!();
    Ok(MapResult {
        map: map.stem.clone(),
        planner_type: name.to_string(),
        scenarios: map.queries.len(),
        solved,
        unsafe_paths: queries.iter().filter(|q| q.touches_blocked).count(),
        length_ratio: if optimal > 0.0 {
            planned / optimal
        } else {
            f64::NAN
        },
        exact_ratio_mean: ratio_sum / ratio_count.max(1) as f64,
        exact_ratio_worst: ratio_worst,
        time_s: query_time,
        preprocessing_s,
        roadmap_vertices: planner.stats().vertices,
        planner: planner.stats(),
        queries,
    })
}

fn run_map(
    args: &BenchP2pArgs,
    map: &Path,
    scen: &Path,
    scratch: &Path,
) -> crate::Result<Vec<MapResult>> {
    let map = load_bench_map(args, map, scen, scratch)?;
    let pipeline = bench_pipeline(args, map.world.clone(), false)?;
    // The exact optima, one query at a time, from a planner of their own (the
    // `visibility` row below starts from a fresh one, its graph built by its queries).
    let (mut exact, _) = exact_planner(&pipeline)?;
    let optima: Vec<Option<f64>> = map
        .queries
        .iter()
        .map(|(s, g, _)| {
            exact.plan(s, g)?;
            Ok(exact.last_optimum()[0])
        })
        .collect::<crate::Result<_>>()?;
    let mut results = Vec::new();
    for name in &args.planners {
        results.push(match name.as_str() {
            "visibility" => {
                let (mut exact, preprocessing_s) = exact_planner(&pipeline)?;
                run_planner(name, &map, &mut exact, &optima, preprocessing_s)?
            }
            "lazy-prm-star" | "lazy-prm-star-default-metric" => {
                let default_metric = name != "lazy-prm-star";
                let mut pipeline = bench_pipeline(args, map.world.clone(), default_metric)?;
                let planner = pipeline
                    .planner
                    .as_mut()
                    .ok_or_else(|| crate::error::invalid!("no planner"))?;
                run_planner(name, &map, planner.as_mut(), &optima, 0.0)?
            }
            other => crate::error::bail!(
                "--planners: unknown planner `{other}`; known: lazy-prm-star, \
                 lazy-prm-star-default-metric, visibility"
            ),
        });
    }
    Ok(results)
}

/// Runs `smug bench p2p`.
pub fn run(args: BenchP2pArgs) -> crate::Result<()> {
    let wants = |name: &str| args.maps.is_empty() || args.maps.iter().any(|m| m == name);
    let movingai = movingai_folder(&args)?;
    let lunar = if wants("lunar") {
        eprintln!("lunar: {} queries", args.lunar_queries);
        Some(lunar::run(&args.lunar_config, &[], args.lunar_queries)?)
    } else {
        None
    };
    let scratch = std::env::temp_dir().join(format!("smug-bench-p2p-{}", std::process::id()));
    std::fs::create_dir_all(&scratch)?;
    let mut maps = match &movingai {
        Some(dir) => maps::movingai_maps(dir, wants),
        None => Vec::new(),
    };
    if args.generated {
        maps.extend(maps::generated_maps(&scratch, args.scenarios, wants)?);
    }
    let mut results = Vec::new();
    for map in &maps {
        let named = args.maps.contains(&map.name);
        if !named && (!map.map.exists() || !map.scen.exists()) {
            eprintln!(
                "{}: skipped, {} or {} is missing",
                map.name,
                map.map.display(),
                map.scen.display()
            );
            continue;
        }
        results.extend(run_map(&args, &map.map, &map.scen, &scratch)?);
    }
    std::fs::remove_dir_all(&scratch).ok();
    let mut report = String::from("# Point-to-point benchmark\n\n");
    // The command that made the report (a data folder named by its last component).
    let command: Vec<String> = std::env::args()
        .skip(1)
        .map(|a| match (&args.data, Path::new(&a).file_name()) {
            (Some(dir), Some(name)) if Path::new(&a) == dir.as_path() => {
                format!("DIR/{}", name.to_string_lossy())
            }
            _ => a,
        })
        .collect();
    report += &format!("Made by `smug {}`.\n\n", command.join(" "));
    if let Some(lunar) = &lunar {
        report += &lunar::markdown(lunar);
    }
    if !results.is_empty() {
        report += &movingai_markdown(&args, &results);
    }
    let raw = serde_json::json!({ "lunar": lunar, "movingai": results });
    crate::output::write_report(&report, &raw, args.out.as_deref(), args.json.as_deref())?;
    Ok(())
}

/// The MovingAI data folder when MovingAI maps are to run: named maps need one; with
/// no `--maps`, one is needed unless `--generated` is given.
fn movingai_folder(args: &BenchP2pArgs) -> crate::Result<Option<PathBuf>> {
    let named = args.maps.iter().any(|m| maps::is_movingai(m));
    match maps::movingai_dir(args.data.as_deref()) {
        Ok(dir) if named || args.maps.is_empty() => Ok(Some(dir)),
        Ok(_) => Ok(None),
        Err(err) if named || (args.maps.is_empty() && !args.generated) => Err(err),
        Err(_) => Ok(None),
    }
}

fn movingai_markdown(args: &BenchP2pArgs, results: &[MapResult]) -> String {
    let mut md = format!(
        "## Grid maps\n\n`configs/p2p-grid.toml`{}, disc radius {} cell, yaw weight 0 \
         (`lazy-prm-star-default-metric`: the config's own metric, yaw weight 0.5; its \
         length is the path's cost, yaw included), {} scenarios per map. Exact optimum: \
         the `visibility` planner's length with exact arcs. `visibility` preprocessing: \
         the grid, its clearance bounds and hidden staircase corners; its time per query \
         includes building the graph lazily, shared by the map's queries.\n\n\
         | map | planner | solved | paths touching a blocked cell | length / exact optimum, mean | \
         worst | length / optimal octile | ms per query | preprocessing (s) | roadmap vertices |\n\
         |---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
        if args.set.is_empty() {
            String::new()
        } else {
            format!(" and `{}`", args.set.join(" "))
        },
        args.radius,
        args.scenarios
    );
    for r in results {
        md += &format!(
            "| {} | {} | {}/{} | {} | {:.4} | {:.4} | {:.4} | {:.2} | {:.2} | {} |\n",
            r.map,
            r.planner_type,
            r.solved,
            r.scenarios,
            r.unsafe_paths,
            r.exact_ratio_mean,
            r.exact_ratio_worst,
            r.length_ratio,
            1e3 * r.time_s / r.scenarios.max(1) as f64,
            r.preprocessing_s,
            r.roadmap_vertices
        );
    }
    md
}
