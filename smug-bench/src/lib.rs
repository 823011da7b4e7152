//! SMUG benchmarks: the harnesses behind `smug bench …` (one module per harness, its
//! report writer beside it) and the TSPLIB / GTSP-LIB suites they read.
//!
//! Every harness takes its clap arguments (the CLI's `smug bench` dispatcher parses them)
//! and prints its Markdown report, writing it and the raw numbers where asked
//! ([`output`]). Imports run one way: a harness calls its report module, never back.

#![warn(missing_docs)]

pub mod error;
pub mod gtsp;
pub mod lattice;
pub mod modes;
pub mod mtsp;
pub mod objectives;
pub mod output;
pub mod p2p;
pub mod paper;
pub mod replan;
pub mod robots;
pub mod solvers;
pub mod team;
pub mod tsp;
pub mod validity;

pub use error::{BenchError, Result};
