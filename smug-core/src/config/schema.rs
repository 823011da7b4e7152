//! SMUG's config schema: the pipeline's sections, the robot, outputs and limits.

use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// A stage's config section: `type = "plugin-name"` and the plugin's `params` table.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PluginSection {
    /// The plugin's registered name.
    #[serde(rename = "type")]
    pub kind: String,
    /// The plugin's parameters (checked by the plugin's typed params struct).
    #[serde(default)]
    pub params: toml::Table,
    /// Where the section sits in the config, e.g. `planner`.
    #[serde(skip)]
    pub key: String,
}

impl PluginSection {
    /// A section for plugin `kind` at config key `key` with no parameters.
    pub fn new(key: &str, kind: &str) -> Self {
        Self {
            kind: kind.to_string(),
            params: toml::Table::new(),
            key: key.to_string(),
        }
    }
}

/// The robot's base as a box, and its height above the terrain.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RobotConfig {
    /// Box length along the heading, metres.
    pub length: f64,
    /// Box width, metres.
    pub width: f64,
    /// Box height, metres.
    pub height: f64,
    /// Height of the box centre above the terrain, metres.
    pub base_height: f64,
}

impl Default for RobotConfig {
    /// ANYmal's torso (the paper's robot): 1.07 × 0.55 × 0.3 m.
    fn default() -> Self {
        Self {
            length: 1.07,
            width: 0.55,
            height: 0.3,
            base_height: 0.5,
        }
    }
}

impl RobotConfig {
    /// The first field with a bad value and why.
    pub(super) fn invalid_field(&self) -> Option<(&'static str, String)> {
        let fields = [
            ("length", self.length),
            ("width", self.width),
            ("height", self.height),
        ];
        if let Some((name, v)) = fields.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
            return Some((name, format!("must be a finite length > 0, got {v}")));
        }
        (!self.base_height.is_finite()).then(|| {
            (
                "base_height",
                format!("must be finite, got {}", self.base_height),
            )
        })
    }
}

/// What `smug plan` writes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputConfig {
    /// Output directory (the `--out` flag overrides it).
    pub dir: Option<PathBuf>,
    /// Write `plan.json`.
    pub json: bool,
    /// Write `plan.csv`.
    pub csv: bool,
    /// Write `plan.svg`.
    pub svg: bool,
}

impl Default for OutputConfig {
    fn default() -> Self {
        Self {
            dir: None,
            json: true,
            csv: true,
            svg: true,
        }
    }
}

/// A whole pipeline: one section per stage. Stages a command does not need may be absent.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PipelineConfig {
    /// Seed of every random choice; the same seed gives bit-identical runs.
    #[serde(default)]
    pub seed: u64,
    /// Where the maps and the mission come from.
    pub world: Option<PluginSection>,
    /// The robot's base box.
    #[serde(default)]
    pub robot: RobotConfig,
    /// Motion model: k-NN distance and local motions (default `se2`).
    pub space: Option<PluginSection>,
    /// What a path costs, with an admissible bound (default `path-length`).
    pub objective: Option<PluginSection>,
    /// Removed: split into `[space]` and `[objective]` (kept to say so clearly).
    #[serde(default, skip_serializing)]
    pub cost: Option<toml::Value>,
    /// Traversability estimator (absent: keep the world's own layer, if any).
    pub traversability: Option<PluginSection>,
    /// State validity checker.
    pub validity: Option<PluginSection>,
    /// Motion validator.
    pub motion: Option<PluginSection>,
    /// Sampler used by the planner.
    pub sampler: Option<PluginSection>,
    /// Point-to-point planner.
    pub planner: Option<PluginSection>,
    /// TSP solver for the visiting order.
    pub sequencer: Option<PluginSection>,
    /// PoI selector.
    pub selector: Option<PluginSection>,
    /// How the mission is run.
    #[serde(default)]
    pub plan: crate::mission::PlanOptions,
    /// Output files.
    #[serde(default)]
    pub output: OutputConfig,
    /// Resource limits (`[limits] memory_gb`).
    #[serde(default)]
    pub limits: crate::limits::LimitsConfig,
}

impl PipelineConfig {
    /// The plugin sections present, in pipeline order, with their keys.
    pub fn sections(&self) -> Vec<&PluginSection> {
        [
            &self.world,
            &self.traversability,
            &self.space,
            &self.objective,
            &self.validity,
            &self.motion,
            &self.sampler,
            &self.planner,
            &self.sequencer,
            &self.selector,
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    pub(super) fn assign_section_keys(&mut self) {
        let slots = [
            ("world", &mut self.world),
            ("traversability", &mut self.traversability),
            ("space", &mut self.space),
            ("objective", &mut self.objective),
            ("validity", &mut self.validity),
            ("motion", &mut self.motion),
            ("sampler", &mut self.sampler),
            ("planner", &mut self.planner),
            ("sequencer", &mut self.sequencer),
            ("selector", &mut self.selector),
        ];
        for (key, slot) in slots {
            if let Some(section) = slot {
                section.key = key.to_string();
            }
        }
    }
}
