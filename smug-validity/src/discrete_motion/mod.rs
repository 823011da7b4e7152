//! `discrete`: a motion is valid when the states along it, at a fixed resolution,
//! are valid and the terrain inclination between consecutive states stays below a
//! limit. States are checked in bisection order (collisions are found early);
//! `check_motion` scans in order from the start to report the last valid state.

use gentle::GentleCells;
use serde::{Deserialize, Serialize};
use smug_core::Counter;
use smug_core::{
    BuildContext, Counters, Error, MotionCheck, MotionValidator, Pose2, StateSpace,
    StateValidityChecker, World,
};
use std::sync::Arc;

mod gentle;

/// Parameters of the discrete motion validator.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DiscreteMotionParams {
    /// Longest space distance between checked states (OMPL's
    /// `longest_valid_segment_length`; reference: 0.5).
    pub resolution: f64,
    /// Largest terrain slope |Δz| / horizontal distance between consecutive states
    /// (reference: 0.58); needs the world's elevation. `inf`: no limit (flat maps:
    /// no height is looked up).
    pub max_inclination: Option<f64>,
}

impl Default for DiscreteMotionParams {
    fn default() -> Self {
        Self {
            resolution: 0.5,
            max_inclination: Some(0.58),
        }
    }
}

/// With a checker that knows its clearance (a disc robot), motions are traced
/// continuously; a point closer to contact than this share of the resolution counts as
/// a contact (0.05 m resolution: 1 mm).
const MIN_STEP_SHARE: f64 = 0.02;

/// The outcome of tracing a motion through the checker's clearance.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Swept {
    /// Every position on the way is valid.
    Clear,
    /// The trace stopped at a contact; the last point it had cleared, as a fraction of
    /// the motion (`None`: the start itself).
    Contact { last_clear: Option<f64> },
}

/// Checks the space's motions (straight, or a car's curves) state by state
/// (continuously for disc robots).
pub struct DiscreteMotionValidator {
    states: Arc<dyn StateValidityChecker>,
    space: Arc<dyn StateSpace>,
    terrain: Option<(Arc<World>, f64)>,
    /// The terrain's gentle cells under the limit, for segments up to the resolution.
    gentle: Option<GentleCells>,
    resolution: f64,
    motions_checked: Counter,
    states_checked: Counter,
}

impl DiscreteMotionValidator {
    /// A validator over `states` along the motions of `space`; `terrain` = the world and its
    /// inclination limit, when the limit applies.
    pub fn new(
        states: Arc<dyn StateValidityChecker>,
        space: Arc<dyn StateSpace>,
        terrain: Option<(Arc<World>, f64)>,
        resolution: f64,
    ) -> Result<Self, Error> {
        if !(resolution.is_finite() && resolution > 0.0) {
            return Err(Error::invalid_param(
                "motion",
                format!("resolution must be > 0, got {resolution}"),
            ));
        }
        if let Some((_, limit)) = &terrain {
            if limit.is_nan() || *limit < 0.0 {
                return Err(Error::invalid_param(
                    "motion",
                    format!("max_inclination must be ≥ 0, got {limit}"),
                ));
            }
        }
        let gentle = terrain
            .as_ref()
            .map(|(world, limit)| GentleCells::new(&world.elevation, *limit, resolution));
        Ok(Self {
            states,
            space,
            terrain,
            gentle,
            resolution,
            motions_checked: Counter::new(),
            states_checked: Counter::new(),
        })
    }

    /// Number of segments the motion `a → b` is split into.
    fn segment_count(&self, a: &Pose2, b: &Pose2) -> usize {
        let n = (self.space.distance(a, b) / self.resolution).ceil();
        if n.is_finite() {
            (n as usize).max(1)
        } else {
            1
        }
    }

    fn state_at(&self, a: &Pose2, b: &Pose2, k: usize, n: usize) -> Pose2 {
        self.space.interpolate(a, b, k as f64 / n as f64)
    }

    fn is_valid_state(&self, s: &Pose2) -> bool {
        self.states_checked.increment();
        self.states.is_valid(s)
    }

    /// True when the terrain between consecutive states is not too steep.
    fn inclination_ok(&self, p: &Pose2, q: &Pose2) -> bool {
        let Some((world, limit)) = &self.terrain else {
            return true;
        };
        let heights = (world.height_at(p.x, p.y), world.height_at(q.x, q.y));
        slope_ok(p.xy_distance(q), heights, *limit)
    }

    /// [`Self::inclination_ok`] for every pair of consecutive states of the
    /// `n`-segment motion `a → b`, looking each state's height up at most once, and
    /// not at all for a segment from a gentle cell ([`GentleCells`]: the same
    /// verdict).
    fn slopes_ok(&self, a: &Pose2, b: &Pose2, along: &mut Along) -> bool {
        let n = along.segments();
        self.slopes_ok_along(a, n, |k| along.state(self, a, b, k))
    }

