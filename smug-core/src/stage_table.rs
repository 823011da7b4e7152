//! The pipeline's stages, written once. [`stage_table!`] hands the list to a macro
//! that generates what every stage needs: the registry's stage markers and the
//! catalogue (`registry.rs`), and the config's section fields, their keys and the
//! default plugins (`config/schema.rs`). The pipeline assembles the stages in this
//! order, the space first (`pipeline/steps.rs`, checked against
//! [`STAGE_KEYS`](crate::registry::STAGE_KEYS) by a test).
//!
//! A new stage is its trait in `stages/`, one entry here, and its step and field in
//! the pipeline (`pipeline/steps.rs`, `pipeline/mod.rs`).

/// Calls `$then!` with every pipeline stage, in pipeline order (config sections,
/// `smug plugins`; assembly too, except that the space, which needs nothing, is built
/// first: each stage's plugin may use the stages built before it). Each entry reads
///
/// ```text
/// /// Extra doc lines for the config field.
/// key: Marker = "what the stage does", ObjectType, default_plugin;
/// ```
///
/// where `key` is the config section (and the `PipelineConfig` field), `Marker` the
/// registry's [`Stage`](crate::registry::Stage) type, `ObjectType` what its plugins
/// build, and `default_plugin` the plugin built when the section is absent
/// (`Some("name")`) or `None` (the stage is then not built).
macro_rules! stage_table {
    ($then:ident) => {
        $then! {
            /// Where the maps and the mission come from.
            world: WorldStage = "terrain maps and the mission",
                $crate::world::Scenario, None;
            /// Absent: the world's own layer, if any, is kept.
            traversability: TraversabilityStage = "traversability layer from the world's maps",
                dyn $crate::stages::TraversabilityEstimator, None;
            /// Default `se2`.
            space: SpaceStage = "motion model: k-NN distance and the local motion between states",
                dyn $crate::space::StateSpace, Some("se2");
            /// Default `path-length`.
            objective: ObjectiveStage = "cost of motions and paths, with an admissible lower bound",
                dyn $crate::objective::Objective, Some("path-length");
            /// Prunes the mission's PoIs the robot cannot stand at.
            validity: ValidityStage = "is the robot safe at a pose",
                dyn $crate::stages::StateValidityChecker, None;
            /// Checks the motions the planner proposes.
            motion: MotionStage = "is a straight motion between two poses safe",
                dyn $crate::stages::MotionValidator, None;
            /// The planner builds its samplers from this section.
            sampler: SamplerStage = "draws SE(2) states for the roadmap",
                dyn $crate::stages::Sampler, None;
            /// Plans the paths between poses.
            planner: PlannerStage = "plans a safe path between two poses on a shared roadmap",
                dyn $crate::stages::PointToPointPlanner, None;
            /// Orders the targets.
            sequencer: SequencerStage = "orders the targets (TSP over path costs)",
                dyn $crate::stages::Sequencer, None;
            /// Picks the PoIs.
            selector: SelectorStage = "chooses one pose of interest per target",
                dyn $crate::stages::PoiSelector, None;
            /// Splits the targets among a team's robots (team missions only).
            team_sequencer: TeamSequencerStage = "assigns and orders the targets of a team of robots",
                dyn $crate::stages::TeamSequencer, None;
        }
    };
}
