//! Properties of the GTSP solvers on random clustered matrices: the exact DP equals
//! brute force, the large-neighbourhood search gives valid tours, is reproducible and
//! mostly finds the optimum of small instances.

use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smug_core::{Clusters, CostMatrix, Sequencer, Tour, TourKind};
use smug_sequencing::{Auto, AutoParams, GtspExact, GtspExactParams, GtspLns, GtspLnsParams};

/// A random clustered instance: `n` nodes in `m` non-empty clusters, integer costs,
/// symmetric or not, with an occasional missing leg (`INFINITY`).
#[derive(Clone, Debug)]
struct Instance {
    costs: CostMatrix,
    clusters: Clusters,
}

fn instance(max_n: usize, max_m: usize) -> impl Strategy<Value = (Instance, bool)> {
    (1..=max_n, any::<bool>())
        .prop_flat_map(move |(n, symmetric)| {
            let cell = prop_oneof![19 => (0u32..100).prop_map(f64::from), 1 => Just(f64::INFINITY)];
            (
                Just(n),
                Just(symmetric),
                1..=n.min(max_m),
                prop::collection::vec(cell, n * n),
                prop::collection::vec(any::<usize>(), n),
            )
        })
        .prop_map(|(n, symmetric, m, cells, owners)| {
            let costs = CostMatrix::from_fn(n, |i, j| {
                let (a, b) = if symmetric {
                    (i.min(j), i.max(j))
                } else {
                    (i, j)
                };
                cells[a * n + b]
            })
            .unwrap();
            (
                Instance {
                    costs,
                    clusters: random_clusters(n, m, &owners),
                },
                symmetric,
            )
        })
}

/// Node `v < m` founds cluster `v`; every other node joins cluster `owners[v] % m`.
fn random_clusters(n: usize, m: usize, owners: &[usize]) -> Clusters {
    let mut members = vec![Vec::new(); m];
    for v in 0..n {
        members[if v < m { v } else { owners[v] % m }].push(v);
    }
    Clusters::new(n, members).unwrap()
}

/// Closed, or open to a cluster chosen by `pick` (when there are at least two).
fn kind_for(m: usize, open: bool, pick: usize) -> TourKind {
    if open && m >= 2 {
        TourKind::OpenTo(1 + pick % (m - 1))
    } else {
        TourKind::Closed
    }
}

/// The cheapest tour over every cluster order and every choice of nodes.
fn brute_force(instance: &Instance, kind: TourKind) -> f64 {
    let m = instance.clusters.len();
    let end = match kind {
        TourKind::OpenTo(c) => Some(c),
        TourKind::Closed => None,
    };
    let middle: Vec<usize> = (1..m).filter(|&c| Some(c) != end).collect();
    let mut best = f64::INFINITY;
    for order in permutations(&middle) {
        let clusters: Vec<usize> = std::iter::once(0).chain(order).chain(end).collect();
        for nodes in choices(&instance.clusters, &clusters) {
            best = best.min(instance.costs.tour_cost(&nodes, kind));
        }
    }
    best
}

fn permutations(items: &[usize]) -> Vec<Vec<usize>> {
    if items.is_empty() {
        return vec![Vec::new()];
    }
    let mut all = Vec::new();
    for k in 0..items.len() {
        let mut rest = items.to_vec();
        let first = rest.remove(k);
        for mut tail in permutations(&rest) {
            tail.insert(0, first);
            all.push(tail);
        }
    }
    all
}

/// Every way to pick one node of each cluster of `order`.
fn choices(clusters: &Clusters, order: &[usize]) -> Vec<Vec<usize>> {
    order.iter().fold(vec![Vec::new()], |partial, &c| {
        partial
            .iter()
            .flat_map(|prefix| {
                clusters.members(c).iter().map(move |&v| {
                    let mut next = prefix.clone();
                    next.push(v);
                    next
                })
            })
            .collect()
    })
}

fn exact() -> GtspExact {
    GtspExact::new(GtspExactParams::default()).unwrap()
}

fn lns(iterations: u64, seed: u64) -> GtspLns {
    let params = GtspLnsParams {
        time_limit_s: 0.0,
        max_iterations: iterations,
        ..GtspLnsParams::default()
    };
    GtspLns::with_seed(params, seed).unwrap()
}

fn same_cost(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-9 * a.abs().max(1.0)
}

