//! The shared roadmap: vertices with lazily known validity, edges with cached
//! validity, compact adjacency, connected components and a reusable A*.

use crate::nn::XyGrid;
use smug_core::{Bounds2, CostMetric, Pose2};
use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};

/// What is known about a vertex or an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Validity {
    /// Not checked yet.
    Unknown,
    /// Checked: valid.
    Valid,
    /// Checked: invalid (removed from the graph).
    Invalid,
}

/// An undirected edge.
#[derive(Clone, Copy, Debug)]
pub struct Edge {
    /// One end.
    pub a: u32,
    /// The other end.
    pub b: u32,
    /// Metric cost.
    pub cost: f64,
    /// Cached validity.
    pub validity: Validity,
}

/// The roadmap graph.
pub struct Roadmap {
    poses: Vec<Pose2>,
    vertex_validity: Vec<Validity>,
    adjacency: Vec<Vec<(u32, u32)>>,
    edges: Vec<Edge>,
    grid: XyGrid,
    by_pose: HashMap<[u64; 3], u32>,
    components: UnionFind,
    components_stale: bool,
    live_edges: usize,
}

impl Roadmap {
    /// An empty roadmap over `bounds`.
    pub fn new(bounds: Bounds2) -> Self {
        let [w, h] = bounds.extent();
        Self {
            poses: Vec::new(),
            vertex_validity: Vec::new(),
            adjacency: Vec::new(),
            edges: Vec::new(),
            grid: XyGrid::new(bounds, (w.max(h) / 8.0).max(1e-3)),
            by_pose: HashMap::new(),
            components: UnionFind::default(),
            components_stale: false,
            live_edges: 0,
        }
    }

    /// Number of vertices ever added (invalid ones included).
    pub fn vertex_count(&self) -> usize {
        self.poses.len()
    }

    /// Number of vertices still in the graph.
    pub fn live_vertex_count(&self) -> usize {
        self.grid.len()
    }

    /// Number of edges still in the graph.
    pub fn live_edge_count(&self) -> usize {
        self.live_edges
    }

    /// The pose of vertex `v`.
    pub fn pose(&self, v: u32) -> &Pose2 {
        &self.poses[v as usize]
    }

    /// What is known about vertex `v`.
    pub fn vertex_validity(&self, v: u32) -> Validity {
        self.vertex_validity[v as usize]
    }

    /// Records that vertex `v` was checked valid.
    pub fn mark_vertex_valid(&mut self, v: u32) {
        self.vertex_validity[v as usize] = Validity::Valid;
    }

    /// Edge `e`.
    pub fn edge(&self, e: u32) -> &Edge {
        &self.edges[e as usize]
    }

    /// Records that edge `e` was checked valid.
    pub fn mark_edge_valid(&mut self, e: u32) {
        self.edges[e as usize].validity = Validity::Valid;
    }

    /// The vertex at exactly `pose`, if there is one.
    pub fn find(&self, pose: &Pose2) -> Option<u32> {
        self.by_pose.get(&pose_key(pose)).copied()
    }

    /// Adds a vertex with known `validity` and connects it to its `k` nearest live
    /// vertices; returns its id.
    pub fn add_vertex(
        &mut self,
        pose: Pose2,
        validity: Validity,
        k: usize,
        metric: &dyn CostMetric,
        w_t: f64,
    ) -> u32 {
        let id = self.poses.len() as u32;
        let neighbours = self
            .grid
            .k_nearest(&pose, k, &self.poses, metric, w_t, None);
        self.poses.push(pose);
        self.vertex_validity.push(validity);
        self.adjacency.push(Vec::with_capacity(neighbours.len()));
        self.components.push();
        self.grid.insert(id, &pose, &self.poses);
        self.by_pose.insert(pose_key(&pose), id);
        for n in neighbours {
            self.add_edge(id, n.id, n.distance);
        }
        id
    }

    fn add_edge(&mut self, a: u32, b: u32, cost: f64) {
        let e = self.edges.len() as u32;
        self.edges.push(Edge {
            a,
            b,
            cost,
            validity: Validity::Unknown,
        });
        self.adjacency[a as usize].push((b, e));
        self.adjacency[b as usize].push((a, e));
        self.components.union(a, b);
        self.live_edges += 1;
    }

