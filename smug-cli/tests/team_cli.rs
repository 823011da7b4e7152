//! Team missions through the CLI (issue 32): `smug plan` on a team config in both
//! objectives (every target served once, PoIs valid for their robot, the rover's
//! curvature), and bad team configs (exit 2 naming the key; exit 1 for a target no
//! robot can serve).

mod common;

use common::*;
use serde_json::Value;
use std::collections::BTreeSet;

/// A smaller lunar mission, so the team plans in seconds.
const SMALL: [&str; 4] = [
    "--set",
    "world.params.targets=5",
    "--set",
    "world.params.pois_per_target=4",
];

/// A flat world with a corridor 1.1 m wide: `slot`'s only PoI lies in it, where
/// ANYmal fits and the `big` robot does not; `gauge-b` is the rover's (a car on the
/// lattice, turning radius 1.5 m).
const FLAT_TEAM: &str = r#"seed = 1
[world]
type = "flat"
[world.params]
size = [12.0, 8.0]
obstacles = [
    { min = [6.0, 0.0], max = [7.0, 2.2], height = 1.0 },
    { min = [8.1, 0.0], max = [9.0, 2.2], height = 1.0 },
]
[world.params.mission]
start = { x = 1.0, y = 1.0 }
[[world.params.mission.targets]]
id = "gauge-a"
position = { x = 2.5, y = 6.5 }
pois = [{ x = 2.5, y = 5.5, yaw = 1.5708 }, { x = 1.5, y = 6.5, yaw = 0.0 }]
[[world.params.mission.targets]]
id = "gauge-b"
position = { x = 10.5, y = 6.0 }
pois = [{ x = 10.5, y = 5.0, yaw = 1.5708 }]
[[world.params.mission.targets]]
id = "slot"
position = { x = 7.55, y = 0.3 }
pois = [{ x = 7.55, y = 1.2, yaw = -1.5708 }]
[traversability]
type = "geometric"
[sampler]
type = "informed"
[planner]
type = "lazy-prm-star"
[team]
objective = "makespan"
[[team.robots]]
name = "small"
include = "robots/anymal.toml"
start = { x = 1.0, y = 1.0 }
validity = { type = "volumetric" }
[[team.robots]]
name = "big"
include = "robots/anymal.toml"
start = { x = 1.5, y = 3.0 }
validity = { type = "volumetric" }
robot = { length = 1.5, width = 1.2, max_speed = 2.0 }
[[team.robots]]
name = "rover"
include = "robots/rover.toml"
start = { x = 2.0, y = 4.5, yaw = 0.0 }
validity = { type = "volumetric" }
[[team.targets]]
id = "gauge-b"
robots = ["rover"]
"#;

/// Writes `text` as a config beside a copy of the robot profiles (so includes resolve),
/// in a directory of its own: tests run side by side, and a profile copied again while
/// another test's plan reads it is read half written.
fn config(name: &str, text: &str) -> String {
    let dir = workspace()
        .join("target/cli-test-team")
        .join(name.trim_end_matches(".toml"));
    std::fs::create_dir_all(dir.join("robots")).unwrap();
    for profile in ["anymal.toml", "rover.toml", "wheeled.toml"] {
        let from = workspace().join("configs/robots").join(profile);
        std::fs::copy(from, dir.join("robots").join(profile)).unwrap();
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// Plans `config` with `set`; the plan.json written and what stdout said.
fn plan(config: &str, name: &str, set: &[&str]) -> (Value, String) {
    let out = scratch_dir("cli-test-team", name);
    let mut args = vec!["plan", config, "--out", out.to_str().unwrap()];
    args.extend(set);
    let run = smug(&args);
    assert_eq!(run.status.code(), Some(0), "{name}: {}", stderr(&run));
    for file in ["plan.json", "plan.csv", "plan.svg"] {
        assert!(out.join(file).exists(), "{name}: no {file}");
    }
    let csv = std::fs::read_to_string(out.join("plan.csv")).unwrap();
    assert!(csv.starts_with("robot,x,y,z,yaw"), "{csv}");
    let text = std::fs::read_to_string(out.join("plan.json")).unwrap();
    (serde_json::from_str(&text).unwrap(), stdout(&run))
}

/// The robot entry called `name`.
fn robot<'a>(plan: &'a Value, name: &str) -> &'a Value {
    plan["robots"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["name"] == name)
        .unwrap_or_else(|| panic!("no robot `{name}` in {plan}"))
}

