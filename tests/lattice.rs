//! The `lattice` planner end to end on a flat world with obstacles, for a Dubins and a
//! Reeds–Shepp car: valid curves for the model and the checker, costs no lower than the
//! model's analytic distance, one-to-many equal to per-pair, closed pockets proved,
//! leavable poses never proved dead ends, bad input named, and paths no costlier than
//! LazyPRM*'s with a large budget.

use smug_core::{LoadedConfig, NoPathReason, Pipeline, PlannerOutcome, Pose2, Proof};
use std::path::Path;

use smug_app as _;

/// A 16 × 12 m flat world: two walls and a closed box around (13.5, 2.5); a disc robot
/// of radius 0.3, a car of turning radius 1 m.
const CONFIG: &str = r#"
seed = 3
[world]
type = "flat"
[world.params]
size = [16.0, 12.0]
obstacles = [
    { min = [5.0, 0.0], max = [5.4, 7.0] },
    { min = [10.0, 5.0], max = [10.4, 12.0] },
    { min = [12.0, 1.0], max = [15.0, 1.2] },
    { min = [12.0, 3.8], max = [15.0, 4.0] },
    { min = [12.0, 1.0], max = [12.2, 4.0] },
    { min = [14.8, 1.0], max = [15.0, 4.0] },
]
mission = { start = { x = 1.5, y = 1.5 } }
[space]
type = "dubins"
params = { turning_radius = 1.0 }
[validity]
type = "clearance-2d"
params = { radius = 0.3 }
[motion]
type = "discrete"
params = { resolution = 0.05, max_inclination = inf }
[sampler]
type = "informed"
[planner]
type = "lattice"
[sequencer]
type = "auto"
[selector]
type = "idp"
"#;

fn pipeline(overrides: &[&str]) -> Pipeline {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let loaded =
        LoadedConfig::from_text(CONFIG, "lattice.toml", Path::new("."), &overrides).unwrap();
    Pipeline::assemble(&loaded).unwrap()
}

fn assembly_error(overrides: &[&str]) -> String {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let loaded =
        LoadedConfig::from_text(CONFIG, "lattice.toml", Path::new("."), &overrides).unwrap();
    match Pipeline::assemble(&loaded) {
        Ok(_) => panic!("assembled with {overrides:?}"),
        Err(e) => e.to_string(),
    }
}

/// Start and goal pairs across the walls, all valid for the disc.
fn queries() -> Vec<(Pose2, Pose2)> {
    vec![
        (Pose2::new(1.5, 1.5, 0.0), Pose2::new(8.0, 2.0, -1.5)),
        (Pose2::new(2.0, 10.0, 0.0), Pose2::new(13.5, 10.0, 3.0)),
        (Pose2::new(13.0, 7.0, 1.5), Pose2::new(2.0, 3.0, 3.1)),
        (Pose2::new(7.5, 9.0, -1.5), Pose2::new(8.0, 9.0, 1.5)),
    ]
}

const SPACES: [&str; 2] = ["space.type=dubins", "space.type=reeds-shepp"];

/// Every motion of the path is valid (validator, and states at the validator's
/// resolution along the model's curve), the curve is the model's (forward only for
/// Dubins), and the cost is no lower than the model's analytic distance.
fn check_path(p: &Pipeline, start: &Pose2, goal: &Pose2, states: &[Pose2], cost: f64) {
    let motions = p.motion_validator.as_ref().unwrap();
    let checker = p.state_validity.as_ref().unwrap();
    let space = p.space.as_ref();
    assert_eq!(states.first(), Some(start));
    assert_eq!(states.last(), Some(goal));
    for w in states.windows(2) {
        assert!(
            motions.is_valid_motion(&w[0], &w[1]),
            "invalid motion {w:?}"
        );
        let length = space.motion_extent(&w[0], &w[1]).length;
        let pieces = (length / 0.05).ceil().max(1.0) as usize;
        for i in 0..=pieces {
            let t = i as f64 / pieces as f64;
            let s = space.interpolate(&w[0], &w[1], t);
            assert!(checker.is_valid(&s), "invalid state {s:?} on {w:?}");
            if !space.has_reverse_gear() {
                assert!(
                    !space.is_reversing(&w[0], &w[1], t),
                    "a Dubins car reversed"
                );
            }
        }
    }
    let analytic = space.distance(start, goal);
    assert!(
        cost >= analytic - 1e-9,
        "cost {cost} below the analytic {analytic}"
    );
}

