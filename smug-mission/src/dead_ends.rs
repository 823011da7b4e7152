//! PoIs a directed model cannot use: ones the start cannot reach, and ones from which
//! the end cannot be reached (a forward-only car facing a stone up close cannot leave;
//! one whose only way in is blocked cannot enter). Left in, they make some visiting
//! orders infeasible and the PoI selection fail; dropped before sequencing (only where
//! the planner proves it), every remaining PoI is joined to every other through the
//! start, so every order has a route.

use crate::assembly::original_index;
use crate::layout::Layout;
use crate::oracle::PathOracle;
use smug_core::error::Result;
use smug_core::mission::Mission;
use smug_core::plan::DeadEndPoi;

/// Expansions a proof that a PoI cannot reach the end may take: enough for the few
/// poses a boxed-in car reaches, far too few to search a map.
const PROOF_EFFORT: u64 = 20_000;

/// Drops from `layout` the PoIs of `targets` that the start provably cannot reach or
/// that provably cannot reach the end, for directed models (symmetric ones: the
/// start's reach decides both ways, checked later for whole targets) and planners that
/// prove dead ends cheaply (others are not asked: their plans do not change). Plans the start's
/// row of paths to every PoI (one search where the planner answers many; the sequencer
/// and selector reuse it).
pub(super) fn drop_dead_ends(
    oracle: &mut PathOracle,
    mission: &Mission,
    given: &Mission,
    layout: &mut Layout,
    targets: &[usize],
) -> Result<Vec<DeadEndPoi>> {
    if oracle.is_symmetric() || !oracle.proves_dead_ends() {
        return Ok(Vec::new());
    }
    let all: Vec<usize> = targets
        .iter()
        .flat_map(|&t| layout.pois[t].iter().copied())
        .collect();
    if oracle.answers_many() {
        oracle.plan_from(layout.start, &all)?;
    }
    let mut dropped = Vec::new();
    for &t in targets {
        let mut kept = Vec::with_capacity(layout.pois[t].len());
        for &p in &layout.pois[t] {
            match closed_way(oracle, layout, p)? {
                None => kept.push(p),
                Some(why) => {
                    let pose = *oracle.pose(p);
                    let id = &mission.targets[t].id;
                    dropped.push(DeadEndPoi {
                        target: id.clone(),
                        index: original_index(given, id, &pose),
                        pose,
                        why,
                    });
                }
            }
        }
        layout.pois[t] = kept;
    }
    Ok(dropped)
}

/// Why PoI `p` cannot be part of a route, when the planner proves it.
fn closed_way(oracle: &mut PathOracle, layout: &Layout, p: usize) -> Result<Option<String>> {
    let from_start = oracle.path(layout.start, p)?;
    if let Some(reason) = from_start.outcome.no_path_reason() {
        if reason.is_proved() {
            return Ok(Some(format!("cannot be reached from the start: {reason}")));
        }
    }
    if let Some(reason) = oracle.prove_unreachable(p, layout.end, PROOF_EFFORT)? {
        return Ok(Some(format!("the end cannot be reached from it: {reason}")));
    }
    Ok(None)
}
