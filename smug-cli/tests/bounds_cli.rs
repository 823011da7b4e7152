//! Bounded runs: `smug plan --deadline` ends by its deadline, with a complete plan marked
//! as cut short or with exit 1 saying that the deadline passed; inputs that would need
//! more memory or work than the limits allow are refused naming what and how much.

mod common;

use common::*;
use std::time::{Duration, Instant};

#[test]
fn a_plan_found_after_the_deadline_cut_a_search_is_written_and_marked() {
    let out = "target/cli-test-deadline-marked";
    // LazyPRM* (the config's `auto` would plan exactly, and `visibility` does not watch
    // the deadline): its first search is cut at once.
    let run = smug(&[
        "plan",
        "configs/indoor-disc.toml",
        "--set",
        "planner.type=lazy-prm-star",
        "--deadline",
        "0.000001",
        "--out",
        out,
    ]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(0), "{err}");
    assert!(err.contains("the deadline cut a search short"), "{err}");
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(workspace().join(out).join("plan.json")).unwrap())
            .unwrap();
    assert_eq!(plan["deadline_reached"], true);
    assert!(plan["cost"].as_f64().unwrap().is_finite());
}

#[test]
fn a_deadline_without_a_complete_plan_exits_1_within_its_grace() {
    let out = workspace().join("target/cli-test-deadline-none");
    std::fs::remove_dir_all(&out).ok();
    let started = Instant::now();
    // Indoor: the paths between rooms need roadmap samples through the doors, which a
    // passed deadline stops. (On lunar the first samples of each query already join
    // every target: a query keeps the path its first search finds, so a passed
    // deadline still ends there with a plan marked cut short.)
    let run = smug(&[
        "plan",
        "configs/indoor.toml",
        "--deadline",
        "0.000001",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(1), "{err}");
    assert!(
        err.contains("the deadline of 0.000001 s passed during path planning"),
        "{err}"
    );
    // plan.json says there is no plan, and why; nothing is drawn.
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    assert_eq!(report["status"], "no_plan");
    assert_eq!(report["cause"], "deadline");
    assert!(report.get("cost").is_none(), "{report}");
    assert!(!out.join("plan.svg").exists(), "no drawing is written");
    // A second of grace after the deadline, plus the world's build and the process.
    assert!(
        started.elapsed() < Duration::from_secs(20),
        "{:?}",
        started.elapsed()
    );
}

#[test]
fn a_deadline_that_is_not_a_positive_number_names_the_key() {
    for bad in ["0", "nan", "inf", "-2"] {
        let run = smug(&["plan", "configs/lunar.toml", &format!("--deadline={bad}")]);
        let err = stderr(&run);
        assert_eq!(run.status.code(), Some(2), "{bad}: {err}");
        assert!(err.contains("`plan.deadline`"), "{bad}: {err}");
    }
    let run = smug(&["plan", "configs/lunar.toml", "--deadline=soon"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("plan.deadline"), "{}", stderr(&run));
}

#[test]
fn allocations_above_the_memory_limit_are_refused_with_their_size() {
    let cases = [
        (
            "planner.params.initial_samples=1000000000",
            "planner: a roadmap of initial_samples = 1000000000 vertices (1000000000 × 512 B) \
             would need 512.000 GB, above the memory limit of 8.000 GB (`limits.memory_gb`)",
        ),
        (
            "limits.memory_gb=0.000001",
            "world: a 300×290 grid (87000 × 4 B) would need 348.000 kB, above the memory \
             limit of 1.000 kB (`limits.memory_gb`)",
        ),
    ];
    for (set, expected) in cases {
        let run = smug(&["plan", "configs/lunar.toml", "--set", set]);
        let err = stderr(&run);
        assert_eq!(run.status.code(), Some(2), "{set}: {err}");
        assert!(err.contains(expected), "{set}: {err}");
    }
}

#[test]
fn a_selection_beyond_the_pose_pair_bound_is_refused_naming_the_target() {
    let run = smug(&[
        "plan",
        "configs/lunar.toml",
        "--set",
        "world.params.pois_per_target=4000",
    ]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(err.contains("4000 of them at target `stone-"), "{err}");
    assert!(err.contains("give the targets fewer PoIs"), "{err}");
}
