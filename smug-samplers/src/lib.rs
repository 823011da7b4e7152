//! SMUG samplers: uniform and informed SE(2) sampling.
//!
//! Plugins: `uniform` (uniform in the map bounds) and `informed` (uniform in the
//! informed ellipse of the current query, intersected with the bounds).

#![warn(missing_docs)]

pub mod informed;
pub mod uniform;

pub use informed::{InformedEllipse, InformedSampler};
pub use uniform::UniformSampler;
