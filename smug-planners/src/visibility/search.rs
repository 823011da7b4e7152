//! The tangent graph of the `visibility` planner, built lazily corner by corner and
//! shared by every query, and its exact search (A* for one goal, Dijkstra for many).
//!
//! A shortest path of a disc of radius `r` among blocked grid cells is a chain of
//! straight segments tangent to the circles of radius `r` around the convex corners of
//! the blocked cells, joined by arcs of those circles. A graph node is a *departure*:
//! a point of a corner's circle where a tangent segment leaves it, in one travel
//! direction (lane). A node continues along its lane's arc to the next departure, or
//! along its segment to the circle it arrives at, where it continues on the arc (in the
//! arrival's lane) to the first departure at or after the arrival point. Arcs stay in
//! the corner's quarter circle, where the inflated obstacle's boundary is that circle.

use super::geometry::{circle_tangents, dist, point_tangents, Grid, Lane, Pt};
use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};

/// A tangent segment leaving a corner's circle.
#[derive(Clone, Copy, Debug)]
pub struct Departure {
    /// Angle of the departure point relative to the corner's quadrant.
    pub rel: f64,
    /// The departure point.
    pub point: Pt,
    /// The corner the segment arrives at.
    pub to: u32,
    /// Angle of the arrival point relative to that corner's quadrant.
    pub arrive_rel: f64,
    /// The lane the segment arrives in.
    pub arrive_lane: Lane,
    /// Segment length.
    pub len: f64,
    /// True when the lane has a next departure and the arc on to it is clear (always
    /// for discs below half a cell, whose arcs no other cell can reach).
    pub to_next: bool,
}

/// Where a built corner's departures sit among the nodes: its counter-clockwise lane
/// from `first`, then its clockwise lane, each in travel order.
#[derive(Clone, Copy, Debug, Default)]
struct Lanes {
    first: u32,
    ccw: u32,
    cw: u32,
}

impl Lanes {
    /// The node ids of `lane`.
    fn range(&self, lane: Lane) -> std::ops::Range<usize> {
        let start = self.first as usize
            + match lane {
                Lane::Ccw => 0,
                Lane::Cw => self.ccw as usize,
            };
        let len = match lane {
            Lane::Ccw => self.ccw,
            Lane::Cw => self.cw,
        } as usize;
        start..start + len
    }
}

/// Where a path to a node or goal came from.
#[derive(Clone, Copy, Debug)]
enum Src {
    Start,
    Node(u32),
}

/// How a node was reached.
#[derive(Clone, Copy, Debug)]
enum Via {
    /// Along the arc from the previous departure of the same lane.
    Chain(u32),
    /// Along a segment from `from`, arriving at angle `rel_in`, then along the arc.
    Tangent { from: Src, rel_in: f64 },
}

/// How a goal was reached: directly from the start, or from an arrival at a corner
/// (`from`, at `rel_in`), along its arc to the exit at `rel_out`, then straight.
#[derive(Clone, Copy, Debug)]
struct GoalVia {
    from: Src,
    exit: Option<(u32, Lane, f64, f64)>,
}

/// A segment from a corner's circle straight to a goal.
#[derive(Clone, Copy, Debug)]
struct Exit {
    goal: usize,
    lane: Lane,
    rel: f64,
    len: f64,
}

/// One piece of a path around a corner: along its circle in `lane` from `rel_in` to `rel_out`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Visit {
    /// The corner.
    pub corner: u32,
    /// Arrival angle (relative).
    pub rel_in: f64,
    /// Departure angle (relative).
    pub rel_out: f64,
}

/// A shortest path: its length (arcs exact) and the corners it wraps.
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    /// Exact length, grid units.
    pub length: f64,
    /// The arcs, in order.
    pub visits: Vec<Visit>,
}

/// Counters of the graph.
#[derive(Clone, Copy, Debug, Default)]
pub struct GraphCounts {
    /// Corners whose departures are built.
    pub corners_built: u64,
    /// Departures (graph nodes).
    pub departures: u64,
    /// Segment clearance checks.
    pub segment_checks: u64,
    /// Nodes expanded by searches.
    pub expansions: u64,
}

#[derive(Clone, Copy, PartialEq)]
struct Entry {
    f: f64,
    g: f64,
    id: u32,
}

