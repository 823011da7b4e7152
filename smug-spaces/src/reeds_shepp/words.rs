//! The shortest Reeds–Shepp curve (Reeds & Shepp 1990, §8): the five families CSC,
//! CCC, CCCC, CCSC and CCSCC, each solved for one base word and mapped onto the others
//! by time flip (drive the word in reverse), reflection (swap left and right) and, for
//! CCC and CCSC, backwards (drive the word from the goal), 48 words in all.
//!
//! Coordinates are in unit-radius form: the goal `(x, y, φ)` in the start's frame.
//! Formulas as in the paper's §8 (and OMPL's `ReedsSheppStateSpace`), with a small
//! slack on every domain and sign test so that tangent cases survive rounding.

use crate::curve::{unit_length, Curve, Steer, MAX_SEGMENTS};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

use Steer::{Left as L, Right as R, Straight as S};

/// Slack of the domain tests (rounding of exact tangencies).
const SLACK: f64 = 1e-10;

/// Slack of the sign tests: at a tangency a length `√s` of a rounded `s ≈ 0` is ~1e-8
/// and tilts the next arc by as much. Every signed solution is a real curve to the
/// goal (it is sampled with its signs), so the slack never admits a false length.
const SIGN_SLACK: f64 = 1e-7;

/// `x` wrapped into `(-π, π]`.
fn mod2pi(x: f64) -> f64 {
    let v = x.rem_euclid(TAU);
    if v > PI {
        v - TAU
    } else {
        v
    }
}

/// The goal in unit-radius form, with the sine and cosine of its heading (computed once
/// for all 48 words: the variants only flip signs).
#[derive(Clone, Copy, Debug)]
struct Goal {
    x: f64,
    y: f64,
    phi: f64,
    sin: f64,
    cos: f64,
}

impl Goal {
    fn new(x: f64, y: f64, phi: f64) -> Self {
        let (sin, cos) = phi.sin_cos();
        Self {
            x,
            y,
            phi,
            sin,
            cos,
        }
    }

    /// Time flip: `(-x, y, -φ)`.
    fn flipped(self) -> Self {
        Self {
            x: -self.x,
            phi: -self.phi,
            sin: -self.sin,
            ..self
        }
    }

    /// Reflection: `(x, -y, -φ)`.
    fn reflected(self) -> Self {
        Self {
            y: -self.y,
            phi: -self.phi,
            sin: -self.sin,
            ..self
        }
    }

    /// The start seen from the goal driving the word backwards (§8: "backwards").
    fn backwards(self) -> Self {
        Self {
            x: self.x * self.cos + self.y * self.sin,
            y: self.x * self.sin - self.y * self.cos,
            ..self
        }
    }

    /// `(x - sin φ, y - 1 + cos φ)`: the centre of the goal's left circle, seen from the
    /// start's left circle (the CSC, CCC and CCSC words with equal end turns).
    fn left_centres(&self) -> (f64, f64) {
        (self.x - self.sin, self.y - 1.0 + self.cos)
    }

    /// `(x + sin φ, y - 1 - cos φ)`: the goal's right circle from the start's left one.
    fn opposite_centres(&self) -> (f64, f64) {
        (self.x + self.sin, self.y - 1.0 - self.cos)
    }
}

/// `‖(x, y)‖` (the coordinates are bounded: no overflow to guard against).
fn norm(x: f64, y: f64) -> f64 {
    (x * x + y * y).sqrt()
}

/// The first and last arcs `(τ, ω)` of the CCCC words (paper §8.7–8.8).
fn tau_omega(u: f64, v: f64, xi: f64, eta: f64, phi: f64) -> (f64, f64) {
    let delta = mod2pi(u - v);
    let a = u.sin() - delta.sin();
    let b = u.cos() - delta.cos() - 1.0;
    let t1 = (eta * a - xi * b).atan2(xi * a + eta * b);
    let t2 = 2.0 * (delta.cos() - v.cos() - u.cos()) + 3.0;
    let tau = if t2 < 0.0 {
        mod2pi(t1 + PI)
    } else {
        mod2pi(t1)
    };
    (tau, mod2pi(tau - u + v - phi))
}

