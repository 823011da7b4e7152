//! Assembling a pipeline: the steps before the world, the world (or the caller's),
//! then the steps after it.

use super::steps::{AFTER_WORLD, BEFORE_WORLD};
use super::world::{GivenEstimator, GivenWorld};
use super::{Phase, Pipeline};
use crate::config::{KeyPath, LoadedConfig};
use crate::error::Result;
use crate::mission::Mission;
use crate::stages::TraversabilityEstimator;
use crate::world::World;

/// The message for a config that still has the `[cost]` section of earlier versions.
const REMOVED_COST: &str =
    "`[cost]` was split into `[space]` (the motion model and k-NN distance, \
     e.g. type = \"se2\") and `[objective]` (what a path costs, e.g. type = \"path-length\"); \
     both take the weights `translation_weight` and `rotation_weight`: move the section there";

impl Pipeline {
    /// Builds every stage the config names.
    pub fn assemble(loaded: &LoadedConfig) -> Result<Self> {
        Self::assemble_inner(loaded, None, None)
    }

    /// Builds every stage, using `world` (maps only, no mission: point-to-point
    /// queries) instead of the config's `[world]` section.
    pub fn assemble_with_world(loaded: &LoadedConfig, world: World) -> Result<Self> {
        Self::assemble_inner(loaded, Some((world, None)), None)
    }

    /// Builds every stage, with `world` and its mission (when given) instead of the
    /// config's `[world]` section and `estimator` (when given) instead of its
    /// `[traversability]` section. The estimator is recorded as stage
    /// `traversability`, plugin `name`.
    pub fn assemble_with(
        loaded: &LoadedConfig,
        world: Option<(World, Option<Mission>)>,
        estimator: Option<(&str, Box<dyn TraversabilityEstimator>)>,
    ) -> Result<Self> {
        Self::assemble_inner(loaded, world, estimator)
    }

    fn assemble_inner(
        loaded: &LoadedConfig,
        given_world: GivenWorld,
        given_estimator: GivenEstimator<'_>,
    ) -> Result<Self> {
        if loaded.config.cost.is_some() {
            let key = KeyPath::dotted("cost");
            return Err(loaded.sources.key_error(&key, REMOVED_COST).into());
        }
        let mut pipeline = Self::empty(loaded);
        pipeline.run_steps(&BEFORE_WORLD, Phase::Assemble, None)?;
        pipeline.build_world(loaded, given_world, given_estimator)?;
        pipeline.run_steps(&AFTER_WORLD, Phase::Assemble, None)?;
        Ok(pipeline)
    }
}