    /// [`Self::slopes_ok`] for the states `state(1..=n)` after `start`, in turn.
    fn slopes_ok_along(
        &self,
        start: &Pose2,
        n: usize,
        mut state: impl FnMut(usize) -> Pose2,
    ) -> bool {
        let (Some((world, limit)), Some(gentle)) = (&self.terrain, &self.gentle) else {
            return true;
        };
        let mut p = *start;
        // `p`'s height, once looked up.
        let mut zp = None;
        for k in 1..=n {
            let q = state(k);
            let horizontal = p.xy_distance(&q);
            if gentle.vouches(&p, horizontal) {
                (p, zp) = (q, None);
                continue;
            }
            let zp_known = zp.unwrap_or_else(|| world.height_at(p.x, p.y));
            let zq = world.height_at(q.x, q.y);
            if !slope_ok(horizontal, (zp_known, zq), *limit) {
                return false;
            }
            (p, zp) = (q, Some(zq));
        }
        true
    }

    /// Traces the motion `a → b` through the checker's clearance (when it has one):
    /// from each point, the next one is a clearance further along, so every position on
    /// the way is covered, not only states at the resolution. A point whose clearance is
    /// below [`MIN_STEP_SHARE`] × the resolution counts as a contact (grazing motions are
    /// rejected, conservatively, in a bounded number of steps). `None` when the checker
    /// has no clearance.
    fn swept(&self, a: &Pose2, b: &Pose2) -> Option<Swept> {
        // The start's clearance first: a checker without one (a box robot) answers
        // `None` before the motion's curve is solved for its length.
        let mut at_start = Some(self.states.clearance(a)?);
        // Straight motions are traced on their segment; a curved model's along its own
        // curve, whose fractions are fractions of its planar length (a step of the
        // clearance along the curve moves the disc at most that far).
        let straight = self.space.is_holonomic();
        let length = if straight {
            a.xy_distance(b)
        } else {
            self.space.motion_extent(a, b).length
        };
        let min_step = MIN_STEP_SHARE * self.resolution;
        let (mut travelled, mut last_clear) = (0.0, None);
        loop {
            let t = if length > 0.0 {
                travelled / length
            } else {
                0.0
            };
            self.states_checked.increment();
            // The first point is the start (`t` = 0), whose clearance is known.
            let clearance = match at_start.take() {
                Some(clearance) => clearance,
                None => {
                    let point = if straight {
                        Pose2::new(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.yaw)
                    } else {
                        self.space.interpolate(a, b, t)
                    };
                    self.states.clearance(&point)?
                }
            };
            if clearance.is_nan() || clearance < min_step {
                return Some(Swept::Contact { last_clear });
            }
            if travelled + clearance >= length {
                return Some(Swept::Clear);
            }
            last_clear = Some(t);
            travelled += clearance;
        }
    }

