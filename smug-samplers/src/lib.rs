//! SMUG samplers: uniform, informed and bridge-test SE(2) sampling.
//!
//! Plugins: `uniform` (uniform in the map bounds), `informed` (uniform in the
//! informed ellipse of the current query, intersected with the bounds) and `bridge`
//! (informed plus a share of bridge-test samples in narrow passages).

#![warn(missing_docs)]

pub mod bridge;
pub mod informed;
pub mod uniform;

pub use bridge::{BridgeParams, BridgeSampler};
pub use informed::{InformedEllipse, InformedSampler};
pub use uniform::UniformSampler;
