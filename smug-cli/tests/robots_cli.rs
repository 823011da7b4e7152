//! Every robot profile plans the lunar mission through the CLI, and the plans of the
//! car-like models are checked from `plan.json` alone: consecutive waypoints never turn
//! tighter than the turning radius, Dubins plans never back up, Reeds–Shepp waypoints
//! marked `reversing` are driven backwards and the others forwards.

mod common;

use common::*;
use serde_json::Value;

/// A smaller lunar mission, so every profile plans in seconds.
const SMALL: [&str; 4] = [
    "--set",
    "world.params.targets=4",
    "--set",
    "world.params.pois_per_target=4",
];

fn plan(config: &str, set: &[&str]) -> Value {
    let out_dir = workspace().join("target/cli-test-robots").join(config);
    let mut args = vec!["plan", config, "--out", out_dir.to_str().unwrap()];
    args.extend(set);
    let run = smug(&args);
    assert_eq!(run.status.code(), Some(0), "{config}: {}", stderr(&run));
    let text = std::fs::read_to_string(out_dir.join("plan.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// `[x, y, z, yaw]` of every waypoint.
fn waypoints(plan: &Value) -> Vec<[f64; 4]> {
    plan["waypoints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| {
            let w: Vec<f64> = w
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            [w[0], w[1], w[2], w[3]]
        })
        .collect()
}

/// The shortest signed difference `b − a` of two angles.
fn turn(a: f64, b: f64) -> f64 {
    let d = (b - a).rem_euclid(std::f64::consts::TAU);
    if d > std::f64::consts::PI {
        d - std::f64::consts::TAU
    } else {
        d
    }
}

/// Waypoints of curved models lie at most this far apart along the curve (the
/// documented sampling of `smug plan`).
const SPACING: f64 = 0.1;

/// Checks curvature and direction of travel between consecutive waypoints; returns
/// how many steps were driven backwards. A step's arc is at most the spacing and turns
/// the heading by at most arc / r, so |Δyaw| ≤ spacing / r at every step (the chord
/// alone says less: within a step the curve may bend both ways, or back up at a cusp).
fn check_curve(plan: &Value, radius: f64, may_reverse: bool) -> usize {
    let points = waypoints(plan);
    let reversing: Vec<bool> = plan["reversing"]
        .as_array()
        .map(|r| r.iter().map(|v| v.as_bool().unwrap()).collect())
        .unwrap_or_else(|| vec![false; points.len()]);
    assert_eq!(reversing.len(), points.len());
    let gear = |j: usize| reversing.get(j).copied();
    let mut backwards = 0;
    for (k, w) in points.windows(2).enumerate() {
        let (dx, dy) = (w[1][0] - w[0][0], w[1][1] - w[0][1]);
        let chord = dx.hypot(dy);
        let dyaw = turn(w[0][3], w[1][3]).abs();
        let near_cusp =
            gear(k) != gear(k + 1) || gear(k + 2).is_some_and(|g| Some(g) != gear(k + 1));
        assert!(
            dyaw <= SPACING / radius * (1.0 + 1e-6) + 1e-9,
            "step {k}: turns {dyaw} rad within {SPACING} m, tighter than r = {radius}"
        );
        assert!(
            chord <= SPACING * (1.0 + 1e-6),
            "step {k}: waypoints {chord} m apart"
        );
        if reversing[k + 1] {
            assert!(may_reverse, "step {k} is marked reversing");
            backwards += 1;
        }
        if chord < 1e-9 || near_cusp {
            continue;
        }
        let heading = w[0][3] + 0.5 * turn(w[0][3], w[1][3]);
        let along = (dx * heading.cos() + dy * heading.sin()) / chord;
        if reversing[k + 1] {
            assert!(
                along < 1e-6,
                "step {k} is marked reversing but drives forwards"
            );
        } else {
            assert!(
                along > -1e-6,
                "step {k} drives backwards unmarked ({along})"
            );
        }
    }
    backwards
}

#[test]
fn every_robot_profile_plans_the_lunar_mission_under_every_objective() {
    let robots = ["lunar.toml", "lunar-wheeled.toml", "lunar-rover.toml"];
    let objectives = ["path-length", "traversability", "energy", "time"];
    for robot in robots {
        for objective in objectives {
            let config = format!("configs/{robot}");
            let set = format!("objective.type=\"{objective}\"");
            let mut args = SMALL.to_vec();
            args.extend(["--set", set.as_str()]);
            let plan = plan(&config, &args);
            assert_eq!(plan["metrics"]["objective"], objective, "{robot}");
            if robot != "lunar-rover.toml" {
                assert!(
                    plan["reversing"].is_null(),
                    "{robot}: holonomic plans never reverse"
                );
            }
        }
    }
}

#[test]
fn reeds_shepp_plans_keep_the_turning_radius_and_mark_reverse_gear() {
    let plan = plan("configs/lunar-rover.toml", &SMALL);
    assert!(
        check_curve(&plan, 1.5, true) > 0,
        "the rover backs up somewhere"
    );
    // plan.csv carries the same gears in a fifth column.
    let csv_path = workspace().join("target/cli-test-robots/configs/lunar-rover.toml/plan.csv");
    let csv = std::fs::read_to_string(csv_path).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("x,y,z,yaw,reversing"));
    let gears: Vec<bool> = lines
        .map(|line| match line.rsplit(',').next() {
            Some("1") => true,
            Some("0") => false,
            other => panic!("gear {other:?} in {line}"),
        })
        .collect();
    let expected: Vec<bool> = plan["reversing"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r.as_bool().unwrap())
        .collect();
    assert_eq!(gears, expected);
}

#[test]
fn dubins_plans_keep_the_turning_radius_and_never_reverse() {
    let plan = plan("configs/flat-dubins.toml", &[]);
    assert!(plan["reversing"].is_null());
    assert_eq!(check_curve(&plan, 1.0, false), 0);
}

#[test]
fn bad_radii_unknown_models_and_oversized_robots_name_the_key() {
    for (set, needles) in [
        (
            "space.params.turning_radius=0.0",
            &["turning_radius", "> 0"][..],
        ),
        ("space.params.turning_radius=nan", &["turning_radius"][..]),
        (
            "space.type=\"ackermann\"",
            &["space.type", "dubins", "reeds-shepp", "se2"][..],
        ),
        (
            "robot.length=40.0",
            &["robot.length", "larger than world"][..],
        ),
    ] {
        assert_bad_input(
            &smug(&["check", "configs/lunar-rover.toml", "--set", set]),
            needles,
        );
    }
}

/// The lattice planner's own bad input, through the CLI: a turning radius the map
/// cannot hold, too few headings, a holonomic model it cannot serve; one line naming
/// the key, exit 2.
#[test]
fn lattice_bad_input_names_the_key_and_exits_2() {
    for (set, needles) in [
        (
            &["space.params.turning_radius=20.0"][..],
            &["space.params.turning_radius", "does not fit"][..],
        ),
        (
            &["space.params.turning_radius=inf"][..],
            &["turning_radius", "finite"][..],
        ),
        (
            &["planner.params.headings=8"][..],
            &["planner.params.headings", "16"][..],
        ),
        (
            &["space.type=\"se2\"", "space.params={}"][..],
            &["space.type", "curvature-limited"][..],
        ),
    ] {
        let mut args = vec!["check", "configs/lunar-rover.toml"];
        for s in set {
            args.extend(["--set", s]);
        }
        assert_bad_input(&smug(&args), needles);
    }
}

#[test]
fn a_dubins_car_on_lunar_ends_in_seconds_naming_the_end_pose_it_cannot_enter() {
    // The paper's config with its robot swapped for a forward-only car by the space
    // alone: `auto` plans it on the lattice. The closed tour ends at the start, (2, 2)
    // facing 45° in the map's corner, which a car of that radius cannot enter: the
    // early probe proves it from every PoI and names the end pose, without searching
    // the map (it used to run for minutes with LazyPRM*, saying nothing; then it named
    // every stone, each PoI "a dead end").
    let out_dir = scratch_dir("cli-test-robots", "dubins-lunar");
    // A plan from before in the directory: its drawings must not outlive it.
    std::fs::write(out_dir.join("plan.csv"), "x,y,z,yaw\n").unwrap();
    let started = std::time::Instant::now();
    let run = smug(&[
        "plan",
        "configs/lunar.toml",
        "--set",
        "space.type=\"dubins\"",
        "--set",
        "space.params.turning_radius=1.5",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let seconds = started.elapsed().as_secs_f64();
    let err = stderr(&run);
    assert_eq!(run.status.code(), Some(1), "{err}");
    assert!(
        err.contains("no path enters the end pose (2.000, 2.000, yaw 0.785)"),
        "{err}"
    );
    assert!(err.contains("proved"), "{err}");
    assert!(seconds < 60.0, "{seconds} s");
    // plan.json says there is no plan, why, and what the run did; nothing is drawn.
    let plan: Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("plan.json")).unwrap()).unwrap();
    assert_eq!(plan["status"], "no_plan");
    assert_eq!(plan["cause"], "cut_off");
    let reason = plan["reason"].as_str().unwrap();
    assert!(
        !reason.is_empty() && err.contains(reason),
        "{reason} / {err}"
    );
    let end = &plan["unreachable"][0];
    assert_eq!(end["kind"], "end");
    assert_eq!(end["no_path"], "proved");
    assert_eq!(end["why"], "exhausted");
    assert_eq!(end["pose"].as_array().unwrap().len(), 3);
    assert!(plan["stats"]["validity_queries"].as_u64().unwrap() > 0);
    assert!(plan["stats"]["stage_times_s"]["total"].as_f64().unwrap() > 0.0);
    for file in ["plan.csv", "plan.svg", "plan.mcap"] {
        assert!(
            !out_dir.join(file).exists(),
            "{file} written without a plan"
        );
    }
}
