//! Turning a chosen route into a [`Plan`]: its segments, chosen PoIs and statistics.

use crate::oracle::PathOracle;
use smug_core::error::{Error, Result};
use smug_core::mission::Mission;
use smug_core::pipeline::Pipeline;
use smug_core::plan::{ChosenPoi, Plan, PlanStats, Segment};
use smug_core::pose::Pose2;

/// The index of `pose` among the PoIs of target `id` in `given` (the mission as
/// given, before PoIs invalid for the robot were dropped).
pub(super) fn original_index(given: &Mission, id: &str, pose: &Pose2) -> usize {
    given
        .targets
        .iter()
        .find(|t| t.id == id)
        .and_then(|t| t.pois.iter().position(|p| p == pose))
        .unwrap_or(0)
}

/// The plan that visits `order`'s targets at the `chosen` oracle poses along `route`.
pub(super) fn assemble_plan(
    oracle: &mut PathOracle,
    mission: &Mission,
    given: &Mission,
    order: &[usize],
    chosen: &[usize],
    route: &[usize],
) -> Result<Plan> {
    let name = |k: usize| -> String {
        if k == 0 {
            "start".into()
        } else if k == route.len() - 1 {
            if mission.end.is_some() {
                "end".into()
            } else {
                "start".into()
            }
        } else {
            mission.targets[order[k - 1]].id.clone()
        }
    };
    let mut segments = Vec::new();
    for k in 0..route.len() - 1 {
        let planned = oracle.path(route[k], route[k + 1])?;
        let path = planned.path().cloned().ok_or_else(|| {
            Error::InvalidInput(format!("no path from {} to {}", name(k), name(k + 1)))
        })?;
        segments.push(Segment {
            from: name(k),
            to: name(k + 1),
            path,
        });
    }
    let pois = order
        .iter()
        .zip(chosen)
        .map(|(&t, &p)| {
            let pose = *oracle.pose(p);
            let id = mission.targets[t].id.clone();
            ChosenPoi {
                index: original_index(given, &id, &pose),
                target: id,
                pose,
            }
        })
        .collect();
    Ok(Plan {
        sequence: order
            .iter()
            .map(|&t| mission.targets[t].id.clone())
            .collect(),
        pois,
        segments,
        ..Plan::default()
    })
}

/// The plan's statistics from the oracle's, the planner's and the validity checker's counters.
pub(super) fn stats(
    oracle: &PathOracle,
    pipeline: &Pipeline,
    times: std::collections::BTreeMap<String, f64>,
) -> PlanStats {
    let planner = oracle.planner().stats();
    let validity = pipeline
        .state_validity
        .as_ref()
        .map(|c| c.counters())
        .unwrap_or_default();
    let mut counters = planner.counters.clone();
    counters.insert("roadmap_vertices".into(), planner.vertices);
    counters.insert("roadmap_edges".into(), planner.edges);
    counters.insert("oracle_cache_hits".into(), oracle.stats().cache_hits);
    if oracle.stats().known_hits > 0 {
        counters.insert("oracle_known_hits".into(), oracle.stats().known_hits);
    }
    for (k, v) in &validity {
        counters.insert(format!("validity_{k}"), *v);
    }
    PlanStats {
        paths_planned: oracle.stats().paths_planned,
        validity_queries: validity.get("checks").copied().unwrap_or(0),
        stage_times_s: times,
        breakdown: planner.breakdown,
        counters,
        legs_without_path: oracle.no_path_counts(),
    }
}
