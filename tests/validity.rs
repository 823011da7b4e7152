//! The volumetric checker against the exact reference on the procedural worlds.

use proptest::prelude::*;
use rand::SeedableRng;
use smug_core::rng::StageRng;
use smug_core::{Mission, Pose2, RobotConfig, Scenario, StateValidityChecker, World};
use smug_validity::volumetric::VolumetricParams;
use smug_validity::{ExactChecker, RobotBox, Volumes, VolumetricChecker};
use smug_worlds::indoor::{indoor_world, IndoorParams};
use smug_worlds::lunar::{lunar_world, LunarParams};
use std::sync::{Arc, OnceLock};

struct Checkers {
    world: Arc<World>,
    mission: Mission,
    volumetric: VolumetricChecker,
    exact: ExactChecker,
}

fn checkers_for(scenario: Scenario) -> Checkers {
    let world = Arc::new(scenario.world);
    let robot = RobotBox::from_robot(&RobotConfig::default());
    let volumes = Arc::new(Volumes::from_world(&world, robot.headroom()).unwrap());
    Checkers {
        volumetric: VolumetricChecker::new(
            world.clone(),
            volumes.clone(),
            robot,
            VolumetricParams::default(),
        )
        .unwrap(),
        exact: ExactChecker::new(world.clone(), volumes, robot),
        world,
        mission: scenario.mission,
    }
}

fn lunar() -> &'static Checkers {
    static LUNAR: OnceLock<Checkers> = OnceLock::new();
    LUNAR.get_or_init(|| {
        checkers_for(
            lunar_world(&LunarParams::default(), &mut StageRng::seed_from_u64(11)).unwrap(),
        )
    })
}

fn indoor() -> &'static Checkers {
    static INDOOR: OnceLock<Checkers> = OnceLock::new();
    INDOOR.get_or_init(|| {
        checkers_for(
            indoor_world(&IndoorParams::default(), &mut StageRng::seed_from_u64(11)).unwrap(),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]
    #[test]
    fn volumetric_never_calls_free_what_exact_finds_in_collision(
        fx in 0.0f64..1.0, fy in 0.0f64..1.0, yaw in -std::f64::consts::PI..std::f64::consts::PI, in_lunar in any::<bool>(),
    ) {
        let c = if in_lunar { lunar() } else { indoor() };
        let b = c.world.bounds();
        let state = Pose2::new(b.min[0] + fx * (b.max[0] - b.min[0]), b.min[1] + fy * (b.max[1] - b.min[1]), yaw);
        if c.volumetric.is_valid(&state) {
            prop_assert!(c.exact.is_valid(&state), "volumetric calls {state:?} free, exact finds a collision");
        }
    }
}

/// Classifies `n` seeded random states by both checkers:
/// `[both valid, only exact valid, both invalid, only volumetric valid]`.
fn agreement(c: &Checkers, n: usize, seed: u64) -> [usize; 4] {
    use rand::Rng;
    let mut rng = StageRng::seed_from_u64(seed);
    let b = c.world.bounds();
    let mut counts = [0; 4];
    for _ in 0..n {
        let state = Pose2::new(
            rng.random_range(b.min[0]..b.max[0]),
            rng.random_range(b.min[1]..b.max[1]),
            rng.random_range(-std::f64::consts::PI..std::f64::consts::PI),
        );
        let k = match (c.volumetric.is_valid(&state), c.exact.is_valid(&state)) {
            (true, true) => 0,
            (false, true) => 1,
            (false, false) => 2,
            (true, false) => 3,
        };
        counts[k] += 1;
    }
    counts
}

#[test]
fn volumetric_is_safe_and_not_much_more_conservative_than_exact() {
    for (name, c) in [("lunar", lunar()), ("indoor", indoor())] {
        check_agreement(name, c);
    }
}

fn check_agreement(name: &str, c: &Checkers) {
    let [both_valid, only_exact, both_invalid, only_volumetric] = agreement(c, 4000, 5);
    println!("{name}: both valid {both_valid}, only exact {only_exact}, both invalid {both_invalid}, unsafe {only_volumetric}");
    assert_eq!(
        only_volumetric, 0,
        "the volumetric checker called colliding states free"
    );
    assert!(
        both_invalid >= 40,
        "too few colliding states sampled ({both_invalid}): the test would be vacuous"
    );
    assert!(
        only_exact * 10 <= both_valid + only_exact,
        "volumetric rejects {only_exact} of {} free states",
        both_valid + only_exact
    );
}

#[test]
fn the_start_and_most_pois_of_both_worlds_are_valid() {
    for c in [lunar(), indoor()] {
        check_mission_validity(c);
    }
}

fn check_mission_validity(c: &Checkers) {
    let mission = &c.mission;
    let valid_pois = mission
        .targets
        .iter()
        .flat_map(|t| &t.pois)
        .filter(|p| c.volumetric.is_valid(p))
        .count();
    assert!(
        c.volumetric.is_valid(&mission.start),
        "the start must be valid"
    );
    assert!(
        valid_pois * 10 >= mission.poi_count() * 6,
        "only {valid_pois} of {} PoIs are valid",
        mission.poi_count()
    );
}

/// Builds the lunar pipeline's world with a validity checker of `kind` and `params`.
fn lunar_checker(kind: &str, params: &str) -> Arc<dyn StateValidityChecker> {
    let text = format!(
        "seed = 3\n[world]\ntype = \"lunar\"\n[traversability]\ntype = \"geometric\"\n[validity]\ntype = \"{kind}\"\nparams = {{ {params} }}\n"
    );
    let loaded =
        smug_core::LoadedConfig::from_text(&text, "bench.toml", std::path::Path::new("."), &[])
            .unwrap();
    smug_core::Pipeline::assemble(&loaded)
        .unwrap()
        .state_validity
        .unwrap()
}

#[test]
fn hierarchical_checking_needs_at_least_30_percent_fewer_distance_queries() {
    use rand::Rng;
    let volumetric = lunar_checker("volumetric", "");
    let hierarchical = lunar_checker("hierarchical", "t_low = 0.3, t_high = 0.8");
    let fastest = lunar_checker("hierarchical", "t_low = 0.3, t_high = 0.3");
    let mut rng = StageRng::seed_from_u64(9);
    for _ in 0..3000 {
        let s = Pose2::new(
            rng.random_range(0.0..30.0),
            rng.random_range(0.0..29.0),
            rng.random_range(-3.1..3.1),
        );
        volumetric.is_valid(&s);
        hierarchical.is_valid(&s);
        fastest.is_valid(&s);
    }
    let queries = |c: &Arc<dyn StateValidityChecker>| c.counters()["esdf_queries"] as f64;
    println!(
        "ESDF queries: volumetric {}, 0.3/0.8 {}, 0.3/0.3 {}",
        queries(&volumetric),
        queries(&hierarchical),
        queries(&fastest)
    );
    assert!(queries(&hierarchical) <= 0.7 * queries(&volumetric));
    assert!(queries(&fastest) <= queries(&hierarchical));
    assert!(hierarchical.counters()["traversability_decided"] > 0);
}