#[test]
fn paths_are_the_models_curves_valid_and_no_cheaper_than_the_analytic_distance() {
    for space in SPACES {
        let mut p = pipeline(&[space]);
        for (start, goal) in queries() {
            let outcome = p.planner.as_mut().unwrap().plan(&start, &goal).unwrap();
            let path = outcome
                .exact_path()
                .unwrap_or_else(|| panic!("{space}: {outcome:?}"));
            check_path(&p, &start, &goal, &path.states, path.cost);
        }
    }
}

#[test]
fn one_to_many_equals_per_pair() {
    for space in SPACES {
        let settings = [space, "planner.params.shortcut=false"];
        let (start, _) = queries()[0];
        let goals: Vec<Pose2> = queries().iter().map(|q| q.1).collect();
        let mut many = pipeline(&settings);
        let together = many
            .planner
            .as_mut()
            .unwrap()
            .plan_many(&start, &goals)
            .unwrap();
        let mut single = pipeline(&settings);
        for (goal, outcome) in goals.iter().zip(&together) {
            let alone = single.planner.as_mut().unwrap().plan(&start, goal).unwrap();
            let (a, b) = (alone.exact_path().unwrap(), outcome.exact_path().unwrap());
            assert!(
                (a.cost - b.cost).abs() <= 1e-6 * a.cost,
                "{space}: {} alone, {} together",
                a.cost,
                b.cost
            );
        }
    }
}

/// A DP layer in one search (sources with offsets) settles every goal at the least,
/// over the sources, of the offset plus the path cost one search from that source
/// gives, and names a source that attains it.
#[test]
fn a_layer_search_equals_the_least_over_its_sources_of_searches_alone() {
    for space in SPACES {
        let settings = [
            space,
            "planner.params.shortcut=false",
            "planner.params.smooth=false",
        ];
        let sources: Vec<(Pose2, f64)> = queries()
            .iter()
            .zip([3.0, 0.0, 1.25, 7.5])
            .map(|(q, offset)| (q.0, offset))
            .collect();
        let goals: Vec<Pose2> = queries().iter().map(|q| q.1).collect();
        let mut layer = pipeline(&settings);
        let layer = layer.planner.as_mut().unwrap();
        assert!(layer.answers_layers());
        let answers = layer.plan_layer(&sources, &goals, &[]).unwrap();
        let mut alone = pipeline(&settings);
        let alone = alone.planner.as_mut().unwrap();
        let totals: Vec<Vec<f64>> = sources
            .iter()
            .map(|(start, offset)| {
                let outcomes = alone.plan_many(start, &goals).unwrap();
                let cost = |o: &PlannerOutcome| o.exact_path().map_or(f64::INFINITY, |p| p.cost);
                outcomes.iter().map(|o| offset + cost(o)).collect()
            })
            .collect();
        let mut winners = std::collections::BTreeSet::new();
        for (k, answer) in answers.iter().enumerate() {
            let least = totals.iter().map(|t| t[k]).fold(f64::INFINITY, f64::min);
            let path = answer.outcome.exact_path().expect("every goal is reached");
            let got = sources[answer.source].1 + path.cost;
            assert!(
                (got - least).abs() <= 1e-6 * least,
                "{space}, goal {k}: {got} in the layer, {least} alone"
            );
            assert_eq!(path.states[0], sources[answer.source].0);
            winners.insert(answer.source);
        }
        assert!(winners.len() > 1, "{space}: one source won every goal");
        // The next layer's search run ahead beside it changes no answer.
        let mut ahead = pipeline(&settings);
        let ahead = ahead.planner.as_mut().unwrap();
        let next: Vec<Pose2> = sources.iter().map(|s| s.0).collect();
        let with_next = ahead.plan_layer(&sources, &goals, &next).unwrap();
        assert_eq!(
            with_next, answers,
            "{space}: the next layer changed the answers"
        );
    }
}

