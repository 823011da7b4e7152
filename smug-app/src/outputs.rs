//! The files a plan is written to: plan.json, plan.csv, plan.svg and plan.mcap (as the
//! config's `[output]` asks), each whole or not at all.

use crate::no_plan::{NoPlanReport, PLANNED};
use crate::plan_mcap::{write_plan_mcap, PlanScene, RunInfo, WriteMode};
use crate::{AppError, Result};
use smug_core::config::OutputConfig;
use smug_core::{LoadedConfig, Mission, Pipeline, PipelineConfig, Plan, World};
use smug_worlds::render::{render_svg, RenderOptions};
use std::path::{Path, PathBuf};

/// The files [`write_outputs`] may write into its directory.
pub const OUTPUT_FILES: [&str; 4] = ["plan.json", "plan.csv", "plan.svg", "plan.mcap"];

/// Writes `plan` (made by `pipeline`, in its world) into `dir` as the config's
/// `[output]` asks; each file whole or not at all, so a killed run leaves the previous
/// plan intact. `mcap` says whether plan.mcap starts anew (a plan) or gets the plan
/// appended (a replan). The text files, plan.mcap and plan.svg are made side by side
/// (on the caller's rayon pool); the first error in that order is returned.
pub fn write_outputs(plan: &Plan, pipeline: &Pipeline, dir: &Path, mcap: WriteMode) -> Result<()> {
    let output = &pipeline.config.output;
    let write = file_writer(dir)?;
    let texts = || -> Result<()> {
        if output.json {
            write("plan.json", plan_json(plan)?)?;
        }
        if output.csv {
            write("plan.csv", plan_csv(plan))?;
        }
        Ok(())
    };
    let world = pipeline.world.as_deref();
    let mission = pipeline
        .given_mission
        .as_ref()
        .or(pipeline.mission.as_ref());
    let (Some(world), Some(mission)) = (world, mission) else {
        texts()?;
        return Err(AppError::NoWorld);
    };
    let write_mcap = || -> Result<()> {
        if output.mcap {
            let invalid: Vec<(String, usize)> = pipeline
                .dropped_pois
                .iter()
                .map(|d| (d.target.clone(), d.index))
                .collect();
            let scene = PlanScene {
                plan,
                world,
                mission,
                invalid_pois: &invalid,
            };
            let run = run_info(pipeline, mcap);
            write_plan_mcap(&dir.join("plan.mcap"), &scene, &run, mcap)?;
        }
        Ok(())
    };
    let write_svg = || -> Result<()> {
        if output.svg {
            write(
                "plan.svg",
                render_svg(world, Some(mission), &render_options(plan, world, mission)),
            )?;
        }
        Ok(())
    };
    let (texts, (mcap, svg)) = rayon::join(texts, || rayon::join(write_mcap, write_svg));
    texts.and(mcap).and(svg)
}

/// `plan.json`'s text: the plan with `"status": "planned"` first (what `smug plan
/// --json` prints and `smug.Plan.to_json()` returns).
pub fn plan_json(plan: &Plan) -> Result<String> {
    #[derive(serde::Serialize)]
    struct Planned<'a> {
        status: &'static str,
        #[serde(flatten)]
        plan: &'a Plan,
    }
    let planned = Planned {
        status: PLANNED,
        plan,
    };
    Ok(serde_json::to_string_pretty(&planned)?)
}

/// Writes the plan.json of a mission that ended without a plan into `dir` (when the
/// config's `[output]` asks for plan.json); the other files are not written, there is
/// nothing to draw, and those of an earlier plan in `dir` are removed, so that the
/// directory does not show a plan beside a plan.json that says there is none. A
/// replan's ([`WriteMode::Append`]) plan.mcap is kept: it holds the earlier plans, a
/// history rather than the current plan.
pub fn write_no_plan(
    report: &NoPlanReport,
    output: &OutputConfig,
    dir: &Path,
    mcap: WriteMode,
) -> Result<()> {
    if output.json {
        file_writer(dir)?("plan.json", serde_json::to_string_pretty(report)?)?;
    }
    let stale = OUTPUT_FILES.iter().filter(|name| {
        !(output.json && **name == "plan.json"
            || mcap == WriteMode::Append && **name == "plan.mcap")
    });
    for name in stale {
        let path = dir.join(name);
        match std::fs::remove_file(&path) {
            Err(source) if source.kind() != std::io::ErrorKind::NotFound => {
                return Err(AppError::Write {
                    path,
                    what: "cannot remove",
                    source,
                })
            }
            _ => {}
        }
    }
    Ok(())
}

