//! What `smug bench modes` runs and measures: its missions, modes and runs (read by
//! the harness and by its report).

use serde::Serialize;

/// A mission of the benchmark: a config and the overrides that size it.
#[derive(Debug)]
pub struct Mission {
    /// The name `--missions` takes.
    pub name: &'static str,
    /// The name in the report.
    pub label: &'static str,
    /// The config, relative to the working directory.
    pub config: &'static str,
    /// Overrides applied on top of the config.
    pub set: &'static [&'static str],
    /// A polygon map instead of the config's world (`config` is then empty).
    pub polygons: Option<Polygons>,
}

/// Where a polygon mission's map comes from.
#[derive(Clone, Copy, Debug)]
pub enum Polygons {
    /// Generated for each seed with this many targets.
    Generated(usize),
    /// The `--data` map: a closed tour from its start city, or (`open`) a path to its
    /// end city.
    Data {
        /// A path to the file's end city instead of back to the start.
        open: bool,
    },
}

/// Every mission `--missions` knows.
pub const MISSIONS: [Mission; 15] = [
    Mission {
        name: "lunar",
        label: "lunar 13×10",
        config: "configs/lunar.toml",
        set: &[],
        polygons: None,
    },
    Mission {
        name: "indoor",
        label: "indoor 12×2",
        config: "configs/indoor.toml",
        set: &[],
        polygons: None,
    },
    Mission {
        name: "lunar-48x6",
        label: "lunar 48×6",
        config: "configs/lunar.toml",
        set: &["world.params.targets=48", "world.params.pois_per_target=6"],
        polygons: None,
    },
    Mission {
        name: "lunar-200x10",
        label: "lunar 200×10 (100×100 m)",
        config: "configs/lunar.toml",
        set: &[
            "world.params.targets=200",
            "world.params.pois_per_target=10",
            "world.params.size=[100.0,100.0]",
            // One search per source: the paper's one query per pair takes ~330 s here.
            "planner.params.one_to_many=true",
        ],
        polygons: None,
    },
    shipped("flat-demo", "flat demo", "configs/flat-demo.toml"),
    shipped(
        "flat-dubins",
        "flat, Dubins car",
        "configs/flat-dubins.toml",
    ),
    shipped(
        "imported-map",
        "imported map 32×32",
        "configs/imported-map.toml",
    ),
    shipped(
        "indoor-disc",
        "indoor, disc robot",
        "configs/indoor-disc.toml",
    ),
    shipped(
        "lunar-wheeled",
        "lunar, wheeled robot",
        "configs/lunar-wheeled.toml",
    ),
    shipped(
        "lunar-rover",
        "lunar, rover (lattice)",
        "configs/lunar-rover.toml",
    ),
    polygon_mission("poly-20", "polygons 2000² 20×1", Polygons::Generated(20)),
    polygon_mission("poly-40", "polygons 2000² 40×1", Polygons::Generated(40)),
    polygon_mission("poly-60", "polygons 2000² 60×1", Polygons::Generated(60)),
    polygon_mission(
        "data",
        "--data map, closed tour",
        Polygons::Data { open: false },
    ),
    polygon_mission(
        "data-open",
        "--data map, open path",
        Polygons::Data { open: true },
    ),
];

/// A shipped config's own mission.
const fn shipped(name: &'static str, label: &'static str, config: &'static str) -> Mission {
    Mission {
        name,
        label,
        config,
        set: &[],
        polygons: None,
    }
}

/// A mission on a polygon map.
const fn polygon_mission(name: &'static str, label: &'static str, polygons: Polygons) -> Mission {
    Mission {
        name,
        label,
        config: "",
        set: &[],
        polygons: Some(polygons),
    }
}

/// The pipeline of the polygon missions: `configs/p2p-grid.toml` (a disc on the
/// grid) with the `auto` sequencer and the `idp` selector, these overrides on top. The
/// planner is the missions' default `auto`, which plans with the exact `visibility`
/// planner here (a disc on a grid, straight motions, path length): what a mission
/// config on such a map gets (`--set planner.type=lazy-prm-star` for LazyPRM*).
pub const POLYGON_SET: [&str; 6] = [
    "planner.type=auto",
    "space.type=se2",
    "space.params.rotation_weight=0",
    "objective.type=path-length",
    "objective.params.rotation_weight=0",
    "validity.params.radius=0.5",
];

/// A planning mode: the overrides that select it.
#[derive(Debug)]
pub struct Mode {
    /// The name `--modes` takes.
    pub name: &'static str,
    /// The name in the report.
    pub label: &'static str,
    /// Overrides applied on top of the mission's.
    pub set: &'static [&'static str],
}

/// Every mode `--modes` knows.
pub const MODES: [Mode; 4] = [
    Mode {
        name: "full",
        label: "sequential, full matrix",
        set: &[
            "plan.mode=sequential",
            "plan.sequencing_costs=full",
            "plan.refine_legs=true",
        ],
    },
    Mode {
        name: "lazy",
        label: "sequential, lazy matrix",
        set: &[
            "plan.mode=sequential",
            "plan.sequencing_costs=lazy",
            "plan.refine_legs=true",
        ],
    },
    Mode {
        name: "lazy-unsettled",
        label: "sequential, lazy matrix, early legs not planned again",
        set: &[
            "plan.mode=sequential",
            "plan.sequencing_costs=lazy-unsettled",
            "plan.refine_legs=true",
        ],
    },
    Mode {
        name: "joint",
        label: "joint, auto",
        set: &[
            "plan.mode=joint",
            "sequencer.type=auto",
            "plan.refine_legs=true",
        ],
    },
];

/// One plan's measurements; `error` set (and the numbers `None`) when planning failed.
#[derive(Clone, Debug, Serialize)]
pub struct Run {
    /// The mission's name.
    pub mission: String,
    /// The mode's name.
    pub mode: String,
    /// The seed (world and planner).
    pub seed: u64,
    /// The plan's cost.
    pub cost: Option<f64>,
    /// Paths the path oracle planned (the plan's `stats.paths_planned`).
    pub paths_planned: Option<u64>,
    /// The plan's `total` time minus the pipeline's build times, seconds.
    pub planning_s: Option<f64>,
    /// The plan's `total` time (building the pipeline included), seconds.
    #[serde(default)]
    pub total_s: Option<f64>,
    /// The threads of the pool the run ran on (`None`: rayon's default).
    #[serde(default)]
    pub threads: Option<usize>,
    /// CPU time of the process's threads during the run (config loading, building and
    /// planning), seconds (`None` where the system does not say).
    #[serde(default)]
    pub cpu_s: Option<f64>,
    /// Time the process's threads were ready to run but waited for a core during the
    /// run (other jobs on the machine), seconds.
    #[serde(default)]
    pub waited_s: Option<f64>,
    /// The plan's target order (`sequence`).
    #[serde(default)]
    pub order: Vec<String>,
    /// Why planning failed.
    pub error: Option<String>,
}
