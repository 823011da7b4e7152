//! The world step of assembly: the world and its mission (from the `world` plugin or
//! the caller), checked against the robot, with the traversability layer the
//! `traversability` plugin (or the caller's estimator) derives from its maps.

use super::{Pipeline, ResolvedStage};
use crate::config::{KeyPath, LoadedConfig, PluginSection};
use crate::error::{Error, Result};
use crate::grid::GridLayer;
use crate::mission::Mission;
use crate::registry::{Stage, TraversabilityStage, WorldStage};
use crate::stages::TraversabilityEstimator;
use crate::world::{Scenario, World};
use std::sync::Arc;
use std::time::Instant;

/// A world (and its mission, if any) the caller gives instead of the `[world]` section.
pub(super) type GivenWorld = Option<(World, Option<Mission>)>;
/// An estimator (and the plugin name it is recorded as) the caller gives instead of
/// the `[traversability]` section.
pub(super) type GivenEstimator<'a> = Option<(&'a str, Box<dyn TraversabilityEstimator>)>;

impl Pipeline {
    /// Builds the world (the given one, else the `[world]` section's, else none), checks
    /// its mission and that the robot fits, and fills its traversability layer.
    pub(super) fn build_world(
        &mut self,
        loaded: &LoadedConfig,
        given_world: GivenWorld,
        given_estimator: GivenEstimator<'_>,
    ) -> Result<()> {
        let world = match (given_world, &self.config.world) {
            (Some(given), _) => Some(given),
            (None, Some(section)) => {
                let section = section.clone();
                let Scenario { world, mission } =
                    *self.build_stage::<WorldStage>(&self.context(), &section)?;
                Some((world, Some(mission)))
            }
            (None, None) => None,
        };
        let Some((mut world, mission)) = world else {
            return Ok(());
        };
        if let Some(mission) = &mission {
            mission.validate()?;
        }
        check_robot_fits(loaded, &world)?;
        if let Some((section, estimator)) = self.estimator(given_estimator)? {
            let started = Instant::now();
            let layer = estimator.estimate(&world)?;
            world.traversability = Some(check_layer_fits(layer, &world, &section)?);
            self.add_time(&section.key, started);
        }
        self.given_mission = mission.clone();
        self.mission = mission;
        self.world = Some(Arc::new(world));
        Ok(())
    }

    /// The traversability estimator: the given one (recorded under its name), else the
    /// `[traversability]` section's, else none.
    fn estimator(
        &mut self,
        given: GivenEstimator<'_>,
    ) -> Result<Option<(PluginSection, Box<dyn TraversabilityEstimator>)>> {
        Ok(match (given, &self.config.traversability) {
            (Some((name, estimator)), _) => {
                let section = PluginSection::new(TraversabilityStage::NAME, name);
                self.resolved.push(ResolvedStage {
                    key: section.key.clone(),
                    plugin: section.kind.clone(),
                    params: toml::Table::new(),
                });
                Some((section, estimator))
            }
            (None, Some(section)) => {
                let section = section.clone();
                let estimator =
                    self.build_stage::<TraversabilityStage>(&self.context(), &section)?;
                Some((section, estimator))
            }
            (None, None) => None,
        })
    }
}

/// A robot whose base box is longer or wider than the world cannot stand anywhere in it:
/// an error naming the key and both sizes.
fn check_robot_fits(loaded: &LoadedConfig, world: &World) -> Result<()> {
    let robot = &loaded.config.robot;
    let [w, h] = world.bounds().extent();
    let room = w.min(h);
    for (key, size) in [("robot.length", robot.length), ("robot.width", robot.width)] {
        if size > room {
            let message = format!(
                "the robot ({size} m) is larger than world `{}` ({w} × {h} m)",
                world.name
            );
            return Err(loaded
                .sources
                .key_error(&KeyPath::dotted(key), message)
                .into());
        }
    }
    Ok(())
}

/// The layer an estimator returned, unless its grid differs from the world's elevation
/// grid: an error naming the plugin and both grids.
fn check_layer_fits(layer: GridLayer, world: &World, section: &PluginSection) -> Result<GridLayer> {
    let (got, want) = (layer.geometry, world.elevation.geometry);
    let same = got.size == want.size
        && (got.resolution - want.resolution).abs() <= 1e-9 * want.resolution
        && (got.origin[0] - want.origin[0]).abs() <= 1e-6
        && (got.origin[1] - want.origin[1]).abs() <= 1e-6;
    if same && layer.data.len() == want.len() {
        Ok(layer)
    } else {
        Err(Error::invalid_param(
            &section.key,
            format!(
                "plugin `{}` returned a layer of {}×{} cells at {} m from {:?}; the world's \
                 elevation is {}×{} at {} m from {:?}",
                section.kind,
                got.size[0],
                got.size[1],
                got.resolution,
                got.origin,
                want.size[0],
                want.size[1],
                want.resolution,
                want.origin
            ),
        ))
    }
}
