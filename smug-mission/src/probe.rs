//! A budgeted early probe of the mission's start and end poses, before any row of
//! paths is planned: a car boxed in where it starts (or an end pose whose only ways in
//! are blocked: a forward-only car must arrive facing the end's heading) makes every
//! later search run out of lattice poses far away, each one over the whole map. A small
//! search from the start (and small ones from the PoIs into the end, each cheap when
//! the end cannot be entered) exhausts the few poses they reach at once: a proof,
//! reported by naming the pose and why. When a budget runs out first nothing is
//! proved and the mission goes on as before.

use crate::layout::Layout;
use crate::oracle::PathOracle;
use smug_core::error::{Error, Result};
use smug_core::{NoPathReason, Pose2};

/// Expansions each probe may take: enough for the few poses a boxed-in car reaches,
/// far too few to search a map (a lunar map's lattice has millions of poses).
pub(super) const PROBE_EFFORT: u64 = 20_000;

/// Which of the mission's poses a probe proved cut off.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// The start: no PoI can be reached from it.
    Start,
    /// The end: no PoI leads into it.
    End,
}

/// The start pose reaches no PoI, or no PoI reaches the end pose: proved, the plan
/// fails and names the pose.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}", describe(self))]
pub struct CutOff {
    /// Which pose.
    pub side: Side,
    /// Where it is.
    pub pose: Pose2,
    /// True when the end pose is the start's (a closed tour).
    pub closed: bool,
    /// The PoIs tried (every PoI of every target).
    pub pois: usize,
    /// The proof.
    pub reason: NoPathReason,
}

/// The message of a [`CutOff`].
fn describe(cut: &CutOff) -> String {
    let p = &cut.pose;
    let at = format!("({:.3}, {:.3}, yaw {:.3})", p.x, p.y, p.yaw);
    let why = match (cut.reason.is_proved(), cut.side) {
        (false, _) => cut.reason.to_string(),
        (true, Side::Start) => {
            "proved: a search from it ran out of the lattice poses it reaches".to_string()
        }
        (true, Side::End) => {
            "proved: the search from each ran out of the lattice poses it reaches".to_string()
        }
    };
    match cut.side {
        Side::Start => format!(
            "the start pose {at} is boxed in: none of the {} PoIs of the targets can be \
             reached from it ({why})",
            cut.pois
        ),
        Side::End => format!(
            "no path enters the end pose {at}{}: none of the {} PoIs tried leads into it, \
             arriving with its heading ({why})",
            if cut.closed {
                " (the start: a closed tour ends where it began, facing the same way)"
            } else {
                ""
            },
            cut.pois,
        ),
    }
}

/// Probes the start (and, for a directed model or a separate end pose, the end) with
/// searches of at most [`PROBE_EFFORT`] expansions towards every PoI of `targets`;
/// fails with a [`CutOff`] when one proves that no PoI can be used, does nothing when
/// the planner does not prove dead ends cheaply.
pub(super) fn probe_start_and_end(
    oracle: &mut PathOracle,
    layout: &Layout,
    targets: &[usize],
) -> Result<()> {
    if !oracle.proves_dead_ends() {
        return Ok(());
    }
    let pois: Vec<usize> = targets
        .iter()
        .flat_map(|&t| layout.pois[t].iter().copied())
        .collect();
    if pois.is_empty() {
        return Ok(());
    }
    let closed = layout.end == layout.start;
    let cut = |side, at: usize, reason, oracle: &PathOracle| CutOff {
        side,
        pose: *oracle.pose(at),
        closed,
        pois: pois.len(),
        reason,
    };
    // The end first: its searches stop at the first PoI that proves nothing (the
    // start's ends at the first PoI it reaches). (A symmetric model
    // enters a pose wherever it can leave it: the start's probe decides for both.)
    if !(closed && oracle.is_symmetric()) {
        let into_end = oracle.prove_unenterable(layout.end, &pois, PROBE_EFFORT)?;
        if let Some(reason) = all_proved(&into_end) {
            return Err(Error::stage(
                "plan",
                cut(Side::End, layout.end, reason, oracle),
            ));
        }
    }
    let from_start = oracle.prove_unreachable_from(layout.start, &pois, PROBE_EFFORT)?;
    if let Some(reason) = all_proved(&from_start) {
        return Err(Error::stage(
            "plan",
            cut(Side::Start, layout.start, reason, oracle),
        ));
    }
    Ok(())
}

/// The first proof when every entry is proved.
fn all_proved(proofs: &[Option<NoPathReason>]) -> Option<NoPathReason> {
    proofs
        .iter()
        .all(Option::is_some)
        .then(|| proofs[0])
        .flatten()
}

/// After a failed PoI selection: the end pose named as the reason when every leg
/// planned into it from a PoI has no path (at least one was planned), with the reason
/// of those legs (a proof where one of them has it).
pub(super) fn end_not_entered(
    oracle: &mut PathOracle,
    layout: &Layout,
    targets: &[usize],
) -> Result<Option<CutOff>> {
    let mut tried = 0;
    let mut reason: Option<NoPathReason> = None;
    for &t in targets {
        for &p in &layout.pois[t] {
            if p == layout.end || !oracle.is_planned(p, layout.end) {
                continue;
            }
            let planned = oracle.path(p, layout.end)?;
            let Some(why) = planned.outcome.no_path_reason() else {
                return Ok(None);
            };
            tried += 1;
            if reason.is_none_or(|r| !r.is_proved()) {
                reason = Some(why);
            }
        }
    }
    Ok(reason.map(|reason| CutOff {
        side: Side::End,
        pose: *oracle.pose(layout.end),
        closed: layout.end == layout.start,
        pois: tried,
        reason,
    }))
}
