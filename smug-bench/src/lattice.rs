//! `smug bench lattice`: the lattice planner against LazyPRM* with ten times its
//! budget, query by query, on generated maps of the open families, for every car model:
//! how often the lattice's path is costlier, by how much, and the time each takes.

use crate::output::ReportArgs;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use smug_core::{LoadedConfig, Pipeline, Pose2};
use smug_worlds::grid_gen::{generate, GridFamily, GridParams};
use smug_worlds::map_file::load_map;
use smug_worlds::movingai::{convert_movingai, write_map};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// Arguments of `smug bench lattice`.
#[derive(clap::Args, Debug)]
pub struct BenchLatticeArgs {
    /// Generated map families (`terrain`, `polygons`: open ground with obstacles; the
    /// one-cell corridors of the others are too narrow for a car).
    #[arg(long, value_delimiter = ',', default_value = "terrain,polygons")]
    families: Vec<String>,
    /// Cells per side of each map.
    #[arg(long, default_value_t = 128)]
    cells: usize,
    /// Side of a cell, metres.
    #[arg(long, default_value_t = 0.25)]
    cell_size: f64,
    /// Queries per map and model: valid poses with random headings, at least a
    /// quarter of the map apart.
    #[arg(long, default_value_t = 20)]
    queries: usize,
    /// Car models.
    #[arg(long, value_delimiter = ',', default_value = "dubins,reeds-shepp")]
    models: Vec<String>,
    /// Their turning radius, metres.
    #[arg(long, default_value_t = 1.5)]
    turning_radius: f64,
    /// The disc robot's radius, metres.
    #[arg(long, default_value_t = 0.4)]
    radius: f64,
    /// LazyPRM*'s budget as a multiple of its defaults (`max_samples` 20,000 and
    /// `max_stall` 3).
    #[arg(long, default_value_t = 10)]
    budget: u64,
    /// Seed of the maps and the queries.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Lattice resolutions to compare, metres (one row each; LazyPRM* plans each query
    /// once); empty: the planner's default (a sixth of the turning radius).
    #[arg(long, value_delimiter = ',')]
    resolutions: Vec<f64>,
    /// `--set`, `--out`, `--json`.
    #[command(flatten)]
    report: ReportArgs,
}

/// One query's answers.
#[derive(Debug, Serialize)]
struct Query {
    map: String,
    model: String,
    /// The lattice's resolution (`None`: its default).
    resolution: Option<f64>,
    start: [f64; 3],
    goal: [f64; 3],
    /// The lattice's path cost (`None`: no path) and seconds.
    lattice: (Option<f64>, f64),
    /// LazyPRM*'s.
    prm: (Option<f64>, f64),
}

