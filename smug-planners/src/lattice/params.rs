//! The `lattice` planner's parameters: their defaults, and the checks that name the
//! key at fault.

use serde::{Deserialize, Serialize};
use smug_core::{Error, Result};

/// Parameters of the `lattice` planner.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LatticeParams {
    /// Headings per lattice point (a multiple of 8, at least 16).
    pub headings: usize,
    /// Spacing of the lattice points, metres (default: a sixth of the turning radius,
    /// rounded down to a multiple of 1/64 m).
    pub resolution: Option<f64>,
    /// Shots to a goal start within this distance of it, metres (default: three
    /// turning radii).
    pub shot_radius: Option<f64>,
    /// The search's cost of a reverse motion is its objective cost times this (≥ 1).
    pub reverse_penalty: f64,
    /// Added to the search's cost at each change of gear (≥ 0).
    pub gear_change_cost: f64,
    /// Lattice poses one query may expand (0: as many as the lattice has).
    pub max_expansions: u64,
    /// Seconds one query may take (`inf`: no limit).
    pub time_limit: f64,
    /// Use the 2D obstacle-aware heuristic (else only the objective's bound).
    pub obstacle_heuristic: bool,
    /// The heuristic is multiplied by this (≥ 1; 1: optimal on the lattice, above:
    /// weighted A*, paths at most this factor dearer than the lattice's optimum, found
    /// with fewer expansions).
    pub heuristic_weight: f64,
    /// The heuristic's weight in the searches of a sequencing matrix's rows (≥ 1):
    /// their costs only order the targets (a path of theirs serves a route only where
    /// the PoI selection finds none cheaper), so they may trade a few per cent of cost
    /// for far fewer expansions.
    pub order_heuristic_weight: f64,
    /// Shortcut every path found with the model's curves (the cost never rises).
    pub shortcut: bool,
    /// Smooth every path found: rounds of shortcutting and corner cutting with the
    /// model's curves, each new curve checked (the cost never rises; as LazyPRM*'s
    /// `smooth`). Pulls a path taut where the lattice's spacing made it swerve.
    pub smooth: bool,
}

impl Default for LatticeParams {
    fn default() -> Self {
        Self {
            headings: 64,
            resolution: None,
            shot_radius: None,
            reverse_penalty: 1.0,
            gear_change_cost: 0.0,
            max_expansions: 0,
            time_limit: 30.0,
            obstacle_heuristic: true,
            heuristic_weight: 1.0,
            order_heuristic_weight: 1.0,
            shortcut: true,
            smooth: true,
        }
    }
}

/// The error for parameter `key` (a config path) and what is wrong with it.
pub(super) fn invalid(key: &str, message: impl std::fmt::Display) -> Error {
    Error::invalid_param("planner", format!("`{key}`: {message}"))
}

/// A sixth of the turning radius rounded down to a multiple of 1/64 m (at least
/// 1/64 m): lattice positions and their differences are then exact in binary, so the
/// same primitive gives the same relative pose everywhere and the model solves its
/// curve once.
pub(super) fn default_resolution(radius: f64) -> f64 {
    ((radius / 6.0 * 64.0).floor() / 64.0).max(1.0 / 64.0)
}

/// An error naming `key` unless `value` is finite and at least `min`.
fn finite_at_least(key: &str, value: f64, min: f64) -> Result<()> {
    if value.is_finite() && value >= min {
        return Ok(());
    }
    Err(invalid(
        key,
        format!("must be finite and ≥ {min}, got {value}"),
    ))
}

/// Checks the parameters, naming the key at fault.
pub(super) fn check_params(p: &LatticeParams) -> Result<()> {
    if p.headings < 16 || !p.headings.is_multiple_of(8) || p.headings > 1024 {
        return Err(invalid(
            "planner.params.headings",
            format!(
                "must be a multiple of 8 from 16 to 1024, got {}",
                p.headings
            ),
        ));
    }
    if let Some(r) = p.resolution {
        if !(r.is_finite() && r > 0.0) {
            return Err(invalid(
                "planner.params.resolution",
                format!("must be finite and > 0, got {r}"),
            ));
        }
    }
    if let Some(r) = p.shot_radius {
        if !(r.is_finite() && r >= 0.0) {
            return Err(invalid(
                "planner.params.shot_radius",
                format!("must be finite and ≥ 0, got {r}"),
            ));
        }
    }
    finite_at_least("planner.params.reverse_penalty", p.reverse_penalty, 1.0)?;
    finite_at_least("planner.params.gear_change_cost", p.gear_change_cost, 0.0)?;
    finite_at_least("planner.params.heuristic_weight", p.heuristic_weight, 1.0)?;
    finite_at_least(
        "planner.params.order_heuristic_weight",
        p.order_heuristic_weight,
        1.0,
    )?;
    if p.time_limit.is_nan() || p.time_limit <= 0.0 {
        return Err(invalid(
            "planner.params.time_limit",
            format!("must be > 0 (inf: no limit), got {}", p.time_limit),
        ));
    }
    Ok(())
}
