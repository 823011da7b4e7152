//! What the lattice planner learns of the world, kept across queries and shared by
//! searches running on several threads: which lattice poses are valid, what each
//! primitive costs and whether it is valid, which shots are valid, and the
//! obstacle-aware heuristics of recent goal sets.
//!
//! Every entry is a pure function of the world (the same key always gets the same
//! value), so threads that race to fill one store the same value, and what a search
//! finds never depends on which entries other searches filled first.

use super::primitives::{Lattice, StateId};
use super::sources::Joins;
use lru::LruCache;
use smug_core::Pose2;
use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicU32, AtomicU8, Ordering::Relaxed};
use std::sync::{Arc, Mutex};

/// Bytes of obstacle-aware heuristics of goal sets kept (a mission's selection asks
/// for each PoI's again and again: on lunar, 56 kB each, every one is kept).
const HEURISTIC_BYTES: usize = 64 << 20;

/// Bytes of shot tables kept (on lunar about half a megabyte per goal).
const SHOT_BYTES: usize = 96 << 20;

/// How many starts' curves onto the lattice are kept.
const JOINS_KEPT: usize = 4096;

/// How many proofs of unreachable goals are kept.
const PROOFS_KEPT: usize = 8;

/// A proof that goals cannot be reached: the lattice poses an exhausted search closed
/// (a bitmap) and the goals (poses as bits) it found no way to from any of them.
type KeptProof = (Arc<Vec<u64>>, Vec<[u64; 3]>);

fn pose_bits(p: &Pose2) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.yaw.to_bits()]
}

/// The planner's caches.
pub(crate) struct Caches {
    /// Per lattice pose: 0 unknown, 1 valid, 2 invalid.
    state: Vec<AtomicU8>,
    /// Per lattice point: 0 unknown, 1 some heading valid (open to the heuristic's 2D
    /// relaxation), 2 none.
    point: Vec<AtomicU8>,
    /// Per lattice pose and primitive (stride: the most primitives of a heading), the
    /// bits of an `f32`: 0.0 unknown, infinity invalid, else the objective's cost of
    /// the motion, negative while its validity is not known.
    edge: Vec<AtomicU32>,
    /// The shot tables of recent goals (by their poses as bits): [`SHOT_BYTES`]
    /// worth, at least 2.
    shots: Mutex<LruCache<[u64; 3], Arc<ShotTable>>>,
    /// Obstacle-aware heuristics of recent goal sets (by the goals' poses as
    /// bits): [`HEURISTIC_BYTES`] worth, at least 2.
    heuristics: Mutex<LruCache<Vec<u64>, Arc<Vec<f32>>>>,
    /// Proofs of unreachable goals from recent exhausted searches, the latest last.
    proofs: Mutex<Vec<KeptProof>>,
    /// The curves onto the lattice of recent starts (by their poses as bits): a PoI
    /// is a search's start several times in a mission (its dead-end probe, its
    /// sequencing row, its DP layer).
    joins: Mutex<LruCache<[u64; 3], Arc<Joins>>>,
}

impl Caches {
    /// Empty caches for `lattice`, whose poses have at most `stride` primitives each,
    /// with shots from within `shot_radius` of a goal.
    pub(crate) fn new(lattice: &Lattice, stride: usize, shot_radius: f64) -> Self {
        let poses = lattice.len();
        let table_bytes = ShotTable::box_poses(lattice, shot_radius) * ShotTable::BYTES_PER_POSE;
        Self {
            state: (0..poses).map(|_| AtomicU8::new(0)).collect(),
            point: (0..lattice.points()).map(|_| AtomicU8::new(0)).collect(),
            edge: (0..poses * stride).map(|_| AtomicU32::new(0)).collect(),
            shots: Mutex::new(LruCache::new(at_least_two(SHOT_BYTES / table_bytes.max(1)))),
            heuristics: Mutex::new(LruCache::new(at_least_two(
                HEURISTIC_BYTES / (4 * lattice.points().max(1)),
            ))),
            proofs: Mutex::new(Vec::new()),
            joins: Mutex::new(LruCache::new(at_least_two(JOINS_KEPT))),
        }
    }

