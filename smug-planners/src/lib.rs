//! SMUG point-to-point planners.
//!
//! Plugins: `lazy-prm-star` (LazyPRM* with informed sampling on a shared roadmap).

#![warn(missing_docs)]

pub mod lazy_prm_star;
pub mod nn;
pub mod roadmap;
pub mod shortcut;

pub use lazy_prm_star::{LazyPrmStar, LazyPrmStarParams, SearchMode};