/// Checks every target of `ids` is served exactly once, and the team's sum and
/// makespan are its robots' costs'.
fn check_served_once(plan: &Value, ids: &[String]) {
    let mut served = Vec::new();
    let mut costs = Vec::new();
    for robot in plan["robots"].as_array().unwrap() {
        let sequence: Vec<String> = robot["sequence"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_str().unwrap().to_string())
            .collect();
        assert_eq!(robot["pois"].as_array().unwrap().len(), sequence.len());
        served.extend(sequence);
        costs.push(robot["cost"].as_f64().unwrap());
    }
    served.sort();
    assert_eq!(served, ids, "every target exactly once");
    let total: f64 = costs.iter().sum();
    let makespan = costs.iter().copied().fold(0.0, f64::max);
    assert!((plan["total"].as_f64().unwrap() - total).abs() < 1e-6);
    assert!((plan["makespan"].as_f64().unwrap() - makespan).abs() < 1e-6);
}

/// `|Δyaw| ≤ spacing / r` between consecutive waypoints (sampled every 0.1 m along
/// the model's own curves, as `smug plan` documents), and no two farther apart.
fn check_curvature(robot: &Value, radius: f64) -> usize {
    let points: Vec<Vec<f64>> = robot["waypoints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| {
            w.as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect()
        })
        .collect();
    for (k, w) in points.windows(2).enumerate() {
        let d = (w[1][3] - w[0][3]).rem_euclid(std::f64::consts::TAU);
        let dyaw = d.min(std::f64::consts::TAU - d);
        assert!(
            dyaw <= 0.1 / radius * (1.0 + 1e-6) + 1e-9,
            "step {k} turns {dyaw}"
        );
        let chord = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
        assert!(chord <= 0.1 * (1.0 + 1e-6), "step {k}: {chord} m");
    }
    points.len()
}

#[test]
fn the_lunar_team_plans_for_the_sum_and_for_the_makespan() {
    let ids: Vec<String> = (1..=5).map(|k| format!("stone-{k:02}")).collect();
    let mut plans = Vec::new();
    for objective in ["sum", "makespan"] {
        let set = format!("team.objective={objective}");
        let mut args = SMALL.to_vec();
        args.extend(["--set", set.as_str()]);
        let (plan, printed) = plan("configs/lunar-team.toml", objective, &args);
        assert_eq!(plan["objective"], objective);
        assert_eq!(plan["unit"], "time");
        check_served_once(&plan, &ids);
        for name in ["anymal", "rover", "wheeled"] {
            assert!(printed.contains(name), "{printed}");
            let r = robot(&plan, name);
            assert!(r["time"].as_f64().unwrap() >= 0.0);
            assert_eq!(r["metrics"]["objective"], "time");
        }
        check_curvature(robot(&plan, "rover"), 1.5);
        assert!(robot(&plan, "anymal")["reversing"].is_null());
        assert!(robot(&plan, "wheeled")["reversing"].is_null());
        plans.push(plan);
    }
    let makespan_plan_serves: usize = plans[1]["robots"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| !r["sequence"].as_array().unwrap().is_empty())
        .count();
    assert!(makespan_plan_serves >= 2, "the makespan splits the targets");
}

#[test]
fn a_poi_invalid_for_a_robot_is_never_its_own() {
    let path = config("flat-team.toml", FLAT_TEAM);
    let ids: Vec<String> = ["gauge-a", "gauge-b", "slot"].map(String::from).to_vec();
    for objective in ["sum", "makespan"] {
        let set = format!("team.objective={objective}");
        let (plan, _) = plan(&path, &format!("flat-{objective}"), &["--set", &set]);
        check_served_once(&plan, &ids);
        let small = robot(&plan, "small")["sequence"].to_string();
        assert!(small.contains("slot"), "only `small` fits the slot: {plan}");
        let rover = robot(&plan, "rover");
        assert_eq!(rover["sequence"], serde_json::json!(["gauge-b"]));
        assert!(
            check_curvature(rover, 1.5) > 50,
            "the rover drives its curves"
        );
    }
    let svg =
        std::fs::read_to_string(workspace().join("target/cli-test-team/flat-makespan/plan.svg"))
            .unwrap();
    let colours: BTreeSet<&str> = ["#1f77b4", "#d62728", "#9467bd"]
        .into_iter()
        .filter(|c| svg.contains(&format!("stroke=\"{c}\"")))
        .collect();
    assert!(colours.len() >= 2, "the robots' colours: {colours:?}");
}