    /// The curves onto the lattice of `start`: the ones kept, or new ones from `make`
    /// (then kept).
    pub(crate) fn joins(&self, start: &Pose2, make: impl FnOnce() -> Joins) -> Arc<Joins> {
        let key = pose_bits(start);
        if let Some(kept) = self.joins.lock().expect("joins cache").get(&key) {
            return kept.clone();
        }
        let made = Arc::new(make());
        let mut kept = self.joins.lock().expect("joins cache");
        kept.get_or_insert(key, || made).clone()
    }

    /// A pose's validity, if known.
    pub(crate) fn state(&self, id: StateId) -> Option<bool> {
        known(&self.state[id as usize])
    }

    /// Records a pose's validity.
    pub(crate) fn set_state(&self, id: StateId, valid: bool) {
        record(&self.state[id as usize], valid);
    }

    /// Whether some heading is valid at lattice point `point` (`nx · row + column`),
    /// if known.
    pub(crate) fn point(&self, point: usize) -> Option<bool> {
        known(&self.point[point])
    }

    /// Records whether some heading is valid at lattice point `point`.
    pub(crate) fn set_point(&self, point: usize, open: bool) {
        record(&self.point[point], open);
    }

    /// How many poses' validity is known.
    pub(crate) fn states_known(&self) -> u64 {
        self.state.iter().filter(|s| s.load(Relaxed) != 0).count() as u64
    }

    /// A primitive's entry (see [`Caches::edge`]'s encoding).
    pub(crate) fn edge(&self, slot: usize) -> f32 {
        f32::from_bits(self.edge[slot].load(Relaxed))
    }

    /// Fetches a primitive's entry into the cache early ([`super::buffers::prefetch`]).
    pub(crate) fn prefetch_edge(&self, slot: usize) {
        if let Some(entry) = self.edge.get(slot) {
            super::buffers::prefetch(entry);
        }
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

    /// The shot table of `goal`: the one kept, or a new one from `make` (then kept).
    pub(crate) fn shot_table(
        &self,
        goal: &Pose2,
        make: impl FnOnce() -> ShotTable,
    ) -> Arc<ShotTable> {
        let mut kept = self.shots.lock().expect("shot tables");
        kept.get_or_insert(pose_bits(goal), || Arc::new(make()))
            .clone()
    }

    /// The heuristic kept for the goal set `key`, if any.
    pub(crate) fn heuristic(&self, key: &[u64]) -> Option<Arc<Vec<f32>>> {
        let mut kept = self.heuristics.lock().expect("heuristic cache");
        kept.get(key).cloned()
    }

    /// Keeps a goal set's heuristic (the least recently used goes when as many as
    /// [`HEURISTIC_BYTES`] allow are kept).
    pub(crate) fn keep_heuristic(&self, key: Vec<u64>, values: Arc<Vec<f32>>) {
        let mut kept = self.heuristics.lock().expect("heuristic cache");
        kept.put(key, values);
    }

    /// True when a kept proof shows `goal` unreachable from every pose of `joined`
    /// (all of them closed by the search that proved it).
    pub(crate) fn proved_unreachable(&self, joined: &[StateId], goal: &Pose2) -> bool {
        let bits = pose_bits(goal);
        let kept = self.proofs.lock().expect("proof cache");
        kept.iter().any(|(closed, goals)| {
            goals.contains(&bits) && joined.iter().all(|&id| holds(closed, id))
        })
    }

    /// The poses of a kept proof that every goal of `goals` is unreachable from (the
    /// largest such set; `None` when no kept proof covers them all).
    pub(crate) fn proof_covering(&self, goals: &[Pose2]) -> Option<Arc<Vec<u64>>> {
        let bits: Vec<[u64; 3]> = goals.iter().map(pose_bits).collect();
        let kept = self.proofs.lock().expect("proof cache");
        kept.iter()
            .filter(|(_, proved)| bits.iter().all(|b| proved.contains(b)))
            .max_by_key(|(closed, _)| closed_count(closed))
            .map(|(closed, _)| closed.clone())
    }

    /// Keeps the proof that `goals` cannot be reached from the poses of `closed`.
    pub(crate) fn keep_proof(&self, closed: Vec<u64>, goals: &[Pose2]) {
        let mut kept = self.proofs.lock().expect("proof cache");
        if kept.len() >= PROOFS_KEPT {
            kept.remove(0);
        }
        kept.push((Arc::new(closed), goals.iter().map(pose_bits).collect()));
    }
}

/// How many poses a bitmap of poses holds.
fn closed_count(bits: &[u64]) -> u32 {
    bits.iter().map(|w| w.count_ones()).sum()
}

/// Adds pose `id` to the bitmap `bits`.
pub(crate) fn insert(bits: &mut [u64], id: StateId) {
    bits[id as usize / 64] |= 1 << (id % 64);
}

/// True when pose `id` is in the bitmap `bits`.
pub(crate) fn holds(bits: &[u64], id: StateId) -> bool {
    bits[id as usize / 64] & (1 << (id % 64)) != 0
}

/// A validity kept in one byte (0 unknown, 1 valid, 2 invalid), if known.
pub(crate) fn known(validity: &AtomicU8) -> Option<bool> {
    match validity.load(Relaxed) {
        0 => None,
        v => Some(v == 1),
    }
}

/// Keeps a validity in one byte (see [`known`]).
pub(crate) fn record(validity: &AtomicU8, valid: bool) {
    validity.store(if valid { 1 } else { 2 }, Relaxed);
}

/// `n`, at least 2, as a cache capacity.
fn at_least_two(n: usize) -> NonZeroUsize {
    NonZeroUsize::new(n.max(2)).expect("at least 2")
}

/// An unknown cost's bits (a NaN no cost has).
pub(crate) const UNKNOWN_COST: u32 = u32::MAX;

/// The shots to one goal from the lattice poses within the shot radius of it.
pub(crate) struct ShotTable {
    /// Column and row of the first point of the box of points around the goal.
    corner: (i64, i64),
    /// Points per side of the box.
    side: usize,
    /// Per pose of the box: the cost rounded down to an `f32`, as bits.
    pub(crate) costs: Vec<AtomicU32>,
    /// Per pose of the box: whether the shot is valid, if known (see [`known`]).
    pub(crate) valid: Vec<AtomicU8>,
}

impl ShotTable {
    /// Bytes a table takes per pose of its box.
    const BYTES_PER_POSE: usize = 5;

