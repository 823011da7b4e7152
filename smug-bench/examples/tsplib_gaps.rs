//! Local search on the TSPLIB suite with its construction and first-descent gaps (a
//! tuning aid; `smug bench tsp` is the benchmark proper):
//! `SEED=1 cargo run --release -p smug-bench --example tsplib_gaps -- [--data DIR]
//! [budget_s] [names…]`. The suite is `--data DIR`, else `$SMUG_DATA/tsplib`.

use smug_bench::tsp::suite::{gap_percent, load_suite, suite_dir, DATA_ENV, SUITE_DESCRIPTION};
use smug_core::TourKind;
use smug_sequencing::{read_tsplib, LocalSearch, LocalSearchParams};
use std::path::PathBuf;
use std::time::Instant;

/// Removes `--data DIR` from `args` and returns `DIR`.
fn take_data_option(args: &mut Vec<String>) -> Result<Option<PathBuf>, String> {
    let Some(at) = args.iter().position(|a| a == "--data") else {
        return Ok(None);
    };
    if at + 1 == args.len() {
        return Err("--data needs a folder".into());
    }
    let dir = args.remove(at + 1);
    args.remove(at);
    Ok(Some(PathBuf::from(dir)))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let given = take_data_option(&mut args)?;
    let dir = suite_dir(given.as_deref(), std::env::var_os(DATA_ENV).as_deref())
        .ok_or_else(|| format!("pass --data DIR or set {DATA_ENV}: {SUITE_DESCRIPTION}"))?;
    let mut args = args.into_iter();
    let budget: f64 = args.next().map(|a| a.parse()).transpose()?.unwrap_or(1.0);
    let only: Vec<String> = args.collect();
    let (mut sym, mut asym) = (Vec::new(), Vec::new());
    for instance in load_suite(&dir)? {
        if !only.is_empty() && !only.contains(&instance.name) {
            continue;
        }
        let tsp = read_tsplib(&instance.path)?;
        let solver = LocalSearch::with_seed(
            LocalSearchParams {
                time_limit_s: budget,
                ..LocalSearchParams::default()
            },
            std::env::var("SEED")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(1),
        )?;
        let started = Instant::now();
        let (tour, stats) = solver.solve_with_stats(&tsp.costs, TourKind::Closed)?;
        let gap = gap_percent(tour.cost, instance.optimum);
        println!(
            "{:10} n={:5} opt={:8} cost={:8} gap={:6.2}% constr={:6.2}% first={:6.2}% iters={:8} t={:.2}s",
            instance.name,
            tsp.costs.len(),
            instance.optimum,
            tour.cost,
            gap,
            gap_percent(stats.construction_cost, instance.optimum),
            gap_percent(stats.first_optimum_cost, instance.optimum),
            stats.iterations,
            started.elapsed().as_secs_f64()
        );
        assert!(tour.is_valid_for(tsp.costs.len(), TourKind::Closed));
        if tsp.costs.is_symmetric(0.0) {
            sym.push(gap)
        } else {
            asym.push(gap)
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    println!("mean sym {:.3}%  asym {:.3}%", mean(&sym), mean(&asym));
    Ok(())
}
