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
    /// Top speed on good flat ground, m/s: the `time` objective's `max_speed` when a
    /// team compares its robots in time (`[team] unit = "time"`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_speed: Option<f64>,
    /// Turning rate, rad/s: the `time` objective's `turn_rate` in a team's time unit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turn_rate: Option<f64>,
}

impl Default for RobotConfig {
    /// ANYmal's torso (the paper's robot): 1.07 × 0.55 × 0.3 m.
    fn default() -> Self {
        Self {
            length: 1.07,
            width: 0.55,
            height: 0.3,
            base_height: 0.5,
            max_speed: None,
            turn_rate: None,
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
        let rates = [("max_speed", self.max_speed), ("turn_rate", self.turn_rate)];
        if let Some((name, Some(v))) = rates
            .iter()
            .find(|(_, v)| v.is_some_and(|v| !(v.is_finite() && v > 0.0)))
        {
            return Some((name, format!("must be a finite rate > 0, got {v}")));
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
    /// Write `plan.mcap` (ROS 2 messages for Foxglove, RViz2 and `ros2 bag`).
    pub mcap: bool,
}

impl Default for OutputConfig {
    fn default() -> Self {
        Self {
            dir: None,
            json: true,
            csv: true,
            svg: true,
            mcap: true,
        }
    }
}

/// Generates [`PipelineConfig`] from the stage table: one optional section per stage,
/// then the settings of the run.
macro_rules! pipeline_config {
    ($($(#[$doc:meta])* $key:ident: $marker:ident = $summary:literal, $object:ty, $default:expr;)*) => {
        /// A whole pipeline: one section per stage (stages a command does not need may
        /// be absent), the robot and the run's settings.
        #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct PipelineConfig {
            /// Seed of every random choice; the same seed gives bit-identical runs.
            #[serde(default)]
            pub seed: u64,
            $(
                #[doc = concat!("`[", stringify!($key), "]`: ", $summary, ".")]
                $(#[$doc])*
                pub $key: Option<PluginSection>,
            )*
            /// The robot's base box.
            #[serde(default)]
            pub robot: RobotConfig,
            /// Removed: split into `[space]` and `[objective]` (kept to say so clearly).
            #[serde(default, skip_serializing)]
            pub cost: Option<toml::Value>,
            /// How the mission is run.
            #[serde(default)]
            pub plan: crate::mission::PlanOptions,
            /// Output files.
            #[serde(default)]
            pub output: OutputConfig,
            /// Resource limits (`[limits] memory_gb`).
            #[serde(default)]
            pub limits: crate::limits::LimitsConfig,
            /// A team of robots (`[team]`, team missions only).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub team: Option<super::team::TeamConfig>,
        }

        impl PipelineConfig {
            /// The plugin sections present, in pipeline order, with their keys.
            pub fn sections(&self) -> Vec<&PluginSection> {
                [$(&self.$key),*].into_iter().flatten().collect()
            }

            /// The section of the stage at config key `key`: the configured one, else
            /// its default plugin's (`se2`, `path-length`), else `None`.
            pub fn section(&self, key: &str) -> Option<PluginSection> {
                match key {
                    $(stringify!($key) => self.$key.clone().or_else(|| {
                        let default: Option<&str> = $default;
                        default.map(|kind| PluginSection::new(key, kind))
                    }),)*
                    _ => None,
                }
            }

            /// Removes every stage section whose key is not in `keep` (to build part of
            /// a pipeline, e.g. only its world).
            pub fn keep_sections(&mut self, keep: &[&str]) {
                $(if !keep.contains(&stringify!($key)) {
                    self.$key = None;
                })*
            }

            pub(super) fn assign_section_keys(&mut self) {
                $(if let Some(section) = &mut self.$key {
                    section.key = stringify!($key).to_string();
                })*
            }
        }
    };
}

stage_table!(pipeline_config);

#[cfg(test)]
mod tests {
    use super::{PipelineConfig, PluginSection};

    fn config(text: &str) -> PipelineConfig {
        let mut config: PipelineConfig = toml::from_str(text).unwrap();
        config.assign_section_keys();
        config
    }

    #[test]
    fn an_absent_section_is_its_stage_default_or_none() {
        let c = config("[planner]\ntype = \"lazy-prm-star\"\n");
        assert_eq!(c.section("space"), Some(PluginSection::new("space", "se2")));
        let objective = PluginSection::new("objective", "path-length");
        assert_eq!(c.section("objective"), Some(objective));
        assert_eq!(c.section("validity"), None);
        assert_eq!(c.section("planner").unwrap().kind, "lazy-prm-star");
        assert_eq!(c.section("planner").unwrap().key, "planner");
        assert_eq!(c.section("no-such-stage"), None);
    }

    #[test]
    fn keep_sections_clears_the_other_stages_only() {
        let mut c = config("seed = 3\n[world]\ntype = \"flat\"\n[planner]\ntype = \"x\"\n");
        c.keep_sections(&["world", "space"]);
        assert_eq!(c.world.as_ref().unwrap().kind, "flat");
        assert!(c.planner.is_none());
        assert_eq!(c.seed, 3);
        assert_eq!(c.sections().len(), 1);
    }
}
