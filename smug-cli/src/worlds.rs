//! `smug worlds`: look at, convert, generate and export worlds.
//!
//! A world is named in one of three ways: a registered world plugin built with its
//! default parameters (`lunar`; `--set world.params.KEY=VALUE` changes them), a pipeline
//! config (`configs/lunar.toml`: its world and traversability stages are built), or a map
//! YAML (`map.yaml`: imported as is, the mission optional).

use crate::Outcome;
use anyhow::{bail, Context};
use clap::Subcommand;
use smug_core::{LoadedConfig, Mission, Pipeline, Scenario, World};
use smug_worlds::export::ExportOptions;
use smug_worlds::map_file::{
    check_mission_inside, file_stem, load_terrain, MapLayers, TerrainKind, DEFAULT_OBSTACLE_HEIGHT,
};
use smug_worlds::point_cloud::Reduce;
use smug_worlds::render::RasterLayer;
use smug_worlds::{load_map, load_mission, RenderOptions};
use std::path::{Path, PathBuf};

/// Arguments of `smug worlds`.
#[derive(clap::Args, Debug)]
pub struct WorldsArgs {
    #[command(subcommand)]
    command: WorldsCommand,
}

#[derive(Subcommand, Debug)]
enum WorldsCommand {
    /// Draw a world (and its mission) as an SVG picture.
    Show(ShowArgs),
    /// Convert a MovingAI `.map` grid into a map YAML + PGM.
    ConvertMovingai(ConvertArgs),
    /// Convert a GeoTIFF DEM (`.tif`) or a point cloud (`.ply`, `.pcd`) into a map YAML +
    /// occupancy PGM + 16-bit elevation PNG + mission TOML (what `smug worlds export`
    /// writes).
    Convert(ExportArgs),
    /// Generate a seeded grid map (random, rooms, maze, terrain, polygons) as a MovingAI `.map`,
    /// with scenarios and a map YAML + PGM on request.
    Generate(crate::worlds_generate::GenerateArgs),
    /// Export a world as map YAML + occupancy PGM + elevation and traversability PNGs +
    /// mission TOML.
    Export(ExportArgs),
}

