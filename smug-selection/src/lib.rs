//! SMUG PoI selection: which pose of interest to visit for each target, given the
//! visiting order, using only the path oracle.
//!
//! Plugins: `dp` (plans every leg between consecutive targets' PoIs, then dynamic
//! programming: optimal), `idp` (iterative DP over lower bounds: DP's cost, far fewer
//! paths), `irba` (iterative rubber band: local sweeps, fast, no guarantee) and
//! `brute-force` (every combination; the reference for tests).
//!
//! When no route exists, `dp`, `idp` and `irba` fail with [`SelectionError::Unreachable`]
//! naming the group (index in visiting order) with no reachable PoI (or
//! [`SelectionError::EndUnreachable`] when there are no groups), wrapped in
//! `smug_core::Error::Stage { stage: "selector", .. }`; `brute-force` returns cost
//! `INFINITY` instead.

#![warn(missing_docs)]

pub mod brute_force;
pub mod dp;
pub mod error;
pub mod idp;
pub mod irba;
mod layered;
#[cfg(test)]
mod test_support;

pub use brute_force::BruteForceSelector;
pub use dp::{DpParams, DpSelector};
pub use error::{unreachable_group, SelectionError};
pub use idp::{IdpParams, IdpSelector};
pub use irba::{IrbaParams, IrbaSelector};
