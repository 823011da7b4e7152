//! The shared roadmap: vertices with lazily known validity, edges with cached
//! validity, compact adjacency, connected components and a reusable A*.

pub mod file;
pub mod memo;
mod search;
mod snapshot;

pub use search::{dijkstra, AStar, Evaluator, GraphPath, Repair};

use crate::nn::XyGrid;
use smug_core::{Bounds2, Objective, Pose2, StateSpace};
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering as AtomicOrdering};

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

/// An edge: undirected (the motion `a → b` and its reverse are one motion, as for
/// symmetric spaces), or the directed motion `a → b` on a directed roadmap.
#[derive(Clone, Copy, Debug)]
pub struct Edge {
    /// One end (where a directed edge starts).
    pub a: u32,
    /// The other end (where a directed edge ends).
    pub b: u32,
    /// The objective's cost of the motion from `a` to `b` (the adjacency lists hold each
    /// direction's cost).
    pub cost: f64,
    /// Cached validity.
    pub validity: Validity,
}

/// The roadmap graph.
pub struct Roadmap {
    /// Unique among the roadmaps of this process (keys [`AStar`]'s heuristic cache).
    id: u64,
    poses: Vec<Pose2>,
    vertex_validity: Vec<Validity>,
    /// Edges leaving each vertex (every incident edge when undirected).
    adjacency: Vec<Vec<(u32, u32)>>,
    /// On a directed roadmap, the edges entering each vertex (empty lists otherwise).
    incoming: Vec<Vec<u32>>,
    /// Whether each motion and its reverse are separate edges (asymmetric spaces).
    directed: bool,
    /// Whether some edge costs differ by direction (then repairs search afresh).
    asymmetric_costs: bool,
    /// Longest connection (space distance); `INFINITY`: the k nearest at any distance.
    range: f64,
    /// The costs of the edges in `adjacency`, in the same order (read by the searches
    /// without touching the edge array).
    adjacent_costs: Vec<Vec<f64>>,
    edges: Vec<Edge>,
    /// Each edge's validity as in `edges`, one byte per edge: the searches read it for
    /// every neighbour they consider, and the edge array (24 bytes per edge) does not
    /// stay in the cache on big roadmaps.
    edge_validity: Vec<Validity>,
    grid: XyGrid,
    by_pose: HashMap<[u64; 3], u32>,
    components: UnionFind,
    components_stale: bool,
    live_edges: usize,
    /// Edges and vertices removed so far (a search's distances stay exact while it
    /// does not change).
    removals: u64,
}

impl Roadmap {
    /// An empty roadmap over `bounds`.
    pub fn new(bounds: Bounds2) -> Self {
        static NEXT_ID: AtomicU64 = AtomicU64::new(0);
        let [w, h] = bounds.extent();
        Self {
            id: NEXT_ID.fetch_add(1, AtomicOrdering::Relaxed),
            poses: Vec::new(),
            vertex_validity: Vec::new(),
            adjacency: Vec::new(),
            incoming: Vec::new(),
            directed: false,
            asymmetric_costs: false,
            range: f64::INFINITY,
            adjacent_costs: Vec::new(),
            edges: Vec::new(),
            edge_validity: Vec::new(),
            grid: XyGrid::new(bounds, (w.max(h) / 8.0).max(1e-3)),
            by_pose: HashMap::new(),
            components: UnionFind::default(),
            components_stale: false,
            live_edges: 0,
            removals: 0,
        }
    }

    /// The same roadmap with directed edges (for asymmetric spaces, whose motion `b → a`
    /// is not `a → b` reversed): each connection adds both motions as separate edges,
    /// checked and removed on their own. Call before adding vertices.
    pub fn with_directed_edges(mut self, directed: bool) -> Self {
        self.directed = directed;
        self
    }

    /// The same roadmap connecting vertices only to neighbours within `range` (space
    /// distance; OMPL's LazyPRM range). Call before adding vertices.
    pub fn with_range(mut self, range: f64) -> Self {
        self.range = range;
        self
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
        self.set_edge_validity(e, Validity::Valid);
    }

    /// True when edge `e` is known valid (as `edge(e).validity == Valid`, from a
    /// compact copy).
    pub fn edge_known_valid(&self, e: u32) -> bool {
        self.edge_validity[e as usize] == Validity::Valid
    }

    /// What is known about edge `e` (as `edge(e).validity`, from a compact copy).
    pub fn edge_validity(&self, e: u32) -> Validity {
        self.edge_validity[e as usize]
    }

    /// Sets what is known about edge `e` (in the edge and its compact copy).
    fn set_edge_validity(&mut self, e: u32, validity: Validity) {
        self.edges[e as usize].validity = validity;
        self.edge_validity[e as usize] = validity;
    }

    /// The vertex at exactly `pose`, if there is one.
    pub fn find(&self, pose: &Pose2) -> Option<u32> {
        self.by_pose.get(&pose_key(pose)).copied()
    }

