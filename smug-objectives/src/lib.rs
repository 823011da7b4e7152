//! SMUG objectives beyond path length: what a motion costs on the terrain.
//!
//! - `traversability`: length weighted by `1 + w·(1 − τ)^p` (plans keep to safer ground);
//! - `energy`: `μ·m·g·length + m·g·Σ max(0, Δz)` (climbing costs, descending is not
//!   recovered; asymmetric);
//! - `time`: `length / v(τ, slope)` plus turning time, `v ≤ v_max`.
//!
//! Each integrates along the space's local motion (`smug_core::objective::integrate_motion`)
//! and gives an admissible bound for A*, the informed sampler, IDP and lazy sequencing.
//! `path-length` lives in `smug-core` (the default).

#![warn(missing_docs)]

pub mod energy;
pub mod terrain;
pub mod time;
pub mod traversability;

pub use energy::{Energy, EnergyParams};
pub use terrain::Terrain;
pub use time::{TravelTime, TravelTimeParams};
pub use traversability::{RiskAware, RiskAwareParams};
