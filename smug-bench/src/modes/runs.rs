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
}

/// Every mission `--missions` knows.
pub const MISSIONS: [Mission; 4] = [
    Mission {
        name: "lunar",
        label: "lunar 13×10",
        config: "configs/lunar.toml",
        set: &[],
    },
    Mission {
        name: "indoor",
        label: "indoor 12×2",
        config: "configs/indoor.toml",
        set: &[],
    },
    Mission {
        name: "lunar-48x6",
        label: "lunar 48×6",
        config: "configs/lunar.toml",
        set: &["world.params.targets=48", "world.params.pois_per_target=6"],
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
    },
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
pub const MODES: [Mode; 3] = [
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
#[derive(Debug, Serialize)]
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
    /// Why planning failed.
    pub error: Option<String>,
}