    /// Adds a vertex with known `validity` and connects it to its `k` nearest live
    /// vertices under `space` (`w_t`: its xy lower-bound weight), with edge costs from
    /// `objective` in each direction; returns its id.
    pub fn add_vertex(
        &mut self,
        pose: Pose2,
        validity: Validity,
        k: usize,
        (space, w_t): (&dyn StateSpace, f64),
        objective: &dyn Objective,
    ) -> u32 {
        let id = self.poses.len() as u32;
        let neighbours = self
            .grid
            .k_nearest(&pose, k, &self.poses, space, w_t, self.range, None);
        self.poses.push(pose);
        self.vertex_validity.push(validity);
        // Later vertices connect to this one too: room for about as many again.
        let capacity = 2 * neighbours.len() + 4;
        self.adjacency.push(Vec::with_capacity(capacity));
        self.adjacent_costs.push(Vec::with_capacity(capacity));
        self.incoming.push(Vec::new());
        self.components.push();
        self.grid.insert(id, &pose, &self.poses);
        self.by_pose.insert(pose_key(&pose), id);
        // On a directed roadmap the reverse edge is another motion: cost it on its own.
        let symmetric = objective.is_symmetric() && !self.directed;
        for n in neighbours {
            let other = self.poses[n.id as usize];
            let there = objective.motion_cost(&pose, &other);
            let back = if symmetric {
                there
            } else {
                objective.motion_cost(&other, &pose)
            };
            self.asymmetric_costs |= there != back;
            if self.directed {
                self.add_directed_edge(id, n.id, there);
                self.add_directed_edge(n.id, id, back);
            } else {
                self.add_edge(id, n.id, there, back);
            }
        }
        id
    }

    /// Adds the directed edge (motion) `a → b` with its cost.
    fn add_directed_edge(&mut self, a: u32, b: u32, cost: f64) {
        let e = self.edges.len() as u32;
        self.edges.push(Edge {
            a,
            b,
            cost,
            validity: Validity::Unknown,
        });
        self.edge_validity.push(Validity::Unknown);
        self.adjacency[a as usize].push((b, e));
        self.adjacent_costs[a as usize].push(cost);
        self.incoming[b as usize].push(e);
        self.components.union(a, b);
        self.live_edges += 1;
    }

    /// Adds the edge `a — b` with the costs of `a → b` and `b → a`.
    fn add_edge(&mut self, a: u32, b: u32, there: f64, back: f64) {
        let e = self.edges.len() as u32;
        self.edges.push(Edge {
            a,
            b,
            cost: there,
            validity: Validity::Unknown,
        });
        self.edge_validity.push(Validity::Unknown);
        self.adjacency[a as usize].push((b, e));
        self.adjacency[b as usize].push((a, e));
        self.adjacent_costs[a as usize].push(there);
        self.adjacent_costs[b as usize].push(back);
        self.components.union(a, b);
        self.live_edges += 1;
    }

    /// Removes edge `e` (found invalid).
    pub fn remove_edge(&mut self, e: u32) {
        let edge = self.edges[e as usize];
        if edge.validity == Validity::Invalid {
            return;
        }
        self.set_edge_validity(e, Validity::Invalid);
        let (a, b) = (edge.a, edge.b);
        for v in [a, b] {
            let list = &mut self.adjacency[v as usize];
            if let Some(k) = list.iter().position(|&(_, id)| id == e) {
                list.swap_remove(k);
                self.adjacent_costs[v as usize].swap_remove(k);
            }
        }
        let entering = &mut self.incoming[b as usize];
        if let Some(k) = entering.iter().position(|&id| id == e) {
            entering.swap_remove(k);
        }
        self.live_edges -= 1;
        self.removals += 1;
        self.components_stale = true;
    }

    /// Removes vertex `v` (found invalid) and all its edges.
    pub fn remove_vertex(&mut self, v: u32) {
        if self.vertex_validity[v as usize] == Validity::Invalid {
            return;
        }
        self.vertex_validity[v as usize] = Validity::Invalid;
        let incident: Vec<u32> = self.adjacency[v as usize]
            .iter()
            .map(|&(_, e)| e)
            .chain(self.incoming[v as usize].iter().copied())
            .collect();
        for e in incident {
            self.remove_edge(e);
        }
        let pose = self.poses[v as usize];
        self.grid.remove(v, &pose);
        self.by_pose.remove(&pose_key(&pose));
        self.removals += 1;
        self.components_stale = true;
    }

    /// True when `a` and `b` may be connected (exact once components are refreshed).
    pub fn maybe_connected(&mut self, a: u32, b: u32) -> bool {
        self.components.find(a) == self.components.find(b)
    }

    /// The number of vertices in `v`'s connected component (exact once components are
    /// refreshed; removed vertices are components of their own).
    pub fn component_size(&mut self, v: u32) -> usize {
        let root = self.components.find(v);
        self.components.size[root as usize] as usize
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

    /// Neighbours of `v` as `(neighbour, edge id, edge cost)`, in [`Roadmap::neighbours`]
    /// order, without looking the costs up in the edge array.
    fn neighbours_with_costs(&self, v: u32) -> impl Iterator<Item = (u32, u32, f64)> + '_ {
        let v = v as usize;
        self.adjacency[v]
            .iter()
            .zip(&self.adjacent_costs[v])
            .map(|(&(w, e), &cost)| (w, e, cost))
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