fn check_tour(tour: &Tour, instance: &Instance, kind: TourKind) -> Result<(), TestCaseError> {
    prop_assert!(
        instance.clusters.is_valid_tour(tour, kind),
        "{:?} is not a {kind:?} GTSP tour of {:?}",
        tour.order,
        instance.clusters
    );
    prop_assert!(same_cost(
        tour.cost,
        instance.costs.tour_cost(&tour.order, kind)
    ));
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn exact_equals_brute_force((instance, _) in instance(9, 6), open: bool, pick in 0usize..100) {
        let kind = kind_for(instance.clusters.len(), open, pick);
        let tour = exact().solve_clusters(&instance.costs, &instance.clusters, kind).unwrap();
        check_tour(&tour, &instance, kind)?;
        let reference = brute_force(&instance, kind);
        prop_assert!(same_cost(tour.cost, reference), "{} vs {reference}", tour.cost);
    }

    #[test]
    fn lns_tours_are_valid_and_reproducible(
        (instance, _) in instance(14, 9),
        open: bool,
        pick in 0usize..100,
        seed in 0u64..1000,
    ) {
        let kind = kind_for(instance.clusters.len(), open, pick);
        let solver = lns(20, seed);
        let tour = solver.solve_clusters(&instance.costs, &instance.clusters, kind).unwrap();
        check_tour(&tour, &instance, kind)?;
        let again = solver.solve_clusters(&instance.costs, &instance.clusters, kind).unwrap();
        prop_assert_eq!(&tour, &again);
        let optimum = exact().solve_clusters(&instance.costs, &instance.clusters, kind).unwrap();
        prop_assert!(tour.cost >= optimum.cost - 1e-9);
    }

    #[test]
    fn warm_started_lns_tours_are_valid_reproducible_and_no_worse_than_their_start(
        (instance, _) in instance(14, 9),
        open: bool,
        pick in 0usize..100,
        seed in 0u64..1000,
    ) {
        let kind = kind_for(instance.clusters.len(), open, pick);
        // A start tour: a one-iteration solve with another seed.
        let start = lns(1, seed + 1).solve_clusters(&instance.costs, &instance.clusters, kind).unwrap();
        let solver = lns(20, seed);
        let tour = solver.solve_clusters_from(&instance.costs, &instance.clusters, kind, &start).unwrap();
        check_tour(&tour, &instance, kind)?;
        let again = solver.solve_clusters_from(&instance.costs, &instance.clusters, kind, &start).unwrap();
        prop_assert_eq!(&tour, &again);
        if start.cost.is_finite() {
            prop_assert!(tour.cost <= start.cost + 1e-9, "{} after starting from {}", tour.cost, start.cost);
        }
        // A start that is no tour of these clusters is ignored.
        let foreign = Tour { order: vec![0; instance.clusters.len() + 1], cost: 0.0 };
        let cold = solver.solve_clusters_from(&instance.costs, &instance.clusters, kind, &foreign).unwrap();
        prop_assert_eq!(&cold, &solver.solve_clusters(&instance.costs, &instance.clusters, kind).unwrap());
    }

    #[test]
    fn auto_solves_small_clustered_problems_exactly_and_large_ones_with_valid_tours(
        (instance, _) in instance(14, 9),
        open: bool,
        pick in 0usize..100,
        seed in 0u64..1000,
    ) {
        let kind = kind_for(instance.clusters.len(), open, pick);
        let optimum = exact().solve_clusters(&instance.costs, &instance.clusters, kind).unwrap();
        // Default work limit: instances this small are solved by the exact DP.
        let auto = Auto::new(AutoParams::default(), smug_core::rng::stage_rng(seed, "sequencer")).unwrap();
        let tour = auto.solve_clusters(&instance.costs, &instance.clusters, kind).unwrap();
        check_tour(&tour, &instance, kind)?;
        prop_assert!(same_cost(tour.cost, optimum.cost), "{} vs {}", tour.cost, optimum.cost);
        let warm = auto.solve_clusters_from(&instance.costs, &instance.clusters, kind, &tour).unwrap();
        prop_assert!(same_cost(warm.cost, optimum.cost));
        // No exact work allowed: the LNS answers, with a valid tour no better than the optimum,
        // the same one gtsp-lns with the same seed gives.
        let params = AutoParams { exact_cluster_work: 0.0, ..AutoParams::default() };
        let auto = Auto::new(params, smug_core::rng::stage_rng(seed, "sequencer")).unwrap();
        let heuristic = auto.solve_clusters(&instance.costs, &instance.clusters, kind).unwrap();
        check_tour(&heuristic, &instance, kind)?;
        prop_assert!(heuristic.cost >= optimum.cost - 1e-9);
        let lns = GtspLns::with_seed(GtspLnsParams::default(), seed).unwrap();
        prop_assert_eq!(heuristic, lns.solve_clusters(&instance.costs, &instance.clusters, kind).unwrap());
    }

    #[test]
    fn singleton_clusters_are_the_tsp((instance, _) in instance(8, 8), open: bool, pick in 0usize..100) {
        let n = instance.costs.len();
        let kind = kind_for(n, open, pick);
        let tsp = exact().solve(&instance.costs, kind).unwrap();
        prop_assert!(tsp.is_valid_for(n, kind));
        let reference = smug_sequencing::BruteForce.solve(&instance.costs, kind).unwrap();
        prop_assert!(same_cost(tsp.cost, reference.cost));
    }
}

