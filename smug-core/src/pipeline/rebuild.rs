//! Rebuilding a pipeline's world-dependent stages after obstacles were added to its
//! world (what a `MissionSession` does per new obstacle), and what plugins are told
//! about the change.

use super::steps::AFTER_WORLD;
use super::{Phase, Pipeline};
use crate::context::WorldChange;
use crate::error::Result;
use crate::world::World;
use std::sync::Arc;

impl Pipeline {
    /// Puts `world` (this pipeline's world with obstacles added) in place of the world
    /// and rebuilds the stages that read it, through the config's plugins: the
    /// objective, the validity checker and the motion validator, each timed in
    /// [`build_times_s`](Self::build_times_s). The planner, sequencer and selector are
    /// kept: the caller tells the planner
    /// ([`PointToPointPlanner::update_world`](crate::stages::PointToPointPlanner::update_world)
    /// with [`context`](Self::context)). With `change` (how `world` came from the
    /// current one), plugins may update what they derived instead of deriving it again
    /// ([`BuildContext::world_change`](crate::context::BuildContext::world_change)).
    pub fn rebuild_on_world(
        &mut self,
        world: Arc<World>,
        change: Option<WorldChange>,
    ) -> Result<()> {
        // On an error the world stays the one the stages were built for.
        let previous = self.world.replace(world);
        let rebuilt = self.run_steps(&AFTER_WORLD, Phase::Rebuild, change.map(Arc::new));
        if rebuilt.is_err() {
            self.world = previous;
        }
        rebuilt
    }
}