    /// [`Self::swept`] in one direction whatever the order of `a` and `b` (the one
    /// from the lower `(x, y)`), so that a motion and its reverse get the same verdict:
    /// where the trace lands, and so which grazing points it meets, depends on where it
    /// starts.
    fn swept_either_way(&self, a: &Pose2, b: &Pose2) -> Option<Swept> {
        // A model whose motion `b → a` is not `a → b` reversed is traced as asked.
        let forward =
            !self.space.is_symmetric() || a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)).is_le();
        if forward {
            self.swept(a, b)
        } else {
            self.swept(b, a)
        }
    }

    /// The checker's exact verdict on a straight motion (a disc on a grid), when the
    /// model's motions are straight in the plane and the checker has one.
    fn exact_segment(&self, a: &Pose2, b: &Pose2) -> Option<bool> {
        if !self.space.is_holonomic() {
            return None;
        }
        self.states.segment_valid(a, b)
    }

    /// True when every position of the `n`-segment motion `a → b` is valid: traced
    /// through the checker's clearance when it has one, else its states at the
    /// resolution, the ends first (unless `ends_known_valid`), then the inner ones in
    /// bisection order (each computed once, into `along`).
    fn states_valid(
        &self,
        a: &Pose2,
        b: &Pose2,
        along: &mut Along,
        ends_known_valid: bool,
    ) -> bool {
        match self.swept_either_way(a, b) {
            Some(swept) => swept == Swept::Clear,
            None => {
                let ends = (!ends_known_valid).then_some((a, b));
                let n = along.segments();
                self.resolution_states_valid(ends, n, |k| along.state(self, a, b, k))
            }
        }
    }

    /// True when the `ends` (when given: the end, then the start) and the inner
    /// states `state(1..n)` of an `n`-segment motion are valid, the inner ones asked in
    /// bisection order. The states checked are counted here and added once (one
    /// counter bump per motion, not one per state).
    fn resolution_states_valid(
        &self,
        ends: Option<(&Pose2, &Pose2)>,
        n: usize,
        mut state: impl FnMut(usize) -> Pose2,
    ) -> bool {
        let mut checked = 0u64;
        let mut valid = |s: &Pose2| {
            checked += 1;
            self.states.is_valid(s)
        };
        let ends_valid = ends.is_none_or(|(a, b)| valid(b) && valid(a));
        let all_valid = ends_valid && all_in_bisection_order(n, |k| valid(&state(k)));
        self.states_checked.add(checked);
        all_valid
    }

    /// True when the verdict on the motion `a → b` is its states' at the resolution
    /// alone: the checker has no clearance to trace it with (a box robot) and no exact
    /// verdict on it.
    fn states_decide(&self, a: &Pose2, b: &Pose2) -> bool {
        self.states.clearance(a).is_none() && self.exact_segment(a, b).is_none()
    }

    /// [`MotionValidator::is_valid_motion`], with the ends' checks skipped when
    /// `ends_known_valid`.
    fn motion_valid(&self, a: &Pose2, b: &Pose2, ends_known_valid: bool) -> bool {
        self.motions_checked.increment();
        let mut along = Along::new(self.segment_count(a, b));
        // The states first: a blocked motion usually ends within a few of them, where
        // the slopes look up every state's height.
        let states_valid = match self.exact_segment(a, b) {
            Some(valid) => valid,
            None => self.states_valid(a, b, &mut along, ends_known_valid),
        };
        states_valid && self.slopes_ok(a, b, &mut along)
    }
}

/// True when `check(k)` holds for every interior state index `1..n`, asked in
/// bisection order (the motion's midpoint first, then the midpoints of its halves,
/// level by level, left to right: collisions are found early), stopping at the first
/// that fails. Each level is walked from the top instead of queued: no allocation.
fn all_in_bisection_order(n: usize, mut check: impl FnMut(usize) -> bool) -> bool {
    for depth in 0.. {
        match level_passes(0, n, depth, &mut check) {
            None => return true,
            Some(false) => return false,
            Some(true) => {}
        }
    }
    unreachable!("the levels run out")
}

/// The midpoints `depth` halvings below the interval `lo..hi` (intervals of fewer
/// than two segments have none), left to right: `Some(false)` at the first whose
/// check fails, `Some(true)` when there were some and all passed, `None` when there
/// were none.
fn level_passes(
    lo: usize,
    hi: usize,
    depth: u32,
    check: &mut impl FnMut(usize) -> bool,
) -> Option<bool> {
    if hi - lo < 2 {
        return None;
    }
    let mid = lo + (hi - lo) / 2;
    if depth == 0 {
        return Some(check(mid));
    }
    match level_passes(lo, mid, depth - 1, check) {
        Some(false) => Some(false),
        left => match level_passes(mid, hi, depth - 1, check) {
            Some(false) => Some(false),
            right => left.or(right),
        },
    }
}

/// The states of an `n`-segment motion at the resolution, each interpolated once
/// (the state checks and the slope checks ask for the same ones); nothing is allocated
/// until a state is asked for (an exact or traced verdict asks for none).
struct Along {
    segments: usize,
    states: Vec<Option<Pose2>>,
}

impl Along {
    fn new(segments: usize) -> Self {
        Self {
            segments,
            states: Vec::new(),
        }
    }

    /// Segments of the motion.
    fn segments(&self) -> usize {
        self.segments
    }

    /// State `k` of the motion `a → b`, interpolated on first use.
    fn state(
        &mut self,
        validator: &DiscreteMotionValidator,
        a: &Pose2,
        b: &Pose2,
        k: usize,
    ) -> Pose2 {
        let n = self.segments;
        if self.states.is_empty() {
            self.states.resize(n + 1, None);
        }
        *self.states[k].get_or_insert_with(|| validator.state_at(a, b, k, n))
    }
}

/// True when the slope between two states `horizontal` apart with heights `(zp, zq)`
/// is at most `limit` (no horizontal move: always; a height off the map: never).
fn slope_ok(horizontal: f64, (zp, zq): (Option<f64>, Option<f64>), limit: f64) -> bool {
    if horizontal <= 1e-12 {
        return true;
    }
    match (zp, zq) {
        (Some(zp), Some(zq)) => (zq - zp).abs() / horizontal <= limit,
        _ => false,
    }
}

