//! Local search on the TSPLIB suite with its construction and first-descent gaps (a
//! tuning aid; `smug bench tsp` is the benchmark proper):
//! `SEED=1 cargo run --release -p smug-sequencing --example tsplib_gaps -- [budget_s] [names…]`.

use smug_core::TourKind;
use smug_sequencing::bench::{gap_percent, load_suite};
use smug_sequencing::{read_tsplib, LocalSearch, LocalSearchParams};
use std::path::Path;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let budget: f64 = args.next().map(|a| a.parse()).transpose()?.unwrap_or(1.0);
    let only: Vec<String> = args.collect();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data/tsplib");
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
