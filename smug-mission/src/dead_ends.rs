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

/// Expansions a proof that a PoI cannot reach the end may take for a symmetric model:
/// a PoI boxed in where it stands (the lunar rover's, between stones) runs out of
/// poses within a few dozen (at most 45 on 10 lunar worlds and 5 seeds each of the
/// indoor, imported and cluttered maps), and the probe of each PoI that is not stays
/// cheap against the search of the whole map that would prove the same later.
const SYMMETRIC_PROOF_EFFORT: u64 = 128;

/// Drops from `layout` the PoIs of `targets` that provably cannot reach the end or
/// that the start provably cannot reach, for planners that prove dead ends cheaply
/// (others are not asked: their plans do not change). For a symmetric model only the
/// PoIs boxed in where they stand are looked for (with a smaller effort): a path to
/// such a PoI would be one from it reversed, and the start's reach decides the rest,
/// checked later for whole targets.
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
    if !oracle.proves_dead_ends() {
        return Ok(Vec::new());
    }
    let mut dead = DeadEnds {
        mission,
        given,
        targets,
        dropped: Vec::new(),
    };
    if oracle.is_symmetric() {
        let boxed_in = cannot_leave(oracle, layout, targets, SYMMETRIC_PROOF_EFFORT)?;
        dead.drop(oracle, layout, boxed_in);
        return Ok(dead.dropped);
    }
    let cannot_leave = cannot_leave(oracle, layout, targets, PROOF_EFFORT)?;
    dead.drop(oracle, layout, cannot_leave);
    let left = pois_of(layout, targets);
    if !left.is_empty() && oracle.answers_many() {
        oracle.plan_from(layout.start, &left)?;
    }
    let cannot_enter = left
        .iter()
        .map(|&p| cannot_enter(oracle, layout, p))
        .collect::<Result<_>>()?;
    dead.drop(oracle, layout, cannot_enter);
    Ok(dead.dropped)
}

/// The PoIs `layout` keeps for `targets`, target by target.
fn pois_of(layout: &Layout, targets: &[usize]) -> Vec<usize> {
    targets
        .iter()
        .flat_map(|&t| layout.pois[t].iter().copied())
        .collect()
}

/// The PoIs of a mission's `targets` dropped so far, and what naming them needs.
struct DeadEnds<'a> {
    mission: &'a Mission,
    given: &'a Mission,
    targets: &'a [usize],
    dropped: Vec<DeadEndPoi>,
}

impl DeadEnds<'_> {
    /// Drops from `layout` the PoIs of the targets that have a reason in `why` (one
    /// entry per PoI [`pois_of`] lists, in its order), recording each.
    fn drop(&mut self, oracle: &PathOracle, layout: &mut Layout, why: Vec<Option<String>>) {
        let mut why = why.into_iter();
        for &t in self.targets {
            let mut kept = Vec::with_capacity(layout.pois[t].len());
            for &p in &layout.pois[t] {
                match why.next().flatten() {
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
    }
}

/// For each PoI of `targets` (as [`pois_of`] lists them), the proof, when a search of
/// `effort` expansions from it finds one, that the end cannot be reached from it.
fn cannot_leave(
    oracle: &mut PathOracle,
    layout: &Layout,
    targets: &[usize],
    effort: u64,
) -> Result<Vec<Option<String>>> {
    let pairs: Vec<(usize, usize)> = pois_of(layout, targets)
        .into_iter()
        .map(|p| (p, layout.end))
        .collect();
    Ok(oracle
        .prove_each_unreachable(&pairs, effort)?
        .into_iter()
        .map(|proof| proof.map(|reason| format!("the end cannot be reached from it: {reason}")))
        .collect())
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
