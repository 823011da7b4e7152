//! The tangent graph of the `visibility` planner, built lazily corner by corner and
//! shared by every query, and its exact search (A* towards the nearest goal; Dijkstra
//! for more than 64 goals).
//!
//! A shortest path of a disc of radius `r` among blocked grid cells is a chain of
//! straight segments tangent to the circles of radius `r` around the convex corners of
//! the blocked cells, joined by arcs of those circles. A graph node is a *departure*:
//! a point of a corner's circle where a tangent segment leaves it, in one travel
//! direction (lane). A node continues along its lane's arc to the next departure, or
//! along its segment to the circle it arrives at, where it continues on the arc (in the
//! arrival's lane) to the first departure at or after the arrival point. Arcs stay in
//! the corner's quarter circle, where the inflated obstacle's boundary is that circle.

mod build;

use super::geometry::{circle_tangents, dist, point_tangents, Grid, Lane, Pt};
use super::shadow::Lines;
use super::staircase::{hidden_corners, Pocket};
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

/// Where a path to a node or goal came from: the start or a node.
#[derive(Clone, Copy, Debug)]
enum Src {
    Start,
    Node(u32),
}

/// How a node was reached, packed in a `u32`: [`VIA_CHAIN`] along the arc from the
/// previous departure of the same lane (node `id − 1`); `START | k` along the start's
/// `k`-th segment, then the arc; else along the segment of that node, then the arc.
type Via = u32;

/// See [`Via`].
const VIA_CHAIN: Via = u32::MAX;

/// See [`Via`].
const VIA_START: Via = 1 << 31;

/// Goals of one query up to which the search is A* towards the nearest (beyond:
/// Dijkstra, the heuristic's cost per node growing with the goals).
const MAX_AIMED_GOALS: usize = 64;

/// Angles within this (radians) of an arrival count as at it.
const REL_TOL: f64 = 1e-12;

/// Greatest common divisor.
fn gcd(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// A node's successor not computed yet (see `TangentGraph::successor`).
const SUCC_UNSET: u32 = u32::MAX - 1;

/// A node without a successor along its segment.
const SUCC_NONE: u32 = u32::MAX;

/// What the search reads and writes of a node, in one cache line: its edges (the
/// arc to the lane's next departure, the segment and arc to its successor) and the
/// current query's state (stale when `query` differs), beside its departure point
/// (the heuristic's input).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Slot {
    point: Pt,
    cost: f64,
    /// Cost along the arc to the lane's next departure (∞ when there is none).
    chain_cost: f64,
    /// Segment plus arc to `succ`.
    succ_cost: f64,
    query: u32,
    via: Via,
    /// The first departure at or after the segment's arrival, in the arrival's lane,
    /// whose arc is clear ([`SUCC_NONE`]: none; [`SUCC_UNSET`]: not computed yet).
    succ: u32,
    /// The corner the node's segment arrives at.
    arrive_at: u32,
}

/// How a goal was reached: directly from the start, or from an arrival at a corner
/// (`from`, at `rel_in`), along its arc to the exit at `rel_out`, then straight.
#[derive(Clone, Copy, Debug)]
struct GoalVia {
    from: Src,
    exit: Option<(u32, Lane, f64, f64)>,
}

/// One query's search: the heap, the goals' costs and how they were reached, the exits.
struct Search {
    /// The goals the heuristic aims at (none: Dijkstra, for many goals).
    targets: Vec<Pt>,
    /// Heap ids from this one on are goals (`goal_base + k`).
    goal_base: u32,
    goal_cost: Vec<f64>,
    goal_via: Vec<Option<GoalVia>>,
    heap: BinaryHeap<Entry>,
    /// The best entry offered since the last pop, held out of the heap: when it comes
    /// before the heap's top it is the next to expand, without a push and a pop (an
    /// expansion's successors often are: arcs are short).
    held: Option<Entry>,
    exits: HashMap<u32, Vec<Exit>>,
}

impl Search {
    /// Offers a node's entry: held if it is the best offered since the last pop.
    fn offer(&mut self, entry: Entry) {
        match self.held {
            Some(held) if held >= entry => self.heap.push(entry),
            Some(held) => {
                self.heap.push(held);
                self.held = Some(entry);
            }
            None => self.held = Some(entry),
        }
    }

    /// The next entry in A* order (least `f`, then least id).
    fn next(&mut self) -> Option<Entry> {
        match self.held.take() {
            Some(held) if self.heap.peek().is_none_or(|top| held >= *top) => Some(held),
            Some(held) => {
                // Swap it with the top: one sift instead of a pop and a push.
                let mut top = self.heap.peek_mut().expect("a top beats the held entry");
                Some(std::mem::replace(&mut *top, held))
            }
            None => self.heap.pop(),
        }
    }