impl Eq for Entry {}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .f
            .total_cmp(&self.f)
            .then_with(|| other.id.cmp(&self.id))
    }
}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// The lazily built tangent graph of one grid and one radius.
#[derive(Debug)]
pub struct TangentGraph {
    /// The grid.
    pub grid: Grid,
    /// Radius of the circles (grid units), slightly above the robot's.
    pub r: f64,
    /// Clearance every segment must keep (grid units): the robot's radius plus a margin.
    pub r_check: f64,
    /// True when arcs may come near cells other than their corner's (radius about half
    /// a cell or more): arcs are then checked too.
    pub big: bool,
    lanes: Vec<Option<Lanes>>,
    /// Every node's departure, corner by corner.
    nodes: Vec<Departure>,
    /// Corner of each node.
    node_corner: Vec<u32>,
    stamp_corner: Vec<u32>,
    stamp: u32,
    // Per-query search state, indexed by node.
    query: u32,
    node_query: Vec<u32>,
    cost: Vec<f64>,
    via: Vec<Via>,
    /// Counters.
    pub counts: GraphCounts,
}

impl TangentGraph {
    /// The graph of `grid` for circles of radius `r`, segments keeping clearance `r_check`.
    pub fn new(grid: Grid, r: f64, r_check: f64) -> Self {
        let n = grid.corners.len();
        Self {
            grid,
            r,
            r_check,
            big: r + r_check > 1.0 - 1e-6,
            lanes: vec![None; n],
            nodes: Vec::new(),
            node_corner: Vec::new(),
            stamp_corner: vec![0; n],
            stamp: 0,
            query: 0,
            node_query: Vec::new(),
            cost: Vec::new(),
            via: Vec::new(),
            counts: GraphCounts::default(),
        }
    }

    /// The tangent points `p` on the circles of the corners `q` may see whose segment
    /// to `q` is clear by `need` (`segment_clear` is symmetric, so this serves segments
    /// into and out of `q`): `(corner, unit normal at p, angle relative to the corner,
    /// p)`, in corner and tangent order.
    fn clear_tangents(&mut self, q: Pt, need: f64) -> Vec<(u32, Pt, f64, Pt)> {
        let mut tangents = Vec::new();
        for c in self.visible_corners(q, None) {
            let corner = self.grid.corners[c as usize];
            for n in point_tangents(q, corner.at, self.r) {
                let Some(rel) = corner.relative_angle(n) else {
                    continue;
                };
                let p = [corner.at[0] + self.r * n[0], corner.at[1] + self.r * n[1]];
                self.counts.segment_checks += 1;
                if self.grid.segment_clear(q, p, need) {
                    tangents.push((c, n, rel, p));
                }
            }
        }
        tangents
    }

