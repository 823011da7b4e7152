//! What the curvature-limited models share: a space of shortest curves of a turning
//! radius, generic over the solver that finds them (Dubins, Reeds–Shepp).

use crate::curve::{relative, Curve};
use smug_core::pose::{angle_distance, Pose2};
use smug_core::space::{MotionExtent, StateSpace};
use std::cell::{Cell, RefCell};
use std::fmt::Debug;
use std::marker::PhantomData;

/// A shortest-curve solver in unit-radius form.
pub trait Solver: Copy + Debug + PartialEq + Send + Sync + 'static {
    /// Tells this solver's curves apart in the per-thread cache.
    const KIND: u8;
    /// Whether the curve `b → a` is the curve `a → b` reversed (a metric).
    const SYMMETRIC: bool;
    /// The shortest curve to `(x, y, phi)` from the origin facing +x, unit radius.
    fn shortest(x: f64, y: f64, phi: f64) -> Curve;

    /// [`Solver::shortest`] when its unit length is at most `bound`, else `None`; a
    /// solver may skip the words that cannot come within it, but returns the same curve
    /// as `shortest` whenever it returns one.
    fn shortest_within(x: f64, y: f64, phi: f64, bound: f64) -> Option<Curve> {
        let curve = Self::shortest(x, y, phi);
        (curve.unit_length() <= bound).then_some(curve)
    }
}

/// Curvature-limited motion: the shortest curves of [`Solver`] `S` at a turning radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvatureSpace<S: Solver> {
    radius: f64,
    solver: PhantomData<S>,
}

impl<S: Solver> CurvatureSpace<S> {
    /// A space of turning radius `turning_radius` (finite and > 0).
    pub fn new(turning_radius: f64) -> smug_core::Result<Self> {
        Ok(Self {
            radius: crate::check_turning_radius(turning_radius)?,
            solver: PhantomData,
        })
    }

    /// The minimum turning radius, metres.
    pub fn turning_radius(&self) -> f64 {
        self.radius
    }

    /// The shortest curve from `a` to `b` (unit-radius form); an endless straight one
    /// when their offset is beyond what the solvers compute in `f64`.
    pub fn curve(&self, a: &Pose2, b: &Pose2) -> Curve {
        cached_curve(S::KIND, self.radius, a, b, || {
            let (x, y, phi) = relative(a, b, self.radius);
            if !solvable(x, y, phi) {
                return endless();
            }
            memo_relative(S::KIND, [x, y, phi], || S::shortest(x, y, phi))
        })
    }
}

impl<S: Solver> StateSpace for CurvatureSpace<S> {
    fn distance(&self, a: &Pose2, b: &Pose2) -> f64 {
        self.radius * self.curve(a, b).unit_length()
    }

    fn distance_within(&self, a: &Pose2, b: &Pose2, bound: f64) -> Option<f64> {
        // The unit bound is widened by far more than its rounding, so that no curve
        // within `bound` metres is skipped; the answer is then checked in metres.
        let (x, y, phi) = relative(a, b, self.radius);
        if !solvable(x, y, phi) {
            return None; // no finite curve, so none within any bound
        }
        let curve = S::shortest_within(x, y, phi, bound / self.radius * (1.0 + 1e-9))?;
        let distance = self.radius * curve.unit_length();
        (distance <= bound).then_some(distance)
    }

    fn interpolate(&self, a: &Pose2, b: &Pose2, t: f64) -> Pose2 {
        if t <= 0.0 {
            return *a;
        }
        if t >= 1.0 {
            return *b;
        }
        self.curve(a, b).sample(a, self.radius, t)
    }

    fn lower_bound_weights(&self) -> (f64, f64) {
        (1.0, 0.0)
    }

    fn distance_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        // A curve turns at most 1/r per metre: turning d(yaw) takes r·d(yaw) of it.
        a.xy_distance(b)
            .max(self.radius * angle_distance(a.yaw, b.yaw))
    }

    fn is_symmetric(&self) -> bool {
        S::SYMMETRIC
    }

    fn motion_extent(&self, a: &Pose2, b: &Pose2) -> MotionExtent {
        self.curve(a, b).extent(self.radius)
    }

    fn length_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        self.distance(a, b)
    }

    fn is_reversing(&self, a: &Pose2, b: &Pose2, t: f64) -> bool {
        self.curve(a, b).is_reversing(t)
    }

    fn is_holonomic(&self) -> bool {
        false
    }

    fn turning_radius(&self) -> Option<f64> {
        Some(self.radius)
    }

    fn has_reverse_gear(&self) -> bool {
        // The symmetric solver is Reeds–Shepp's (both gears); Dubins' is forward only.
        S::SYMMETRIC
    }

    fn is_translation_invariant(&self) -> bool {
        // Curves are solved for the goal relative to the start.
        true
    }
}