    /// The heuristic: the straight-line distance to the nearest goal (a minimum of
    /// consistent heuristics is consistent, and 0 at every goal); 0 with more than
    /// [`MAX_AIMED_GOALS`] goals.
    fn h(&self, p: Pt) -> f64 {
        let mut best = f64::INFINITY;
        for t in &self.targets {
            let (dx, dy) = (p[0] - t[0], p[1] - t[1]);
            best = best.min(dx * dx + dy * dy);
        }
        if self.targets.is_empty() {
            0.0
        } else {
            best.sqrt()
        }
    }

    /// Goal `k` reached at `cost` from `from` (through `exit` at a corner, or straight).
    fn reach_goal(&mut self, k: usize, cost: f64, from: Src, exit: Option<(u32, Lane, f64, f64)>) {
        if cost < self.goal_cost[k] {
            self.goal_cost[k] = cost;
            self.goal_via[k] = Some(GoalVia { from, exit });
            self.heap.push(Entry {
                f: cost,
                g: cost,
                id: self.goal_base + k as u32,
            });
        }
    }
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
    /// Tangents left out: they pass a corner whose pieces the graph has.
    pub pruned: u64,
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
    /// The grid's bit rows and corner lists, for the shadowcast.
    lines: Lines,
    /// Radius of the circles (grid units), slightly above the robot's.
    pub r: f64,
    /// Clearance every segment must keep (grid units): the robot's radius plus a margin.
    pub r_check: f64,
    /// True when arcs may come near cells other than their corner's (radius about half
    /// a cell or more): arcs are then checked too.
    pub big: bool,
    lanes: Vec<Option<Lanes>>,
    /// Corners in the graph: all but the hidden staircase corners not yet activated.
    active: Vec<bool>,
    /// The hidden corners and their pockets (see `staircase`), until activated.
    hidden: Vec<(u32, Pocket)>,
    /// Every node's departure, corner by corner.
    nodes: Vec<Departure>,
    /// Corner of each node.
    node_corner: Vec<u32>,
    stamp_corner: Vec<u32>,
    stamp: u32,
    // Per-query search state.
    query: u32,
    slot: Vec<Slot>,
    /// Corners with exits to goals in this query (`exit_query[c] == query`).
    exit_query: Vec<u32>,
    /// Arrival angles of the start's segments to corners, this query.
    start_rel: Vec<f64>,
    /// Counters.
    pub counts: GraphCounts,
}

