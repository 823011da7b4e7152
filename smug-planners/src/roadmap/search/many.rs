//! One-to-many shortest valid paths on the roadmap: one lazy Dijkstra search from a
//! source that stops once every goal it was asked for is settled. It reads the
//! roadmap held still and checks through a memo ([`crate::roadmap::memo`]), so that
//! searches from many sources can run side by side.

use super::records::{Marks, Reached, VertexRecord, NO_PARENT};
use super::{AStar, GraphPath, Roadmap};
use crate::nn::from_total_order_key;
use crate::roadmap::memo::MemoEvaluator;

impl AStar {
    /// The cheapest valid path from `start` to each of `goals` (`None` where no valid
    /// path is left), found by one lazy Dijkstra search: the edge into a vertex (and
    /// the vertex) is checked when the vertex is about to be settled, as in Lazy
    /// Weighted A* ([`AStar::search_lazy`]) without a heuristic; the search ends once
    /// every goal is settled. Decisions read the roadmap as it is (its validity marks),
    /// checks go through `evaluator`: the answer depends on the roadmap alone, not on
    /// what other searches found before.
    pub fn search_many_lazy(
        &mut self,
        map: &Roadmap,
        start: u32,
        goals: &[u32],
        evaluator: &mut dyn MemoEvaluator,
    ) -> Vec<Option<GraphPath>> {
        let marks = self.prepare_without_heuristic(map);
        let mut wanted: Vec<u32> = goals.to_vec();
        wanted.sort_unstable();
        wanted.dedup();
        let mut unsettled = wanted.len();
        let mut open = std::mem::take(&mut self.many_heap);
        open.clear();
        open.push(Reached::new(0.0, start, NO_PARENT));
        while unsettled > 0 {
            let Some(Reached { g_key, v, parent }) = open.pop() else {
                break;
            };
            if self.records[v as usize].mark == marks.closed {
                continue;
            }
            let (_, e) = parent;
            let reachable = (e == u32::MAX || evaluator.edge(map, e)) && evaluator.vertex(map, v);
            if !reachable {
                continue;
            }
            let g = from_total_order_key(g_key);
            let record = &mut self.records[v as usize];
            (record.mark, record.g, record.parent) = (marks.closed, g, parent);
            if wanted.binary_search(&v).is_ok() {
                unsettled -= 1;
            }
            self.expansions += 1;
            for (w, e, cost) in map.neighbours_with_costs(v) {
                let record = &mut self.records[w as usize];
                if record.mark == marks.closed {
                    continue;
                }
                let candidate = g + cost;
                if record.mark == marks.open && candidate >= record.g {
                    continue;
                }
                if map.edge_known_valid(e) {
                    (record.mark, record.g) = (marks.open, candidate);
                }
                open.push(Reached::new(candidate, w, (v, e)));
            }
        }
        self.many_heap = open;
        goals
            .iter()
            .map(|&goal| {
                (self.records[goal as usize].mark == marks.closed).then(|| self.trace(start, goal))
            })
            .collect()
    }

    /// Sizes the records for `map` and starts a new search generation (the cached
    /// heuristic values stay: Dijkstra reads none); forgets the settled search.
    fn prepare_without_heuristic(&mut self, map: &Roadmap) -> Marks {
        let n = map.vertex_count();
        if self.records.len() < n {
            self.records.resize(n, VertexRecord::default());
        }
        self.heap.clear();
        self.settled = None;
        self.next_generation()
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::memo::CheckMemo;
    use super::super::super::Validity;
    use super::super::dijkstra;
    use super::*;
    use proptest::prelude::*;
    use smug_core::{Bounds2, PathLength, Pose2, Se2Space};
    use std::collections::BTreeSet;

    /// Edges whose id is in `invalid` are invalid; every vertex is valid.
    struct Marked {
        invalid: BTreeSet<u32>,
        checked: Vec<u32>,
        memo: CheckMemo,
    }

    impl MemoEvaluator for Marked {
        fn vertex(&mut self, _: &Roadmap, _: u32) -> bool {
            true
        }
        fn edge(&mut self, map: &Roadmap, e: u32) -> bool {
            let invalid = &self.invalid;
            let checked = &mut self.checked;
            self.memo
                .edge(map, e, || !invalid.contains(&e), || checked.push(e))
        }
    }

    proptest! {
        #[test]
        fn one_lazy_search_finds_every_goal_at_its_shortest_valid_distance(
            points in proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0), 2..120),
            invalid in proptest::collection::btree_set(0u32..2000, 0..300),
            k in 1usize..8,
            picks in proptest::collection::vec(0usize..1000, 1..12),
        ) {
            let metric = Se2Space::default();
            let objective = PathLength::default();
            let mut map = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
            for &(x, y, t) in &points {
                map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
            }
            // The truth: the roadmap without its invalid edges.
            let mut valid_map = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
            for &(x, y, t) in &points {
                valid_map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, (&metric, 1.0), &objective);
            }
            for &e in &invalid {
                if (e as usize) < valid_map.edges.len() { valid_map.remove_edge(e); }
            }
            let dist = dijkstra(&valid_map, 0);
            let goals: Vec<u32> = picks.iter().map(|p| (p % map.vertex_count()) as u32).collect();
            let mut marked = Marked { invalid: invalid.clone(), checked: Vec::new(), memo: CheckMemo::new(&map) };
            let found = AStar::default().search_many_lazy(&map, 0, &goals, &mut marked);
            marked.memo.apply(&mut map);
            prop_assert_eq!(found.len(), goals.len());
            // The compact copy of the edges' validity follows the edges.
            for e in 0..map.edge_count() as u32 {
                prop_assert_eq!(map.edge_validity(e), map.edge(e).validity);
            }
            // No edge is checked twice (validity is cached on the roadmap).
            let distinct: BTreeSet<u32> = marked.checked.iter().copied().collect();
            prop_assert_eq!(distinct.len(), marked.checked.len());
            for (&goal, path) in goals.iter().zip(&found) {
                match path {
                    None => prop_assert!(dist[goal as usize].is_infinite()),
                    Some(path) => {
                        let tolerance = 1e-9 * (1.0 + path.cost);
                        prop_assert!((path.cost - dist[goal as usize]).abs() <= tolerance);
                        prop_assert_eq!(path.vertices[0], 0);
                        prop_assert_eq!(*path.vertices.last().unwrap(), goal);
                        let mut sum = 0.0;
                        for (pair, &e) in path.vertices.windows(2).zip(&path.edges) {
                            prop_assert!(!invalid.contains(&e));
                            prop_assert_eq!(map.edge(e).validity, Validity::Valid);
                            let edge = map.edge(e);
                            prop_assert!((edge.a, edge.b) == (pair[0], pair[1]) || (edge.b, edge.a) == (pair[0], pair[1]));
                            sum += map.neighbours_with_costs(pair[0]).find(|&(w, id, _)| w == pair[1] && id == e).unwrap().2;
                        }
                        prop_assert!((sum - path.cost).abs() <= tolerance);
                    }
                }
            }
        }
    }
}
