//! Tests of the searches: A* against Dijkstra, repairs against searching again, Lazy
//! Weighted A* against A* on the valid elements.

use super::records::open_order;
use super::*;
use crate::nn::{from_total_order_key, total_order_key};
use proptest::prelude::*;
use smug_core::{Bounds2, PathLength, Se2Space};

proptest! {
    #[test]
    fn astar_finds_the_dijkstra_shortest_path(
        points in proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0), 2..120),
        removed in proptest::collection::vec(0usize..2000, 0..60),
        k in 1usize..8, goal_pick in 0usize..1000, slack in prop_oneof![Just(0.0), 0.0f64..5.0],
    ) {
        let metric = Se2Space::default();
        let objective = PathLength::default();
        let mut map = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
        for &(x, y, t) in &points {
            map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
        }
        for r in removed {
            if r < map.edges.len() { map.remove_edge(r as u32); }
        }
        let goal = (goal_pick % map.vertex_count()) as u32;
        let dist = dijkstra(&map, 0);
        let found = AStar::default().search(&map, 0, goal, &objective, f64::INFINITY);
        // A bound at or above the shortest cost changes nothing; below it, no path.
        let exact = dist[goal as usize];
        let mut bounded = AStar::default();
        prop_assert_eq!(bounded.search(&map, 0, goal, &objective, exact * (1.0 + 1e-9) + slack), found.clone());
        if exact > 0.0 {
            prop_assert_eq!(bounded.search(&map, 0, goal, &objective, exact * (1.0 - 1e-9) - 1e-9), None);
        }
        match found {
            None => prop_assert!(dist[goal as usize].is_infinite()),
            Some(path) => {
                prop_assert!((path.cost - dist[goal as usize]).abs() < 1e-9, "{} vs {}", path.cost, dist[goal as usize]);
                let sum: f64 = path.edges.iter().map(|&e| map.edge(e).cost).sum();
                prop_assert!((sum - path.cost).abs() < 1e-9);
                prop_assert_eq!(path.vertices.first(), Some(&0));
                prop_assert_eq!(path.vertices.last(), Some(&goal));
            }
        }
        map.refresh_components();
        prop_assert_eq!(map.maybe_connected(0, goal), dist[goal as usize].is_finite());
    }
}

proptest! {
    #[test]
    fn repairs_find_what_searching_again_finds(
        points in proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0), 2..80),
        batches in proptest::collection::vec(
            proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0), 1..6), 1..6),
        k in 1usize..8, goal_pick in 0usize..1000,
    ) {
        let metric = Se2Space::default();
        let objective = PathLength::default();
        let mut map = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
        for &(x, y, t) in &points {
            map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
        }
        let goal = (goal_pick % map.vertex_count()) as u32;
        let mut incremental = AStar::default();
        let Some(mut best) = incremental.search(&map, 0, goal, &objective, f64::INFINITY) else {
            return Ok(());
        };
        for batch in batches {
            let fresh_from = map.vertex_count() as u32;
            for &(x, y, t) in &batch {
                map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
            }
            let again = AStar::default().search(&map, 0, goal, &objective, f64::INFINITY).unwrap();
            match incremental.repair(&map, 0, goal, fresh_from, &objective) {
                Repair::Cheaper(path) => {
                    prop_assert!(path.cost < best.cost);
                    prop_assert!((path.cost - again.cost).abs() <= 1e-9 * again.cost);
                    let sum: f64 = path.edges.iter().map(|&e| map.edge(e).cost).sum();
                    prop_assert!((sum - path.cost).abs() <= 1e-9 * path.cost.max(1.0));
                    prop_assert_eq!(path.vertices.first(), Some(&0));
                    prop_assert_eq!(path.vertices.last(), Some(&goal));
                    best = path;
                }
                Repair::NoCheaper => prop_assert!(again.cost >= best.cost * (1.0 - 1e-9)),
                Repair::NoBase => prop_assert!(false, "the base was lost"),
            }
            prop_assert_eq!(incremental.settled_path_cost(&map, 0, goal), Some(best.cost));
        }
        // A removal ends the base: the next attempt must search.
        if let Some(&e) = best.edges.first() {
            map.remove_edge(e);
            prop_assert_eq!(incremental.repair(&map, 0, goal, map.vertex_count() as u32, &objective), Repair::NoBase);
        }
    }
}

#[test]
fn total_order_keys_order_like_total_cmp_and_round_trip() {
    let values = [
        f64::NEG_INFINITY,
        -1e300,
        -1.5,
        -f64::MIN_POSITIVE,
        -0.0,
        0.0,
        f64::MIN_POSITIVE,
        1e-300,
        1.0,
        1.0 + f64::EPSILON,
        1e300,
        f64::INFINITY,
        f64::NAN,
        -f64::NAN,
    ];
    for a in values {
        assert_eq!(
            from_total_order_key(total_order_key(a)).to_bits(),
            a.to_bits()
        );
        for b in values {
            assert_eq!(total_order_key(a).cmp(&total_order_key(b)), a.total_cmp(&b));
            let (ca, cb) = (Candidate::new(a, b, 1), Candidate::new(b, a, 2));
            let expected = open_order((a, b, 1), (b, a, 2));
            assert_eq!(ca.cmp(&cb), expected, "{a} {b}");
        }
    }
}

