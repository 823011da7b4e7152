//! The stage traits: one per pipeline stage.

mod clusters;
mod motion;
mod path_costs;
mod planner;
mod roadmap;
mod sampler;
mod selector;
mod sequencer;
mod team;
mod tour;
mod traversability;
mod validity;

pub use clusters::Clusters;
pub use motion::{MotionCheck, MotionValidator};
pub use path_costs::PathCosts;
pub use planner::{
    plan_layer_by_sources, refuse_world_update, Budget, LayerOutcome, NoPathReason, NoRoadmap,
    PlannerOutcome, PlannerStats, PointToPointPlanner, Proof,
};
pub use roadmap::{ChangedDisc, Fingerprint};
pub use sampler::{InformedSet, Sampler};
pub use selector::{PoiSelector, Selection, SelectionError, SelectionProblem};
pub use sequencer::{CostMatrix, Sequencer, Tour, TourKind};
pub use team::{
    better_of, lex_less, RouteSize, TeamError, TeamObjective, TeamProblem, TeamRobot,
    TeamSequencer, TeamSolution, TeamTarget, Visit,
};
pub use traversability::{CellRect, TraversabilityEstimator};
pub use validity::{Counters, DiscOnGrid, EndpointFault, StateValidityChecker};
