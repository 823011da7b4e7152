//! Every built-in objective on the lunar world: its contract (bound ≤ cost on random
//! motions and paths, consistency, additivity), IDP == DP on a fixed roadmap (including
//! the asymmetric `energy`), recorded path-length plans, the trade-offs the objectives
//! exist for, and errors naming the culprit.

use proptest::prelude::*;
use smug_core::testing::{check_objective, check_objective_path};
use smug_core::{
    LoadedConfig, Objective, Path, Pipeline, Plan, PlannerOutcome, PlannerStats, PoiSelector,
    PointToPointPlanner, Pose2, Result, SelectionProblem,
};
use smug_mission::{plan_mission, PathOracle};
use smug_selection::{DpSelector, IdpSelector};
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::sync::{Arc, OnceLock};

use smug_app as _;

const OBJECTIVES: [&str; 4] = ["path-length", "traversability", "energy", "time"];

fn config(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../configs")
        .join(name)
}

fn lunar(objective: &str, step: Option<f64>) -> Pipeline {
    lunar_in(objective, step, "se2")
}

fn lunar_in(objective: &str, step: Option<f64>, space: &str) -> Pipeline {
    let mut set = vec![
        format!("objective.type=\"{objective}\""),
        format!("space.type=\"{space}\""),
    ];
    set.extend(step.map(|s| format!("objective.params.step={s}")));
    let loaded = LoadedConfig::from_file(&config("lunar.toml"), &set).unwrap();
    Pipeline::assemble(&loaded).unwrap()
}

/// The lunar pipeline under each objective with its default parameters, built once.
fn pipelines() -> &'static Vec<(&'static str, Pipeline)> {
    static PIPELINES: OnceLock<Vec<(&'static str, Pipeline)>> = OnceLock::new();
    PIPELINES.get_or_init(|| OBJECTIVES.iter().map(|&o| (o, lunar(o, None))).collect())
}

/// The lunar pipeline under each objective on each curvature-limited space, default
/// parameters (names `objective/space`).
fn curved_pipelines() -> &'static Vec<(String, Pipeline)> {
    static PIPELINES: OnceLock<Vec<(String, Pipeline)>> = OnceLock::new();
    PIPELINES.get_or_init(|| {
        let mut all = Vec::new();
        for space in ["reeds-shepp", "dubins"] {
            for &o in &OBJECTIVES {
                all.push((format!("{o}/{space}"), lunar_in(o, None, space)));
            }
        }
        all
    })
}

/// Integration step of the additivity checks: a split motion samples the terrain at other
/// points, an error that shrinks with the step (at the default 0.2 m, up to ~17% on
/// motions through τ = 0 ground, where `time` is 25× slower).
const FINE_STEP: f64 = 0.01;