    /// Removes edge `e` (found invalid).
    pub fn remove_edge(&mut self, e: u32) {
        let edge = &mut self.edges[e as usize];
        if edge.validity == Validity::Invalid {
            return;
        }
        edge.validity = Validity::Invalid;
        let (a, b) = (edge.a, edge.b);
        for v in [a, b] {
            let list = &mut self.adjacency[v as usize];
            if let Some(k) = list.iter().position(|&(_, id)| id == e) {
                list.swap_remove(k);
            }
        }
        self.live_edges -= 1;
        self.components_stale = true;
    }

    /// Removes vertex `v` (found invalid) and all its edges.
    pub fn remove_vertex(&mut self, v: u32) {
        if self.vertex_validity[v as usize] == Validity::Invalid {
            return;
        }
        self.vertex_validity[v as usize] = Validity::Invalid;
        let incident: Vec<u32> = self.adjacency[v as usize].iter().map(|&(_, e)| e).collect();
        for e in incident {
            self.remove_edge(e);
        }
        let pose = self.poses[v as usize];
        self.grid.remove(v, &pose);
        self.by_pose.remove(&pose_key(&pose));
        self.components_stale = true;
    }

    /// True when `a` and `b` may be connected (exact once components are refreshed).
    pub fn maybe_connected(&mut self, a: u32, b: u32) -> bool {
        self.components.find(a) == self.components.find(b)
    }

    /// Recomputes the connected components if edges were removed; returns whether
    /// they changed.
    pub fn refresh_components(&mut self) -> bool {
        if !self.components_stale {
            return false;
        }
        self.components = UnionFind::with_len(self.poses.len());
        for e in &self.edges {
            if e.validity != Validity::Invalid {
                self.components.union(e.a, e.b);
            }
        }
        self.components_stale = false;
        true
    }

    /// Neighbours of `v` with edge ids.
    pub fn neighbours(&self, v: u32) -> &[(u32, u32)] {
        &self.adjacency[v as usize]
    }
}

/// Bit-exact key of a pose.
fn pose_key(p: &Pose2) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.yaw.to_bits()]
}

/// Disjoint sets with path halving and union by size.
#[derive(Clone, Debug, Default)]
struct UnionFind {
    parent: Vec<u32>,
    size: Vec<u32>,
}

impl UnionFind {
    fn with_len(n: usize) -> Self {
        Self {
            parent: (0..n as u32).collect(),
            size: vec![1; n],
        }
    }

    fn push(&mut self) {
        self.parent.push(self.parent.len() as u32);
        self.size.push(1);
    }

    fn find(&mut self, mut v: u32) -> u32 {
        while self.parent[v as usize] != v {
            let grandparent = self.parent[self.parent[v as usize] as usize];
            self.parent[v as usize] = grandparent;
            v = grandparent;
        }
        v
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return;
        }
        let (big, small) = if self.size[ra as usize] >= self.size[rb as usize] {
            (ra, rb)
        } else {
            (rb, ra)
        };
        self.parent[small as usize] = big;
        self.size[big as usize] += self.size[small as usize];
    }
}

/// A path found by A*: vertices and the edges between them.
#[derive(Clone, Debug, PartialEq)]
pub struct GraphPath {
    /// Vertices from start to goal.
    pub vertices: Vec<u32>,
    /// Edge ids, `vertices.len() − 1` of them.
    pub edges: Vec<u32>,
    /// Sum of the edge costs.
    pub cost: f64,
}

/// An open-list entry: a vertex, its cost so far and estimate, and (for the lazy
/// search) the parent edge it is reached through.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Open {
    f: f64,
    g: f64,
    v: u32,
    parent: (u32, u32),
}

/// No parent (the search's start).
const NO_PARENT: (u32, u32) = (u32::MAX, u32::MAX);

/// Checks roadmap elements for the lazy search (and records what it finds).
pub trait Evaluator {
    /// Checks vertex `v` if unknown; true when valid (invalid ones are removed).
    fn vertex(&mut self, map: &mut Roadmap, v: u32) -> bool;
    /// Checks edge `e` if unknown; true when valid (invalid ones are removed).
    fn edge(&mut self, map: &mut Roadmap, e: u32) -> bool;
}

impl Eq for Open {}