/// Which world, and how to build it.
#[derive(clap::Args, Debug)]
struct WorldSource {
    /// A world plugin name (e.g. `lunar`), a pipeline config (`.toml`) or a map (`.yaml`).
    world: String,
    /// Override a key: `world.params.KEY=VALUE` for a plugin name, any key for a config.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Seed of the world's random choices (overrides the config's `seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// A mission file (TOML or JSON) replacing the world's mission.
    #[arg(long, value_name = "FILE")]
    mission: Option<PathBuf>,
    /// Cell size of a rasterised point cloud (`.ply`, `.pcd`), metres.
    #[arg(long, default_value_t = smug_worlds::map_file::DEFAULT_CELL_SIZE)]
    cell_size: f64,
    /// How a point cloud cell's points make its height.
    #[arg(long, value_enum, default_value_t = ReduceArg::Max)]
    reduce: ReduceArg,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum ReduceArg {
    /// The highest point.
    Max,
    /// The mean height.
    Mean,
}

#[derive(clap::Args, Debug)]
struct ShowArgs {
    #[command(flatten)]
    source: WorldSource,
    /// The SVG file to write.
    #[arg(long, value_name = "FILE.svg")]
    out: PathBuf,
    /// Title above the picture (default: the world's name).
    #[arg(long)]
    title: Option<String>,
    /// The layer drawn under the mission.
    #[arg(long, value_enum, default_value_t = LayerArg::Auto)]
    layer: LayerArg,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum LayerArg {
    /// Traversability when the world has it, elevation otherwise.
    Auto,
    /// The elevation.
    Elevation,
    /// The traversability.
    Traversability,
}

#[derive(clap::Args, Debug)]
struct ConvertArgs {
    /// The MovingAI `.map` file.
    input: PathBuf,
    /// The map YAML to write (the PGM goes beside it, with the same stem).
    output: PathBuf,
    /// Metres per grid cell.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    resolution: f64,
}

#[derive(clap::Args, Debug)]
struct ExportArgs {
    #[command(flatten)]
    source: WorldSource,
    /// The folder to write into.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// File name stem (default: the world's name).
    #[arg(long)]
    stem: Option<String>,
    /// Cells higher than the lowest elevation plus this (metres) are occupied in the PGM.
    #[arg(long, default_value_t = smug_worlds::export::DEFAULT_OBSTACLE_THRESHOLD, allow_negative_numbers = true)]
    obstacle_threshold: f64,
}

/// Runs `smug worlds`.
pub fn run(args: WorldsArgs) -> anyhow::Result<Outcome> {
    match args.command {
        WorldsCommand::Show(args) => show(args),
        WorldsCommand::ConvertMovingai(args) => convert(args),
        WorldsCommand::Generate(args) => crate::worlds_generate::run(args),
        WorldsCommand::Export(args) => export(args),
        WorldsCommand::Convert(args) => {
            if !matches!(world_spec(&args.source.world)?, WorldSpec::Terrain(..)) {
                bail!(
                    "{}: not a GeoTIFF DEM (.tif, .tiff) or a point cloud (.ply, .pcd)",
                    args.source.world
                );
            }
            export(args)
        }
    }
}

fn show(args: ShowArgs) -> anyhow::Result<Outcome> {
    let (world, mission) = load_world(&args.source)?;
    let options = RenderOptions {
        title: Some(args.title.unwrap_or_else(|| world.name.clone())),
        layer: match args.layer {
            LayerArg::Auto => RasterLayer::Auto,
            LayerArg::Elevation => RasterLayer::Elevation,
            LayerArg::Traversability => RasterLayer::Traversability,
        },
        ..RenderOptions::default()
    };
    let svg = smug_worlds::render_svg(&world, mission.as_ref(), &options);
    create_parent(&args.out)?;
    smug_core::output::write_atomic(&args.out, svg.as_bytes())
        .with_context(|| format!("{}: cannot write", args.out.display()))?;
    println!(
        "wrote {}: {}",
        args.out.display(),
        describe(&world, mission.as_ref())
    );
    Ok(Outcome::Ok)
}

fn convert(args: ConvertArgs) -> anyhow::Result<Outcome> {
    let pgm = smug_worlds::convert_movingai(&args.input, &args.output, args.resolution)?;
    println!(
        "wrote {} and {} ({} m per cell)",
        args.output.display(),
        pgm.display(),
        args.resolution
    );
    Ok(Outcome::Ok)
}

fn export(args: ExportArgs) -> anyhow::Result<Outcome> {
    let (world, mission) = load_world(&args.source)?;
    let stem = args.stem.unwrap_or_else(|| file_safe(&world.name));
    let options = ExportOptions {
        obstacle_threshold: args.obstacle_threshold,
    };
    let yaml =
        smug_worlds::export_world_with(&world, mission.as_ref(), &args.out, &stem, &options)?;
    println!(
        "wrote {}: {}",
        yaml.display(),
        describe(&world, mission.as_ref())
    );
    Ok(Outcome::Ok)
}

/// How the command line names a world.
enum WorldSpec<'a> {
    Map(&'a Path),
    Terrain(&'a Path, TerrainKind),
    Config(&'a Path),
    Plugin(&'a str),
}

fn world_spec(text: &str) -> anyhow::Result<WorldSpec<'_>> {
    let path = Path::new(text);
    if let Some(kind) = TerrainKind::of(path) {
        return Ok(WorldSpec::Terrain(path, kind));
    }
    match path.extension().and_then(|e| e.to_str()) {
        Some("yaml" | "yml") => Ok(WorldSpec::Map(path)),
        Some("toml") => Ok(WorldSpec::Config(path)),
        _ if text.contains(['/', '\\']) || path.is_file() => {
            bail!(
                "{text}: not a world plugin name, a pipeline config (.toml), a map (.yaml), \
                 a GeoTIFF DEM (.tif) or a point cloud (.ply, .pcd)"
            )
        }
        _ => Ok(WorldSpec::Plugin(text)),
    }
}

/// Builds the world the command line names and its mission: `--mission` if given, else
/// the world's own (none for a map without one).
fn load_world(source: &WorldSource) -> anyhow::Result<(World, Option<Mission>)> {
    let mut overrides = source.set.clone();
    if let Some(seed) = source.seed {
        overrides.push(format!("seed={seed}"));
    }
    let (world, own) = match world_spec(&source.world)? {
        WorldSpec::Map(path) => {
            if !source.set.is_empty() {
                bail!(
                    "{}: --set applies to world plugins and pipeline configs, not to maps",
                    path.display()
                );
            }
            return load_map_world(path, source.mission.as_deref());
        }
        WorldSpec::Terrain(path, kind) => {
            if !source.set.is_empty() {
                bail!(
                    "{}: --set applies to world plugins and pipeline configs, not to terrain files",
                    path.display()
                );
            }
            let reduce = match source.reduce {
                ReduceArg::Max => Reduce::Max,
                ReduceArg::Mean => Reduce::Mean,
            };
            let layers = load_terrain(
                path,
                kind,
                source.cell_size,
                reduce,
                smug_core::MemoryLimit::default(),
            )?;
            return layers_world(layers, path, source.mission.as_deref());
        }
        WorldSpec::Config(path) => {
            let loaded = LoadedConfig::from_file(path, &overrides)?;
            build_world(loaded).with_context(|| path.display().to_string())?
        }
        WorldSpec::Plugin(name) => {
            let text = format!("[world]\ntype = {}\n", toml::Value::String(name.into()));
            let loaded =
                LoadedConfig::from_text(&text, "<command line>", Path::new("."), &overrides)?;
            build_world(loaded).with_context(|| format!("world plugin `{name}`"))?
        }
    };
    match &source.mission {
        Some(path) => {
            let mission = load_mission(path)?;
            check_mission_inside(&mission, &world.elevation.geometry, path)?;
            Ok((world, Some(mission)))
        }
        None => Ok((world, own)),
    }
}

/// Builds the world and traversability stages of a config (the others are not needed);
/// the world and its mission.
fn build_world(mut loaded: LoadedConfig) -> anyhow::Result<(World, Option<Mission>)> {
    loaded.config.keep_sections(&smug_app::WORLD_STAGES);
    let pipeline = Pipeline::assemble(&loaded)?;
    match pipeline.world {
        Some(world) => Ok((World::clone(&world), pipeline.given_mission)),
        None => bail!("the config has no [world] section"),
    }
}

/// Imports a map YAML and its mission (`--mission` or the YAML's `mission` key), if any.
fn load_map_world(path: &Path, mission: Option<&Path>) -> anyhow::Result<(World, Option<Mission>)> {
    let layers = load_map(path, DEFAULT_OBSTACLE_HEIGHT)?;
    layers_world(layers, path, mission)
}

/// The world of imported layers and its mission (given, or the layers' own), if any.
fn layers_world(
    layers: MapLayers,
    path: &Path,
    mission: Option<&Path>,
) -> anyhow::Result<(World, Option<Mission>)> {
    let file = mission
        .map(Path::to_path_buf)
        .or(layers.mission_file.clone());
    match file {
        Some(file) => {
            let Scenario { world, mission } =
                layers.into_scenario(file_stem(path), load_mission(&file)?, path)?;
            Ok((world, Some(mission)))
        }
        None => Ok((layers.into_world(file_stem(path)), None)),
    }
}

fn describe(world: &World, mission: Option<&Mission>) -> String {
    let g = world.elevation.geometry;
    let what = match mission {
        Some(m) => format!(
            "{} targets, {} poses of interest",
            m.targets.len(),
            m.poi_count()
        ),
        None => "no mission".to_string(),
    };
    format!(
        "world `{}`, {}×{} cells at {} m, {what}",
        world.name, g.size[0], g.size[1], g.resolution,
    )
}

/// `name` with every character but letters, digits, `-`, `_` and `.` replaced by `-`.
fn file_safe(name: &str) -> String {
    let safe: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '-'
            }
        })
        .collect();
    let trimmed = safe.trim_matches(['-', '.']);
    if trimmed.is_empty() {
        "world".to_string()
    } else {
        trimmed.to_string()
    }
}

fn create_parent(file: &Path) -> anyhow::Result<()> {
    match file.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create folder", dir.display())),
        _ => Ok(()),
    }
}