#[test]
fn bad_teams_are_named() {
    let bad = |name: &str, text: String, needles: &[&str]| {
        let path = config(name, &text);
        let out = scratch_dir("cli-test-team-out", name);
        let run = smug(&["plan", &path, "--out", out.to_str().unwrap()]);
        assert_bad_input(&run, needles);
    };
    let team_start = FLAT_TEAM.find("[team]").unwrap();
    bad(
        "no-robots.toml",
        format!("{}[team]\nobjective = \"sum\"\n", &FLAT_TEAM[..team_start]),
        &["team.robots", "at least one robot"],
    );
    bad(
        "twice.toml",
        FLAT_TEAM.replace("name = \"big\"", "name = \"small\""),
        &["team.robots[1].name", "`small` is used twice"],
    );
    let restricted = |robots: &str, id: &str| {
        format!("{FLAT_TEAM}[[team.targets]]\nid = \"{id}\"\nrobots = [{robots}]\n")
    };
    bad(
        "unknown-robot.toml",
        restricted("\"small\", \"drone\"", "slot"),
        &["team.targets[1].robots", "`drone`"],
    );
    bad(
        "unknown-target.toml",
        restricted("\"small\"", "valve"),
        &["team.targets[1].id", "no target `valve`"],
    );
    // A target only `big` may serve, whose PoI `big` cannot stand at: no solution.
    let path = config("unservable.toml", &restricted("\"big\"", "slot"));
    let out = scratch_dir("cli-test-team-out", "unservable");
    let run = smug(&["plan", &path, "--out", out.to_str().unwrap()]);
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(1), "{err}");
    for needle in [
        "`slot`",
        "robot `big`: none of its 1 PoIs is valid",
        "robot `small`: not allowed",
    ] {
        assert!(err.contains(needle), "`{needle}` missing from: {err}");
    }
    // plan.json says so too, as a single robot's does.
    let text = std::fs::read_to_string(out.join("plan.json")).unwrap();
    let plan: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(plan["status"], "no_plan", "{plan}");
    assert_eq!(plan["cause"], "unreachable", "{plan}");
    assert_eq!(plan["unreachable"][0]["target"], "slot", "{plan}");
    assert!(plan["reason"].as_str().unwrap().contains("robot `big`"));
    assert!(plan["stats"]["stage_times_s"]["total"].as_f64().unwrap() > 0.0);
}

