//! A search's sources: poses off the lattice where it starts, each with the cost
//! already paid to be there, and their node ids (above every lattice pose's).

use super::primitives::StateId;
use smug_core::Pose2;
use std::sync::Arc;

/// The start's node id (lattice poses are `0..len`): the first source's.
pub(super) const START: u32 = u32::MAX;

/// Sources one search may have at most ([`source_id`]).
pub(super) const MAX_SOURCES: usize = 4096;

/// The node id of a search's source `s` (`s < MAX_SOURCES`): ids down from [`START`],
/// above every lattice pose's (at most `MAX_STATES`).
pub(super) fn source_id(s: usize) -> u32 {
    START - s as u32
}

/// Which source a node id is, if it is one.
pub(super) fn source_of(id: u32) -> Option<usize> {
    let s = (START - id) as usize;
    (s < MAX_SOURCES).then_some(s)
}

/// Whether a node id is a source's (off the lattice).
pub(super) fn is_source(id: u32) -> bool {
    source_of(id).is_some()
}

/// A start's curves onto the lattice: the lattice pose, the cost, and whether the curve
/// reverses.
pub(crate) type Joins = Vec<(StateId, f64, bool)>;

/// One of a search's sources: a pose off the lattice, the cost already paid to be
/// there (a DP layer's value; 0 for a plain start), and its curves onto the lattice
/// (taken when it is expanded).
pub(super) struct Source {
    pub(super) pose: Pose2,
    pub(super) offset: f64,
    pub(super) joins: Arc<Joins>,
}
