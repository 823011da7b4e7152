//! SMUG sequencing: TSP solvers (Held-Karp, local search) and a TSPLIB reader.
//!
//! Plugins of the `sequencer` stage:
//! - `held-karp`: exact dynamic programming (small instances, n ≤ ~20);
//! - `local-search`: iterated LK-style / Or-opt local search (any size);
//! - `auto`: Held-Karp up to a threshold, local search above;
//! - `brute-force`: every order (tests only, n ≤ 9);
//! - `gtsp-exact`: exact DP over clusters for the generalized TSP (few clusters);
//! - `gtsp-lns`: GLNS-style large-neighbourhood search for the generalized TSP.
//!
//! The GTSP solvers answer [`Sequencer::solve_clusters`] (one node per cluster) and
//! plain TSPs as singleton clusters; [`read_gtsplib`] reads GTSP-LIB files.
//!
//! All of them accept asymmetric matrices, `INFINITY` legs (a tour still comes back,
//! with its true, infinite cost, when no finite one is found) and open paths
//! (`TourKind::OpenTo(end)`).

#![warn(missing_docs)]

pub mod auto;
pub mod bench;
pub mod bench_gtsp;
pub mod brute_force;
mod costs;
pub mod error;
pub mod gtsp_exact;
pub mod gtsp_lns;
pub mod gtsplib;
pub mod held_karp;
pub mod local_search;
pub mod tsplib;

pub use auto::{Auto, AutoParams};
pub use brute_force::{BruteForce, BRUTE_FORCE_MAX_NODES};
pub use error::SequencingError;
pub use gtsp_exact::{GtspExact, GtspExactParams};
pub use gtsp_lns::{GtspLns, GtspLnsParams};
pub use gtsplib::{read_gtsplib, GtspInstance};
pub use held_karp::{HeldKarp, HeldKarpParams};
pub use local_search::{construct_tour, Construction, LocalSearch, LocalSearchParams, SearchStats};
pub use tsplib::{read_tour, read_tsplib, TsplibError, TsplibInstance};

use smug_core::Sequencer;

/// The GTSP solvers, in the order `smug gtsp --help` lists them.
pub const GTSP_SOLVER_NAMES: [&str; 2] = ["gtsp-lns", "gtsp-exact"];

/// The solvers [`solver_by_name`] knows, in the order `smug tsp --help` lists them.
pub const SOLVER_NAMES: [&str; 4] = ["auto", "held-karp", "local-search", "brute-force"];

/// Budget and seed for [`solver_by_name`]; the exact solvers ignore them.
#[derive(Clone, Debug, PartialEq)]
pub struct SolverOptions {
    /// Local search wall-time budget in seconds (0 = none).
    pub time_limit_s: f64,
    /// Local search budget of perturbation rounds (`None`: no limit).
    pub max_iterations: Option<u64>,
    /// Seed (the solver's generator is derived from it as a pipeline would).
    pub seed: u64,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            time_limit_s: 1.0,
            max_iterations: None,
            seed: 0,
        }
    }
}

/// A solver from its plugin name (one of [`SOLVER_NAMES`] or [`GTSP_SOLVER_NAMES`]) with
/// default parameters apart from the budget and seed.
pub fn solver_by_name(
    name: &str,
    options: &SolverOptions,
) -> smug_core::Result<Box<dyn Sequencer>> {
    let rng = smug_core::rng::stage_rng(options.seed, "sequencer");
    let local = LocalSearchParams {
        time_limit_s: options.time_limit_s,
        max_iterations: options.max_iterations.unwrap_or(0),
        ..LocalSearchParams::default()
    };
    Ok(match name {
        "auto" => {
            let params = AutoParams {
                time_limit_s: local.time_limit_s,
                max_iterations: local.max_iterations,
                ..AutoParams::default()
            };
            Box::new(Auto::new(params, rng)?)
        }
        "held-karp" => Box::new(HeldKarp::new(HeldKarpParams::default())?),
        "local-search" => Box::new(LocalSearch::new(local, rng)?),
        "brute-force" => Box::new(BruteForce),
        "gtsp-lns" => {
            let params = GtspLnsParams {
                time_limit_s: options.time_limit_s,
                max_iterations: options.max_iterations.unwrap_or(0),
                ..GtspLnsParams::default()
            };
            Box::new(GtspLns::new(params, rng)?)
        }
        "gtsp-exact" => Box::new(GtspExact::new(GtspExactParams::default())?),
        other => {
            return Err(smug_core::Error::invalid_param(
                "sequencer",
                format!(
                    "unknown solver `{other}`; known: {}, {}",
                    SOLVER_NAMES.join(", "),
                    GTSP_SOLVER_NAMES.join(", ")
                ),
            ))
        }
    })
}
