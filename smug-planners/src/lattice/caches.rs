//! What the lattice planner learns of the world, kept across queries and shared by
//! searches running on several threads: which lattice poses are valid, what each
//! primitive costs and whether it is valid, which shots are valid, and the
//! obstacle-aware heuristics of recent goal sets.
//!
//! Every entry is a pure function of the world (the same key always gets the same
//! value), so threads that race to fill one store the same value, and what a search
//! finds never depends on which entries other searches filled first.

use super::primitives::StateId;
use smug_core::Pose2;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU32, AtomicU8, Ordering::Relaxed};
use std::sync::{Arc, Mutex};

/// How many obstacle-aware heuristics of goal sets are kept.
const HEURISTICS_KEPT: usize = 32;

/// A shot's key: the lattice pose it leaves from and the goal pose's bits.
pub(crate) type ShotKey = (StateId, [u64; 3]);

/// A goal set's heuristic: the goals' positions as bits, and the distances per point.
type KeptHeuristic = (Vec<u64>, Arc<Vec<f32>>);

/// How many proofs of unreachable goals are kept.
const PROOFS_KEPT: usize = 8;

/// A proof that goals cannot be reached: the lattice poses an exhausted search closed
/// (a bitmap) and the goals (poses as bits) it found no way to from any of them.
type KeptProof = (Vec<u64>, Vec<[u64; 3]>);

fn pose_bits(p: &Pose2) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.yaw.to_bits()]
}

/// The planner's caches.
pub(crate) struct Caches {
    /// Per lattice pose: 0 unknown, 1 valid, 2 invalid.
    state: Vec<AtomicU8>,
    /// Per lattice pose and primitive (stride: the most primitives of a heading), the
    /// bits of an `f32`: 0.0 unknown, infinity invalid, else the objective's cost of
    /// the motion, negative while its validity is not known.
    edge: Vec<AtomicU32>,
    /// Shots checked from lattice poses → valid.
    shots: Mutex<HashMap<ShotKey, bool>>,
    /// Obstacle-aware heuristics of recent goal sets, the latest last.
    heuristics: Mutex<Vec<KeptHeuristic>>,
    /// Proofs of unreachable goals from recent exhausted searches, the latest last.
    proofs: Mutex<Vec<KeptProof>>,
}

impl Caches {
    /// Empty caches for `poses` lattice poses of at most `stride` primitives each.
    pub(crate) fn new(poses: usize, stride: usize) -> Self {
        Self {
            state: (0..poses).map(|_| AtomicU8::new(0)).collect(),
            edge: (0..poses * stride).map(|_| AtomicU32::new(0)).collect(),
            shots: Mutex::new(HashMap::new()),
            heuristics: Mutex::new(Vec::new()),
            proofs: Mutex::new(Vec::new()),
        }
    }

    /// A pose's validity, if known.
    pub(crate) fn state(&self, id: StateId) -> Option<bool> {
        match self.state[id as usize].load(Relaxed) {
            0 => None,
            v => Some(v == 1),
        }
    }

    /// Records a pose's validity.
    pub(crate) fn set_state(&self, id: StateId, valid: bool) {
        self.state[id as usize].store(if valid { 1 } else { 2 }, Relaxed);
    }

    /// How many poses' validity is known.
    pub(crate) fn states_known(&self) -> u64 {
        self.state.iter().filter(|s| s.load(Relaxed) != 0).count() as u64
    }

    /// A primitive's entry (see [`Caches::edge`]'s encoding).
    pub(crate) fn edge(&self, slot: usize) -> f32 {
        f32::from_bits(self.edge[slot].load(Relaxed))
    }

    /// Records a primitive's validity (its cost, or infinity).
    pub(crate) fn set_edge(&self, slot: usize, value: f32) {
        self.edge[slot].store(value.to_bits(), Relaxed);
    }

    /// Records a primitive's cost (negative: validity unknown) unless the entry is
    /// known already; returns the entry.
    pub(crate) fn set_edge_cost(&self, slot: usize, value: f32) -> f32 {
        match self.edge[slot].compare_exchange(0, value.to_bits(), Relaxed, Relaxed) {
            Ok(_) => value,
            Err(known) => f32::from_bits(known),
        }
    }

    /// A shot's validity, if known.
    pub(crate) fn shot(&self, key: &ShotKey) -> Option<bool> {
        self.shots.lock().expect("shot cache").get(key).copied()
    }

    /// Records a shot's validity.
    pub(crate) fn set_shot(&self, key: ShotKey, valid: bool) {
        self.shots.lock().expect("shot cache").insert(key, valid);
    }

    /// The heuristic kept for the goal set `key`, if any (then the latest).
    pub(crate) fn heuristic(&self, key: &[u64]) -> Option<Arc<Vec<f32>>> {
        let mut kept = self.heuristics.lock().expect("heuristic cache");
        let pos = kept.iter().position(|(k, _)| k == key)?;
        let hit = kept.remove(pos);
        let values = hit.1.clone();
        kept.push(hit);
        Some(values)
    }

    /// Keeps a goal set's heuristic (the oldest goes when [`HEURISTICS_KEPT`] are).
    pub(crate) fn keep_heuristic(&self, key: Vec<u64>, values: Arc<Vec<f32>>) {
        let mut kept = self.heuristics.lock().expect("heuristic cache");
        if kept.iter().any(|(k, _)| *k == key) {
            return;
        }
        if kept.len() >= HEURISTICS_KEPT {
            kept.remove(0);
        }
        kept.push((key, values));
    }

    /// True when a kept proof shows `goal` unreachable from every pose of `joined`
    /// (all of them closed by the search that proved it).
    pub(crate) fn proved_unreachable(&self, joined: &[StateId], goal: &Pose2) -> bool {
        let bits = pose_bits(goal);
        let kept = self.proofs.lock().expect("proof cache");
        kept.iter().any(|(closed, goals)| {
            goals.contains(&bits)
                && joined
                    .iter()
                    .all(|&id| closed[id as usize / 64] & (1 << (id % 64)) != 0)
        })
    }

    /// Keeps the proof that `goals` cannot be reached from the poses of `closed`.
    pub(crate) fn keep_proof(&self, closed: Vec<u64>, goals: &[Pose2]) {
        let mut kept = self.proofs.lock().expect("proof cache");
        if kept.len() >= PROOFS_KEPT {
            kept.remove(0);
        }
        kept.push((closed, goals.iter().map(pose_bits).collect()));
    }
}
