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
//! Plugins of the `team_sequencer` stage ([`team`]): `team-exact`, `team-lns`, `team-auto`.
//!
//! The GTSP solvers answer [`Sequencer::solve_clusters`](smug_core::Sequencer::solve_clusters) (one node per cluster) and
//! plain TSPs as singleton clusters; [`read_gtsplib`] reads GTSP-LIB files.
//!
//! All of them accept asymmetric matrices, `INFINITY` legs (a tour still comes back,
//! with its true, infinite cost, when no finite one is found) and open paths
//! (`TourKind::OpenTo(end)`).

#![warn(missing_docs)]

pub mod auto;
pub mod brute_force;
mod costs;
pub mod error;
pub mod gtsp_exact;
pub mod gtsp_lns;
pub mod gtsplib;
pub mod held_karp;
pub mod local_search;
pub mod team;
pub mod tsplib;

pub use auto::{Auto, AutoParams};
pub use brute_force::{BruteForce, BRUTE_FORCE_MAX_NODES};
pub use error::{ParamError, SequencingError};
pub use gtsp_exact::{GtspExact, GtspExactParams};
pub use gtsp_lns::{GtspLns, GtspLnsParams};
pub use gtsplib::{read_gtsplib, GtspInstance};
pub use held_karp::{HeldKarp, HeldKarpParams};
pub use local_search::{construct_tour, Construction, LocalSearch, LocalSearchParams, SearchStats};
pub use tsplib::{read_tour, read_tsplib, TsplibError, TsplibInstance};