/// The rows of a matrix that only orders targets, searched with the heuristic weighted
/// by `order_heuristic_weight`: paths of the model, never cheaper than the optimal
/// ones and at most that factor dearer (weighted A*), and with weight 1 the same as
/// rows asked for anything else.
#[test]
fn order_rows_are_weighted_a_star_within_their_weight() {
    let mut differ = false;
    for space in SPACES {
        let (start, _) = queries()[0];
        let goals: Vec<Pose2> = queries().iter().map(|q| q.1).collect();
        let rows = vec![(start, goals.clone())];
        let costs = |weight: &str, order: bool| -> Vec<f64> {
            let settings = [
                space,
                "planner.params.shortcut=false",
                "planner.params.smooth=false",
                weight,
            ];
            let mut p = pipeline(&settings);
            let planner = p.planner.as_mut().unwrap();
            let answers = if order {
                planner.plan_order_rows(&rows).unwrap()
            } else {
                planner.plan_rows(&rows).unwrap()
            };
            answers[0]
                .iter()
                .map(|o| o.exact_path().expect("a path").cost)
                .collect()
        };
        let exact = costs("planner.params.order_heuristic_weight=1.0", false);
        assert_eq!(
            exact,
            costs("planner.params.order_heuristic_weight=1.0", true)
        );
        let weighted = costs("planner.params.order_heuristic_weight=1.5", true);
        assert_eq!(
            exact,
            costs("planner.params.order_heuristic_weight=1.5", false)
        );
        differ |= weighted != exact;
        for (w, e) in weighted.iter().zip(&exact) {
            assert!(
                *w >= e * (1.0 - 1e-6) && *w <= 1.5 * e * (1.0 + 1e-6),
                "{space}: {w} against {e}"
            );
        }
    }
    assert!(differ, "the weight changed no path");
}

#[test]
fn cost_bounds_stay_below_the_lattice_costs_and_see_the_walls() {
    let mut tighter = false;
    for space in SPACES {
        let settings = [
            space,
            "planner.params.shortcut=false",
            "planner.params.smooth=false",
        ];
        let mut p = pipeline(&settings);
        let planner = p.planner.as_mut().unwrap();
        let starts: Vec<Pose2> = queries().iter().map(|q| q.0).collect();
        let goals: Vec<Pose2> = queries().iter().map(|q| q.1).collect();
        let rows = planner
            .cost_bounds(&starts, &goals)
            .unwrap()
            .expect("the lattice bounds its costs");
        for (start, bounds) in starts.iter().zip(rows) {
            let answers = planner.plan_many(start, &goals).unwrap();
            for ((goal, bound), answer) in goals.iter().zip(bounds).zip(answers) {
                let straight = start.xy_distance(goal);
                assert!(
                    bound >= straight * (1.0 - 1e-9),
                    "{space}: {bound} < {straight}"
                );
                if let Some(path) = answer.exact_path() {
                    assert!(
                        bound <= path.cost * (1.0 + 1e-9),
                        "{space}: bound {bound} above the lattice's cost {}",
                        path.cost
                    );
                }
                tighter |= bound > 1.2 * straight;
            }
        }
    }
    assert!(tighter, "no bound saw a wall");
}

#[test]
fn a_goal_in_a_closed_box_is_proved_unreachable() {
    for space in SPACES {
        let mut p = pipeline(&[space]);
        let outcome = p
            .planner
            .as_mut()
            .unwrap()
            .plan(&Pose2::new(1.5, 1.5, 0.0), &Pose2::new(13.5, 2.5, 0.0))
            .unwrap();
        assert_eq!(
            outcome,
            PlannerOutcome::NoPath(NoPathReason::Proved(Proof::Exhausted)),
            "{space}"
        );
    }
}

#[test]
fn a_pose_a_car_can_leave_is_never_proved_a_dead_end() {
    // Open poses (at least two turning radii from every wall and the border) on a
    // pseudo-random sequence: every pair is joined, none proved unreachable.
    let mut state = 7u64;
    let mut unit = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let open = [(2.5, 2.5), (2.5, 9.5), (7.7, 3.0), (7.7, 9.0), (13.5, 7.5)];
    for space in SPACES {
        let mut p = pipeline(&[space]);
        for k in 0..6 {
            let (a, b) = (open[k % open.len()], open[(k + 2) % open.len()]);
            let start = Pose2::new(a.0, a.1, (unit() - 0.5) * std::f64::consts::TAU);
            let goal = Pose2::new(b.0, b.1, (unit() - 0.5) * std::f64::consts::TAU);
            let outcome = p.planner.as_mut().unwrap().plan(&start, &goal).unwrap();
            assert!(
                outcome.exact_path().is_some(),
                "{space} {start:?} → {goal:?}: {outcome:?}"
            );
        }
    }
}

