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

/// Drops from `layout` the PoIs of `targets` that provably cannot reach the end or
/// that the start provably cannot reach, for directed models (symmetric ones: the
/// start's reach decides both ways, checked later for whole targets) and planners that
/// prove dead ends cheaply (others are not asked: their plans do not change).
///
/// The cheap proofs come first: a small search from each PoI (a car boxed in where it
/// stands runs out of poses within [`PROOF_EFFORT`] expansions). The start's row of
/// paths (one search where the planner answers many; the sequencer and selector reuse
/// it) is then planned only to the PoIs left, and not at all when none is: a mission
/// whose every PoI is a dead end ends without searching the map.
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
    let mut dead = DeadEnds {
        mission,
        given,
        targets,
        dropped: Vec::new(),
    };
    dead.drop_where(oracle, layout, cannot_leave)?;
    let left: Vec<usize> = targets
        .iter()
        .flat_map(|&t| layout.pois[t].iter().copied())
        .collect();
    if !left.is_empty() && oracle.answers_many() {
        oracle.plan_from(layout.start, &left)?;
    }
    dead.drop_where(oracle, layout, cannot_enter)?;
    Ok(dead.dropped)
}

/// Why PoI `p` cannot be part of a route, when a proof says so.
type DeadEndProof = fn(&mut PathOracle, &Layout, usize) -> Result<Option<String>>;

/// The PoIs of a mission's `targets` dropped so far, and what naming them needs.
struct DeadEnds<'a> {
    mission: &'a Mission,
    given: &'a Mission,
    targets: &'a [usize],
    dropped: Vec<DeadEndPoi>,
}

impl DeadEnds<'_> {
    /// Drops from `layout` the PoIs of the targets that `proof` rules out, recording
    /// each.
    fn drop_where(
        &mut self,
        oracle: &mut PathOracle,
        layout: &mut Layout,
        proof: DeadEndProof,
    ) -> Result<()> {
        for &t in self.targets {
            let mut kept = Vec::with_capacity(layout.pois[t].len());
            for &p in &layout.pois[t] {
                match proof(oracle, layout, p)? {
                    None => kept.push(p),
                    Some(why) => {
                        let pose = *oracle.pose(p);
                        let id = &self.mission.targets[t].id;
                        self.dropped.push(DeadEndPoi {
                            target: id.clone(),
                            index: original_index(self.given, id, &pose),
                            pose,
                            why,
                        });
                    }
                }
            }
            layout.pois[t] = kept;
        }
        Ok(())
    }
}

/// The proof, when a small search finds one, that the end cannot be reached from PoI
/// `p`.
fn cannot_leave(oracle: &mut PathOracle, layout: &Layout, p: usize) -> Result<Option<String>> {
    Ok(oracle
        .prove_unreachable(p, layout.end, PROOF_EFFORT)?
        .map(|reason| format!("the end cannot be reached from it: {reason}")))
}

/// The proof, when the start's search gives one, that PoI `p` cannot be reached from
/// the start.
fn cannot_enter(oracle: &mut PathOracle, layout: &Layout, p: usize) -> Result<Option<String>> {
    let from_start = oracle.path(layout.start, p)?;
    Ok(from_start
        .outcome
        .no_path_reason()
        .filter(|reason| reason.is_proved())
        .map(|reason| format!("cannot be reached from the start: {reason}")))
}
