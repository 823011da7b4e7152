//! The stage steps around the world's (`world.rs`), in the stage table's order: each
//! builds its stage from the config's section (or the stage's default plugin) and
//! puts it where the pipeline holds it, once. The steps of stages that read the world
//! run again in [`Pipeline::rebuild_on_world`].

use super::{prune_mission, Phase, Pipeline};
use crate::config::PluginSection;
use crate::context::{BuildContext, WorldChange};
use crate::error::Result;
use crate::registry::{
    MotionStage, ObjectiveStage, PlannerStage, SamplerStage, SelectorStage, SequencerStage,
    SpaceStage, Stage, TeamSequencerStage, ValidityStage,
};
use std::sync::Arc;

/// One stage's step.
pub(super) struct Step {
    /// The stage's config key.
    pub(super) key: &'static str,
    /// True when what it builds reads the world: rebuilt on a changed world.
    pub(super) reads_world: bool,
    /// Builds the stage from `section` in the context and holds it in the pipeline.
    run: fn(&mut Pipeline, &BuildContext, &PluginSection, Phase) -> Result<()>,
}

/// The stages before the world.
pub(super) const BEFORE_WORLD: [Step; 1] = [Step {
    key: SpaceStage::NAME,
    reads_world: false,
    run: |p, ctx, section, phase| {
        p.space = p.build_stage_in::<SpaceStage>(ctx, section, phase)?.into();
        Ok(())
    },
}];

/// The stages after `world` and `traversability` (built with the world), in order.
pub(super) const AFTER_WORLD: [Step; 8] = [
    Step {
        key: ObjectiveStage::NAME,
        reads_world: true,
        run: |p, ctx, section, phase| {
            p.objective = p
                .build_stage_in::<ObjectiveStage>(ctx, section, phase)?
                .into();
            Ok(())
        },
    },
    Step {
        key: ValidityStage::NAME,
        reads_world: true,
        run: validity,
    },
    Step {
        key: MotionStage::NAME,
        reads_world: true,
        run: |p, ctx, section, phase| {
            let validator = p.build_stage_in::<MotionStage>(ctx, section, phase)?;
            p.motion_validator = Some(validator.into());
            Ok(())
        },
    },
    Step {
        key: SamplerStage::NAME,
        reads_world: false,
        // Built once here to check it and record its parameters; planners build their own.
        run: |p, ctx, section, phase| {
            p.build_stage_in::<SamplerStage>(ctx, section, phase)?;
            p.sampler = Some(section.clone());
            Ok(())
        },
    },
    Step {
        key: PlannerStage::NAME,
        reads_world: false,
        run: |p, ctx, section, phase| {
            p.planner = Some(p.build_stage_in::<PlannerStage>(ctx, section, phase)?);
            Ok(())
        },
    },
    Step {
        key: SequencerStage::NAME,
        reads_world: false,
        run: |p, ctx, section, phase| {
            p.sequencer = Some(p.build_stage_in::<SequencerStage>(ctx, section, phase)?);
            Ok(())
        },
    },
    Step {
        key: SelectorStage::NAME,
        reads_world: false,
        run: |p, ctx, section, phase| {
            p.selector = Some(p.build_stage_in::<SelectorStage>(ctx, section, phase)?);
            Ok(())
        },
    },
    Step {
        key: TeamSequencerStage::NAME,
        reads_world: false,
        run: |p, ctx, section, phase| {
            p.team_sequencer = Some(p.build_stage_in::<TeamSequencerStage>(ctx, section, phase)?);
            Ok(())
        },
    },
];

/// The validity checker; when assembling, the mission without the PoIs it rejects (a
/// mission without targets has nothing to prune).
fn validity(
    p: &mut Pipeline,
    ctx: &BuildContext,
    section: &PluginSection,
    phase: Phase,
) -> Result<()> {
    let checker: Arc<dyn crate::stages::StateValidityChecker> = p
        .build_stage_in::<ValidityStage>(ctx, section, phase)?
        .into();
    let mission = p.mission.as_ref().filter(|m| !m.targets.is_empty());
    if let (Phase::Assemble, Some(mission)) = (phase, mission) {
        let (pruned, dropped) = prune_mission(mission, checker.as_ref())?;
        p.mission = Some(pruned);
        p.dropped_pois = dropped;
    }
    p.state_validity = Some(checker);
    Ok(())
}

impl Pipeline {
    /// Runs `steps` (when rebuilding, those that read the world, told `change`), each
    /// in a context holding the stages built before it; a stage without a section and
    /// without a default plugin is not built.
    pub(super) fn run_steps(
        &mut self,
        steps: &[Step],
        phase: Phase,
        change: Option<Arc<WorldChange>>,
    ) -> Result<()> {
        let steps = steps
            .iter()
            .filter(|step| phase == Phase::Assemble || step.reads_world);
        for step in steps {
            let Some(section) = self.config.section(step.key) else {
                continue;
            };
            let ctx = self.context().with_world_change(change.clone());
            (step.run)(self, &ctx, &section, phase)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::{AFTER_WORLD, BEFORE_WORLD};
    use crate::registry::{SpaceStage, Stage, TraversabilityStage, WorldStage, STAGE_KEYS};

    #[test]
    fn the_pipeline_builds_every_stage_of_the_table_in_its_order_the_space_first() {
        let with_world = [WorldStage::NAME, TraversabilityStage::NAME];
        let built: Vec<&str> = BEFORE_WORLD
            .iter()
            .map(|step| step.key)
            .chain(with_world)
            .chain(AFTER_WORLD.iter().map(|step| step.key))
            .collect();
        let mut table = STAGE_KEYS.to_vec();
        table.retain(|key| *key != SpaceStage::NAME);
        table.insert(0, SpaceStage::NAME);
        assert_eq!(built, table);
    }
}