/// `sqrt(s)` for `s ≥ -SLACK` (0 on the slack).
fn sqrt_slack(s: f64) -> f64 {
    s.max(0.0).sqrt()
}

/// L⁺S⁺L⁺ (§8.1). Length ≥ `u`.
fn lp_sp_lp(g: &Goal, best: &Best) -> Option<[f64; 3]> {
    let (xi, eta) = g.left_centres();
    let u = norm(xi, eta);
    // t = atan2(η, ξ) < 0 when η < 0, and |t| ≥ |η|/u: skip the arctangent when the
    // sign test would fail.
    if !best.admits(u) || eta < -SIGN_SLACK * u {
        return None;
    }
    let t = eta.atan2(xi);
    let v = mod2pi(g.phi - t);
    (t >= -SIGN_SLACK && v >= -SIGN_SLACK).then_some([t, u, v])
}

/// L⁺S⁺R⁺ (§8.2). Length ≥ `u`.
fn lp_sp_rp(g: &Goal, best: &Best) -> Option<[f64; 3]> {
    let (xi, eta) = g.opposite_centres();
    let u1 = xi * xi + eta * eta;
    if u1 < 4.0 - SLACK {
        return None;
    }
    let u = sqrt_slack(u1 - 4.0);
    if !best.admits(u) {
        return None;
    }
    let t = mod2pi(eta.atan2(xi) + 2.0f64.atan2(u));
    let v = mod2pi(t - g.phi);
    (t >= -SIGN_SLACK && v >= -SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁻L (§8.3). Length ≥ `|u| = 2·asin(u1/4) ≥ u1/2`.
fn lp_rm_l(g: &Goal, best: &Best) -> Option<[f64; 3]> {
    let (xi, eta) = g.left_centres();
    let u1 = norm(xi, eta);
    if u1 > 4.0 + SLACK || !best.admits(0.5 * u1) {
        return None;
    }
    let u = -2.0 * (u1 / 4.0).min(1.0).asin();
    if !best.admits(-u) {
        return None;
    }
    let t = mod2pi(eta.atan2(xi) + 0.5 * u + PI);
    let v = mod2pi(g.phi - t + u);
    (t >= -SIGN_SLACK && u <= SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁺ᵤL⁻ᵤR⁻ (§8.7): lengths `(t, u, v)` of `t, u, -u, v`. Length ≥ `2u`.
fn lp_rup_lum_rm(g: &Goal, best: &Best) -> Option<[f64; 3]> {
    let (xi, eta) = g.opposite_centres();
    let rho = 0.25 * (2.0 + norm(xi, eta));
    if rho > 1.0 + SLACK {
        return None;
    }
    let u = rho.min(1.0).acos();
    if !best.admits(u + u) {
        return None;
    }
    let (t, v) = tau_omega(u, -u, xi, eta, g.phi);
    (t >= -SIGN_SLACK && v <= SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁻ᵤL⁻ᵤR⁺ (§8.8): lengths `(t, u, v)` of `t, u, u, v`. Length ≥ `2|u|`.
fn lp_rum_lum_rp(g: &Goal, best: &Best) -> Option<[f64; 3]> {
    let (xi, eta) = g.opposite_centres();
    let rho = (20.0 - xi * xi - eta * eta) / 16.0;
    if !(-SLACK..=1.0 + SLACK).contains(&rho) {
        return None;
    }
    let u = -rho.clamp(0.0, 1.0).acos();
    if u < -FRAC_PI_2 - SLACK || !best.admits(-u - u) {
        return None;
    }
    let (t, v) = tau_omega(u, u, xi, eta, g.phi);
    (t >= -SIGN_SLACK && v >= -SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁻_{π/2}S⁻L⁻ (§8.9): lengths `(t, u, v)` of `t, -π/2, u, v`. Length ≥ `π/2 + |u|`.
fn lp_rm_sm_lm(g: &Goal, best: &Best) -> Option<[f64; 3]> {
    let (xi, eta) = g.left_centres();
    let rho = norm(xi, eta);
    if rho < 2.0 - SLACK {
        return None;
    }
    let r = sqrt_slack(rho * rho - 4.0);
    let u = 2.0 - r;
    if u > SIGN_SLACK || !best.admits(FRAC_PI_2 + u.abs()) {
        return None;
    }
    let t = mod2pi(eta.atan2(xi) + r.atan2(-2.0));
    let v = mod2pi(g.phi - FRAC_PI_2 - t);
    (t >= -SIGN_SLACK && v <= SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁻_{π/2}S⁻R⁻ (§8.10): lengths `(t, u, v)` of `t, -π/2, u, v`. Length ≥ `π/2 + |u|`.
fn lp_rm_sm_rm(g: &Goal, best: &Best) -> Option<[f64; 3]> {
    let (xi, eta) = g.opposite_centres();
    let rho = norm(-eta, xi);
    if rho < 2.0 - SLACK {
        return None;
    }
    let u = 2.0 - rho;
    if u > SIGN_SLACK || !best.admits(FRAC_PI_2 + u.abs()) {
        return None;
    }
    let t = xi.atan2(-eta);
    let v = mod2pi(t + FRAC_PI_2 - g.phi);
    (t >= -SIGN_SLACK && v <= SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁻_{π/2}S⁻L⁻_{π/2}R⁺ (§8.11): lengths `(t, u, v)` of `t, -π/2, u, -π/2, v`.
/// Length ≥ `π/2 + |u| + π/2`.
fn lp_rm_slm_rp(g: &Goal, best: &Best) -> Option<[f64; 3]> {
    let (xi, eta) = g.opposite_centres();
    let rho = norm(xi, eta);
    if rho < 2.0 - SLACK {
        return None;
    }
    let u = 4.0 - sqrt_slack(rho * rho - 4.0);
    if u > SIGN_SLACK || !best.admits(FRAC_PI_2 + u.abs() + FRAC_PI_2) {
        return None;
    }
    let t = mod2pi(((4.0 - u) * xi - 2.0 * eta).atan2(-2.0 * xi + (u - 4.0) * eta));
    let v = mod2pi(t - g.phi);
    (t >= -SIGN_SLACK && v >= -SIGN_SLACK).then_some([t, u, v])
}

/// The shortest word seen so far, and the bound the caller needs an answer within.
/// A family is only solved while the lower bound of its length can still win
/// ([`Best::admits`]); words are compared by `Σ |length|` in driving order, the sum
/// [`Curve::unit_length`] computes, so the winner is the word the full search finds.
struct Best {
    length: f64,
    bound: f64,
    word: Option<([Steer; MAX_SEGMENTS], [f64; MAX_SEGMENTS], usize)>,
}

impl Best {
    fn within(bound: f64) -> Self {
        Self {
            length: f64::INFINITY,
            bound,
            word: None,
        }
    }

    /// True when a word at least `lower` long could still be the answer: shorter than
    /// the best so far (the first of equal words wins) and within the bound.
    fn admits(&self, lower: f64) -> bool {
        lower < self.length && lower <= self.bound
    }

    fn consider(&mut self, steers: &[Steer], lengths: &[f64]) {
        let length = unit_length(lengths.iter().copied());
        if length < self.length {
            let mut word = ([S; MAX_SEGMENTS], [0.0; MAX_SEGMENTS], steers.len());
            word.0[..steers.len()].copy_from_slice(steers);
            word.1[..lengths.len()].copy_from_slice(lengths);
            self.length = length;
            self.word = Some(word);
        }
    }

    /// The shortest word as a curve, if one was found within the bound.
    fn into_curve(self) -> Option<Curve> {
        let (steers, lengths, n) = self.word?;
        (self.length <= self.bound).then(|| Curve::from_word(&steers[..n], &lengths[..n]))
    }
}

/// Swaps left and right.
fn reflect<const N: usize>(steers: [Steer; N]) -> [Steer; N] {
    steers.map(|s| match s {
        L => R,
        R => L,
        S => S,
    })
}

/// A family's base solver: the base word's lengths `(t, u, v)` to `goal`, if they exist
/// and can still beat `best`.
type Family = fn(&Goal, &Best) -> Option<[f64; 3]>;

/// Tries `solve` on the goal as given, time-flipped, reflected and both; `word` maps
/// the base solution to signed segment lengths of `steers`.
fn four_ways<const N: usize>(
    best: &mut Best,
    goal: Goal,
    steers: [Steer; N],
    solve: Family,
    word: impl Fn([f64; 3]) -> [f64; N],
) {
    let negated = |l: [f64; N]| l.map(|v| -v);
    if let Some(s) = solve(&goal, best) {
        best.consider(&steers, &word(s));
    }
    if let Some(s) = solve(&goal.flipped(), best) {
        best.consider(&steers, &negated(word(s)));
    }
    if let Some(s) = solve(&goal.reflected(), best) {
        best.consider(&reflect(steers), &word(s));
    }
    if let Some(s) = solve(&goal.flipped().reflected(), best) {
        best.consider(&reflect(steers), &negated(word(s)));
    }
}

/// The shortest Reeds–Shepp curve to `(x, y, phi)` from the origin facing +x, unit
/// radius.
pub(crate) fn shortest(x: f64, y: f64, phi: f64) -> Curve {
    shortest_within(x, y, phi, f64::INFINITY).expect("CSC always has a solution")
}

/// [`shortest`] when its length is at most `bound` (unit radii), else `None`; families
/// that cannot come within the bound are not solved. The same curve as [`shortest`]
/// whenever it returns one.
pub(crate) fn shortest_within(x: f64, y: f64, phi: f64, bound: f64) -> Option<Curve> {
    let goal = Goal::new(x, y, phi);
    let back = goal.backwards();
    let mut best = Best::within(bound);
    // CSC
    four_ways(&mut best, goal, [L, S, L], lp_sp_lp, |l| l);
    four_ways(&mut best, goal, [L, S, R], lp_sp_rp, |l| l);
    // CCC
    four_ways(&mut best, goal, [L, R, L], lp_rm_l, |l| l);
    four_ways(&mut best, back, [L, R, L], lp_rm_l, |[t, u, v]| [v, u, t]);
    // CCCC
    four_ways(&mut best, goal, [L, R, L, R], lp_rup_lum_rm, |[t, u, v]| {
        [t, u, -u, v]
    });
    four_ways(&mut best, goal, [L, R, L, R], lp_rum_lum_rp, |[t, u, v]| {
        [t, u, u, v]
    });
    // CCSC
    let h = -FRAC_PI_2;
    four_ways(&mut best, goal, [L, R, S, L], lp_rm_sm_lm, |[t, u, v]| {
        [t, h, u, v]
    });
    four_ways(&mut best, goal, [L, R, S, R], lp_rm_sm_rm, |[t, u, v]| {
        [t, h, u, v]
    });
    four_ways(&mut best, back, [L, S, R, L], lp_rm_sm_lm, |[t, u, v]| {
        [v, u, h, t]
    });
    four_ways(&mut best, back, [R, S, R, L], lp_rm_sm_rm, |[t, u, v]| {
        [v, u, h, t]
    });
    // CCSCC
    four_ways(
        &mut best,
        goal,
        [L, R, S, L, R],
        lp_rm_slm_rp,
        |[t, u, v]| [t, h, u, h, v],
    );
    best.into_curve()
}