impl TangentGraph {
    /// The graph of `grid` for circles of radius `r`, segments keeping clearance `r_check`;
    /// with `collapse`, hidden staircase corners wait for a query beside them.
    pub fn new(grid: Grid, r: f64, r_check: f64, collapse: bool) -> Self {
        let n = grid.corners.len();
        let hidden: Vec<(u32, Pocket)> = if collapse {
            hidden_corners(&grid, r, r_check)
                .into_iter()
                .enumerate()
                .filter_map(|(c, p)| Some((c as u32, p?)))
                .collect()
        } else {
            Vec::new()
        };
        let mut active = vec![true; n];
        for &(c, _) in &hidden {
            active[c as usize] = false;
        }
        Self {
            active,
            hidden,
            lines: Lines::new(&grid),
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
            slot: Vec::new(),
            exit_query: vec![0; n],
            start_rel: Vec::new(),
            counts: GraphCounts::default(),
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
        // A departure within rounding before the arrival counts as at it: through a
        // corner touched on the way (see `touches_corner_between`) the arrival and the
        // departure are the same point, computed from different vectors.
        let k = match lane {
            Lane::Ccw => list.partition_point(|d| d.rel < rel - REL_TOL),
            Lane::Cw => list.partition_point(|d| d.rel > rel + REL_TOL),
        };
        list.get(k).map(|d| ((range.start + k) as u32, d.rel))
    }

    fn node_cost(&self, id: u32) -> f64 {
        let slot = &self.slot[id as usize];
        if slot.query == self.query {
            slot.cost
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
            for slot in &mut self.slot {
                slot.query = 0;
            }
            self.exit_query.fill(0);
            self.query = 1;
        }
        self.activate_pockets(s, goals);
        let targets: Vec<Pt> = if goals.len() <= MAX_AIMED_GOALS {
            goals.iter().map(|g| g.0).collect()
        } else {
            Vec::new()
        };
        // Exits: segments from corners straight to each goal.
        let mut exits: HashMap<u32, Vec<Exit>> = HashMap::new();
        for (k, &(g, clear_g)) in goals.iter().enumerate() {
            for (c, n, rel, p) in self.clear_tangents(g, self.r_check.min(clear_g)) {
                let t = [g[0] - p[0], g[1] - p[1]];
                self.exit_query[c as usize] = self.query;
                exits.entry(c).or_default().push(Exit {
                    goal: k,
                    lane: Lane::of(n, t),
                    rel,
                    len: dist(p, g),
                });
            }
        }
        let mut search = Search {
            targets,
            goal_base: u32::MAX - goals.len() as u32,
            goal_cost: vec![f64::INFINITY; goals.len()],
            goal_via: vec![None; goals.len()],
            heap: BinaryHeap::new(),
            held: None,
            exits,
        };
        let mut goal_done = vec![false; goals.len()];
        for (k, &(g, clear_g)) in goals.iter().enumerate() {
            self.counts.segment_checks += 1;
            if self
                .grid
                .segment_clear(s, g, self.r_check.min(clear_s).min(clear_g))
            {
                search.reach_goal(k, dist(s, g), Src::Start, None);
            }
        }
        // Segments from the start to the corners it sees.
        self.start_rel.clear();
        for (c, n, rel, p) in self.clear_tangents(s, self.r_check.min(clear_s)) {
            let t = [p[0] - s[0], p[1] - s[1]];
            let k = self.start_rel.len() as u32;
            self.start_rel.push(rel);
            self.build_corner(c);
            let lane = Lane::of(n, t);
            let g0 = dist(s, p);
            let corner = self.grid.corners[c as usize];
            if let Some((id, to)) = self.first_after(c, lane, rel).filter(|&(_, to)| {
                !self.big || self.grid.arc_clear(&corner, self.r, rel, to, self.r_check)
            }) {
                let cost = g0 + self.r * (to - rel).abs();
                self.relax(id, cost, VIA_START | k, &mut search);
            }
            self.exits_at(c, lane, rel, g0, Src::Start, &mut search);
        }
        let mut left = goals.len();
        while let Some(Entry { g, id, .. }) = search.next() {
            if id >= search.goal_base {
                let k = (id - search.goal_base) as usize;
                if !goal_done[k] && g <= search.goal_cost[k] {
                    goal_done[k] = true;
                    left -= 1;
                    if left == 0 {
                        break;
                    }
                }
                continue;
            }
            let i = id as usize;
            if g > self.node_cost(id) {
                continue;
            }
            self.counts.expansions += 1;
            // Along the arc to the next departure of the lane.
            let edges = self.slot[i];
            if edges.chain_cost < f64::INFINITY {
                self.relax(id + 1, g + edges.chain_cost, VIA_CHAIN, &mut search);
            }
            // Along the segment, then the arc at the corner it arrives at: to the
            // first departure at or after the arrival, and to every exit after it.
            let next = match edges.succ {
                SUCC_UNSET => self.successor(id),
                next => next,
            };
            if next != SUCC_NONE {
                self.relax(next, g + self.slot[i].succ_cost, id, &mut search);
            }
            let c = edges.arrive_at;
            if self.exit_query[c as usize] == self.query {
                let dep = self.nodes[i];
                self.exits_at(
                    c,
                    dep.arrive_lane,
                    dep.arrive_rel,
                    g + dep.len,
                    Src::Node(id),
                    &mut search,
                );
            }
        }
        (0..goals.len())
            .map(|k| {
                goal_done[k].then(|| Route {
                    length: search.goal_cost[k],
                    visits: self.visits(search.goal_via[k].expect("reached goal has a via")),
                })
            })
            .collect()
    }

    fn relax(&mut self, id: u32, cost: f64, via: Via, search: &mut Search) {
        let i = id as usize;
        let query = self.query;
        let slot = &mut self.slot[i];
        if slot.query != query || cost < slot.cost {
            slot.cost = cost;
            slot.query = query;
            slot.via = via;
            let f = cost + search.h(slot.point);
            search.offer(Entry { f, g: cost, id });
        }
    }

    /// Arrives at corner `c` in `lane` at angle `rel_in` with cost `g0`: on to every
    /// exit to a goal at or after it.
    fn exits_at(
        &mut self,
        c: u32,
        lane: Lane,
        rel_in: f64,
        g0: f64,
        from: Src,
        search: &mut Search,
    ) {
        let Some(list) = search.exits.get(&c) else {
            return;
        };
        let corner = self.grid.corners[c as usize];
        let mut reached = Vec::new();
        for e in list {
            let ahead = match lane {
                Lane::Ccw => e.rel >= rel_in,
                Lane::Cw => e.rel <= rel_in,
            };
            if e.lane != lane
                || !ahead
                || (self.big
                    && !self
                        .grid
                        .arc_clear(&corner, self.r, rel_in, e.rel, self.r_check))
            {
                continue;
            }
            let cost = g0 + self.r * (e.rel - rel_in).abs() + e.len;
            reached.push((e.goal, cost, (c, lane, rel_in, e.rel)));
        }
        for (goal, cost, exit) in reached {
            search.reach_goal(goal, cost, from, Some(exit));
        }
    }

    /// The arrival angle of a tangent from `from` (a node's segment, or the start's).
    fn rel_in(&self, via: Via) -> f64 {
        if via & VIA_START != 0 {
            self.start_rel[(via & !VIA_START) as usize]
        } else {
            self.nodes[via as usize].arrive_rel
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
            match self.slot[id as usize].via {
                VIA_CHAIN => cur = Src::Node(id - 1),
                from => {
                    out.push(Visit {
                        corner: self.node_corner[id as usize],
                        rel_in: self.rel_in(from),
                        rel_out: out_rel,
                    });
                    pending = None;
                    cur = if from & VIA_START != 0 {
                        Src::Start
                    } else {
                        Src::Node(from)
                    };
                }
            }
        }
        out.reverse();
        out
    }
}
