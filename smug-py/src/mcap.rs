//! `Plan.to_mcap`: a plan (or a team plan) with its world as plan.mcap, as `smug plan`
//! writes it.

use crate::{app_to_py, input_error, PyWorld};
use pyo3::prelude::*;
use smug_app::plan_mcap::{PlanScene, RunInfo, TeamScene, WriteMode};
use smug_core::{Plan, TeamPlan};
use std::path::PathBuf;

/// Writes `plan_json`'s plan in `world` to `path` (appended after the file's plans when
/// `append`), with the run's config TOML and seed as metadata.
#[pyfunction]
#[pyo3(signature = (path, plan_json, world, config_toml, seed, append=false))]
pub fn write_plan_mcap(
    py: Python<'_>,
    path: PathBuf,
    plan_json: &str,
    world: PyRef<'_, PyWorld>,
    config_toml: String,
    seed: u64,
    append: bool,
) -> PyResult<()> {
    let team = serde_json::from_str::<TeamPlan>(plan_json).ok();
    let plan: Plan = match team {
        Some(_) => Plan::default(),
        None => serde_json::from_str(plan_json)
            .map_err(|e| input_error(format!("the plan's JSON: {e}")))?,
    };
    let (world_, mission, invalid) = (
        world.world.clone(),
        world.mission.clone(),
        world.invalid_pois.clone(),
    );
    let (mode, kind) = match append {
        true => (WriteMode::Append, "replan"),
        false => (WriteMode::Replace, "plan"),
    };
    let run = RunInfo {
        kind,
        config_toml,
        seed,
    };
    py.detach(move || {
        if let Some(plan) = &team {
            let scene = TeamScene {
                plan,
                world: &world_,
                mission: &mission,
            };
            return smug_app::plan_mcap::write_team_plan_mcap(&path, &scene, &run, mode);
        }
        let scene = PlanScene {
            plan: &plan,
            world: &world_,
            mission: &mission,
            invalid_pois: &invalid,
        };
        smug_app::plan_mcap::write_plan_mcap(&path, &scene, &run, mode)
    })
    .map_err(|e| app_to_py(e.into()))
}
