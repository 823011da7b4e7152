//! The exact `visibility` planner from the command line: a multi-goal plan on the
//! imported-map mission (a disc on a generated 32×32 grid) no dearer than LazyPRM*'s,
//! refusals naming the key (exit 2), and `smug p2p` choosing it by default with honest
//! statuses.

mod common;

use common::{assert_bad_input, smug, stderr, stdout};

/// LazyPRM* instead of the configs' `auto` (which plans with `visibility` here).
const LAZY: &str = "planner.type=lazy-prm-star";

#[test]
fn auto_plans_the_disc_configs_exactly() {
    let root = std::env::temp_dir().join(format!("smug-visibility-auto-{}", std::process::id()));
    for config in ["configs/imported-map.toml", "configs/indoor-disc.toml"] {
        let auto = plan_cost_of(config, &root.join("auto"), &[]);
        let exact = plan_cost_of(
            config,
            &root.join("exact"),
            &["planner.type=visibility", "planner.params={}"],
        );
        assert_eq!(
            auto.to_bits(),
            exact.to_bits(),
            "{config}: auto {auto}, exact {exact}"
        );
        let plan = std::fs::read_to_string(root.join("auto").join("plan.json")).unwrap();
        assert!(
            plan.contains("corners_hidden"),
            "{config}: not the exact planner"
        );
    }
    std::fs::remove_dir_all(&root).ok();
}

/// The imported-map mission's cost in the joint mode with the exact GTSP solver: the
/// best route over the planned legs, so a planner whose legs are never dearer gives a
/// plan never dearer (the sequential mode orders on representatives, a heuristic: the
/// order LazyPRM*'s legs lead to can happen to select better PoIs).
fn plan_cost(dir: &std::path::Path, set: &[&str]) -> f64 {
    let mut all = vec!["plan.mode=joint", "sequencer.type=gtsp-exact"];
    all.extend(set);
    plan_cost_of("configs/imported-map.toml", dir, &all)
}

fn plan_cost_of(config: &str, dir: &std::path::Path, set: &[&str]) -> f64 {
    let mut args = vec!["plan", config, "--out"];
    let out_dir = dir.to_str().unwrap();
    args.push(out_dir);
    for s in set {
        args.push("--set");
        args.push(s);
    }
    let out = smug(&args);
    assert_eq!(out.status.code(), Some(0), "stderr: {}", stderr(&out));
    let plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("plan.json")).unwrap()).unwrap();
    plan["cost"].as_f64().unwrap()
}

#[test]
fn plans_the_imported_map_mission_no_dearer_than_lazy_prm_star() {
    let root = std::env::temp_dir().join(format!("smug-visibility-cli-{}", std::process::id()));
    let exact = plan_cost(
        &root.join("exact"),
        &["planner.type=visibility", "planner.params={}"],
    );
    let lazy = plan_cost(&root.join("lazy"), &[LAZY]);
    assert!(exact <= lazy, "exact {exact} > lazy {lazy}");
    // Same under pure length (no yaw term), where only the planar path differs.
    let set = [
        "objective.type=path-length",
        "objective.params.rotation_weight=0",
    ];
    let exact = plan_cost(
        &root.join("exact0"),
        &[
            set[0],
            set[1],
            "planner.type=visibility",
            "planner.params={}",
        ],
    );
    let lazy = plan_cost(&root.join("lazy0"), &[set[0], set[1], LAZY]);
    assert!(exact <= lazy, "exact {exact} > lazy {lazy} (length only)");
    std::fs::remove_dir_all(&root).ok();
}

#[test]
fn plans_the_indoor_mission_for_a_disc_no_dearer_than_lazy_prm_star() {
    let root = std::env::temp_dir().join(format!("smug-visibility-indoor-{}", std::process::id()));
    let config = "configs/indoor-disc.toml";
    let exact = plan_cost_of(
        config,
        &root.join("exact"),
        &["planner.type=visibility", "planner.params={}"],
    );
    let lazy = plan_cost_of(config, &root.join("lazy"), &[LAZY]);
    assert!(exact <= lazy, "exact {exact} > lazy {lazy}");
    std::fs::remove_dir_all(&root).ok();
}

#[test]
fn refuses_a_box_robot_a_car_and_other_objectives_naming_the_key() {
    let check = |config: &str, extra: &[&str]| {
        let mut args = vec![
            "check",
            config,
            "--set",
            "planner.type=visibility",
            "--set",
            "planner.params={}",
        ];
        for s in extra {
            args.push("--set");
            args.push(s);
        }
        smug(&args)
    };
    assert_bad_input(
        &check("configs/flat-demo.toml", &[]),
        &["validity.type", "not a disc"],
    );
    assert_bad_input(
        &check("configs/imported-map.toml", &["space.type=dubins"]),
        &["space.type", "curved"],
    );
    assert_bad_input(
        &check("configs/imported-map.toml", &["objective.type=energy"]),
        &["objective.type", "path length"],
    );
}

#[test]
fn p2p_uses_the_exact_planner_by_default_and_names_invalid_goals() {
    let dir = std::env::temp_dir().join(format!("smug-p2p-exact-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let queries = dir.join("q.csv");
    let results = dir.join("results.json");
    // Corner to corner, then a goal off the map: bad input (exit 2), every query
    // still answered in the results.
    std::fs::write(
        &queries,
        "sx,sy,syaw,gx,gy,gyaw\n0.5,0.5,0,30.5,30.5,1\n0.5,0.5,0,40.5,1.5,0\n",
    )
    .unwrap();
    let out = smug(&[
        "p2p",
        "--map",
        "configs/maps/random-32x32-d10-s1.yaml",
        "--queries",
        queries.to_str().unwrap(),
        "--radius",
        "0.25",
        "--out",
        results.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "stderr: {}", stderr(&out));
    assert!(stdout(&out).contains("(visibility)"), "{}", stdout(&out));
    assert!(
        stderr(&out).contains("query 2: invalid_goal: the goal (40.5, 1.5) is off the map"),
        "{}",
        stderr(&out)
    );
    assert!(
        stderr(&out).contains("error: bad query: query 2: the goal (40.5, 1.5) is off the map"),
        "{}",
        stderr(&out)
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&results).unwrap()).unwrap();
    assert_eq!(json["planner_type"], "visibility");
    assert_eq!(json["queries"][0]["status"], "exact");
    assert_eq!(json["queries"][1]["status"], "invalid_goal");
    assert_eq!(json["queries"][1]["why"], "off_map");
    // Its length is at least the straight line and at most the 8-connected detour.
    let cost = json["queries"][0]["cost"].as_f64().unwrap();
    assert!(
        cost >= 30.0 * 2f64.sqrt() && cost < 30.0 * 2f64.sqrt() * 1.1,
        "{cost}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
