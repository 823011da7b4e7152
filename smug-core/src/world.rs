//! A world: terrain layers and volumetric maps; a scenario: a world and the mission to
//! plan in it (what a `world` plugin builds).

use crate::grid::{GridLayer, VoxelGrid};
use crate::mission::Mission;
use crate::pose::Bounds2;
use serde::{Deserialize, Serialize};

/// Everything a pipeline plans in.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct World {
    /// Name for reports.
    pub name: String,
    /// Terrain height (2.5D), metres; NaN = no data. Defines the planning bounds.
    pub elevation: GridLayer,
    /// Traversability in `[0, 1]`, NaN = no data; filled by a traversability estimator.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub traversability: Option<GridLayer>,
    /// Occupancy voxels (ground and everything below it occupied).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub occupancy: Option<VoxelGrid<bool>>,
    /// Euclidean signed distance field of `occupancy`, metres (negative inside).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub esdf: Option<VoxelGrid<f32>>,
}

/// A world and the mission to plan in it: what a `world` plugin builds (a procedural
/// world generates its targets; a map world reads its mission file).
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Maps and layers.
    pub world: World,
    /// What to visit.
    pub mission: Mission,
}

impl World {
    /// A world with only an elevation layer.
    pub fn new(name: impl Into<String>, elevation: GridLayer) -> Self {
        Self {
            name: name.into(),
            elevation,
            traversability: None,
            occupancy: None,
            esdf: None,
        }
    }

    /// This world with `mission` to plan in it.
    pub fn with_mission(self, mission: Mission) -> Scenario {
        Scenario {
            world: self,
            mission,
        }
    }

    /// The planning bounds (the elevation layer's extent).
    pub fn bounds(&self) -> Bounds2 {
        self.elevation.geometry.bounds()
    }

    /// Terrain height at `(x, y)`, bilinear; `None` outside or where unknown.
    #[inline]
    pub fn height_at(&self, x: f64, y: f64) -> Option<f64> {
        self.elevation.bilinear(x, y)
    }
}