#[test]
fn runs_are_reproducible() {
    let costs = || {
        let mut p = pipeline(&["space.type=reeds-shepp"]);
        queries()
            .iter()
            .map(|(s, g)| {
                p.planner
                    .as_mut()
                    .unwrap()
                    .plan(s, g)
                    .unwrap()
                    .exact_path()
                    .unwrap()
                    .states
                    .clone()
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(costs(), costs());
}

#[test]
fn no_costlier_than_lazy_prm_star_with_a_large_budget() {
    for space in SPACES {
        let mut lattice = pipeline(&[space]);
        let mut prm = pipeline(&[
            space,
            "planner.type=lazy-prm-star",
            "planner.params.max_samples=40000",
            "planner.params.shortcut=true",
        ]);
        for (start, goal) in queries() {
            let ours = lattice
                .planner
                .as_mut()
                .unwrap()
                .plan(&start, &goal)
                .unwrap();
            let theirs = prm.planner.as_mut().unwrap().plan(&start, &goal).unwrap();
            let ours = ours.exact_path().unwrap().cost;
            if let Some(theirs) = theirs.exact_path() {
                assert!(
                    ours <= theirs.cost * 1.02,
                    "{space} {start:?} → {goal:?}: lattice {ours}, LazyPRM* {}",
                    theirs.cost
                );
            }
        }
    }
}

#[test]
fn bad_input_names_the_key() {
    let radius = assembly_error(&["space.params.turning_radius=7.0"]);
    assert!(radius.contains("space.params.turning_radius"), "{radius}");
    let holonomic = assembly_error(&["space.type=se2", "space.params={}"]);
    assert!(holonomic.contains("space.type"), "{holonomic}");
    let headings = assembly_error(&["planner.params.headings=12"]);
    assert!(headings.contains("planner.params.headings"), "{headings}");
    let resolution = assembly_error(&["planner.params.resolution=-1.0"]);
    assert!(
        resolution.contains("planner.params.resolution"),
        "{resolution}"
    );
}

/// The test world with a mission for a Dubins car: `stuck` faces the first wall from
/// 0.6 m (a car of turning radius 1 m cannot leave it), `open` is in the open.
fn dead_end_mission(pois: &str) -> Pipeline {
    let config = CONFIG.replace(
        "mission = { start = { x = 1.5, y = 1.5 } }",
        &format!(
            r#"mission = {{ start = {{ x = 2.5, y = 9.5, yaw = 0.0 }}, targets = [
    {{ id = "wall", position = {{ x = 5.2, y = 3.0 }}, pois = [{pois}] }},
    {{ id = "far", position = {{ x = 8.0, y = 9.0 }}, pois = [{{ x = 8.0, y = 9.0, yaw = 0.0 }}] }},
] }}"#
        ),
    );
    let loaded = LoadedConfig::from_text(&config, "dead-end.toml", Path::new("."), &[]).unwrap();
    Pipeline::assemble(&loaded).unwrap()
}

const STUCK: &str = "{ x = 4.4, y = 3.0, yaw = 0.0 }";
const OPEN: &str = "{ x = 2.5, y = 3.0, yaw = 3.1416 }";

#[test]
fn a_poi_a_forward_only_car_cannot_leave_is_left_out_and_named() {
    let mut p = dead_end_mission(&format!("{STUCK}, {OPEN}"));
    let options = p.config.plan;
    let plan = smug_mission::plan_mission(&mut p, options).unwrap();
    assert_eq!(plan.dead_ends.len(), 1, "{:?}", plan.dead_ends);
    let dead = &plan.dead_ends[0];
    assert_eq!((dead.target.as_str(), dead.index), ("wall", 0));
    assert!(
        dead.why.contains("the end cannot be reached"),
        "{}",
        dead.why
    );
    let chosen = plan.pois.iter().find(|c| c.target == "wall").unwrap();
    assert_eq!(chosen.index, 1);
}