    /// How far the box reaches from the goal's point, in points, for shots from
    /// within `radius`.
    fn reach(lattice: &Lattice, radius: f64) -> i64 {
        (radius / lattice.cell).ceil() as i64 + 1
    }

    /// Poses in the box of a table for shots from within `radius`.
    fn box_poses(lattice: &Lattice, radius: f64) -> usize {
        let side = (2 * Self::reach(lattice, radius) + 1) as usize;
        side * side * lattice.headings
    }

    /// An empty table for the poses of `lattice` within `radius` of `goal`.
    pub(crate) fn new(lattice: &Lattice, goal: &Pose2, radius: f64) -> Self {
        let reach = Self::reach(lattice, radius);
        let column = ((goal.x - lattice.origin[0]) / lattice.cell).round() as i64;
        let row = ((goal.y - lattice.origin[1]) / lattice.cell).round() as i64;
        let side = (2 * reach + 1) as usize;
        let poses = Self::box_poses(lattice, radius);
        Self {
            corner: (column - reach, row - reach),
            side,
            costs: (0..poses).map(|_| AtomicU32::new(UNKNOWN_COST)).collect(),
            valid: (0..poses).map(|_| AtomicU8::new(0)).collect(),
        }
    }

    /// The table's slot for lattice pose `id`, when it lies in the box.
    pub(crate) fn slot(&self, lattice: &Lattice, id: StateId) -> Option<usize> {
        let (ix, iy, k) = lattice.decode(id);
        let (dx, dy) = (ix as i64 - self.corner.0, iy as i64 - self.corner.1);
        let inside = (0..self.side as i64).contains(&dx) && (0..self.side as i64).contains(&dy);
        inside.then(|| (dy as usize * self.side + dx as usize) * lattice.headings + k)
    }
}
