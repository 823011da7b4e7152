//! The `map` world plugin: a map YAML, a DEM or a point cloud, and a mission.

use super::layers::{file_stem, load_map_within, MapLayers};
use super::terrain::{load_terrain, TerrainKind};
use super::yaml::{DEFAULT_CELL_SIZE, DEFAULT_OBSTACLE_HEIGHT};
use serde::{Deserialize, Serialize};
use smug_core::{BuildContext, Error, Mission, Scenario};
use std::path::{Path, PathBuf};

/// Parameters of the `map` world plugin.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MapParams {
    /// The map's YAML file (relative to the config file).
    pub yaml: PathBuf,
    /// The mission from a TOML or JSON file (relative to the config file).
    pub mission_file: Option<PathBuf>,
    /// The mission, inline.
    pub mission: Option<Mission>,
    /// Height of occupied cells above the ground, metres.
    pub obstacle_height: f64,
    /// Name in reports (default: the YAML file's stem).
    pub name: Option<String>,
    /// A GeoTIFF DEM instead of `yaml` (relative to the config file): heights,
    /// resolution and origin come from the file.
    pub dem: Option<PathBuf>,
    /// A point cloud (PLY or PCD) instead of `yaml` (relative to the config file),
    /// rasterised into cells of `cell_size`.
    pub point_cloud: Option<PathBuf>,
    /// Cell size of a rasterised point cloud, metres.
    pub cell_size: f64,
    /// How a cell's points make its height: `max` (default) or `mean`.
    pub reduce: crate::point_cloud::Reduce,
}

impl Default for MapParams {
    fn default() -> Self {
        Self {
            yaml: PathBuf::new(),
            mission_file: None,
            mission: None,
            obstacle_height: DEFAULT_OBSTACLE_HEIGHT,
            name: None,
            dem: None,
            point_cloud: None,
            cell_size: DEFAULT_CELL_SIZE,
            reduce: crate::point_cloud::Reduce::default(),
        }
    }
}

/// The mission of a `map` world: inline, from `mission_file`, or from the YAML's
/// `mission` key, in that order of preference (inline and file together are an error).
fn map_mission(
    params: &MapParams,
    layers: &MapLayers,
    yaml: &Path,
    ctx: &BuildContext,
) -> Result<Mission, Error> {
    let from_file = |path: &Path| crate::load_mission(path).map_err(|e| Error::stage("world", e));
    match (&params.mission, &params.mission_file, &layers.mission_file) {
        (Some(_), Some(_), _) => Err(Error::invalid_param(
            "world",
            "give either `mission` or `mission_file`, not both",
        )),
        (Some(mission), None, _) => Ok(mission.clone()),
        (None, Some(path), _) => from_file(&ctx.resolve_path(path)),
        (None, None, Some(path)) => from_file(path),
        (None, None, None) => Err(Error::invalid_param(
            "world",
            format!(
                "needs a `mission` table or a `mission_file` (or a `mission` key in {})",
                yaml.display()
            ),
        )),
    }
}

/// Builds the `map` world described by `params`.
fn build_map_world(params: &MapParams, ctx: &BuildContext) -> Result<Scenario, Error> {
    let given = [
        !params.yaml.as_os_str().is_empty(),
        params.dem.is_some(),
        params.point_cloud.is_some(),
    ];
    match given.iter().filter(|g| **g).count() {
        0 => {
            return Err(Error::invalid_param(
                "world",
                "`yaml` is required: the map's YAML file (or `dem`, a GeoTIFF, or \
                 `point_cloud`, a PLY or PCD file)",
            ))
        }
        1 => {}
        _ => {
            return Err(Error::invalid_param(
                "world",
                "give one of `yaml`, `dem` and `point_cloud`",
            ))
        }
    }
    let terrain = params.dem.as_ref().or(params.point_cloud.as_ref());
    let (yaml, layers) = if let Some(file) = terrain {
        let path = ctx.resolve_path(file);
        let kind = match params.dem {
            Some(_) => TerrainKind::Dem,
            None => TerrainKind::PointCloud,
        };
        let layers = load_terrain(&path, kind, params.cell_size, params.reduce, ctx.memory())
            .map_err(|e| Error::stage("world", e))?;
        (path, layers)
    } else {
        let yaml = ctx.resolve_path(&params.yaml);
        let layers = load_map_within(&yaml, params.obstacle_height, ctx.memory())
            .map_err(|e| Error::stage("world", e))?;
        (yaml, layers)
    };
    let mission = map_mission(params, &layers, &yaml, ctx)?;
    let name = params.name.clone().unwrap_or_else(|| file_stem(&yaml));
    layers
        .into_scenario(name, mission, &yaml)
        .map_err(|e| Error::stage("world", e))
}

smug_core::register_plugin!(
    smug_core::registry::WorldStage,
    name = "map",
    summary = "ROS map_server-style YAML + PGM/PNG occupancy (elevation, traversability images), a GeoTIFF DEM or a PLY/PCD point cloud",
    params = MapParams,
    build = |params, ctx| Ok(Box::new(build_map_world(&params, ctx)?)),
);