impl Ord for Open {
    fn cmp(&self, other: &Self) -> Ordering {
        // Min-heap on f, then larger g first (deeper), then smaller id.
        other
            .f
            .total_cmp(&self.f)
            .then(self.g.total_cmp(&other.g))
            .then(other.v.cmp(&self.v))
    }
}

impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// A* with buffers reused across searches (generation stamps instead of clearing).
#[derive(Default)]
pub struct AStar {
    g: Vec<f64>,
    parent: Vec<(u32, u32)>,
    seen: Vec<u32>,
    closed: Vec<u32>,
    generation: u32,
    heap: BinaryHeap<Open>,
    lazy_heap: BinaryHeap<Open>,
    best_valid: Vec<f64>,
    /// Vertices expanded over all searches.
    pub expansions: u64,
}

impl AStar {
    /// The cheapest path from `start` to `goal` over the live edges, with the metric
    /// as (admissible, consistent) heuristic; `None` when disconnected.
    pub fn search(
        &mut self,
        map: &Roadmap,
        start: u32,
        goal: u32,
        metric: &dyn CostMetric,
    ) -> Option<GraphPath> {
        self.prepare(map.vertex_count());
        let goal_pose = *map.pose(goal);
        let h = |v: u32| metric.distance(map.pose(v), &goal_pose);
        self.open(start, 0.0, NO_PARENT);
        self.heap.push(Open {
            f: h(start),
            g: 0.0,
            v: start,
            parent: NO_PARENT,
        });
        while let Some(Open { g, v, .. }) = self.heap.pop() {
            if self.closed[v as usize] == self.generation || g > self.g[v as usize] {
                continue;
            }
            if v == goal {
                return Some(self.trace(start, goal));
            }
            self.closed[v as usize] = self.generation;
            self.expansions += 1;
            for &(w, e) in map.neighbours(v) {
                if self.closed[w as usize] == self.generation {
                    continue;
                }
                let candidate = g + map.edge(e).cost;
                if self.seen[w as usize] != self.generation || candidate < self.g[w as usize] {
                    self.open(w, candidate, (v, e));
                    self.heap.push(Open {
                        f: candidate + h(w),
                        g: candidate,
                        v: w,
                        parent: (v, e),
                    });
                }
            }
        }
        None
    }

    /// Lazy Weighted A* (Cohen, Phillips & Likhachev 2014): one search that checks an
    /// element only when the vertex it leads to is about to be expanded. Returns the
    /// cheapest valid path over the live edges (every element on it checked), or `None`.
    pub fn search_lazy(
        &mut self,
        map: &mut Roadmap,
        start: u32,
        goal: u32,
        metric: &dyn CostMetric,
        evaluator: &mut dyn Evaluator,
    ) -> Option<GraphPath> {
        self.prepare(map.vertex_count());
        let goal_pose = *map.pose(goal);
        let mut open = std::mem::take(&mut self.lazy_heap);
        open.clear();
        let h0 = metric.distance(map.pose(start), &goal_pose);
        open.push(Open {
            f: h0,
            g: 0.0,
            v: start,
            parent: NO_PARENT,
        });
        let mut found = None;
        while let Some(Open { g, v, parent, .. }) = open.pop() {
            if self.closed[v as usize] == self.generation {
                continue;
            }
            let (_, e) = parent;
            let reachable = (e == u32::MAX
                || map.edge(e).validity != Validity::Invalid && evaluator.edge(map, e))
                && evaluator.vertex(map, v);
            if !reachable {
                continue;
            }
            self.closed[v as usize] = self.generation;
            self.g[v as usize] = g;
            self.parent[v as usize] = parent;
            if v == goal {
                found = Some(self.trace(start, goal));
                break;
            }
            self.expansions += 1;
            for &(w, e2) in map.neighbours(v) {
                if self.closed[w as usize] == self.generation {
                    continue;
                }
                let candidate = g + map.edge(e2).cost;
                let known = self.seen[w as usize] == self.generation;
                if known && candidate >= self.best_valid[w as usize] {
                    continue;
                }
                if map.edge(e2).validity == Validity::Valid {
                    self.seen[w as usize] = self.generation;
                    self.best_valid[w as usize] = candidate;
                }
                let f = candidate + metric.distance(map.pose(w), &goal_pose);
                open.push(Open {
                    f,
                    g: candidate,
                    v: w,
                    parent: (v, e2),
                });
            }
        }
        self.lazy_heap = open;
        found
    }

