//! Planner stubs for the unit tests.

use crate::SelectionError;
use smug_core::{
    Error, Path, PathLength, PlannerOutcome, PlannerStats, PointToPointPlanner, Pose2, Result,
};
use smug_mission::PathOracle;
use std::sync::Arc;

/// Straight lines, except that nothing reaches x = 9.
struct StraightLine;

impl PointToPointPlanner for StraightLine {
    fn plan(&mut self, a: &Pose2, b: &Pose2) -> Result<PlannerOutcome> {
        if a.x == 9.0 || b.x == 9.0 {
            return Ok(PlannerOutcome::NoPath(smug_core::NoPathReason::Proved(
                smug_core::Proof::Disconnected,
            )));
        }
        Ok(PlannerOutcome::Exact(Path::new(vec![*a, *b], &objective())))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

/// Straight lines, except that paths from or to x = 7 detour through y = 50.
struct Detour;

impl PointToPointPlanner for Detour {
    fn plan(&mut self, a: &Pose2, b: &Pose2) -> Result<PlannerOutcome> {
        let states = if a.x == 7.0 || b.x == 7.0 {
            vec![
                *a,
                Pose2::new(a.x, 50.0, 0.0),
                Pose2::new(b.x, 50.0, 0.0),
                *b,
            ]
        } else {
            vec![*a, *b]
        };
        Ok(PlannerOutcome::Exact(Path::new(states, &objective())))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

/// Straight lines no longer than 10 m; nothing farther is connected.
struct Radius;

impl PointToPointPlanner for Radius {
    fn plan(&mut self, a: &Pose2, b: &Pose2) -> Result<PlannerOutcome> {
        if (a.x - b.x).hypot(a.y - b.y) > 10.0 {
            return Ok(PlannerOutcome::NoPath(smug_core::NoPathReason::Proved(
                smug_core::Proof::Disconnected,
            )));
        }
        Ok(PlannerOutcome::Exact(Path::new(vec![*a, *b], &objective())))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

/// Another planner's answers, with whole DP layers asked at once (the trait's
/// default `plan_layer`: a search per source, the least offset plus cost kept).
struct Layered(Box<dyn PointToPointPlanner>);

impl PointToPointPlanner for Layered {
    fn plan(&mut self, a: &Pose2, b: &Pose2) -> Result<PlannerOutcome> {
        self.0.plan(a, b)
    }

    fn answers_layers(&self) -> bool {
        true
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

fn objective() -> PathLength {
    PathLength::new(1.0, 0.0).expect("valid weights")
}

fn oracle(planner: Box<dyn PointToPointPlanner>, poses: &[(f64, f64)]) -> PathOracle {
    let mut o = PathOracle::new(Arc::new(objective()), planner);
    for &(x, y) in poses {
        o.add_pose(Pose2::new(x, y, 0.0));
    }
    o
}

/// An oracle over straight lines where nothing reaches x = 9.
pub(crate) fn straight_oracle(poses: &[(f64, f64)]) -> PathOracle {
    oracle(Box::new(StraightLine), poses)
}

/// An oracle over straight lines where paths from or to x = 7 detour through y = 50.
pub(crate) fn detour_oracle(poses: &[(f64, f64)]) -> PathOracle {
    oracle(Box::new(Detour), poses)
}

/// An oracle over straight lines of at most 10 m.
pub(crate) fn radius_oracle(poses: &[(f64, f64)]) -> PathOracle {
    oracle(Box::new(Radius), poses)
}

/// An oracle over straight lines of at most 10 m (`layers`: asked layer by layer).
pub(crate) fn radius_oracle_by(layers: bool, poses: &[(f64, f64)]) -> PathOracle {
    if layers {
        oracle(Box::new(Layered(Box::new(Radius))), poses)
    } else {
        radius_oracle(poses)
    }
}

/// The selection error inside a selector's error.
pub(crate) fn selection_error(err: &Error) -> Option<SelectionError> {
    match err {
        Error::Stage { stage, source } if stage == "selector" => {
            source.downcast_ref::<SelectionError>().copied()
        }
        _ => None,
    }
}
