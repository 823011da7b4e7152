//! What `plan.json` says when a mission ends without a plan (`smug plan`'s exit 1):
//! `"status": "no_plan"`, the reason (stderr's message), what could not be reached and
//! why, as far as the library's error says, and the run's statistics up to then.

use crate::outcome::NoSolution;
use serde::Serialize;
use smug_core::{NoPathReason, PlanStats};
use smug_mission::{CutOff, NoTargetLeft, Side, Unreachable};
use std::collections::BTreeMap;

/// `plan.json`'s `status` of a plan.
pub const PLANNED: &str = "planned";
/// `plan.json`'s `status` when the mission ended without a plan.
pub const NO_PLAN: &str = "no_plan";

/// A mission without a plan: why (as the CLI says it) and the report plan.json gets.
#[derive(Debug)]
pub struct NoPlan {
    /// Why, as [`Outcome::of`](crate::Outcome::of) sorts it.
    pub why: NoSolution,
    /// What plan.json says.
    pub report: NoPlanReport,
}

/// The `plan.json` of a mission that ended without a plan.
#[derive(Clone, Debug, Serialize)]
pub struct NoPlanReport {
    /// Always [`NO_PLAN`].
    pub status: &'static str,
    /// The kind of failure: `unreachable` (targets no safe path reaches), `cut_off` (the
    /// start or end pose is proved boxed in, or a probe's budget ran out), `no_target_left`
    /// (a replan with nothing to visit) or `deadline` (the run's deadline passed first).
    pub cause: &'static str,
    /// The same message as on stderr.
    pub reason: String,
    /// What could not be reached, each with why where the error says.
    pub unreachable: Vec<UnreachableItem>,
    /// The run's counters and timings when it ended (`stage_times_s` has `total` and
    /// the build stages; `legs_without_path` counts the pose pairs without a path by
    /// why: proved, or which budget ran out).
    pub stats: PlanStats,
}

/// One target or pose that could not be reached.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UnreachableItem {
    /// `target`, `start` (no PoI reached from the start pose) or `end` (no path into
    /// the end pose).
    pub kind: &'static str,
    /// The target's id (a target).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<String>,
    /// The pose `[x, y, yaw]` (the start or end).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pose: Option<[f64; 3]>,
    /// `proved` (no path exists) or `budget_spent` (one may exist), when known.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub no_path: Option<&'static str>,
    /// The machine-readable cause, when known: `disconnected`, `exhausted`, `samples`,
    /// `time`, `deadline`, `expansions`, `earlier_query`, `unspecified`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub why: Option<&'static str>,
    /// How the legs from the start to a target's PoIs ended, by `kind:why`
    /// (`proved:disconnected`, `budget_spent:samples`, …), when they ruled it out.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub legs: BTreeMap<String, u64>,
    /// Why, in words: the error's lines about it (e.g. one per PoI left out).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub reasons: Vec<String>,
}

impl NoPlan {
    /// The no-plan reading of a library error with the run's `stats`, if it is one.
    pub fn of(err: &smug_core::Error, stats: PlanStats) -> Option<Self> {
        let why = NoSolution::of(err)?;
        let (cause, unreachable) = match err {
            smug_core::Error::Stage { source, .. } => items_of(source.as_ref()),
            _ => ("deadline", Vec::new()),
        };
        let report = NoPlanReport {
            status: NO_PLAN,
            cause,
            reason: why.to_string(),
            unreachable,
            stats,
        };
        Some(Self { why, report })
    }
}