/// Runs the benchmark and writes its report.
pub fn run(args: &BenchLatticeArgs) -> crate::Result<()> {
    let scratch = std::env::temp_dir().join(format!("smug-bench-lattice-{}", std::process::id()));
    std::fs::create_dir_all(&scratch)
        .map_err(|e| crate::error::invalid!("{}: cannot create: {e}", scratch.display()))?;
    let mut queries = Vec::new();
    for family in &args.families {
        let (name, world) = generated_world(args, family, &scratch)?;
        for model in &args.models {
            queries.extend(compare(args, &name, &world, model)?);
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
    args.report.write(&report(args, &queries), &queries)
}

/// A generated map of `family` as a world, with its name.
fn generated_world(
    args: &BenchLatticeArgs,
    family: &str,
    scratch: &Path,
) -> crate::Result<(String, smug_core::World)> {
    let family: GridFamily = family
        .parse()
        .map_err(|e| crate::error::invalid!("--families: {e}"))?;
    let params = GridParams::new(family, args.cells, args.cells, args.seed);
    let name = crate::p2p::maps::generated_name(&params);
    let map = scratch.join(format!("{name}.map"));
    let yaml = scratch.join(format!("{name}.yaml"));
    write_map(&map, &generate(&params)?)?;
    convert_movingai(&map, &yaml, args.cell_size)?;
    Ok((name.clone(), load_map(&yaml, 2.0)?.into_world(name)))
}

/// The disc robot with `model` on `world`, planning with `planner` (and `extra`).
fn pipeline(
    args: &BenchLatticeArgs,
    world: &smug_core::World,
    model: &str,
    planner: &str,
    extra: &[String],
) -> crate::Result<Pipeline> {
    let mut set = vec![
        format!("space.type=\"{model}\""),
        format!("space.params.turning_radius={}", args.turning_radius),
        "objective.type=\"path-length\"".to_string(),
        format!("validity.params.radius={}", args.radius),
        format!("planner.type=\"{planner}\""),
    ];
    set.extend(extra.iter().cloned());
    set.extend(args.report.set.iter().cloned());
    let loaded = LoadedConfig::from_text(
        smug_app::p2p::DEFAULT_CONFIG,
        "<bench lattice>",
        Path::new("."),
        &set,
    )?;
    Ok(Pipeline::assemble_with_world(&loaded, world.clone())?)
}

/// Every query on `world` for `model`, planned by LazyPRM* and by the lattice at each
/// resolution asked for.
fn compare(
    args: &BenchLatticeArgs,
    name: &str,
    world: &smug_core::World,
    model: &str,
) -> crate::Result<Vec<Query>> {
    let resolutions: Vec<Option<f64>> = if args.resolutions.is_empty() {
        vec![None]
    } else {
        args.resolutions.iter().copied().map(Some).collect()
    };
    let mut lattices = resolutions
        .iter()
        .map(|r| {
            let set: Vec<String> = r
                .map(|r| format!("planner.params.resolution={r}"))
                .into_iter()
                .collect();
            pipeline(args, world, model, "lattice", &set)
        })
        .collect::<crate::Result<Vec<Pipeline>>>()?;
    let budget = [
        format!("planner.params.max_samples={}", 20_000 * args.budget),
        format!("planner.params.max_stall={}", 3 * args.budget),
        "planner.params.shortcut=true".to_string(),
    ];
    let mut prm = pipeline(args, world, model, "lazy-prm-star", &budget)?;
    let mut out = Vec::new();
    for (start, goal) in draw_queries(args, world, &lattices[0])? {
        let theirs = plan(&mut prm, &start, &goal)?;
        for (lattice, &resolution) in lattices.iter_mut().zip(&resolutions) {
            let ours = plan(lattice, &start, &goal)?;
            eprintln!(
                "{name} {model} (resolution {resolution:?}): lattice {:?} in {:.2} s, LazyPRM* {:?} in {:.2} s",
                ours.0, ours.1, theirs.0, theirs.1
            );
            out.push(Query {
                map: name.to_string(),
                model: model.to_string(),
                resolution,
                start: [start.x, start.y, start.yaw],
                goal: [goal.x, goal.y, goal.yaw],
                lattice: ours,
                prm: theirs,
            });
        }
    }
    Ok(out)
}

/// The query's path cost with `pipeline`'s planner (`None`: no path) and seconds.
fn plan(pipeline: &mut Pipeline, start: &Pose2, goal: &Pose2) -> crate::Result<(Option<f64>, f64)> {
    let started = Instant::now();
    let planner = pipeline
        .planner
        .as_mut()
        .ok_or_else(|| crate::error::invalid!("the pipeline has no planner"))?;
    let outcome = planner.plan(start, goal)?;
    let cost = outcome.exact_path().map(|p| p.cost);
    Ok((cost, started.elapsed().as_secs_f64()))
}

/// `args.queries` pairs of valid poses with random headings, at least a quarter of
/// the map apart.
fn draw_queries(
    args: &BenchLatticeArgs,
    world: &smug_core::World,
    pipeline: &Pipeline,
) -> crate::Result<Vec<(Pose2, Pose2)>> {
    let states = pipeline
        .state_validity
        .clone()
        .ok_or_else(|| crate::error::invalid!("the pipeline has no validity checker"))?;
    let bounds = world.bounds();
    let span = (bounds.max[0] - bounds.min[0]).min(bounds.max[1] - bounds.min[1]);
    let mut rng = ChaCha8Rng::seed_from_u64(args.seed);
    let mut pose = || -> Option<Pose2> {
        (0..10_000).find_map(|_| {
            let p = Pose2::new(
                rng.random_range(bounds.min[0]..bounds.max[0]),
                rng.random_range(bounds.min[1]..bounds.max[1]),
                rng.random_range(-std::f64::consts::PI..std::f64::consts::PI),
            );
            states.is_valid(&p).then_some(p)
        })
    };
    let mut queries = Vec::with_capacity(args.queries);
    for _ in 0..args.queries * 100 {
        if queries.len() == args.queries {
            break;
        }
        let (Some(a), Some(b)) = (pose(), pose()) else {
            break;
        };
        if a.xy_distance(&b) >= 0.25 * span {
            queries.push((a, b));
        }
    }
    crate::error::ensure!(
        queries.len() == args.queries,
        "{}: found only {} of {} queries with valid poses far enough apart",
        world.name,
        queries.len(),
        args.queries
    );
    Ok(queries)
}

/// The Markdown report: per map and model, how the lattice's costs compare.
fn report(args: &BenchLatticeArgs, queries: &[Query]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# The lattice planner against LazyPRM* with {}× its budget\n\n\
         Generated maps ({} × {} cells of {} m, seed {}), a disc robot of radius {} m, \
         turning radius {} m; {} queries per map and model (valid poses with random \
         headings at least a quarter of the map apart). LazyPRM*: `max_samples` {}, \
         `max_stall` {}, shortcut. Costs: path length; ratio: lattice / LazyPRM* where \
         both found a path; \"costlier\": lattice above LazyPRM* by more than 1e-9.\n",
        args.budget,
        args.cells,
        args.cells,
        args.cell_size,
        args.seed,
        args.radius,
        args.turning_radius,
        args.queries,
        20_000 * args.budget,
        3 * args.budget,
    );
    let _ = writeln!(
        s,
        "| map | model | lattice resolution | both | lattice only | LazyPRM* only | costlier | mean ratio | worst ratio | lattice s | LazyPRM* s |\n|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    let mut groups: Vec<(&str, &str, Option<f64>)> = Vec::new();
    for q in queries {
        let group = (q.map.as_str(), q.model.as_str(), q.resolution);
        if !groups.contains(&group) {
            groups.push(group);
        }
    }
    for (map, model, resolution) in groups {
        let rows: Vec<&Query> = queries
            .iter()
            .filter(|q| q.map == map && q.model == model && q.resolution == resolution)
            .collect();
        let resolution = resolution.map_or("default".to_string(), |r| format!("{r} m"));
        let _ = writeln!(s, "{}", row(map, model, &resolution, &rows));
    }
    s
}

/// One report row.
fn row(map: &str, model: &str, resolution: &str, rows: &[&Query]) -> String {
    let ratios: Vec<f64> = rows
        .iter()
        .filter_map(|q| Some(q.lattice.0? / q.prm.0?))
        .collect();
    let only = |ours: bool| {
        rows.iter()
            .filter(|q| q.lattice.0.is_some() == ours && q.prm.0.is_some() != ours)
            .count()
    };
    let costlier = ratios.iter().filter(|&&r| r > 1.0 + 1e-9).count();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    let worst = ratios.iter().copied().fold(f64::NAN, f64::max);
    let seconds = |f: fn(&Query) -> f64| mean(&rows.iter().map(|q| f(q)).collect::<Vec<_>>());
    format!(
        "| {map} | {model} | {resolution} | {} | {} | {} | {costlier} | {:.4} | {:.4} | {:.3} | {:.3} |",
        ratios.len(),
        only(true),
        only(false),
        mean(&ratios),
        worst,
        seconds(|q| q.lattice.1),
        seconds(|q| q.prm.1),
    )
}