/// Replans `config` from the team state `state` (TOML); the run, and plan.json when
/// it planned.
fn replan(config: &str, name: &str, state: &str) -> (std::process::Output, Option<Value>) {
    let out = scratch_dir("cli-test-team-out", name);
    let file = out.join("state.toml");
    std::fs::write(&file, state).unwrap();
    let plan_dir = out.join("plan");
    let run = smug(&[
        "replan",
        config,
        "--state",
        file.to_str().unwrap(),
        "--out",
        plan_dir.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(plan_dir.join("plan.json")).ok();
    (run, text.map(|t| serde_json::from_str(&t).unwrap()))
}

/// The flat team's robots at their starts, `lost` marking the lost ones.
fn team_state(visited: &[&str], lost: &[&str]) -> String {
    let mut text = format!("visited = {visited:?}\n");
    for (name, pose) in [
        ("small", "[1.0, 1.0, 0.0]"),
        ("big", "[1.5, 3.0, 0.0]"),
        ("rover", "[2.0, 4.5, 0.0]"),
    ] {
        text += &format!("[[robots]]\nname = \"{name}\"\n");
        if lost.contains(&name) {
            text += "lost = true\n";
        } else {
            text += &format!("pose = {pose}\n");
        }
    }
    text
}

#[test]
fn a_team_replan_from_the_starts_is_the_plan() {
    let path = config("flat-team-replan.toml", FLAT_TEAM);
    let (planned, _) = plan(&path, "flat-replan-reference", &[]);
    let (run, replanned) = replan(&path, "from-starts", &team_state(&[], &[]));
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let replanned = replanned.unwrap();
    for key in ["total", "makespan", "objective"] {
        assert_eq!(replanned[key], planned[key], "{key}");
    }
    for name in ["small", "big", "rover"] {
        assert_eq!(
            robot(&replanned, name)["sequence"],
            robot(&planned, name)["sequence"]
        );
    }
    assert!(planned["replan"].is_null());
    assert_eq!(replanned["replan"]["state"]["robots"][0]["name"], "small");
}

#[test]
fn a_lost_robots_targets_go_to_the_others() {
    let path = config("flat-team-lost.toml", FLAT_TEAM);
    // The rover is lost: `gauge-b` (the rover's only) is skipped, the rest shared.
    let (run, plan) = replan(&path, "rover-lost", &team_state(&["gauge-a"], &["rover"]));
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let plan = plan.unwrap();
    check_served_once(&plan, &["slot".to_string()]);
    assert!(robot(&plan, "small")["sequence"]
        .to_string()
        .contains("slot"));
    let names: Vec<&str> = plan["robots"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["small", "big"], "a lost robot plans nothing");
    assert_eq!(plan["replan"]["lost"], serde_json::json!(["rover"]));
    assert_eq!(plan["replan"]["skipped"][0]["target"], "gauge-b");
    let reason = plan["replan"]["skipped"][0]["reason"].as_str().unwrap();
    assert!(reason.contains("only lost robots") && reason.contains("rover"));
    assert!(stdout(&run).contains("lost: rover"), "{}", stdout(&run));
    // `small` is lost: `gauge-a` goes to the others, `slot` fits nobody left (exit 1).
    let (run, plan) = replan(&path, "small-lost", &team_state(&[], &["small"]));
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(1), "{err}");
    assert!(
        err.contains("`slot`") && err.contains("robot `big`"),
        "{err}"
    );
    let plan = plan.expect("a failed replan writes plan.json");
    assert_eq!(plan["status"], "no_plan", "{plan}");
    assert_eq!(plan["unreachable"][0]["target"], "slot", "{plan}");
    // A robot elsewhere with an obstacle seen: its route keeps out of the obstacle.
    let moved = team_state(&[], &["rover"]).replace("[1.5, 3.0, 0.0]", "[4.0, 5.0, 0.0]")
        + "[[obstacles]]\ncenter = [5.0, 3.5]\nradius = 0.4\nheight = 1.0\n";
    let (run, plan) = replan(&path, "obstacle", &moved);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let plan = plan.unwrap();
    for r in plan["robots"].as_array().unwrap() {
        let points: Vec<[f64; 2]> = r["waypoints"]
            .as_array()
            .unwrap()
            .iter()
            .map(|w| [w[0].as_f64().unwrap(), w[1].as_f64().unwrap()])
            .collect();
        for w in points.windows(2) {
            let gap = distance_to_segment([5.0, 3.5], w[0], w[1]);
            assert!(
                gap > 0.4,
                "{}: {w:?} passes {gap} m from the centre",
                r["name"]
            );
        }
    }
    let big = robot(&plan, "big");
    let first = &big["waypoints"][0];
    assert_eq!(
        (first[0].as_f64(), first[1].as_f64()),
        (Some(4.0), Some(5.0))
    );
}

#[test]
fn bad_team_states_are_named() {
    let path = config("flat-team-bad-state.toml", FLAT_TEAM);
    let bad = |name: &str, state: String, needles: &[&str]| {
        let (run, _) = replan(&path, name, &state);
        assert_bad_input(&run, needles);
    };
    let good = team_state(&[], &[]);
    bad(
        "unknown-robot",
        good.replace("name = \"big\"", "name = \"drone\""),
        &["robots[1].name", "no robot `drone`"],
    );
    bad(
        "missing-robot",
        good[..good.find("[[robots]]\nname = \"rover\"").unwrap()].to_string(),
        &["`robots`", "`rover`", "not listed"],
    );
    bad(
        "all-lost",
        team_state(&[], &["small", "big", "rover"]),
        &["every robot is lost"],
    );
    bad(
        "off-map",
        good.replace("[1.5, 3.0, 0.0]", "[40.0, 3.0, 0.0]"),
        &["robots[1].pose", "off the map"],
    );
    bad(
        "one-robot-state",
        "pose = [1.0, 1.0, 0.0]\n".to_string(),
        &["team state", "[[robots]]"],
    );
}

/// The distance from `p` to the segment `a`–`b`.
fn distance_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length2 = dx * dx + dy * dy;
    let t = if length2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a[0] + t * dx - p[0]).hypot(a[1] + t * dy - p[1])
}