#[test]
fn a_target_whose_every_poi_is_a_dead_end_is_named_and_why() {
    let mut p = dead_end_mission(STUCK);
    let options = p.config.plan;
    let err = smug_mission::plan_mission(&mut p, options).unwrap_err();
    let message = err.to_string();
    assert!(message.contains("`wall`"), "{message}");
    assert!(
        message.contains("PoI 0: the end cannot be reached from it"),
        "{message}"
    );
    match err {
        smug_core::Error::Stage { source, .. } => {
            assert!(source.is::<smug_mission::Unreachable>())
        }
        other => panic!("{other}"),
    }
}

/// Every path's states as bits, `None` for no path.
fn bits(outcomes: &[Vec<PlannerOutcome>]) -> Vec<Option<Vec<[u64; 3]>>> {
    outcomes
        .iter()
        .flatten()
        .map(|o| {
            o.exact_path().map(|p| {
                p.states
                    .iter()
                    .map(|s| [s.x.to_bits(), s.y.to_bits(), s.yaw.to_bits()])
                    .collect()
            })
        })
        .collect()
}

#[test]
fn rows_searched_side_by_side_equal_rows_searched_alone_bit_for_bit() {
    for space in SPACES {
        let poses: Vec<Pose2> = queries().iter().flat_map(|q| [q.0, q.1]).collect();
        let rows: Vec<(Pose2, Vec<Pose2>)> = poses
            .iter()
            .enumerate()
            .map(|(i, s)| (*s, poses[i + 1..].to_vec()))
            .filter(|(_, goals)| !goals.is_empty())
            .collect();
        let on_threads = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut p = pipeline(&[space]);
            let legs: usize = rows.iter().map(|(_, goals)| goals.len()).sum();
            let progress = p.run().progress.clone();
            progress.ask(legs as u64);
            let answered = pool.install(|| p.planner.as_mut().unwrap().plan_rows(&rows).unwrap());
            // Each row counts its legs in the run's progress as it ends.
            assert_eq!(progress.legs(), (legs as u64, legs as u64));
            answered
        };
        let one = on_threads(1);
        let two = on_threads(2);
        assert_eq!(bits(&one), bits(&two), "{space}: 1 thread vs 2");
        let mut p = pipeline(&[space]);
        let alone: Vec<Vec<PlannerOutcome>> = rows
            .iter()
            .map(|(s, g)| p.planner.as_mut().unwrap().plan_many(s, g).unwrap())
            .collect();
        assert_eq!(bits(&one), bits(&alone), "{space}: rows vs one by one");
        assert!(bits(&one).iter().filter(|b| b.is_some()).count() >= 20);
    }
}

/// A reversing car enters a pose wherever it can leave it: the boxed PoI's small search
/// towards the end proves it a dead end before sequencing (no leg to it is searched,
/// which would exhaust everything the start reaches), and it is named.
#[test]
fn a_poi_in_a_closed_box_is_never_chosen_and_is_proved_a_dead_end_for_a_reversing_car_too() {
    let boxed = "{ x = 13.5, y = 2.5, yaw = 0.0 }";
    let config = CONFIG
        .replace(
            "mission = { start = { x = 1.5, y = 1.5 } }",
            &format!(
                r#"mission = {{ start = {{ x = 2.5, y = 9.5, yaw = 0.0 }}, targets = [
    {{ id = "box", position = {{ x = 13.5, y = 2.5 }}, pois = [{boxed}, {OPEN}] }},
    {{ id = "far", position = {{ x = 8.0, y = 9.0 }}, pois = [{{ x = 8.0, y = 9.0, yaw = 0.0 }}] }},
] }}"#
            ),
        )
        .replace("type = \"dubins\"", "type = \"reeds-shepp\"");
    let loaded = LoadedConfig::from_text(&config, "boxed.toml", Path::new("."), &[]).unwrap();
    let mut p = Pipeline::assemble(&loaded).unwrap();
    let options = p.config.plan;
    let plan = smug_mission::plan_mission(&mut p, options).unwrap();
    let chosen = plan.pois.iter().find(|c| c.target == "box").unwrap();
    assert_eq!(chosen.index, 1);
    assert_eq!(plan.dead_ends.len(), 1, "{:?}", plan.dead_ends);
    let dead = &plan.dead_ends[0];
    assert_eq!((dead.target.as_str(), dead.index), ("box", 0));
    assert!(
        dead.why.contains("cannot be reached from it"),
        "{}",
        dead.why
    );
    assert!(plan.stats.legs_without_path.is_empty());
}