impl MotionValidator for DiscreteMotionValidator {
    fn is_valid_motion(&self, a: &Pose2, b: &Pose2) -> bool {
        self.motion_valid(a, b, false)
    }

    fn is_valid_motion_between_valid(&self, a: &Pose2, b: &Pose2) -> bool {
        self.motion_valid(a, b, true)
    }

    /// The states at the resolution when they decide (the checker has no clearance to
    /// trace the motion with and no exact verdict on it): `a`, then state `k` of `n`,
    /// the space's interpolation at `k / n` (the last: at 1, `b` for the shipped
    /// models).
    fn check_states(&self, a: &Pose2, b: &Pose2) -> Option<Vec<Pose2>> {
        if !self.states_decide(a, b) {
            return None;
        }
        let n = self.segment_count(a, b);
        let inner = (1..=n).map(|k| self.state_at(a, b, k, n));
        Some(std::iter::once(*a).chain(inner).collect())
    }

    /// [`Self::is_valid_motion_between_valid`]'s verdict and counts through the given
    /// states: the inner ones in bisection order, then the slopes between consecutive
    /// ones. States the validator would not check this way (a clearance to trace them
    /// with) are judged by the motion between the first and the last.
    fn states_valid_between_valid(&self, states: &[Pose2]) -> bool {
        let (Some(a), Some(b)) = (states.first(), states.last()) else {
            return true;
        };
        if states.len() < 2 || !self.states_decide(a, b) {
            return self.motion_valid(a, b, true);
        }
        self.motions_checked.increment();
        let n = states.len() - 1;
        self.resolution_states_valid(None, n, |k| states[k])
            && self.slopes_ok_along(a, n, |k| states[k])
    }

    fn check_motion(&self, a: &Pose2, b: &Pose2) -> MotionCheck {
        self.motions_checked.increment();
        let clear = self.exact_segment(a, b) == Some(true);
        if clear && self.terrain.is_none() {
            return MotionCheck::Valid;
        }
        let n = self.segment_count(a, b);
        // With a continuous trace (or an exact verdict that the motion is clear),
        // states at the resolution only check the slopes, up to the contact the trace
        // found.
        let traced = if clear {
            Some(Swept::Clear)
        } else {
            self.swept_either_way(a, b)
        };
        let (contact, states_decide) = match traced {
            Some(Swept::Clear) => (None, false),
            // Where the contact is, seen from `a` (at `a` itself when only the trace
            // from the other end meets a grazing point).
            Some(Swept::Contact { .. }) => match self.swept(a, b) {
                Some(Swept::Contact { last_clear }) => (Some(last_clear), false),
                _ => (Some(Some(0.0)), false),
            },
            None => (None, true),
        };
        if contact == Some(None) || states_decide && !self.is_valid_state(a) {
            return MotionCheck::Invalid { last_valid: None };
        }
        let mut previous = (*a, 0.0);
        for k in 1..=n {
            let fraction = k as f64 / n as f64;
            if let Some(Some(last_clear)) = contact {
                if fraction > last_clear {
                    break;
                }
            }
            let state = self.state_at(a, b, k, n);
            if !(self.inclination_ok(&previous.0, &state)
                && (!states_decide || self.is_valid_state(&state)))
            {
                return MotionCheck::Invalid {
                    last_valid: Some(previous),
                };
            }
            previous = (state, fraction);
        }
        match contact {
            Some(Some(last_clear)) if last_clear > previous.1 => MotionCheck::Invalid {
                last_valid: Some((self.space.interpolate(a, b, last_clear), last_clear)),
            },
            Some(_) => MotionCheck::Invalid {
                last_valid: Some(previous),
            },
            None => MotionCheck::Valid,
        }
    }

    fn counters(&self) -> Counters {
        Counters::from([
            ("motion_checks".to_string(), self.motions_checked.total()),
            (
                "motion_state_checks".to_string(),
                self.states_checked.total(),
            ),
        ])
    }
}

fn build_validator(
    params: DiscreteMotionParams,
    ctx: &BuildContext,
) -> Result<DiscreteMotionValidator, Error> {
    let terrain = match params.max_inclination {
        Some(limit) if limit != f64::INFINITY => Some((ctx.world()?, limit)),
        _ => None,
    };
    DiscreteMotionValidator::new(
        ctx.state_validity()?,
        ctx.space(),
        terrain,
        params.resolution,
    )
}

smug_core::register_plugin!(
    smug_core::registry::MotionStage,
    name = "discrete",
    summary = "states at a fixed resolution in bisection order, plus a terrain inclination limit",
    params = DiscreteMotionParams,
    build = |params, ctx| Ok(Box::new(build_validator(params, ctx)?)),
);

#[cfg(test)]
mod tests;
