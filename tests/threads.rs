//! The number of threads never changes a plan: the stages that run side by side
//! (traversability and terrain grids, cost-matrix rows and DP layers of one-to-many
//! searches, post-processing, the lattice's rows, probes and DP layers run ahead,
//! the GTSP search's matrix copy,
//! cluster bounds and neighbours) give the plan one thread gives, bit for bit.

use smug_core::{LoadedConfig, Pipeline, Plan, PlanOptions};
use smug_mission::plan_mission;
use std::path::Path;

use smug_app as _;

/// A shipped config with overrides, small enough for a test.
struct Case {
    config: &'static str,
    set: &'static [&'static str],
}

const CASES: [Case; 6] = [
    // LazyPRM*'s one-to-many rows: the full matrix and the IDP layers.
    Case {
        config: "lunar.toml",
        set: &[
            "world.params.targets=12",
            "world.params.pois_per_target=4",
            "planner.params.one_to_many=true",
            "plan.sequencing_costs=\"full\"",
        ],
    },
    // The joint mode with lazy costs and refined legs.
    Case {
        config: "lunar.toml",
        set: &[
            "world.params.targets=8",
            "world.params.pois_per_target=4",
            "planner.params.one_to_many=true",
            "plan.mode=\"joint\"",
            "plan.refine_legs=true",
        ],
    },
    // The joint mode on the GTSP large-neighbourhood search (its matrix copy and
    // cluster bounds are filled side by side, and on 256 nodes or more each
    // iteration's neighbours are built side by side).
    Case {
        config: "lunar.toml",
        set: &[
            "world.params.targets=56",
            "world.params.pois_per_target=5",
            "planner.params.one_to_many=true",
            "plan.mode=\"joint\"",
            "sequencer.type=\"gtsp-lns\"",
            "sequencer.params.max_iterations=150",
        ],
    },
    // The default lazy order, settled.
    Case {
        config: "indoor.toml",
        set: &["plan.sequencing_costs=\"lazy\"", "plan.refine_legs=true"],
    },
    // A car on the lattice.
    Case {
        config: "flat-dubins.toml",
        set: &[],
    },
    // The reversing rover on lunar: its PoIs' dead-end probes side by side, the
    // matrix's order rows, and each DP layer's search with the next one run ahead.
    Case {
        config: "lunar-rover.toml",
        set: &["world.params.targets=7"],
    },
];

/// The plan of `case`, assembled and planned on a pool of `threads` threads.
fn plan_on(case: &Case, threads: usize) -> Plan {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../configs")
        .join(case.config);
    let set: Vec<String> = case.set.iter().map(|s| s.to_string()).collect();
    let config = LoadedConfig::from_file(&path, &set).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut pipeline = Pipeline::assemble(&config).unwrap();
        plan_mission(&mut pipeline, PlanOptions::default()).unwrap()
    })
}

/// What a plan decides, as bits: order, PoIs, waypoints, cost.
fn decided(plan: &Plan) -> (Vec<String>, Vec<usize>, Vec<[u64; 4]>, u64) {
    let waypoints = plan
        .waypoints
        .iter()
        .map(|w| [w.x.to_bits(), w.y.to_bits(), w.z.to_bits(), w.yaw.to_bits()])
        .collect();
    let pois = plan.pois.iter().map(|p| p.index).collect();
    (plan.sequence.clone(), pois, waypoints, plan.cost.to_bits())
}

#[test]
fn one_thread_and_two_give_the_same_plan_bit_for_bit() {
    for case in &CASES {
        let one = plan_on(case, 1);
        let two = plan_on(case, 2);
        assert!(!one.waypoints.is_empty(), "{} {:?}", case.config, case.set);
        assert_eq!(
            decided(&one),
            decided(&two),
            "{} {:?}: 1 thread vs 2",
            case.config,
            case.set
        );
        assert_eq!(
            one.stats.paths_planned, two.stats.paths_planned,
            "{} {:?}",
            case.config, case.set
        );
    }
}