#[test]
fn a_goal_proved_unreachable_once_is_not_searched_for_again_from_the_same_region() {
    let mut p = pipeline(&["space.type=reeds-shepp"]);
    let planner = p.planner.as_mut().unwrap();
    let boxed = Pose2::new(13.5, 2.5, 0.0);
    let expansions =
        |planner: &dyn smug_core::PointToPointPlanner| planner.stats().counters["expansions"];
    let first = planner.plan(&Pose2::new(1.5, 1.5, 0.0), &boxed).unwrap();
    let after_first = expansions(planner.as_ref());
    assert!(after_first > 1000, "the first search exhausts the map");
    let again = planner.plan(&Pose2::new(2.5, 9.5, 0.0), &boxed).unwrap();
    let after_again = expansions(planner.as_ref());
    let proved = PlannerOutcome::NoPath(NoPathReason::Proved(Proof::Exhausted));
    assert_eq!((first, again), (proved.clone(), proved));
    assert_eq!(after_again, after_first, "the kept proof answers at once");
    // A goal the proof does not cover is still searched for.
    let open = planner
        .plan(&Pose2::new(2.5, 9.5, 0.0), &Pose2::new(7.7, 3.0, 0.0))
        .unwrap();
    assert!(open.exact_path().is_some());
}

#[test]
fn a_start_beside_a_proved_region_searches_only_outside_it() {
    // A forward-only car with its back to the first wall: the lattice poses it joins
    // there cannot be driven to from elsewhere, so the kept proof of the first search
    // (the goal in the closed box) does not cover it at once, but its search need not
    // enter what that search closed: the same answer from a few expansions.
    let boxed = Pose2::new(13.5, 2.5, 0.0);
    let beside_the_wall = Pose2::new(5.75, 3.0, 0.0);
    let expansions =
        |planner: &dyn smug_core::PointToPointPlanner| planner.stats().counters["expansions"];
    let proved = PlannerOutcome::NoPath(NoPathReason::Proved(Proof::Exhausted));

    let mut fresh = pipeline(&[]);
    let alone = fresh.planner.as_mut().unwrap();
    assert_eq!(alone.plan(&beside_the_wall, &boxed).unwrap(), proved);
    let searched_alone = expansions(alone.as_ref());

    let mut p = pipeline(&[]);
    let planner = p.planner.as_mut().unwrap();
    assert_eq!(
        planner.plan(&Pose2::new(1.5, 1.5, 0.0), &boxed).unwrap(),
        proved
    );
    let first = expansions(planner.as_ref());
    assert_eq!(planner.plan(&beside_the_wall, &boxed).unwrap(), proved);
    let bounded = expansions(planner.as_ref()) - first;
    assert!(
        bounded > 0 && 20 * bounded < searched_alone,
        "bounded by the proof: {bounded} expansions, alone: {searched_alone}"
    );
    // Its own proof now covers it at once, and a goal it can reach is still planned.
    assert_eq!(planner.plan(&beside_the_wall, &boxed).unwrap(), proved);
    assert_eq!(expansions(planner.as_ref()) - first, bounded);
    let open = planner
        .plan(&beside_the_wall, &Pose2::new(7.7, 3.0, 0.0))
        .unwrap();
    assert!(open.exact_path().is_some(), "{open:?}");
}