/// Offsets (in turning radii) beyond which the solvers' squares and sums would overflow.
const MAX_UNIT_OFFSET: f64 = 1e100;

/// True when the solvers can compute the curve to `(x, y, phi)` in `f64`: all finite and
/// the offset within [`MAX_UNIT_OFFSET`] (non-finite poses, or ones ~1e308 apart, are not).
fn solvable(x: f64, y: f64, phi: f64) -> bool {
    x.abs() <= MAX_UNIT_OFFSET && y.abs() <= MAX_UNIT_OFFSET && phi.is_finite()
}

/// The curve standing for "no finite curve": straight ahead, infinitely long.
fn endless() -> Curve {
    Curve::new(&[crate::curve::Segment {
        steer: crate::curve::Steer::Straight,
        length: f64::INFINITY,
    }])
}

/// What a cached curve was computed for: the solver, the radius and both poses, as bits.
type CurveKey = (u8, [u64; 7]);

thread_local! {
    /// The last curve computed on this thread: a motion validator, a smoother or an
    /// objective samples one motion many times in a row.
    static LAST_CURVE: Cell<Option<(CurveKey, Curve)>> = const { Cell::new(None) };
}

/// Sets of the per-thread table of curves by relative pose (a power of two), each of
/// [`WAYS`] entries.
const RELATIVE_SETS: usize = 8192;

/// Entries per set of the table.
const WAYS: usize = 2;

/// A relative pose's solver and bits, its curve, and whether it was asked for again
/// since it was stored or last spared.
type RelativeEntry = ((u8, [u64; 3]), Curve, bool);

thread_local! {
    /// Curves by the goal's pose relative to the start (unit radius), in a two-way
    /// set-associative table with a second chance: a lattice's motions repeat the same
    /// few hundred relative poses (each both ways) all over the map and keep their
    /// entries; poses asked once (a roadmap's, a shot's, a validator's sub-motions)
    /// take an entry only from one not asked for again since it was stored (no
    /// allocation, no probing beyond the set).
    static BY_RELATIVE: RefCell<Vec<[Option<RelativeEntry>; WAYS]>> =
        RefCell::new(vec![[None; WAYS]; RELATIVE_SETS]);
}

/// The curve of solver `kind` to the relative pose `rel`: from the table when this
/// thread solved the same bits last in its set (the same bits give the same curve),
/// else `compute()` (then stored in an entry not asked for again since it was stored;
/// when both were, both lose that mark and the curve is not kept).
fn memo_relative(kind: u8, rel: [f64; 3], compute: impl FnOnce() -> Curve) -> Curve {
    let key = (kind, rel.map(f64::to_bits));
    let mut h = kind as u64;
    for bits in key.1 {
        h = (h ^ bits).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
    let set = (h >> 40) as usize & (RELATIVE_SETS - 1);
    BY_RELATIVE.with(|table| {
        let mut table = table.borrow_mut();
        let ways = &mut table[set];
        for (k, curve, asked) in ways.iter_mut().flatten() {
            if *k == key {
                *asked = true;
                return *curve;
            }
        }
        let curve = compute();
        match ways
            .iter_mut()
            .find(|entry| !matches!(entry, Some((_, _, true))))
        {
            Some(entry) => *entry = Some((key, curve, false)),
            None => ways.iter_mut().flatten().for_each(|e| e.2 = false),
        }
        curve
    })
}

/// The curve of solver `kind` with `radius` from `a` to `b`: the last one computed on
/// this thread when it was for the same motion, else `compute()` (then remembered).
fn cached_curve(
    kind: u8,
    radius: f64,
    a: &Pose2,
    b: &Pose2,
    compute: impl FnOnce() -> Curve,
) -> Curve {
    let key = (
        kind,
        [radius, a.x, a.y, a.yaw, b.x, b.y, b.yaw].map(f64::to_bits),
    );
    LAST_CURVE.with(|last| match last.get() {
        Some((k, curve)) if k == key => curve,
        _ => {
            let curve = compute();
            last.set(Some((key, curve)));
            curve
        }
    })
}
