//! Targets a mission cannot serve: the error that names them, and how the legs from the
//! start to their PoIs ended; found after a failed selection, or before the order is
//! chosen from the start's row of the full cost matrix.

use crate::layout::Layout;
use crate::oracle::PathOracle;
use smug_core::error::{Error, Result};
use smug_core::mission::Mission;
use std::collections::BTreeMap;

/// Targets that cannot be reached: the plan fails and names them.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("no safe path reaches target(s) {}{}{}", .targets.iter().map(|t| format!("`{t}`")).collect::<Vec<_>>().join(", "), why_suffix(.why), legs_suffix(.targets, .legs))]
pub struct Unreachable {
    /// Ids of the unreachable targets.
    pub targets: Vec<String>,
    /// Why, where known: one line per PoI left out (target, PoI index, reason).
    pub why: Vec<String>,
    /// How the legs from the start to each target's PoIs ended, by `kind:why`
    /// (`proved:disconnected`, `budget_spent:samples`, …), one map per target in
    /// `targets`' order; empty where the legs were not what ruled the target out.
    pub legs: Vec<BTreeMap<String, u64>>,
}

/// The reasons of an [`Unreachable`], on lines of their own.
fn why_suffix(why: &[String]) -> String {
    why.iter().map(|w| format!("\n  {w}")).collect()
}

/// How the start's legs to each target's PoIs ended, a line per target that has them
/// (`10 × budget_spent:samples`: whether no path exists was never decided).
fn legs_suffix(targets: &[String], legs: &[BTreeMap<String, u64>]) -> String {
    targets
        .iter()
        .zip(legs)
        .filter(|(_, counts)| !counts.is_empty())
        .map(|(target, counts)| {
            let ended: Vec<String> = counts
                .iter()
                .map(|(why, n)| format!("{n} × {why}"))
                .collect();
            format!(
                "\n  `{target}`: the legs from the start to its PoIs: {}",
                ended.join(", ")
            )
        })
        .collect()
}

/// Targets none of whose PoIs the start reaches.
pub(crate) fn unreachable_targets(
    oracle: &mut PathOracle,
    layout: &Layout,
    targets: &[usize],
) -> Result<Vec<usize>> {
    let mut unreachable = Vec::new();
    for &t in targets {
        let mut reached = false;
        for &p in &layout.pois[t] {
            if oracle.cost(layout.start, p)?.is_finite() {
                reached = true;
                break;
            }
        }
        if !reached {
            unreachable.push(t);
        }
    }
    Ok(unreachable)
}

/// How the legs from the start to the PoIs of each of `targets` ended, by `kind:why`.
pub(crate) fn start_legs(
    oracle: &mut PathOracle,
    layout: &Layout,
    targets: &[usize],
) -> Result<Vec<BTreeMap<String, u64>>> {
    let mut legs = Vec::with_capacity(targets.len());
    for &t in targets {
        let mut counts = BTreeMap::new();
        for &p in &layout.pois[t] {
            if let Some(reason) = oracle.path(layout.start, p)?.outcome.no_path_reason() {
                *counts
                    .entry(format!("{}:{}", reason.kind(), reason.why()))
                    .or_insert(0) += 1;
            }
        }
        legs.push(counts);
    }
    Ok(legs)
}

/// Why the start reaches no target at all: the start pose and how its legs to the PoIs
/// ended (the same reason for every leg says the start is enclosed).
pub(crate) fn enclosed_start(
    oracle: &mut PathOracle,
    layout: &Layout,
    targets: &[usize],
) -> Result<Vec<String>> {
    let mut reasons: BTreeMap<String, usize> = Default::default();
    for &t in targets {
        for &p in &layout.pois[t] {
            let planned = oracle.path(layout.start, p)?;
            let reason = match planned.outcome.no_path_reason() {
                Some(reason) => reason.to_string(),
                None => format!("{:?}", planned.outcome),
            };
            *reasons.entry(reason).or_default() += 1;
        }
    }
    let start = oracle.pose(layout.start);
    let legs: Vec<String> = reasons
        .iter()
        .map(|(reason, n)| format!("{n} × {reason}"))
        .collect();
    Ok(vec![format!(
        "the start ({:.3}, {:.3}, yaw {:.3}) reaches no PoI of any target: the robot is \
         enclosed where it starts, or every PoI is cut off from it; its legs: {}",
        start.x,
        start.y,
        start.yaw,
        legs.join("; ")
    )])
}

/// Fails naming `unreachable` (mission indices into `targets`) unless the options skip
/// unreachable targets; then records them in `skipped` and drops them from `targets`.
/// When every one of several targets is unreachable the message says whether the start
/// is enclosed; each target's legs from the start say how they ended.
pub(crate) fn fail_or_skip(
    oracle: &mut PathOracle,
    mission: &Mission,
    layout: &Layout,
    targets: &mut Vec<usize>,
    unreachable: &[usize],
    skip: bool,
    skipped: &mut Vec<String>,
) -> Result<()> {
    let ids: Vec<String> = unreachable
        .iter()
        .map(|&t| mission.targets[t].id.clone())
        .collect();
    if !skip {
        let why = if targets.len() > 1 && unreachable.len() == targets.len() {
            enclosed_start(oracle, layout, targets)?
        } else {
            Vec::new()
        };
        let legs = start_legs(oracle, layout, unreachable)?;
        return Err(Error::stage(
            "plan",
            Unreachable {
                targets: ids,
                why,
                legs,
            },
        ));
    }
    skipped.extend(ids);
    targets.retain(|t| !unreachable.contains(t));
    Ok(())
}
