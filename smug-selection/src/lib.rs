//! SMUG PoI selection: which pose of interest to visit for each target, given the
//! visiting order, using only the path oracle.
//!
//! Plugins: `brute-force` (every combination; the reference for tests).

#![warn(missing_docs)]

pub mod brute_force;

pub use brute_force::BruteForceSelector;