#[test]
fn a_start_hemmed_in_joins_the_lattice_farther_out() {
    // In a corridor a few centimetres wider than the disc, between two rows of lattice
    // points: no lattice pose near the start is valid, the first ones out of the
    // corridor are.
    let config = CONFIG.replace(
        "obstacles = [",
        "obstacles = [
    { min = [6.6, 5.9], max = [8.2, 6.08] },
    { min = [6.6, 6.74], max = [8.2, 6.9] },",
    );
    let settings = ["space.type=reeds-shepp", "world.params.resolution=0.02"];
    let loaded = LoadedConfig::from_text(
        &config,
        "hemmed.toml",
        Path::new("."),
        &settings.map(String::from),
    )
    .unwrap();
    let mut p = Pipeline::assemble(&loaded).unwrap();
    let start = Pose2::new(7.4, 6.40625, 0.0);
    let goal = Pose2::new(2.5, 9.5, 0.0);
    let checker = p.state_validity.as_ref().unwrap();
    assert!(checker.is_valid(&start));
    for dy in [-0.078125, 0.078125] {
        assert!(!checker.is_valid(&Pose2::new(7.4, 6.40625 + dy, 0.0)));
    }
    let outcome = p.planner.as_mut().unwrap().plan(&start, &goal).unwrap();
    let path = outcome
        .exact_path()
        .unwrap_or_else(|| panic!("{outcome:?}"));
    check_path(&p, &start, &goal, &path.states, path.cost);
}

#[test]
fn a_start_that_reaches_no_target_is_named_with_how_its_legs_ended() {
    // The start inside the closed box: every target is out of reach.
    let config = CONFIG.replace(
        "mission = { start = { x = 1.5, y = 1.5 } }",
        r#"mission = { start = { x = 13.5, y = 2.5, yaw = 0.0 }, targets = [
    { id = "a", position = { x = 2.5, y = 9.5 }, pois = [{ x = 2.5, y = 9.5, yaw = 0.0 }] },
    { id = "b", position = { x = 8.0, y = 9.0 }, pois = [{ x = 8.0, y = 9.0, yaw = 0.0 }] },
] }"#,
    );
    let settings = ["space.type=reeds-shepp".to_string()];
    let loaded =
        LoadedConfig::from_text(&config, "enclosed.toml", Path::new("."), &settings).unwrap();
    let mut p = Pipeline::assemble(&loaded).unwrap();
    let options = p.config.plan;
    let message = smug_mission::plan_mission(&mut p, options)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("the start pose (13.500, 2.500, yaw 0.000) is boxed in"),
        "{message}"
    );
    assert!(message.contains("none of the 2 PoIs"), "{message}");
    assert!(message.contains("proved"), "{message}");
    // The early probe proved it: no search of the map.
    let expansions = p.planner.as_ref().unwrap().stats().counters["expansions"];
    assert!(expansions < 25_000, "{expansions} expansions");
}

/// The test world with a closed mission for a Dubins car from `start` to the targets
/// `a` and `b` in the open.
fn closed_dubins_mission(start: &str) -> Pipeline {
    let config = CONFIG.replace(
        "mission = { start = { x = 1.5, y = 1.5 } }",
        &format!(
            r#"mission = {{ start = {start}, targets = [
    {{ id = "a", position = {{ x = 2.5, y = 9.5 }}, pois = [{{ x = 2.5, y = 9.5, yaw = 0.0 }}] }},
    {{ id = "b", position = {{ x = 8.0, y = 9.0 }}, pois = [{{ x = 8.0, y = 9.0, yaw = 0.0 }}] }},
] }}"#
        ),
    );
    let loaded = LoadedConfig::from_text(&config, "closed.toml", Path::new("."), &[]).unwrap();
    Pipeline::assemble(&loaded).unwrap()
}

#[test]
fn an_end_pose_no_path_enters_is_named_not_a_target() {
    // Facing west 0.4 m from the east border: a forward-only car leaves at once, but
    // arriving with that heading needs a turn beyond the border.
    let mut p = closed_dubins_mission("{ x = 15.6, y = 6.0, yaw = 3.14159265 }");
    let options = p.config.plan;
    let err = smug_mission::plan_mission(&mut p, options).unwrap_err();
    let message = err.to_string();
    assert!(
        message.contains("no path enters the end pose (15.600, 6.000, yaw 3.142) (the start"),
        "{message}"
    );
    assert!(message.contains("none of the 2 PoIs"), "{message}");
    assert!(message.contains("proved"), "{message}");
    assert!(
        !message.contains("`a`") && !message.contains("`b`"),
        "{message}"
    );
    match err {
        smug_core::Error::Stage { source, .. } => {
            let cut = source.downcast_ref::<smug_mission::CutOff>().unwrap();
            assert_eq!(cut.side, smug_mission::Side::End);
        }
        other => panic!("{other}"),
    }
}