/// The lunar pipeline under each objective, terrain-integrating ones at [`FINE_STEP`].
fn fine_pipelines() -> &'static Vec<(&'static str, Pipeline)> {
    static PIPELINES: OnceLock<Vec<(&'static str, Pipeline)>> = OnceLock::new();
    PIPELINES.get_or_init(|| {
        OBJECTIVES
            .iter()
            .map(|&o| (o, lunar(o, (o != "path-length").then_some(FINE_STEP))))
            .collect()
    })
}

/// A pose in the lunar bounds from unit coordinates.
fn pose((u, v, yaw): (f64, f64, f64)) -> Pose2 {
    let bounds = pipelines()[0].1.world.as_ref().unwrap().bounds();
    let [x0, y0] = bounds.min;
    let [x1, y1] = bounds.max;
    Pose2::new(x0 + u * (x1 - x0), y0 + v * (y1 - y0), yaw)
}

fn unit_pose() -> impl Strategy<Value = (f64, f64, f64)> {
    (
        0.0..1.0f64,
        0.0..1.0f64,
        -std::f64::consts::PI..std::f64::consts::PI,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn every_objective_keeps_its_contract_on_random_motions(
        a in unit_pose(), b in unit_pose(), c in unit_pose(), t in 0.0..1.0f64,
    ) {
        for (name, p) in fine_pipelines() {
            let (a, b, c) = (pose(a), pose(b), pose(c));
            let split = if *name == "path-length" { 1e-9 } else { 0.02 };
            check_objective(p.objective.as_ref(), p.space.as_ref(), (&a, &b, &c), t, split)
                .map_err(|e| TestCaseError::fail(format!("{name}: {e}")))?;
        }
    }

    #[test]
    fn every_objective_bounds_curved_motions_from_below(
        a in unit_pose(), b in unit_pose(), c in unit_pose(), t in 0.0..1.0f64,
    ) {
        // The cost of a curve sums its arcs, never its chords (which would fall below
        // the shortest curve's length, the bound's length term): at the default step,
        // where a chord falls short of its arc by ~0.2%. Additivity is checked for
        // path length only (to 1e-6: a split at a tangency rounds as the solvers do,
        // see tools/ompl-peer/SPACES.md): where several shortest curves tie, the curve
        // to a point of the motion may be another one of the same length over other
        // ground.
        for (name, p) in curved_pipelines() {
            let (a, b, c) = (pose(a), pose(b), pose(c));
            let split = if name.starts_with("path-length") { 1e-6 } else { f64::INFINITY };
            check_objective(p.objective.as_ref(), p.space.as_ref(), (&a, &b, &c), t, split)
                .map_err(|e| TestCaseError::fail(format!("{name}: {e}")))?;
        }
    }

    #[test]
    fn bounds_never_exceed_random_paths(states in prop::collection::vec(unit_pose(), 2..8)) {
        let states: Vec<Pose2> = states.into_iter().map(pose).collect();
        for (name, p) in pipelines() {
            check_objective_path(p.objective.as_ref(), &states)
                .map_err(|e| TestCaseError::fail(format!("{name}: {e}")))?;
        }
    }
}

/// Exact shortest paths on a fixed lattice over the lunar bounds (2 m spacing,
/// 8-connected), edges costed by the objective in each direction; a query snaps its
/// ends to the nearest lattice vertices.
struct LatticePlanner {
    objective: Arc<dyn Objective>,
    origin: [f64; 2],
    side: [usize; 2],
    /// `costs[v][k]`: cost from `v` to its `k`-th neighbour (`INFINITY`: none).
    costs: Vec<[f64; 8]>,
}

const SPACING: f64 = 2.0;
const STEPS: [(i64, i64); 8] = [
    (1, 0),
    (1, 1),
    (0, 1),
    (-1, 1),
    (-1, 0),
    (-1, -1),
    (0, -1),
    (1, -1),
];

impl LatticePlanner {
    fn new(pipeline: &Pipeline) -> Self {
        let bounds = pipeline.world.as_ref().unwrap().bounds();
        let side = [
            ((bounds.max[0] - bounds.min[0]) / SPACING) as usize,
            ((bounds.max[1] - bounds.min[1]) / SPACING) as usize,
        ];
        let mut planner = Self {
            objective: pipeline.objective.clone(),
            origin: [bounds.min[0] + 1.0, bounds.min[1] + 1.0],
            side,
            costs: Vec::new(),
        };
        planner.costs = (0..side[0] * side[1])
            .map(|v| {
                let mut row = [f64::INFINITY; 8];
                for (k, step) in STEPS.iter().enumerate() {
                    if let Some(w) = planner.neighbour(v, *step) {
                        row[k] = planner
                            .objective
                            .motion_cost(&planner.vertex(v), &planner.vertex(w));
                    }
                }
                row
            })
            .collect();
        planner
    }

    fn vertex(&self, v: usize) -> Pose2 {
        let (i, j) = (v / self.side[1], v % self.side[1]);
        Pose2::new(
            self.origin[0] + i as f64 * SPACING,
            self.origin[1] + j as f64 * SPACING,
            0.0,
        )
    }

    fn neighbour(&self, v: usize, (di, dj): (i64, i64)) -> Option<usize> {
        let (i, j) = (
            (v / self.side[1]) as i64 + di,
            (v % self.side[1]) as i64 + dj,
        );
        let inside = (0..self.side[0] as i64).contains(&i) && (0..self.side[1] as i64).contains(&j);
        inside.then(|| i as usize * self.side[1] + j as usize)
    }

    fn snap(&self, p: &Pose2) -> usize {
        let i = ((p.x - self.origin[0]) / SPACING)
            .round()
            .clamp(0.0, self.side[0] as f64 - 1.0);
        let j = ((p.y - self.origin[1]) / SPACING)
            .round()
            .clamp(0.0, self.side[1] as f64 - 1.0);
        i as usize * self.side[1] + j as usize
    }

    fn dijkstra(&self, from: usize, to: usize) -> Vec<usize> {
        let mut dist = vec![f64::INFINITY; self.costs.len()];
        let mut parent = vec![usize::MAX; self.costs.len()];
        let mut heap = BinaryHeap::from([(Reverse(0u64), from)]);
        dist[from] = 0.0;
        while let Some((Reverse(d), v)) = heap.pop() {
            if f64::from_bits(d) > dist[v] {
                continue;
            }
            for (k, step) in STEPS.iter().enumerate() {
                if let Some(w) = self.neighbour(v, *step) {
                    let candidate = dist[v] + self.costs[v][k];
                    if candidate < dist[w] {
                        (dist[w], parent[w]) = (candidate, v);
                        heap.push((Reverse(candidate.to_bits()), w));
                    }
                }
            }
        }
        let mut path = vec![to];
        while *path.last().unwrap() != from {
            path.push(parent[*path.last().unwrap()]);
        }
        path.reverse();
        path
    }
}

impl PointToPointPlanner for LatticePlanner {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        let vertices = self.dijkstra(self.snap(start), self.snap(goal));
        let states: Vec<Pose2> = std::iter::once(*start)
            .chain(vertices.iter().map(|&v| self.vertex(v)))
            .chain(std::iter::once(*goal))
            .collect();
        Ok(PlannerOutcome::Exact(Path::new(
            states,
            self.objective.as_ref(),
        )))
    }

    fn stats(&self) -> PlannerStats {
        PlannerStats::default()
    }
}

/// The lunar mission's first `targets` targets, in mission order, on a fresh oracle.
fn selection_setup(pipeline: &Pipeline, targets: usize) -> (PathOracle, SelectionProblem) {
    let mission = pipeline.mission.as_ref().unwrap();
    let planner = LatticePlanner::new(pipeline);
    let mut oracle = PathOracle::new(pipeline.objective.clone(), Box::new(planner));
    let start = oracle.add_pose(mission.start);
    let groups = mission.targets[..targets]
        .iter()
        .map(|t| t.pois.iter().map(|p| oracle.add_pose(*p)).collect())
        .collect();
    (
        oracle,
        SelectionProblem {
            start,
            groups,
            end: start,
        },
    )
}

#[test]
fn idp_equals_dp_on_a_fixed_roadmap_under_every_objective() {
    for (name, pipeline) in pipelines() {
        let (mut oracle, problem) = selection_setup(pipeline, 5);
        assert_eq!(oracle.is_symmetric(), *name != "energy", "{name}");
        let dp = DpSelector::default().select(&mut oracle, &problem).unwrap();
        let dp_paths = oracle.stats().paths_planned;
        let (mut oracle, problem) = selection_setup(pipeline, 5);
        let idp = IdpSelector::default()
            .select(&mut oracle, &problem)
            .unwrap();
        let idp_paths = oracle.stats().paths_planned;
        assert!(
            (idp.cost - dp.cost).abs() <= 1e-9 * dp.cost.max(1.0),
            "{name}: IDP {} vs DP {}",
            idp.cost,
            dp.cost
        );
        assert!(
            idp_paths <= dp_paths,
            "{name}: IDP planned {idp_paths} > DP {dp_paths}"
        );
    }
}

#[test]
fn idp_equals_dp_on_a_fixed_roadmap_under_every_motion_model() {
    for space in ["se2", "reeds-shepp", "dubins"] {
        let set = [format!("space.type=\"{space}\"")];
        let loaded = LoadedConfig::from_file(&config("lunar.toml"), &set).unwrap();
        let pipeline = Pipeline::assemble(&loaded).unwrap();
        assert_eq!(
            pipeline.objective.is_symmetric(),
            space != "dubins",
            "{space}"
        );
        let (mut oracle, problem) = selection_setup(&pipeline, 4);
        let dp = DpSelector::default().select(&mut oracle, &problem).unwrap();
        let (mut oracle, problem) = selection_setup(&pipeline, 4);
        let idp = IdpSelector::default()
            .select(&mut oracle, &problem)
            .unwrap();
        assert!(
            (idp.cost - dp.cost).abs() <= 1e-9 * dp.cost,
            "{space}: IDP {} vs DP {}",
            idp.cost,
            dp.cost
        );
    }
}

fn plan(config_name: &str, set: &[&str]) -> Plan {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let loaded = LoadedConfig::from_file(&config(config_name), &set).unwrap();
    let mut pipeline = Pipeline::assemble(&loaded).unwrap();
    plan_mission(&mut pipeline, loaded.config.plan).unwrap()
}

#[test]
fn path_length_plans_are_the_recorded_ones() {
    // Costs of the shipped configs before objectives were separated from the space
    // (seed 1, main at b754893): `path-length` must keep them to the last bit. The
    // planner's endpoint expansion came later and changes `indoor.toml` (one query
    // needs more than `expand_after` samples; 73.57 → 70.54 with it), so it is off here,
    // as are the bridge samples such queries draw (later still).
    for (name, cost) in [
        ("lunar.toml", 96.81261847501415f64),
        ("indoor.toml", 73.57378109544727),
        ("lunar-dp.toml", 96.79606989851067),
        ("lunar-irba.toml", 97.41166442373049),
        ("lunar-full-collision.toml", 97.41288009955495),
        ("flat-demo.toml", 41.56167971049054),
    ] {
        // Recorded with the full sequencing matrix and one query per path, then the
        // defaults (the paper's configs still pin both; flat-demo now defaults to
        // "lazy" and to one search per source).
        let full = "plan.sequencing_costs=\"full\"";
        let per_pair = "planner.params.one_to_many=false";
        // Legs kept as first planned: refining them came later (the paper's configs pin it off).
        let kept = "plan.refine_legs=false";
        let plan = plan(
            name,
            &[
                "planner.params.expand_share=0",
                "planner.params.bridge_sigma=0",
                full,
                per_pair,
                kept,
            ],
        );
        assert_eq!(
            plan.cost.to_bits(),
            cost.to_bits(),
            "{name}: {} vs {cost}",
            plan.cost
        );
        assert_eq!(plan.metrics.objective, "path-length");
        let evaluated = plan.metrics.costs["path-length"];
        assert!(
            (evaluated - cost).abs() <= 1e-9 * cost,
            "{name}: {evaluated}"
        );
    }
}

#[test]
fn each_objective_buys_what_it_is_for_on_the_lunar_mission() {
    let lazy = "plan.sequencing_costs=\"lazy\"";
    let with = |o: &str| plan("lunar.toml", &[&format!("objective.type=\"{o}\""), lazy]);
    let (length, risk, time) = (with("path-length"), with("traversability"), with("time"));
    let mean = |p: &Plan| p.metrics.traversability_mean.unwrap();
    let risky = |p: &Plan| p.metrics.risky_length_m.unwrap();
    assert!(
        mean(&risk) > mean(&length),
        "{} vs {}",
        mean(&risk),
        mean(&length)
    );
    assert!(
        risky(&risk) < risky(&length),
        "{} vs {}",
        risky(&risk),
        risky(&length)
    );
    let cost = |p: &Plan, o: &str| p.metrics.costs[o];
    assert!(cost(&time, "time") < cost(&length, "time"));
    assert!(cost(&risk, "traversability") < cost(&length, "traversability"));
    for p in [&length, &risk, &time] {
        let evaluated = p.metrics.costs[&p.metrics.objective];
        assert!(
            (evaluated - p.cost).abs() <= 1e-9 * p.cost,
            "{evaluated} vs {}",
            p.cost
        );
    }
}

fn error(set: &[&str]) -> String {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let loaded = LoadedConfig::from_file(&config("lunar.toml"), &set).unwrap();
    match Pipeline::assemble(&loaded) {
        Ok(_) => panic!("{set:?} assembled"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_objectives_are_errors_naming_the_culprit() {
    let unknown = error(&["objective.type=\"risk\""]);
    for name in OBJECTIVES {
        assert!(unknown.contains(name), "{unknown}");
    }
    for (set, key) in [
        (
            "objective.params.translation_weight=-1.0",
            "translation_weight",
        ),
        ("objective.params.rotation_weight=nan", "rotation_weight"),
    ] {
        let message = error(&["objective.type=\"path-length\"", set]);
        assert!(message.contains(key), "{set}: {message}");
    }
    for (objective, key, value) in [
        ("energy", "mass", "-50.0"),
        ("energy", "friction", "inf"),
        ("time", "max_speed", "0.0"),
        ("time", "min_speed_fraction", "1.5"),
        ("traversability", "risk_weight", "-1.0"),
        ("traversability", "step", "nan"),
    ] {
        let set = [
            format!("objective.type=\"{objective}\""),
            format!("objective.params.{key}={value}"),
        ];
        let refs: Vec<&str> = set.iter().map(String::as_str).collect();
        let message = error(&refs);
        assert!(
            message.contains(key),
            "{objective}.{key}={value}: {message}"
        );
    }
    // The lunar world without its traversability estimator has no traversability layer.
    let loaded =
        LoadedConfig::from_file(&config("lunar.toml"), &["objective.type=\"time\"".into()])
            .unwrap();
    let mut config = loaded.config.clone();
    config.traversability = None;
    config.validity = None;
    let stripped = LoadedConfig { config, ..loaded };
    let message = Pipeline::assemble(&stripped).err().unwrap().to_string();
    assert!(
        message.contains("`time`") && message.contains("traversability layer"),
        "{message}"
    );
}

#[test]
fn objectives_are_symmetric_only_on_symmetric_spaces() {
    for space in ["se2", "reeds-shepp", "dubins"] {
        for objective in OBJECTIVES {
            let set = [
                format!("space.type=\"{space}\""),
                format!("objective.type=\"{objective}\""),
            ];
            let loaded = LoadedConfig::from_file(&config("lunar.toml"), &set).unwrap();
            let pipeline = Pipeline::assemble(&loaded).unwrap();
            let expected = space != "dubins" && objective != "energy";
            assert_eq!(
                pipeline.objective.is_symmetric(),
                expected,
                "{objective} on {space}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Every state through which a path could beat `best` (by the objective's bound,
    /// checked on a 0.5 m lattice of the whole map with random headings) lies in the
    /// informed ellipse the samplers draw from.
    #[test]
    fn informed_sets_keep_every_state_that_could_improve_the_path(
        s in unit_pose(), g in unit_pose(), slack in 1.0..2.0f64, yaw in -3.0..3.0f64,
    ) {
        let (s, g) = (pose(s), pose(g));
        for (name, p) in pipelines() {
            let objective = p.objective.as_ref();
            let best = objective.cost_bound(&s, &g) * slack + 1e-3;
            let set = smug_core::InformedSet { start: s, goal: g, best_cost: best };
            let (w_t, w_r) = objective.bound_weights();
            let ellipse = smug_samplers::informed::InformedEllipse::new(&set, w_t, w_r);
            let bounds = p.world.as_ref().unwrap().bounds();
            for i in 0..=((bounds.max[0] - bounds.min[0]) / 0.5) as usize {
                for j in 0..=((bounds.max[1] - bounds.min[1]) / 0.5) as usize {
                    let x = Pose2::new(bounds.min[0] + 0.5 * i as f64, bounds.min[1] + 0.5 * j as f64, yaw);
                    if objective.cost_bound(&s, &x) + objective.cost_bound(&x, &g) < best {
                        prop_assert!(
                            ellipse.is_some_and(|e| e.contains(x.x, x.y)),
                            "{name}: ({}, {}) could improve the path but lies outside the informed set",
                            x.x, x.y
                        );
                    }
                }
            }
        }
    }
}