    /// The corners a point may see (a superset of those it sees), without `skip`.
    fn visible_corners(&mut self, s: Pt, skip: Option<u32>) -> Vec<u32> {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.stamp_corner.fill(0);
            self.stamp = 1;
        }
        let mut found = Vec::new();
        let (grid, stamps, stamp) = (&self.grid, &mut self.stamp_corner, self.stamp);
        grid.visible_cells(s, |i, j| {
            for (x, y) in [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)] {
                if let Some(c) = grid.corner_at(x, y) {
                    if stamps[c as usize] != stamp && Some(c) != skip {
                        stamps[c as usize] = stamp;
                        found.push(c);
                    }
                }
            }
        });
        found
    }

    /// Builds corner `a`'s departures (once).
    pub fn build_corner(&mut self, a: u32) {
        if self.lanes[a as usize].is_some() {
            return;
        }
        let ca = self.grid.corners[a as usize];
        let mut lanes: [Vec<Departure>; 2] = [Vec::new(), Vec::new()];
        for b in self.visible_corners(ca.at, Some(a)) {
            let cb = self.grid.corners[b as usize];
            for (na, nb) in circle_tangents(ca.at, cb.at, self.r) {
                let (Some(rel_a), Some(rel_b)) = (ca.relative_angle(na), cb.relative_angle(nb))
                else {
                    continue;
                };
                let pa = [ca.at[0] + self.r * na[0], ca.at[1] + self.r * na[1]];
                let pb = [cb.at[0] + self.r * nb[0], cb.at[1] + self.r * nb[1]];
                self.counts.segment_checks += 1;
                if !self.grid.segment_clear(pa, pb, self.r_check) {
                    continue;
                }
                let t = [pb[0] - pa[0], pb[1] - pa[1]];
                lanes[Lane::of(na, t).index()].push(Departure {
                    rel: rel_a,
                    point: pa,
                    to: b,
                    arrive_rel: rel_b,
                    arrive_lane: Lane::of(nb, t),
                    len: dist(pa, pb),
                    to_next: true,
                });
            }
        }
        lanes[0].sort_by(|x, y| x.rel.total_cmp(&y.rel));
        lanes[1].sort_by(|x, y| y.rel.total_cmp(&x.rel));
        for list in &mut lanes {
            let n = list.len();
            for k in 0..n {
                list[k].to_next = k + 1 < n
                    && (!self.big
                        || self.grid.arc_clear(
                            &ca,
                            self.r,
                            list[k].rel,
                            list[k + 1].rel,
                            self.r_check,
                        ));
            }
        }
        let entry = Lanes {
            first: self.nodes.len() as u32,
            ccw: lanes[0].len() as u32,
            cw: lanes[1].len() as u32,
        };
        let count = lanes[0].len() + lanes[1].len();
        let [ccw, cw] = lanes;
        self.nodes.extend(ccw);
        self.nodes.extend(cw);
        self.node_corner.extend(std::iter::repeat_n(a, count));
        self.node_query.resize(self.nodes.len(), 0);
        self.cost.resize(self.nodes.len(), f64::INFINITY);
        self.via.resize(self.nodes.len(), Via::Chain(0));
        self.counts.corners_built += 1;
        self.counts.departures += count as u64;
        self.lanes[a as usize] = Some(entry);
    }

    /// Builds every corner.
    pub fn build_all(&mut self) {
        for a in 0..self.grid.corners.len() as u32 {
            self.build_corner(a);
        }
    }

    fn lanes(&self, c: u32) -> Lanes {
        self.lanes[c as usize].expect("corner built")
    }

    /// The first departure of `lane` at corner `c` at or after `rel` in travel order:
    /// its node id and angle.
    fn first_after(&self, c: u32, lane: Lane, rel: f64) -> Option<(u32, f64)> {
        let range = self.lanes(c).range(lane);
        let list = &self.nodes[range.clone()];
        let k = match lane {
            Lane::Ccw => list.partition_point(|d| d.rel < rel),
            Lane::Cw => list.partition_point(|d| d.rel > rel),
        };
        list.get(k).map(|d| ((range.start + k) as u32, d.rel))
    }

    fn node_cost(&self, id: u32) -> f64 {
        if self.node_query[id as usize] == self.query {
            self.cost[id as usize]
        } else {
            f64::INFINITY
        }
    }

    /// The exact shortest paths from `s` to each of `goals` (grid units), with the
    /// clearance of the endpoints (`clear_s`, `clear_goals`, the distance to the
    /// nearest blocked cell, which segments touching them need not exceed). `None` for
    /// a goal no path reaches: the whole graph reachable from `s` was searched, so
    /// none exists.
    pub fn shortest(&mut self, s: Pt, clear_s: f64, goals: &[(Pt, f64)]) -> Vec<Option<Route>> {
        self.query = self.query.wrapping_add(1);
        if self.query == 0 {
            self.node_query.fill(0);
            self.query = 1;
        }
        let single = goals.len() == 1;
        let h = |p: Pt| if single { dist(p, goals[0].0) } else { 0.0 };
        // Exits: segments from corners straight to each goal.
        let mut exits: HashMap<u32, Vec<Exit>> = HashMap::new();
        for (k, &(g, clear_g)) in goals.iter().enumerate() {
            for (c, n, rel, p) in self.clear_tangents(g, self.r_check.min(clear_g)) {
                let t = [g[0] - p[0], g[1] - p[1]];
                exits.entry(c).or_default().push(Exit {
                    goal: k,
                    lane: Lane::of(n, t),
                    rel,
                    len: dist(p, g),
                });
            }
        }
        let goal_base = u32::MAX - goals.len() as u32;
        let mut goal_cost = vec![f64::INFINITY; goals.len()];
        let mut goal_via: Vec<Option<GoalVia>> = vec![None; goals.len()];
        let mut goal_done = vec![false; goals.len()];
        let mut heap = BinaryHeap::new();
        for (k, &(g, clear_g)) in goals.iter().enumerate() {
            self.counts.segment_checks += 1;
            if self
                .grid
                .segment_clear(s, g, self.r_check.min(clear_s).min(clear_g))
            {
                goal_cost[k] = dist(s, g);
                goal_via[k] = Some(GoalVia {
                    from: Src::Start,
                    exit: None,
                });
                heap.push(Entry {
                    f: goal_cost[k],
                    g: goal_cost[k],
                    id: goal_base + k as u32,
                });
            }
        }
        // Segments from the start to the corners it sees.
        for (c, n, rel, p) in self.clear_tangents(s, self.r_check.min(clear_s)) {
            let t = [p[0] - s[0], p[1] - s[1]];
            let arrival = (c, Lane::of(n, t), rel);
            let g0 = dist(s, p);
            self.arrive(
                arrival,
                g0,
                Src::Start,
                &exits,
                &h,
                &mut heap,
                |k, cost, via| {
                    if cost < goal_cost[k] {
                        goal_cost[k] = cost;
                        goal_via[k] = Some(via);
                        true
                    } else {
                        false
                    }
                },
                goal_base,
            );
        }
        let mut left = goals.len();
        while let Some(Entry { g, id, .. }) = heap.pop() {
            if id >= goal_base {
                let k = (id - goal_base) as usize;
                if !goal_done[k] && g <= goal_cost[k] {
                    goal_done[k] = true;
                    left -= 1;
                    if left == 0 {
                        break;
                    }
                }
                continue;
            }
            if g > self.node_cost(id) {
                continue;
            }
            self.counts.expansions += 1;
            let dep = self.nodes[id as usize];
            // Along the arc to the next departure of the lane.
            if dep.to_next {
                let rel = self.nodes[id as usize + 1].rel;
                let cost = g + self.r * (rel - dep.rel).abs();
                self.relax(id + 1, cost, Via::Chain(id), &h, &mut heap);
            }
            // Along the segment, then the arc at the corner it arrives at.
            self.arrive(
                (dep.to, dep.arrive_lane, dep.arrive_rel),
                g + dep.len,
                Src::Node(id),
                &exits,
                &h,
                &mut heap,
                |k, cost, via| {
                    if cost < goal_cost[k] {
                        goal_cost[k] = cost;
                        goal_via[k] = Some(via);
                        true
                    } else {
                        false
                    }
                },
                goal_base,
            );
        }
        (0..goals.len())
            .map(|k| {
                goal_done[k].then(|| Route {
                    length: goal_cost[k],
                    visits: self.visits(goal_via[k].expect("reached goal has a via")),
                })
            })
            .collect()
    }

    fn relax(
        &mut self,
        id: u32,
        cost: f64,
        via: Via,
        h: &impl Fn(Pt) -> f64,
        heap: &mut BinaryHeap<Entry>,
    ) {
        if cost < self.node_cost(id) {
            let i = id as usize;
            self.node_query[i] = self.query;
            self.cost[i] = cost;
            self.via[i] = via;
            let point = self.nodes[i].point;
            heap.push(Entry {
                f: cost + h(point),
                g: cost,
                id,
            });
        }
    }

    /// Arrives at corner `c` in `lane` at angle `rel_in` with cost `g0`: continues to
    /// the lane's first departure at or after it, and to every exit at or after it.
    #[allow(clippy::too_many_arguments)]
    fn arrive(
        &mut self,
        (c, lane, rel_in): (u32, Lane, f64),
        g0: f64,
        from: Src,
        exits: &HashMap<u32, Vec<Exit>>,
        h: &impl Fn(Pt) -> f64,
        heap: &mut BinaryHeap<Entry>,
        mut reach_goal: impl FnMut(usize, f64, GoalVia) -> bool,
        goal_base: u32,
    ) {
        self.build_corner(c);
        let corner = self.grid.corners[c as usize];
        let arc_clear = |graph: &Self, to: f64| {
            !graph.big
                || graph
                    .grid
                    .arc_clear(&corner, graph.r, rel_in, to, graph.r_check)
        };
        if let Some((id, rel)) = self
            .first_after(c, lane, rel_in)
            .filter(|&(_, rel)| arc_clear(self, rel))
        {
            let cost = g0 + self.r * (rel - rel_in).abs();
            self.relax(id, cost, Via::Tangent { from, rel_in }, h, heap);
        }
        for e in exits.get(&c).into_iter().flatten() {
            let ahead = match lane {
                Lane::Ccw => e.rel >= rel_in,
                Lane::Cw => e.rel <= rel_in,
            };
            if e.lane != lane || !ahead || !arc_clear(self, e.rel) {
                continue;
            }
            let cost = g0 + self.r * (e.rel - rel_in).abs() + e.len;
            let via = GoalVia {
                from,
                exit: Some((c, lane, rel_in, e.rel)),
            };
            if reach_goal(e.goal, cost, via) {
                heap.push(Entry {
                    f: cost,
                    g: cost,
                    id: goal_base + e.goal as u32,
                });
            }
        }
    }

    /// The arcs of the path that reached a goal through `via`, in order.
    fn visits(&self, via: GoalVia) -> Vec<Visit> {
        let mut out = Vec::new();
        if let Some((corner, _, rel_in, rel_out)) = via.exit {
            out.push(Visit {
                corner,
                rel_in,
                rel_out,
            });
        }
        let mut cur = via.from;
        let mut pending: Option<f64> = None;
        while let Src::Node(id) = cur {
            let rel = self.nodes[id as usize].rel;
            let out_rel = *pending.get_or_insert(rel);
            match self.via[id as usize] {
                Via::Chain(prev) => cur = Src::Node(prev),
                Via::Tangent { from, rel_in } => {
                    out.push(Visit {
                        corner: self.node_corner[id as usize],
                        rel_in,
                        rel_out: out_rel,
                    });
                    pending = None;
                    cur = from;
                }
            }
        }
        out.reverse();
        out
    }
}