/// A random instance of `m` clusters of 1..=4 nodes at random points of a square
/// (Euclidean, so the search meets realistic structure), or random asymmetric costs.
fn random_instance(rng: &mut ChaCha8Rng, m: usize, euclidean: bool) -> Instance {
    let sizes: Vec<usize> = (0..m).map(|_| rng.random_range(1..=4)).collect();
    let n: usize = sizes.iter().sum();
    let points: Vec<(f64, f64)> = (0..n)
        .map(|_| (rng.random_range(0.0..100.0), rng.random_range(0.0..100.0)))
        .collect();
    let cells: Vec<f64> = (0..n * n)
        .map(|_| rng.random_range(1..100) as f64)
        .collect();
    let costs = CostMatrix::from_fn(n, |i, j| match (i == j, euclidean) {
        (true, _) => 0.0,
        (false, true) => {
            let (a, b) = (points[i], points[j]);
            (a.0 - b.0).hypot(a.1 - b.1).round()
        }
        (false, false) => cells[i * n + j],
    })
    .unwrap();
    let mut members = Vec::new();
    let mut next = 0;
    for size in sizes {
        members.push((next..next + size).collect());
        next += size;
    }
    Instance {
        costs,
        clusters: Clusters::new(n, members).unwrap(),
    }
}

#[test]
fn lns_finds_the_optimum_of_small_instances_most_of_the_time() {
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    let (mut hits, mut total) = (0, 0);
    for round in 0..120 {
        let m = rng.random_range(5..=10);
        let instance = random_instance(&mut rng, m, round % 2 == 0);
        let kind = if round % 3 == 0 {
            TourKind::OpenTo(m - 1)
        } else {
            TourKind::Closed
        };
        let optimum = exact()
            .solve_clusters(&instance.costs, &instance.clusters, kind)
            .unwrap();
        let found = lns(300, round)
            .solve_clusters(&instance.costs, &instance.clusters, kind)
            .unwrap();
        assert!(instance.clusters.is_valid_tour(&found, kind));
        assert!(found.cost >= optimum.cost - 1e-9);
        total += 1;
        hits += usize::from(same_cost(found.cost, optimum.cost));
    }
    // Measured: optimal on 113 of the 120 (two neighbours per iteration; 110 with one;
    // the misses are random asymmetric matrices).
    assert!(hits * 100 >= 85 * total, "optimal on {hits} of {total}");
}

/// An iteration's neighbours are built side by side on large instances, each from its
/// own generator: one thread and two give the same tour, bit for bit, closed and open.
#[test]
fn lns_gives_the_same_tour_on_one_thread_and_two() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let instance = random_instance(&mut rng, 140, true);
    assert!(
        instance.costs.len() >= 256,
        "{} nodes",
        instance.costs.len()
    );
    let params = GtspLnsParams {
        time_limit_s: 0.0,
        max_iterations: 60,
        neighbours_per_iteration: 2,
        ..GtspLnsParams::default()
    };
    for kind in [TourKind::Closed, TourKind::OpenTo(139)] {
        let solve_on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let lns = GtspLns::with_seed(params.clone(), 3).unwrap();
            pool.install(|| lns.solve_clusters(&instance.costs, &instance.clusters, kind))
                .unwrap()
        };
        let (one, two) = (solve_on(1), solve_on(2));
        assert!(instance.clusters.is_valid_tour(&one, kind));
        assert_eq!(one.order, two.order, "{kind:?}");
        assert_eq!(one.cost.to_bits(), two.cost.to_bits(), "{kind:?}");
    }
}