/// Knows which edges are secretly invalid.
struct Hidden(Vec<bool>);

impl Evaluator for Hidden {
    fn vertex(&mut self, _: &mut Roadmap, _: u32) -> bool {
        true
    }

    fn edge(&mut self, map: &mut Roadmap, e: u32) -> bool {
        match map.edge(e).validity {
            Validity::Valid => true,
            Validity::Invalid => false,
            Validity::Unknown if self.0[e as usize] => {
                map.mark_edge_valid(e);
                true
            }
            Validity::Unknown => {
                map.remove_edge(e);
                false
            }
        }
    }
}

proptest! {
    #[test]
    fn lazy_weighted_astar_finds_the_shortest_valid_path(
        points in proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0), 2..120),
        validity in proptest::collection::vec(proptest::bool::weighted(0.7), 2000),
        k in 1usize..8, goal_pick in 0usize..1000, bounded: bool,
    ) {
        let metric = Se2Space::default();
        let objective = PathLength::default();
        let mut lazy = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
        for &(x, y, t) in &points {
            lazy.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
        }
        let goal = (goal_pick % lazy.vertex_count()) as u32;
        let mut truth = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
        for &(x, y, t) in &points {
            truth.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
        }
        for e in 0..truth.edges.len() {
            if !validity[e % validity.len()] { truth.remove_edge(e as u32); }
        }
        let hidden: Vec<bool> = (0..lazy.edges.len()).map(|e| validity[e % validity.len()]).collect();
        let best = dijkstra(&truth, 0)[goal as usize];
        // A bound from a known valid path (at or above the cheapest) changes nothing.
        let bound = if bounded { best * (1.0 + 1e-9) } else { f64::INFINITY };
        let found = AStar::default().search_lazy(&mut lazy, 0, goal, &objective, &mut Hidden(hidden), bound);
        match found {
            None => prop_assert!(best.is_infinite()),
            Some(path) => {
                prop_assert!((path.cost - best).abs() < 1e-9, "{} vs {}", path.cost, best);
                prop_assert!(path.edges.iter().all(|&e| lazy.edge(e).validity == Validity::Valid || path.vertices.len() == 1));
            }
        }
    }
}

/// A cost that charges going up in x twice as much as going down (asymmetric).
#[derive(Debug)]
struct Uphill;

impl Objective for Uphill {
    fn motion_cost(&self, a: &Pose2, b: &Pose2) -> f64 {
        a.xy_distance(b) + (b.x - a.x).max(0.0)
    }
    fn cost_bound(&self, a: &Pose2, b: &Pose2) -> f64 {
        self.motion_cost(a, b)
    }
    fn bound_weights(&self) -> (f64, f64) {
        (1.0, 0.0)
    }
    fn is_symmetric(&self) -> bool {
        false
    }
}

proptest! {
    /// Directed edges (both motions of every connection) find the same cheapest
    /// paths as undirected ones, under symmetric and asymmetric costs; removing one
    /// direction leaves the other.
    #[test]
    fn directed_roadmaps_agree_with_undirected_ones(
        points in prop::collection::vec((0.0..10.0f64, 0.0..10.0f64, -3.0..3.0f64), 3..40),
        k in 2usize..6,
        asymmetric in any::<bool>(),
    ) {
        let space = Se2Space::default();
        let (length, uphill) = (PathLength::default(), Uphill);
        let objective: &dyn Objective = if asymmetric { &uphill } else { &length };
        let mut undirected = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
        let mut directed = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] }).with_directed_edges(true);
        for &(x, y, t) in &points {
            for map in [&mut undirected, &mut directed] {
                map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&space, 1.0), objective);
            }
        }
        let goal = points.len() as u32 - 1;
        for start in [0, goal] {
            let (u, d) = (dijkstra(&undirected, start), dijkstra(&directed, start));
            for (a, b) in u.iter().zip(&d) {
                prop_assert!(a == b || (a - b).abs() <= 1e-9 * a.max(1.0), "{a} vs {b}");
            }
        }
        prop_assert_eq!(directed.live_edge_count(), 2 * undirected.live_edge_count());
        if let Some(&(w, e)) = directed.neighbours(0).first() {
            directed.remove_edge(e);
            prop_assert!(directed.neighbours(0).iter().all(|&(_, id)| id != e));
            prop_assert!(directed.neighbours(w).iter().any(|&(v, _)| v == 0), "the reverse motion stays");
        }
    }
}
