//! Two pipelines in one process, each with its own `[limits]` and deadline: neither
//! sees the other's (the run context is carried by each pipeline, nothing is
//! process-wide).

use smug_core::{Error, LoadedConfig, Pipeline, PlanOptions};
use smug_mission::plan_mission;
use std::fmt::Write as _;
use std::path::Path;

use smug_app as _;

/// A flat 20 × 20 m world at 0.5 m (a 40 × 40 grid, 6.4 kB) with `targets` targets of
/// one PoI each: the sequencer's cost matrix has `(targets + 1)²` entries of 8 bytes.
fn config(targets: usize) -> String {
    let mut text = String::from(
        r#"
seed = 1
[world]
type = "flat"
[world.params]
name = "many-targets"
size = [20.0, 20.0]
resolution = 0.5
[world.params.mission]
start = { x = 1.0, y = 1.0, yaw = 0.0 }
[validity]
type = "clearance-2d"
[motion]
type = "discrete"
params = { resolution = 0.1 }
[planner]
type = "visibility"
[sequencer]
type = "auto"
[selector]
type = "dp"
"#,
    );
    for k in 0..targets {
        let (x, y) = (3.0 + 2.0 * (k % 8) as f64, 3.0 + 3.0 * (k / 8) as f64);
        write!(
            text,
            "[[world.params.mission.targets]]\nid = \"t{k}\"\nposition = {{ x = {x}, y = {y} }}\n\
             pois = [{{ x = {x}, y = {}, yaw = 0.0 }}]\n",
            y - 0.5
        )
        .unwrap();
    }
    text
}

fn pipeline(targets: usize, set: &[&str]) -> Pipeline {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let loaded = LoadedConfig::from_text(&config(targets), "many.toml", Path::new("."), &set)
        .unwrap_or_else(|e| panic!("{e}"));
    Pipeline::assemble(&loaded).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn each_pipeline_keeps_its_own_memory_limit() {
    // 41 × 41 × 8 B = 13.4 kB: above 10 kB, the grid (6.4 kB) below.
    let small = || pipeline(40, &["limits.memory_gb=1e-5"]);
    let mut limited = small();
    // Assembled after the limited one, with the default limit (8 GB): before the run
    // context, its assembly set the process's limit for both.
    let mut roomy = pipeline(40, &[]);
    let err = plan_mission(&mut limited, PlanOptions::default()).unwrap_err();
    let message = err.to_string();
    assert!(
        message.contains("a 41×41 cost matrix") && message.contains("10.000 kB"),
        "{message}"
    );
    let plan = plan_mission(&mut roomy, PlanOptions::default()).unwrap();
    assert_eq!(plan.sequence.len(), 40);
    // And the other way round: a limited pipeline assembled last does not limit the
    // roomy one.
    let mut limited = small();
    let plan = plan_mission(&mut roomy, PlanOptions::default()).unwrap();
    assert_eq!(plan.sequence.len(), 40);
    assert!(plan_mission(&mut limited, PlanOptions::default()).is_err());
    assert_eq!(roomy.run().memory.bytes, 8_000_000_000);
    assert_eq!(limited.run().memory.bytes, 10_000);
}

#[test]
fn each_pipeline_keeps_its_own_deadline() {
    let mut hurried = pipeline(40, &[]);
    let mut patient = pipeline(40, &[]);
    assert_ne!(hurried.run().deadline, patient.run().deadline);
    // The hurried pipeline's deadline armed (passed at once) while the patient one
    // plans: the patient one does not see it.
    {
        let deadline = hurried.run().deadline.clone();
        let _armed = deadline.arm(Some(0.0));
        assert!(hurried.run().deadline.passed());
        let plan = plan_mission(&mut patient, PlanOptions::default()).unwrap();
        assert!(!plan.deadline_reached);
        assert_eq!(plan.sequence.len(), 40);
    }
    // A deadline in the options arms the pipeline's own: the stages see it.
    let options = PlanOptions {
        deadline: Some(1e-6),
        ..PlanOptions::default()
    };
    match plan_mission(&mut hurried, options) {
        Ok(plan) => assert!(plan.deadline_reached),
        Err(Error::DeadlinePassed { .. }) => {}
        Err(other) => panic!("{other}"),
    }
    assert!(!hurried.run().deadline.passed(), "lifted after the run");
    let plan = plan_mission(&mut patient, PlanOptions::default()).unwrap();
    assert!(!plan.deadline_reached);
}

/// A run's progress counts every leg the oracle asked of the planner, answers them all
/// by the end of the run, and names the stage running (the last: post-processing);
/// another pipeline's progress stays at nothing.
fn assert_progress_counts_every_leg(set: &[&str]) {
    let mut planned = pipeline(6, set);
    let untouched = pipeline(6, set);
    let plan = plan_mission(&mut planned, PlanOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let legs = plan.stats.paths_planned;
    assert!(legs > 0);
    assert_eq!(planned.run().progress.legs(), (legs, legs));
    assert_eq!(planned.run().progress.stage(), "post-processing");
    assert_eq!(untouched.run().progress.legs(), (0, 0));
    assert_eq!(untouched.run().progress.stage(), "");
}

#[test]
fn progress_counts_every_leg_planned_one_by_one() {
    assert_progress_counts_every_leg(&[]);
}

#[test]
fn progress_counts_every_leg_of_rows_answered_together() {
    assert_progress_counts_every_leg(&[
        r#"planner.type="lazy-prm-star""#,
        r#"sampler.type="uniform""#,
        "planner.params.one_to_many=true",
    ]);
}
