//! SMUG point-to-point planners.
//!
//! Plugins: `lazy-prm-star` (LazyPRM* with informed sampling on a shared roadmap),
//! `visibility` (exact shortest paths of a disc on a 2D occupancy grid) and `lattice`
//! (A* on a lattice of poses for car-like models).

#![warn(missing_docs)]

pub mod auto;
pub mod grid_disc;
pub mod lattice;
pub mod lazy_prm_star;
pub mod nn;
pub mod roadmap;
pub mod shortcut;
pub mod visibility;

pub use lattice::{LatticeParams, LatticePlanner};
pub use lazy_prm_star::{LazyPrmStar, LazyPrmStarParams, SearchMode};
pub use roadmap::file::{read_roadmap, write_roadmap, RoadmapFileError, RoadmapSnapshot};
pub use visibility::{Visibility, VisibilityParams};
