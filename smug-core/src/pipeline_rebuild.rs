//! Rebuilding a pipeline's world-dependent stages after obstacles were added to its
//! world (what a [`MissionSession`](crate::mission::MissionSession) does per new
//! obstacle), and what plugins are told about the change.

use super::Pipeline;
use crate::config::PluginSection;
use crate::context::{BuildContext, WorldChange};
use crate::error::Result;
use crate::objective::Objective;
use crate::registry::{MotionStage, ObjectiveStage, Stage, ValidityStage};
use crate::stages::{MotionValidator, StateValidityChecker};
use crate::world::World;
use std::sync::Arc;
use std::time::Instant;

impl Pipeline {
    /// Puts `world` (this pipeline's world with obstacles added) in place of the world
    /// and rebuilds the stages that read it, through the config's plugins: the
    /// objective (when configured), the validity checker and the motion validator, each
    /// timed in [`build_times_s`](Self::build_times_s). The planner, sequencer and
    /// selector are kept: the caller tells the planner
    /// ([`PointToPointPlanner::update_world`] with [`context`](Self::context)). With
    /// `change` (how `world` came from the current one), plugins may update what they
    /// derived instead of deriving it again ([`BuildContext::world_change`]).
    pub fn rebuild_on_world(
        &mut self,
        world: Arc<World>,
        change: Option<WorldChange>,
    ) -> Result<()> {
        let config = self.config.clone();
        let mut ctx = self
            .context
            .clone()
            .with_world(world.clone())
            .with_world_change(change.map(Arc::new));
        if let Some(section) = &config.objective {
            let objective: Arc<dyn Objective> =
                self.rebuild_stage::<ObjectiveStage>(&ctx, section)?.into();
            ctx = ctx.with_objective(objective.clone());
            self.objective = objective;
        }
        if let Some(section) = &config.validity {
            let checker: Arc<dyn StateValidityChecker> =
                self.rebuild_stage::<ValidityStage>(&ctx, section)?.into();
            ctx = ctx.with_state_validity(checker.clone());
            self.state_validity = Some(checker);
        }
        if let Some(section) = &config.motion {
            let validator: Arc<dyn MotionValidator> =
                self.rebuild_stage::<MotionStage>(&ctx, section)?.into();
            ctx = ctx.with_motion_validator(validator.clone());
            self.motion_validator = Some(validator);
        }
        self.world = Some(world);
        self.context = ctx.with_world_change(None);
        Ok(())
    }

    /// Builds a stage again (already resolved once), timed.
    fn rebuild_stage<S: Stage>(
        &mut self,
        ctx: &BuildContext,
        section: &PluginSection,
    ) -> Result<Box<S::Object>> {
        let started = Instant::now();
        let built = ctx.build::<S>(section)?;
        self.add_time(&section.key, started);
        Ok(built.object)
    }
}
