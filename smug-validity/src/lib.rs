//! SMUG validity: traversability estimators, state validity checkers and motion validators.
//!
//! Plugins: motion validator `discrete` (states at a fixed resolution in bisection
//! order plus a terrain inclination limit).

#![warn(missing_docs)]

pub mod discrete_motion;

pub use discrete_motion::DiscreteMotionValidator;