#[test]
fn a_proved_dead_end_is_never_a_pose_some_path_leaves_or_enters() {
    // Poses on a pseudo-random sequence; every proof found within a probe's budget is
    // checked by a search without a budget (which, once it has exhausted the map,
    // answers later queries from its kept proofs).
    let mut state = 11u64;
    let mut unit = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let open = [Pose2::new(2.5, 9.5, 0.0), Pose2::new(7.7, 3.0, 1.0)];
    let mut p = pipeline(&["space.type=dubins"]);
    let checker = p.state_validity.clone().unwrap();
    let planner = p.planner.as_mut().unwrap();
    let (mut left, mut entered) = (0, 0);
    let mut tried = 0;
    while tried < 60 {
        let pose = Pose2::new(
            0.3 + 15.4 * unit(),
            0.3 + 11.4 * unit(),
            (unit() - 0.5) * std::f64::consts::TAU,
        );
        if !checker.is_valid(&pose) {
            continue;
        }
        tried += 1;
        let out = planner.prove_unreachable_from(&pose, &open, 2_000).unwrap();
        let into = planner.prove_unenterable(&pose, &open, 2_000).unwrap();
        for (k, goal) in open.iter().enumerate() {
            if out[k].is_some() {
                left += 1;
                let outcome = planner.plan(&pose, goal).unwrap();
                assert!(outcome.exact_path().is_none(), "{pose:?} → {goal:?} left");
            }
            if into[k].is_some() {
                entered += 1;
                let outcome = planner.plan(goal, &pose).unwrap();
                assert!(
                    outcome.exact_path().is_none(),
                    "{goal:?} → {pose:?} entered"
                );
            }
        }
    }
    // Proofs that a pose cannot be entered are rarer within the probes' budget (the
    // searches come from the open poses); each one found is checked above.
    assert!(left > 0, "{left} left, {entered} entered");
}

proptest::proptest! {
    /// The lattice's sideways bound never exceeds the Reeds–Shepp distance (the
    /// shortest curve of bounded curvature with either gear), so shots queued at it are
    /// queued at or below their cost.
    #[test]
    fn the_sideways_bound_stays_below_the_reeds_shepp_distance(
        ax in -6.0f64..6.0, ay in -6.0f64..6.0, ayaw in -3.2f64..3.2,
        bx in -6.0f64..6.0, by in -6.0f64..6.0, byaw in -3.2f64..3.2,
        radius in 0.2f64..3.0,
    ) {
        use smug_core::StateSpace;
        let space = smug_spaces::reeds_shepp::ReedsSheppSpace::new(radius).unwrap();
        let (a, b) = (Pose2::new(ax, ay, ayaw), Pose2::new(bx, by, byaw));
        let bound = smug_planners::lattice::sideways_bound(
            radius,
            (&a, ayaw.sin_cos()),
            (&b, byaw.sin_cos()),
        );
        let length = space.distance(&a, &b);
        proptest::prop_assert!(bound <= length * (1.0 + 1e-9) + 1e-9, "{bound} > {length}");
    }
}

#[test]
fn the_sideways_bound_is_tight_for_a_quarter_turn() {
    // From (0, 0, 0) a quarter circle of radius 1 ends at (1, 1, π/2): 1 m beside the
    // start's heading line, π/2 m long; the bound is √2.
    let (a, b) = (
        Pose2::new(0.0, 0.0, 0.0),
        Pose2::new(1.0, 1.0, std::f64::consts::FRAC_PI_2),
    );
    let bound = smug_planners::lattice::sideways_bound(1.0, (&a, (0.0, 1.0)), (&b, (1.0, 0.0)));
    assert!((bound - 2f64.sqrt()).abs() < 1e-12, "{bound}");
    // Two metres beside, same heading: at least 2 + (π/2 − 1).
    let c = Pose2::new(0.0, 2.0, 0.0);
    let bound = smug_planners::lattice::sideways_bound(1.0, (&a, (0.0, 1.0)), (&c, (0.0, 1.0)));
    assert!((bound - (1.0 + std::f64::consts::FRAC_PI_2)).abs() < 1e-12);
}
