//! The shortest Reeds–Shepp curve (Reeds & Shepp 1990, §8): the five families CSC,
//! CCC, CCCC, CCSC and CCSCC, each solved for one base word and mapped onto the others
//! by time flip (drive the word in reverse), reflection (swap left and right) and, for
//! CCC and CCSC, backwards (drive the word from the goal), 48 words in all.
//!
//! Coordinates are in unit-radius form: the goal `(x, y, φ)` in the start's frame.
//! Formulas as in the paper's §8 (and OMPL's `ReedsSheppStateSpace`), with a small
//! slack on every domain and sign test so that tangent cases survive rounding.

use crate::curve::{Curve, Steer};
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

/// `(r, θ)` of the vector `(x, y)`.
fn polar(x: f64, y: f64) -> (f64, f64) {
    (x.hypot(y), y.atan2(x))
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

/// L⁺S⁺L⁺ (§8.1).
fn lp_sp_lp(x: f64, y: f64, phi: f64) -> Option<[f64; 3]> {
    let (u, t) = polar(x - phi.sin(), y - 1.0 + phi.cos());
    let v = mod2pi(phi - t);
    (t >= -SIGN_SLACK && v >= -SIGN_SLACK).then_some([t, u, v])
}

/// L⁺S⁺R⁺ (§8.2).
fn lp_sp_rp(x: f64, y: f64, phi: f64) -> Option<[f64; 3]> {
    let (u1, t1) = polar(x + phi.sin(), y - 1.0 - phi.cos());
    let u1 = u1 * u1;
    if u1 < 4.0 - SLACK {
        return None;
    }
    let u = sqrt_slack(u1 - 4.0);
    let t = mod2pi(t1 + 2.0f64.atan2(u));
    let v = mod2pi(t - phi);
    (t >= -SIGN_SLACK && v >= -SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁻L (§8.3).
fn lp_rm_l(x: f64, y: f64, phi: f64) -> Option<[f64; 3]> {
    let (u1, theta) = polar(x - phi.sin(), y - 1.0 + phi.cos());
    if u1 > 4.0 + SLACK {
        return None;
    }
    let u = -2.0 * (u1 / 4.0).min(1.0).asin();
    let t = mod2pi(theta + 0.5 * u + PI);
    let v = mod2pi(phi - t + u);
    (t >= -SIGN_SLACK && u <= SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁺ᵤL⁻ᵤR⁻ (§8.7): lengths `(t, u, v)` of `t, u, -u, v`.
fn lp_rup_lum_rm(x: f64, y: f64, phi: f64) -> Option<[f64; 3]> {
    let (xi, eta) = (x + phi.sin(), y - 1.0 - phi.cos());
    let rho = 0.25 * (2.0 + xi.hypot(eta));
    if rho > 1.0 + SLACK {
        return None;
    }
    let u = rho.min(1.0).acos();
    let (t, v) = tau_omega(u, -u, xi, eta, phi);
    (t >= -SIGN_SLACK && v <= SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁻ᵤL⁻ᵤR⁺ (§8.8): lengths `(t, u, v)` of `t, u, u, v`.
fn lp_rum_lum_rp(x: f64, y: f64, phi: f64) -> Option<[f64; 3]> {
    let (xi, eta) = (x + phi.sin(), y - 1.0 - phi.cos());
    let rho = (20.0 - xi * xi - eta * eta) / 16.0;
    if !(-SLACK..=1.0 + SLACK).contains(&rho) {
        return None;
    }
    let u = -rho.clamp(0.0, 1.0).acos();
    if u < -FRAC_PI_2 - SLACK {
        return None;
    }
    let (t, v) = tau_omega(u, u, xi, eta, phi);
    (t >= -SIGN_SLACK && v >= -SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁻_{π/2}S⁻L⁻ (§8.9): lengths `(t, u, v)` of `t, -π/2, u, v`.
fn lp_rm_sm_lm(x: f64, y: f64, phi: f64) -> Option<[f64; 3]> {
    let (rho, theta) = polar(x - phi.sin(), y - 1.0 + phi.cos());
    if rho < 2.0 - SLACK {
        return None;
    }
    let r = sqrt_slack(rho * rho - 4.0);
    let u = 2.0 - r;
    let t = mod2pi(theta + r.atan2(-2.0));
    let v = mod2pi(phi - FRAC_PI_2 - t);
    (t >= -SIGN_SLACK && u <= SIGN_SLACK && v <= SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁻_{π/2}S⁻R⁻ (§8.10): lengths `(t, u, v)` of `t, -π/2, u, v`.
fn lp_rm_sm_rm(x: f64, y: f64, phi: f64) -> Option<[f64; 3]> {
    let (xi, eta) = (x + phi.sin(), y - 1.0 - phi.cos());
    let (rho, theta) = polar(-eta, xi);
    if rho < 2.0 - SLACK {
        return None;
    }
    let t = theta;
    let u = 2.0 - rho;
    let v = mod2pi(t + FRAC_PI_2 - phi);
    (t >= -SIGN_SLACK && u <= SIGN_SLACK && v <= SIGN_SLACK).then_some([t, u, v])
}

/// L⁺R⁻_{π/2}S⁻L⁻_{π/2}R⁺ (§8.11): lengths `(t, u, v)` of `t, -π/2, u, -π/2, v`.
fn lp_rm_slm_rp(x: f64, y: f64, phi: f64) -> Option<[f64; 3]> {
    let (xi, eta) = (x + phi.sin(), y - 1.0 - phi.cos());
    let (rho, _) = polar(xi, eta);
    if rho < 2.0 - SLACK {
        return None;
    }
    let u = 4.0 - sqrt_slack(rho * rho - 4.0);
    if u > SIGN_SLACK {
        return None;
    }
    let t = mod2pi(((4.0 - u) * xi - 2.0 * eta).atan2(-2.0 * xi + (u - 4.0) * eta));
    let v = mod2pi(t - phi);
    (t >= -SIGN_SLACK && v >= -SIGN_SLACK).then_some([t, u, v])
}

/// The shortest word seen so far.
struct Best(Option<Curve>);

impl Best {
    fn consider(&mut self, steers: &[Steer], lengths: &[f64]) {
        let curve = Curve::from_word(steers, lengths);
        if self.0.is_none_or(|b| curve.unit_length() < b.unit_length()) {
            self.0 = Some(curve);
        }
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

/// Tries `solve` on the goal as given, time-flipped, reflected and both; `word` maps
/// the base solution to signed segment lengths of `steers`.
fn four_ways<const N: usize>(
    best: &mut Best,
    (x, y, phi): (f64, f64, f64),
    steers: [Steer; N],
    solve: fn(f64, f64, f64) -> Option<[f64; 3]>,
    word: impl Fn([f64; 3]) -> [f64; N],
) {
    let negated = |l: [f64; N]| l.map(|v| -v);
    if let Some(s) = solve(x, y, phi) {
        best.consider(&steers, &word(s));
    }
    if let Some(s) = solve(-x, y, -phi) {
        best.consider(&steers, &negated(word(s)));
    }
    if let Some(s) = solve(x, -y, -phi) {
        best.consider(&reflect(steers), &word(s));
    }
    if let Some(s) = solve(-x, -y, phi) {
        best.consider(&reflect(steers), &negated(word(s)));
    }
}

/// The goal seen from the goal driving the word backwards (§8: "backwards").
fn backwards(x: f64, y: f64, phi: f64) -> (f64, f64, f64) {
    let (s, c) = phi.sin_cos();
    (x * c + y * s, x * s - y * c, phi)
}

/// The shortest Reeds–Shepp curve to `(x, y, phi)` from the origin facing +x, unit
/// radius.
pub(crate) fn shortest(x: f64, y: f64, phi: f64) -> Curve {
    let goal = (x, y, phi);
    let back = backwards(x, y, phi);
    let mut best = Best(None);
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
    best.0.expect("CSC always has a solution")
}