/// The cause and the items of a stage's no-solution error.
fn items_of(
    source: &(dyn std::error::Error + Send + Sync + 'static),
) -> (&'static str, Vec<UnreachableItem>) {
    if let Some(unreachable) = source.downcast_ref::<Unreachable>() {
        return ("unreachable", targets(unreachable));
    }
    if let Some(cut) = source.downcast_ref::<CutOff>() {
        return ("cut_off", vec![cut_off(cut)]);
    }
    if let Some(left) = source.downcast_ref::<NoTargetLeft>() {
        let items = left
            .skipped
            .iter()
            .map(|s| UnreachableItem {
                reasons: vec![s.reason.to_string()],
                ..target_item(&s.target)
            })
            .collect();
        return ("no_target_left", items);
    }
    ("unreachable", Vec::new())
}

/// One item per unreachable target, with the error's lines naming it (a line naming
/// no target, e.g. an enclosed start's, goes to every target).
fn targets(unreachable: &Unreachable) -> Vec<UnreachableItem> {
    let names_a_target = |line: &str| {
        unreachable
            .targets
            .iter()
            .any(|t| line.contains(&format!("`{t}`")))
    };
    unreachable
        .targets
        .iter()
        .enumerate()
        .map(|(k, id)| {
            let legs = unreachable.legs.get(k).cloned().unwrap_or_default();
            let reasons = unreachable
                .why
                .iter()
                .filter(|line| line.contains(&format!("`{id}`")) || !names_a_target(line))
                .cloned()
                .collect();
            match id.as_str() {
                // What the library names an end pose no route reaches.
                "(the end pose)" => UnreachableItem {
                    kind: "end",
                    target: None,
                    reasons,
                    ..target_item(id)
                },
                _ => UnreachableItem {
                    no_path: shared(&legs, 0),
                    why: shared(&legs, 1),
                    legs,
                    reasons,
                    ..target_item(id)
                },
            }
        })
        .collect()
}

/// Part `part` (0: `proved` / `budget_spent`, 1: the cause) of the `kind:why` keys of
/// `legs` when every leg has the same one.
fn shared(legs: &BTreeMap<String, u64>, part: usize) -> Option<&'static str> {
    let mut parts = legs.keys().map(|key| key.split(':').nth(part));
    let first = parts.next()??;
    if !parts.all(|p| p == Some(first)) {
        return None;
    }
    NoPathReason::ALL
        .iter()
        .flat_map(|reason| [reason.kind(), reason.why()])
        .find(|name| *name == first)
}

/// A target item without reasons.
fn target_item(id: &str) -> UnreachableItem {
    UnreachableItem {
        kind: "target",
        target: Some(id.to_string()),
        pose: None,
        no_path: None,
        why: None,
        legs: BTreeMap::new(),
        reasons: Vec::new(),
    }
}

/// The item of a start or end pose a probe found cut off.
fn cut_off(cut: &CutOff) -> UnreachableItem {
    let reason: &NoPathReason = &cut.reason;
    UnreachableItem {
        kind: match cut.side {
            Side::Start => "start",
            Side::End => "end",
        },
        target: None,
        pose: Some([cut.pose.x, cut.pose.y, cut.pose.yaw]),
        no_path: Some(reason.kind()),
        why: Some(reason.why()),
        legs: BTreeMap::new(),
        reasons: vec![cut.to_string()],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::{Pose2, Proof};

    fn report(source: impl std::error::Error + Send + Sync + 'static) -> NoPlanReport {
        let err = smug_core::Error::stage("plan", source);
        NoPlan::of(&err, PlanStats::default()).unwrap().report
    }

    #[test]
    fn unreachable_targets_get_the_lines_naming_them() {
        let report = report(Unreachable {
            targets: vec!["a".into(), "b".into()],
            why: vec![
                "target `a` PoI 0: proved".into(),
                "the start is enclosed".into(),
            ],
            legs: vec![
                BTreeMap::from([
                    ("budget_spent:samples".into(), 2),
                    ("budget_spent:time".into(), 1),
                ]),
                BTreeMap::from([("proved:disconnected".into(), 3)]),
            ],
        });
        assert_eq!(report.status, NO_PLAN);
        assert_eq!(report.cause, "unreachable");
        assert_eq!(report.unreachable.len(), 2);
        assert_eq!(report.unreachable[0].target.as_deref(), Some("a"));
        assert_eq!(report.unreachable[0].reasons.len(), 2);
        assert_eq!(report.unreachable[1].reasons, vec!["the start is enclosed"]);
        let (a, b) = (&report.unreachable[0], &report.unreachable[1]);
        assert_eq!((a.no_path, a.why), (Some("budget_spent"), None));
        assert_eq!((b.no_path, b.why), (Some("proved"), Some("disconnected")));
        assert_eq!(b.legs["proved:disconnected"], 3);
        assert!(report.reason.contains("`a`, `b`"));
    }

    #[test]
    fn a_cut_off_end_names_its_pose_and_proof() {
        let report = report(CutOff {
            side: Side::End,
            pose: Pose2::new(1.0, 2.0, 0.5),
            closed: false,
            pois: 3,
            reason: NoPathReason::Proved(Proof::Exhausted),
        });
        assert_eq!(report.cause, "cut_off");
        let item = &report.unreachable[0];
        assert_eq!(item.kind, "end");
        assert_eq!(item.pose, Some([1.0, 2.0, 0.5]));
        assert_eq!(
            (item.no_path, item.why),
            (Some("proved"), Some("exhausted"))
        );
        assert_eq!(item.reasons, vec![report.reason.clone()]);
    }

    #[test]
    fn other_errors_are_no_no_plan() {
        let err = smug_core::Error::InvalidInput("bad".into());
        assert!(NoPlan::of(&err, PlanStats::default()).is_none());
    }
}