/// Creates `dir`; the writer of whole files `(name, text)` into it (each whole or not
/// at all: a killed run leaves the previous file intact).
pub fn file_writer(dir: &Path) -> Result<impl Fn(&str, String) -> Result<()> + '_> {
    std::fs::create_dir_all(dir).map_err(|source| AppError::Write {
        path: dir.to_path_buf(),
        what: "cannot create",
        source,
    })?;
    Ok(move |name: &str, text: String| {
        let path = dir.join(name);
        smug_core::output::write_atomic(&path, text.as_bytes()).map_err(|source| AppError::Write {
            path,
            what: "cannot write",
            source,
        })
    })
}

/// The run's kind, config and seed for plan.mcap's metadata.
pub fn run_info(pipeline: &Pipeline, mode: WriteMode) -> RunInfo {
    config_run_info(&pipeline.config, mode)
}

/// [`run_info`] of a run of `config` (a team's, whose robots have pipelines of their
/// own).
pub fn config_run_info(config: &PipelineConfig, mode: WriteMode) -> RunInfo {
    RunInfo {
        kind: match mode {
            WriteMode::Replace => "plan",
            WriteMode::Append => "replan",
        },
        config_toml: toml::to_string(config)
            .unwrap_or_else(|err| format!("# the config could not be written as TOML: {err}")),
        seed: config.seed,
    }
}

/// Refuses an output directory where a plan file would overwrite one of the run's
/// inputs (its config files, maps, missions, layers, and `extra`, e.g. a mission state).
pub fn refuse_overwriting_inputs(
    dir: &Path,
    loaded: &LoadedConfig,
    extra: &[PathBuf],
) -> Result<()> {
    let outputs: Vec<PathBuf> = OUTPUT_FILES.iter().map(|name| dir.join(name)).collect();
    let mut inputs = loaded.input_files();
    inputs.extend(extra.iter().cloned());
    match smug_core::output::output_over_input(&outputs, &inputs) {
        Some(path) => Err(AppError::OutputOverInput {
            path: path.to_path_buf(),
        }),
        None => Ok(()),
    }
}

/// `plan.csv`: `x,y,z,yaw` per waypoint, and a `reversing` column (0/1) when the
/// plan ever drives backwards (as `plan.json`'s `reversing`).
pub fn plan_csv(plan: &Plan) -> String {
    let gears = plan.reversing.len() == plan.waypoints.len() && !plan.reversing.is_empty();
    let mut csv = String::from(if gears {
        "x,y,z,yaw,reversing\n"
    } else {
        "x,y,z,yaw\n"
    });
    push_waypoint_rows(&mut csv, "", plan, gears);
    csv
}

/// Appends one line per waypoint of `plan` to `csv`: `prefix` then `x,y,z,yaw`, and
/// `,1` / `,0` for reversing when `gears` (a waypoint without a gear goes forwards).
pub(crate) fn push_waypoint_rows(csv: &mut String, prefix: &str, plan: &Plan, gears: bool) {
    for (i, w) in plan.waypoints.iter().enumerate() {
        *csv += &format!("{prefix}{},{},{},{}", w.x, w.y, w.z, w.yaw);
        if gears {
            let reversing = plan.reversing.get(i).copied().unwrap_or(false);
            *csv += if reversing { ",1" } else { ",0" };
        }
        csv.push('\n');
    }
}

/// How plan.svg draws `plan` on `world` with the mission as given: the path, the
/// chosen PoIs and a title.
pub fn render_options(plan: &Plan, world: &World, mission: &Mission) -> RenderOptions {
    let highlighted = plan
        .pois
        .iter()
        .filter_map(|c| {
            mission
                .targets
                .iter()
                .position(|t| t.id == c.target)
                .map(|t| (t, c.index))
        })
        .collect();
    RenderOptions {
        title: Some(format!(
            "{}: cost {:.2}, {} targets",
            world.name,
            plan.cost,
            plan.sequence.len()
        )),
        paths: vec![plan.waypoints.iter().map(|w| [w.x, w.y]).collect()],
        highlighted_pois: highlighted,
        ..RenderOptions::default()
    }
}
