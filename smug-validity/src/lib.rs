//! SMUG validity: traversability estimators, state validity checkers and motion validators.
//!
//! Plugins:
//! - traversability: `geometric` (slope, roughness, step of a local plane fit), `from-file`,
//!   `onnx` (a learned model from an ONNX file; cargo feature `onnx`, on by default);
//! - state validity: `volumetric` (box vs ESDF by sphere subdivision), `exact` (box vs
//!   voxel cubes with parry3d), `hierarchical` (traversability first, then volumetric),
//!   `clearance-2d` (a disc on a flat map);
//! - motion: `discrete` (states at a fixed resolution in bisection order plus a terrain
//!   inclination limit).

#![warn(missing_docs)]

pub mod clearance_2d;
pub mod counting;
pub mod discrete_motion;
pub mod edt;
pub mod exact;
pub mod from_file;
pub mod geometric;
pub mod hierarchical;
#[cfg(feature = "onnx")]
pub mod onnx;
pub mod robot_box;
pub mod verdicts;
pub mod volumes;
mod volumes_update;
pub mod volumetric;

pub use clearance_2d::Clearance2dChecker;
pub use counting::CountingChecker;
pub use discrete_motion::DiscreteMotionValidator;
pub use exact::ExactChecker;
pub use geometric::GeometricEstimator;
pub use hierarchical::HierarchicalChecker;
pub use robot_box::RobotBox;
pub use volumes::{SharedVolumes, Volumes};
pub use volumetric::VolumetricChecker;

/// Errors of the validity crate.
#[derive(Debug, thiserror::Error)]
pub enum ValidityError {
    /// The world's maps cannot support the check.
    #[error("{0}")]
    Map(String),
}
