//! Loading a map YAML into layers, and the layers into a world.

use super::error::MapFileError;
use super::image::{
    classify, layer_from_image_rows, open_image, optional_image, traversability_sample, CellClass,
    Colour,
};
use super::yaml::{MapMode, MapYaml};
use smug_core::{GridGeometry, GridLayer, MemoryLimit, Mission, Scenario, World};
use std::path::{Path, PathBuf};

/// The layers read from a map file.
#[derive(Clone, Debug, PartialEq)]
pub struct MapLayers {
    /// Terrain height, NaN where unknown.
    pub elevation: GridLayer,
    /// Traversability, when the map provides one.
    pub traversability: Option<GridLayer>,
    /// The mission file the YAML names (resolved), if any.
    pub mission_file: Option<PathBuf>,
}

impl MapLayers {
    /// Layers of an elevation alone (a DEM or a rasterised point cloud).
    pub fn from_elevation(elevation: GridLayer) -> Self {
        Self {
            elevation,
            traversability: None,
            mission_file: None,
        }
    }

    /// A world of these layers (maps only: point-to-point queries).
    pub fn into_world(self, name: impl Into<String>) -> World {
        let mut world = World::new(name, self.elevation);
        world.traversability = self.traversability;
        world
    }

    /// A world of these layers with `mission` to plan in it; errors when a pose lies
    /// outside the map. `yaml` names the map in errors.
    pub fn into_scenario(
        self,
        name: impl Into<String>,
        mission: Mission,
        yaml: &Path,
    ) -> Result<Scenario, MapFileError> {
        check_mission_inside(&mission, &self.elevation.geometry, yaml)?;
        Ok(self.into_world(name).with_mission(mission))
    }
}

/// Checks that the start, the end and every PoI of `mission` lie inside `geometry`;
/// the error names the culprit and `file`.
pub fn check_mission_inside(
    mission: &Mission,
    geometry: &GridGeometry,
    file: &Path,
) -> Result<(), MapFileError> {
    let bounds = geometry.bounds();
    let culprit = mission.first_pose_outside(&bounds);
    match culprit {
        Some(what) => Err(MapFileError::OutsideMap {
            path: file.to_path_buf(),
            what,
            min: bounds.min,
            max: bounds.max,
        }),
        None => Ok(()),
    }
}

/// Reads the map described by `yaml_path`: occupancy, and the elevation and
/// traversability images when given. Occupied cells rise `obstacle_height` metres above
/// the ground.
pub fn load_map(yaml_path: &Path, obstacle_height: f64) -> Result<MapLayers, MapFileError> {
    load_map_within(yaml_path, obstacle_height, MemoryLimit::default())
}

/// [`load_map`] with a grid that must fit `memory` (a run's limit).
pub fn load_map_within(
    yaml_path: &Path,
    obstacle_height: f64,
    memory: MemoryLimit,
) -> Result<MapLayers, MapFileError> {
    if !(obstacle_height.is_finite() && obstacle_height >= 0.0) {
        return Err(MapFileError::Invalid {
            path: yaml_path.to_path_buf(),
            message: format!("obstacle_height must be finite and ≥ 0, got {obstacle_height}"),
        });
    }
    let yaml = MapYaml::read(yaml_path)?;
    let base = yaml_path.parent().unwrap_or(Path::new(""));
    let occupancy_path = base.join(&yaml.image);
    let occupancy = open_image(yaml_path, "image", &occupancy_path, Colour::ToLuma)?;
    let elevation_image =
        optional_image(yaml_path, base, "elevation_image", &yaml.elevation_image)?;
    let traversability_image = optional_image(
        yaml_path,
        base,
        "traversability_image",
        &yaml.traversability_image,
    )?;
    for (path, image) in [&elevation_image, &traversability_image]
        .into_iter()
        .flatten()
    {
        if image.size() != occupancy.size() {
            return Err(MapFileError::SizeMismatch {
                yaml: yaml_path.to_path_buf(),
                first: occupancy_path.clone(),
                first_size: occupancy.size(),
                other: path.clone(),
                other_size: image.size(),
            });
        }
    }
    let geometry = GridGeometry::new_within(
        [yaml.origin[0], yaml.origin[1]],
        yaml.resolution,
        [occupancy.width as usize, occupancy.height as usize],
        memory,
    )
    .map_err(|e| MapFileError::Invalid {
        path: yaml_path.to_path_buf(),
        message: e.to_string(),
    })?;
    let class = |k: usize| classify(&yaml, &occupancy, k);
    let ground = |k: usize| match &elevation_image {
        Some((_, image)) if image.is_transparent(k) => f64::NAN,
        Some((_, image)) => {
            yaml.elevation_offset + yaml.elevation_scale * f64::from(image.samples[k])
        }
        None => 0.0,
    };
    let elevation = layer_from_image_rows(geometry, |k| match class(k) {
        CellClass::Unknown => f32::NAN,
        CellClass::Free | CellClass::Partial(_) => ground(k) as f32,
        CellClass::Occupied if yaml.elevation_includes_obstacles => ground(k) as f32,
        CellClass::Occupied => (ground(k) + obstacle_height) as f32,
    });
    let traversability = match &traversability_image {
        Some((_, image)) => Some(layer_from_image_rows(geometry, |k| {
            traversability_sample(image, yaml.traversability_nodata, k)
        })),
        None if yaml.mode == MapMode::Scale => {
            Some(layer_from_image_rows(geometry, |k| match class(k) {
                CellClass::Free => 1.0,
                CellClass::Occupied => 0.0,
                CellClass::Unknown => f32::NAN,
                CellClass::Partial(t) => t as f32,
            }))
        }
        None => None,
    };
    Ok(MapLayers {
        elevation,
        traversability,
        mission_file: yaml.mission.as_ref().map(|m| base.join(m)),
    })
}

/// The file name of `path` without its extension (`map` when there is none).
pub fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "map".into())
}
