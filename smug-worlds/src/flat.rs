//! `flat`: a flat floor with box obstacles and a mission given in the config (or a
//! mission file) — small, exact worlds for tests, tutorials and wheeled robots.

use serde::{Deserialize, Serialize};
use smug_core::{
    BuildContext, Error, GridGeometry, GridLayer, MemoryLimit, Mission, Scenario, World,
};
use std::path::PathBuf;

/// An axis-aligned box obstacle standing on the floor.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxObstacle {
    /// Lower-left corner `(x, y)`, metres.
    pub min: [f64; 2],
    /// Upper-right corner `(x, y)`, metres.
    pub max: [f64; 2],
    /// Height above the floor, metres.
    #[serde(default = "default_obstacle_height")]
    pub height: f64,
}

fn default_obstacle_height() -> f64 {
    2.0
}

/// Parameters of the flat world.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FlatParams {
    /// Name in reports.
    pub name: String,
    /// Extent `(x, y)` in metres.
    pub size: [f64; 2],
    /// Cell size in metres.
    pub resolution: f64,
    /// World coordinates of the lower-left corner.
    pub origin: [f64; 2],
    /// Box obstacles (raised cells of the elevation layer).
    pub obstacles: Vec<BoxObstacle>,
    /// The mission, inline.
    pub mission: Option<Mission>,
    /// The mission from a TOML or JSON file (relative to the config file).
    pub mission_file: Option<PathBuf>,
}

impl Default for FlatParams {
    fn default() -> Self {
        Self {
            name: "flat".into(),
            size: [10.0, 10.0],
            resolution: 0.1,
            origin: [0.0, 0.0],
            obstacles: Vec::new(),
            mission: None,
            mission_file: None,
        }
    }
}

/// The largest grid a flat world may have (cells), to catch unit mistakes early.
const MAX_CELLS: f64 = 1e8;

/// Builds the world described by `params`, with `mission` to plan in it.
pub fn flat_world(params: &FlatParams, mission: Mission) -> Result<Scenario, Error> {
    flat_world_within(params, mission, MemoryLimit::default())
}

/// [`flat_world`] with grids that must fit `memory` (a run's limit).
pub fn flat_world_within(
    params: &FlatParams,
    mission: Mission,
    memory: MemoryLimit,
) -> Result<Scenario, Error> {
    let bad = |message: String| Error::invalid_param("world", message);
    let [w, h] = params.size;
    if !(w > 0.0 && h > 0.0 && w.is_finite() && h.is_finite()) {
        return Err(bad(format!("size must be positive, got {:?}", params.size)));
    }
    let cells = [
        (w / params.resolution).round(),
        (h / params.resolution).round(),
    ];
    if !(cells[0] >= 1.0 && cells[1] >= 1.0 && cells[0] * cells[1] <= MAX_CELLS) {
        return Err(bad(format!(
            "size {:?} at resolution {} gives {}×{} cells (1 to {MAX_CELLS} allowed)",
            params.size, params.resolution, cells[0], cells[1]
        )));
    }
    let geometry = GridGeometry::new_within(
        params.origin,
        params.resolution,
        [cells[0] as usize, cells[1] as usize],
        memory,
    )
    .map_err(|e| bad(e.to_string()))?;
    if let Some(k) = params
        .obstacles
        .iter()
        .position(|o| !(o.height.is_finite() && o.min[0] <= o.max[0] && o.min[1] <= o.max[1]))
    {
        return Err(bad(format!(
            "obstacle {k} needs min ≤ max and a finite height"
        )));
    }
    let elevation = GridLayer::from_fn(geometry, |i, j| {
        let [x, y] = geometry.center_of(i, j);
        params
            .obstacles
            .iter()
            .filter(|o| x >= o.min[0] && x <= o.max[0] && y >= o.min[1] && y <= o.max[1])
            .map(|o| o.height as f32)
            .fold(0.0, f32::max)
    });
    check_mission_inside(&mission, &geometry)?;
    Ok(World::new(params.name.clone(), elevation).with_mission(mission))
}

fn check_mission_inside(mission: &Mission, geometry: &GridGeometry) -> Result<(), Error> {
    let bounds = geometry.bounds();
    let culprit = mission.first_pose_outside(&bounds);
    match culprit {
        Some(what) => Err(Error::InvalidInput(format!(
            "{what} lies outside the map bounds {:?}–{:?}",
            bounds.min, bounds.max
        ))),
        None => Ok(()),
    }
}

fn mission_from(params: &FlatParams, ctx: &BuildContext) -> Result<Mission, Error> {
    match (&params.mission, &params.mission_file) {
        (Some(mission), None) => Ok(mission.clone()),
        (None, Some(path)) => {
            crate::load_mission(&ctx.resolve_path(path)).map_err(|e| Error::stage("world", e))
        }
        (Some(_), Some(_)) => Err(Error::invalid_param(
            "world",
            "give either `mission` or `mission_file`, not both",
        )),
        (None, None) => Err(Error::invalid_param(
            "world",
            "needs a `mission` table or a `mission_file`",
        )),
    }
}

smug_core::register_plugin!(
    smug_core::registry::WorldStage,
    name = "flat",
    summary = "flat floor with box obstacles; mission inline or from a file",
    params = FlatParams,
    build = |params, ctx| {
        let mission = mission_from(&params, ctx)?;
        Ok(Box::new(flat_world_within(&params, mission, ctx.memory())?))
    },
);

#[cfg(test)]
mod tests {
    use super::*;

    fn mission() -> Mission {
        toml::from_str(
            "start = { x = 1.0, y = 1.0 }\n[[targets]]\nid = \"t\"\nposition = { x = 5.0, y = 5.0 }\npois = [{ x = 4.0, y = 5.0 }]\n",
        )
        .unwrap()
    }

    #[test]
    fn obstacles_raise_the_floor() {
        let params = FlatParams {
            obstacles: vec![BoxObstacle {
                min: [2.0, 2.0],
                max: [3.0, 3.0],
                height: 1.5,
            }],
            ..FlatParams::default()
        };
        let world = flat_world(&params, mission()).unwrap().world;
        assert_eq!(world.elevation.geometry.size, [100, 100]);
        assert_eq!(world.height_at(2.5, 2.5), Some(1.5));
        assert_eq!(world.height_at(5.0, 5.0), Some(0.0));
    }

    #[test]
    fn rejects_bad_sizes_and_poses_outside() {
        let params = FlatParams {
            size: [0.0, 1.0],
            ..FlatParams::default()
        };
        assert!(flat_world(&params, mission()).is_err());
        let mut m = mission();
        m.targets[0].pois[0].x = 50.0;
        let err = flat_world(&FlatParams::default(), m)
            .unwrap_err()
            .to_string();
        assert!(err.contains("PoI 0 of target `t`"), "{err}");
    }
}
