//! `smug bench p2p`: LazyPRM* on MovingAI maps — scenarios solved, path length against
//! the optimal octile length, time — with a disc robot and yaw weight 0; and PoI-to-PoI
//! queries on the lunar world (`bench_p2p_lunar`).

use crate::Outcome;
use serde::Serialize;
use smug_core::{LoadedConfig, Mission, Pipeline, PlannerOutcome, Pose2};
use smug_worlds::map_file::load_map;
use smug_worlds::movingai::{convert_movingai, read_map, read_scenarios, scenario_to_world};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The maps of the benchmark: (map, scenario file) under the data folder.
const MAPS: [(&str, &str); 4] = [
    (
        "mapf/random-32-32-10.map",
        "mapf/random-32-32-10-random-1.scen",
    ),
    (
        "mapf/random-32-32-20.map",
        "mapf/random-32-32-20-random-1.scen",
    ),
    ("dao/arena2.map", "dao/arena2.map.scen"),
    ("room/8room_000.map", "room/8room_000.map.scen"),
];

/// Arguments of `smug bench p2p`.
#[derive(clap::Args, Debug)]
pub struct BenchP2pArgs {
    /// The MovingAI data folder.
    #[arg(long, default_value = "../shared/data/movingai")]
    data: PathBuf,
    /// Only these maps (file stems, comma-separated, `lunar` for the lunar world), e.g.
    /// `lunar,random-32-32-10,arena2`.
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
    /// Override a planner config key, e.g. `planner.params.shortcut=true`.
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
    length_ratio: f64,
    time_s: f64,
    roadmap_vertices: u64,
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
        "cost.type=se2".to_string(),
        "cost.params.rotation_weight=0".to_string(),
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
    for s in &picked {
        if let PlannerOutcome::Exact(path) = planner.plan(&to_pose(s.start), &to_pose(s.goal))? {
            solved += 1;
            planned += path.cost;
            optimal += s.optimal_length;
        }
        eprint!("\r{stem}: {solved}/{} solved", picked.len());
    }
    eprintln!();
    Ok(MapResult {
        map: stem,
        scenarios: picked.len(),
        solved,
        length_ratio: if optimal > 0.0 {
            planned / optimal
        } else {
            f64::NAN
        },
        time_s: started.elapsed().as_secs_f64(),
        roadmap_vertices: planner.stats().vertices,
    })
}

/// Runs `smug bench p2p`.
pub fn run(args: BenchP2pArgs) -> anyhow::Result<Outcome> {
    let wants = |name: &str| args.maps.is_empty() || args.maps.iter().any(|m| m == name);
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
    let mut results = Vec::new();
    for (map, scen) in MAPS {
        let stem = smug_worlds::map_file::file_stem(Path::new(map));
        if !wants(&stem) {
            continue;
        }
        results.push(run_map(
            &args,
            &args.data.join(map),
            &args.data.join(scen),
            &scratch,
        )?);
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

fn movingai_markdown(args: &BenchP2pArgs, results: &[MapResult]) -> String {
    let mut md = format!(
        "## MovingAI maps\n\nLazyPRM*, disc radius {} cell, yaw weight 0, {} scenarios per map.\n\n\
         | map | solved | mean length / optimal octile | time (s) | roadmap vertices |\n|---|---:|---:|---:|---:|\n",
        args.radius, args.scenarios
    );
    for r in results {
        md += &format!(
            "| {} | {}/{} | {:.4} | {:.2} | {} |\n",
            r.map, r.solved, r.scenarios, r.length_ratio, r.time_s, r.roadmap_vertices
        );
    }
    md
}