    fn prepare(&mut self, n: usize) {
        if self.g.len() < n {
            self.g.resize(n, f64::INFINITY);
            self.parent.resize(n, (u32::MAX, u32::MAX));
            self.seen.resize(n, 0);
            self.closed.resize(n, 0);
            self.best_valid.resize(n, f64::INFINITY);
        }
        self.heap.clear();
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.seen.iter_mut().for_each(|s| *s = 0);
            self.closed.iter_mut().for_each(|s| *s = 0);
            self.generation = 1;
        }
    }

    fn open(&mut self, v: u32, g: f64, parent: (u32, u32)) {
        self.seen[v as usize] = self.generation;
        self.g[v as usize] = g;
        self.parent[v as usize] = parent;
    }

    fn trace(&self, start: u32, goal: u32) -> GraphPath {
        let mut vertices = vec![goal];
        let mut edges = Vec::new();
        let mut v = goal;
        while v != start {
            let (p, e) = self.parent[v as usize];
            vertices.push(p);
            edges.push(e);
            v = p;
        }
        vertices.reverse();
        edges.reverse();
        GraphPath {
            vertices,
            edges,
            cost: self.g[goal as usize],
        }
    }
}

/// Dijkstra distances from `start` over the live edges (for tests and diagnostics).
pub fn dijkstra(map: &Roadmap, start: u32) -> Vec<f64> {
    let mut dist = vec![f64::INFINITY; map.vertex_count()];
    let mut heap = BinaryHeap::new();
    dist[start as usize] = 0.0;
    heap.push(Open {
        f: 0.0,
        g: 0.0,
        v: start,
        parent: NO_PARENT,
    });
    while let Some(Open { f, v, .. }) = heap.pop() {
        if f > dist[v as usize] {
            continue;
        }
        for &(w, e) in map.neighbours(v) {
            let d = f + map.edge(e).cost;
            if d < dist[w as usize] {
                dist[w as usize] = d;
                heap.push(Open {
                    f: d,
                    g: 0.0,
                    v: w,
                    parent: (v, e),
                });
            }
        }
    }
    dist
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use smug_core::Se2Metric;

    proptest! {
        #[test]
        fn astar_finds_the_dijkstra_shortest_path(
            points in proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, -3.0f64..3.0), 2..120),
            removed in proptest::collection::vec(0usize..2000, 0..60),
            k in 1usize..8, goal_pick in 0usize..1000,
        ) {
            let metric = Se2Metric::default();
            let mut map = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
            for &(x, y, t) in &points {
                map.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, &metric, 1.0);
            }
            for r in removed {
                if r < map.edges.len() { map.remove_edge(r as u32); }
            }
            let goal = (goal_pick % map.vertex_count()) as u32;
            let dist = dijkstra(&map, 0);
            let found = AStar::default().search(&map, 0, goal, &metric);
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
            k in 1usize..8, goal_pick in 0usize..1000,
        ) {
            let metric = Se2Metric::default();
            let mut lazy = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
            for &(x, y, t) in &points {
                lazy.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, &metric, 1.0);
            }
            let goal = (goal_pick % lazy.vertex_count()) as u32;
            let mut truth = Roadmap::new(Bounds2 { min: [0.0, 0.0], max: [10.0, 10.0] });
            for &(x, y, t) in &points {
                truth.add_vertex(Pose2::new(x, y, t), Validity::Unknown, k, &metric, 1.0);
            }
            for e in 0..truth.edges.len() {
                if !validity[e % validity.len()] { truth.remove_edge(e as u32); }
            }
            let hidden: Vec<bool> = (0..lazy.edges.len()).map(|e| validity[e % validity.len()]).collect();
            let found = AStar::default().search_lazy(&mut lazy, 0, goal, &metric, &mut Hidden(hidden));
            let best = dijkstra(&truth, 0)[goal as usize];
            match found {
                None => prop_assert!(best.is_infinite()),
                Some(path) => {
                    prop_assert!((path.cost - best).abs() < 1e-9, "{} vs {}", path.cost, best);
                    prop_assert!(path.edges.iter().all(|&e| lazy.edge(e).validity == Validity::Valid || path.vertices.len() == 1));
                }
            }
        }
    }
}