#[test]
fn a_team_deadline_holds() {
    let out = scratch_dir("cli-test-team-out", "deadline");
    let started = std::time::Instant::now();
    let run = smug(&[
        "plan",
        "configs/lunar-team.toml",
        "--set",
        "plan.deadline=1.0",
        "--out",
        out.to_str().unwrap(),
    ]);
    let seconds = started.elapsed().as_secs_f64();
    let err = stderr(&run);
    // Unbounded, this team plans for 15-20 s; the hard stop is 1 s after the deadline.
    assert!(seconds < 8.0, "{seconds} s: {err}");
    match run.status.code() {
        Some(0) => {
            assert!(err.contains("deadline cut a search short"), "{err}");
            let text = std::fs::read_to_string(out.join("plan.json")).unwrap();
            let plan: Value = serde_json::from_str(&text).unwrap();
            let ids: Vec<String> = (1..=13).map(|k| format!("stone-{k:02}")).collect();
            check_served_once(&plan, &ids);
            assert_eq!(robot(&plan, "anymal")["deadline_reached"], true);
        }
        Some(1) => assert!(err.contains("deadline"), "{err}"),
        other => panic!("exit {other:?}: {err}"),
    }
}

#[test]
fn a_team_plan_mcap_has_each_robot_on_its_topics_and_a_replan_follows() {
    use smug_app::plan_mcap::{read_plan_mcap, TF_TOPIC};
    let path = config("flat-team-mcap.toml", FLAT_TEAM);
    let (plan, _) = plan(&path, "mcap", &[]);
    let dir = workspace().join("target/cli-test-team/mcap");
    let mcap = read_plan_mcap(&dir.join("plan.mcap")).unwrap();
    let robots = plan["robots"].as_array().unwrap();
    assert_eq!(mcap.paths.len(), robots.len(), "one path per robot");
    let mut transforms = 0;
    for (robot, path) in robots.iter().zip(&mcap.paths) {
        let name = robot["name"].as_str().unwrap();
        let waypoints = robot["waypoints"].as_array().unwrap();
        assert_eq!(path.poses.len(), waypoints.len(), "{name}");
        for (pose, w) in path.poses.iter().zip(waypoints) {
            let p = &pose.pose.position;
            assert_eq!([p.x, p.y], [w[0].as_f64().unwrap(), w[1].as_f64().unwrap()]);
        }
        for (topic, schema) in [
            (format!("/smug/{name}/plan"), "nav_msgs/msg/Path"),
            (format!("/smug/{name}/pois"), "geometry_msgs/msg/PoseArray"),
        ] {
            let channel = (topic, schema.to_owned(), "ros2msg".to_owned());
            assert!(mcap.channels.contains(&channel), "{channel:?}");
        }
        transforms += waypoints.len();
    }
    assert_eq!(mcap.counts[TF_TOPIC], transforms);
    assert_eq!(mcap.counts["/smug/markers"], 1);
    assert_eq!(mcap.metadata[0]["kind"], "plan");
    // A team replan into the same directory follows the plan in plan.mcap.
    let state = dir.join("state.toml");
    std::fs::write(&state, team_state(&["gauge-a"], &["rover"])).unwrap();
    let out = dir.to_str().unwrap();
    let run = smug(&[
        "replan",
        &path,
        "--state",
        state.to_str().unwrap(),
        "--out",
        out,
    ]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let both = read_plan_mcap(&dir.join("plan.mcap")).unwrap();
    let kinds: Vec<&str> = both.metadata.iter().map(|m| m["kind"].as_str()).collect();
    assert_eq!(kinds, ["plan", "replan"]);
    assert_eq!(
        both.paths.len(),
        robots.len() + 2,
        "the replan's two robots follow"
    );
}

#[test]
fn each_robots_progress_counts_its_legs() {
    let config = workspace().join("configs/indoor-team.toml");
    let loaded = smug_app::load_config(&config, &[], None).unwrap();
    let mut followed = Vec::new();
    let outcome = smug_app::team::plan_team_config_with(&loaded, &mut |team| {
        for member in &team.members {
            followed.push((member.name.clone(), member.pipeline.run().progress.clone()));
        }
    });
    let planned = outcome.unwrap().solved().expect("the indoor team plans");
    assert_eq!(followed.len(), 2);
    for ((name, progress), robot) in followed.iter().zip(&planned.plans[0].robots) {
        let (answered, asked) = progress.legs();
        assert!(asked > 0, "{name} asked no leg");
        assert_eq!(answered, asked, "{name}: every leg asked is answered");
        assert!(robot.plan.stats.paths_planned <= asked, "{name}");
    }
}
