//! The parameters of LazyPRM* (`[planner] params` of `lazy-prm-star`).

use serde::{Deserialize, Serialize};

/// How a solution attempt searches the roadmap.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SearchMode {
    /// Classic LazyPRM: A*, check the path, remove what is invalid, search again.
    LazySp,
    /// Lazy Weighted A*: one search checking an edge when its vertex is expanded
    /// (far fewer searches in cluttered maps, a few more edge checks in open ones).
    LazyWeighted,
    /// A few LazySP rounds, then Lazy Weighted A* if the path keeps breaking.
    #[default]
    Auto,
}

/// Parameters of LazyPRM*.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LazyPrmStarParams {
    /// Stop after this many solution attempts in a row without enough improvement
    /// (the reference code's `max_stall`).
    pub max_stall: u32,
    /// Relative improvement that resets the stall count (0.02: the reference's 0.98 factor).
    pub improvement: f64,
    /// Valid samples added between solution attempts once a path is known (at least).
    pub attempt_every: u32,
    /// Once a query has its first path, attempts are spaced by `attempt_share` × the
    /// samples the query drew to find it, if more than `attempt_every`: a query that
    /// had to grow the roadmap a lot to connect start and goal (a sparse roadmap on a
    /// cluttered map) gives its improvement rounds a comparable share, instead of
    /// accepting its first, detouring path after a handful of samples. Queries that
    /// find their path on the roadmap as it is (a mission's dense shared roadmap) are
    /// not affected. 0: every `attempt_every` samples (the reference code).
    pub attempt_share: f64,
    /// The initial excess of a query's focus: the informed set of a provisional cost
    /// `(1 + excess) ×` its straight-line cost, the excess doubling every few samples
    /// (a share of the roadmap, as the wait between failed first attempts). Until the
    /// focus covers the query's informed set (no path yet, or the best path costs more
    /// than the provisional cost), every other sample is drawn in it and attempts do
    /// not count as stalled: a short query on a big map densifies its own
    /// neighbourhood first, and a detour found on a sparse shared roadmap is not
    /// accepted before samples near the straight line had their chance. Queries whose
    /// path costs at most `(1 + focus) ×` the straight line are not affected.
    /// 0 (default): no focus (the reference code).
    pub focus: f64,
    /// Samples drawn per query at most (the query's sample budget).
    pub max_samples: u64,
    /// Seconds per query at most (absent: no time budget; runs stay reproducible).
    pub time_limit: Option<f64>,
    /// Samples added before the first query (a pre-built roadmap).
    pub initial_samples: u64,
    /// Check vertices lazily, only when on a candidate path (default: check each
    /// sample when drawn and keep only valid ones, as the reference code does).
    pub lazy_vertices: bool,
    /// Shortcut returned paths (never raises cost, never makes a path invalid).
    pub shortcut: bool,
    /// Smooth returned paths: rounds of shortcutting and corner cutting, which pull a
    /// path taut around corners (never raises cost, never makes a path invalid; more
    /// motion checks than `shortcut` alone, which it implies).
    pub smooth: bool,
    /// How attempts search: `lazy-sp`, `lazy-weighted` or `auto`.
    pub search: SearchMode,
    /// Once a path is known, an attempt repairs the previous search for the vertices
    /// added since (incremental A*: only the distances they improve are searched)
    /// instead of searching again; the paths are the same, found faster. Off only to
    /// compare.
    pub incremental_attempts: bool,
    /// Longest roadmap connection in space distance (OMPL's LazyPRM `range`): a new
    /// vertex connects to its k nearest within it. Absent: no limit. Curvature-limited
    /// models need one: their k-th nearest is a turn-around away, so unlimited
    /// connections reach across the map.
    pub range: Option<f64>,
    /// A query without a path after this many samples starts expanding its endpoints:
    /// samples along the motion model's curves out of the start and into the goal (see
    /// `expand_share`). Queries that find a path sooner are unaffected.
    pub expand_after: u64,
    /// The share of a query's samples expanded from its endpoints once `expand_after`
    /// passed without a path (0: never): each endpoint grows a tree of valid samples
    /// along the model's own curves, which reaches poses that uniform samples seldom
    /// connect (a car parked facing a rock, a narrow door). In [0, 1].
    pub expand_share: f64,
    /// How far an expansion sample reaches from its tree, metres (its curve's target
    /// is drawn within this distance).
    pub expand_reach: f64,
    /// Once `expand_after` samples passed without a path, each invalid sample becomes
    /// a bridge attempt (module `bridge`): a second pose a Gaussian step of
    /// this standard deviation away (metres; 0: no bridges), and when that is invalid
    /// too, the pose halfway between them, kept when valid — the narrow passages
    /// (a doorway, the gap a new rock leaves beside a wall) uniform samples seldom hit.
    /// Queries that find a path sooner are unaffected.
    pub bridge_sigma: f64,
    /// Retry query endpoints found cut off: when a query ends without a path, the
    /// endpoint whose roadmap component is the smaller one (less than half the roadmap:
    /// a pocket the robot could not leave or enter within the budget) is cut off, and
    /// later queries from or to any pose of its pocket (its component, while that holds
    /// less than half the roadmap) to a pose outside answer "no path" at once: every
    /// PoI of a room a car cannot leave fails once, not once each. True: every query
    /// spends its whole budget again.
    pub retry_cut_off: bool,
    /// Answer a source's many goals (a cost-matrix row, a DP layer) with one search:
    /// one Dijkstra search on the shared roadmap settles every goal it connects, each
    /// path checked lazily as a query's attempt would (re-searched where a check
    /// fails); only goals it does not connect are planned as queries of their own.
    /// The paths are the roadmap's cheapest valid ones, as a query finds them before
    /// its improvement rounds. False: one query per goal (improvement rounds included).
    pub one_to_many: bool,
    /// Before its first one-to-many search, the roadmap grows by this many samples per
    /// square metre of the world's bounds (at most `max_samples`): one search answers
    /// many goals without the improvement rounds that densify a query's roadmap, so
    /// the roadmap it searches is made dense first (uniform samples).
    pub one_to_many_density: f64,
    /// For a disc on a grid (a checker that says so), the roadmap starts with one
    /// vertex beside each convex corner of the blocked cells
    /// ([`corner_waypoints`](crate::grid_disc::corner_waypoints)):
    /// shortest paths bend there, so the roadmap holds every door and every side of
    /// every obstacle before the first sample. At most `max_corner_vertices` of them
    /// (evenly thinned on bigger maps). Other checkers, and curved motion models (a
    /// car's heading at a corner matters as much as its place): no effect.
    pub corner_vertices: bool,
    /// The budget of corner and corridor vertices (`corner_vertices`), apart from the
    /// queries' `max_samples`: a maze's corners fill its corridors without eating a
    /// query's samples, and a map with more of them keeps this many, evenly thinned
    /// (the roadmap's memory check counts them).
    pub max_corner_vertices: u64,
}

impl Default for LazyPrmStarParams {
    fn default() -> Self {
        Self {
            max_stall: 3,
            improvement: 0.02,
            attempt_every: 5,
            attempt_share: 0.0,
            focus: 0.0,
            max_samples: 20_000,
            time_limit: None,
            initial_samples: 0,
            lazy_vertices: false,
            shortcut: false,
            smooth: false,
            search: SearchMode::Auto,
            incremental_attempts: true,
            range: None,
            expand_after: 500,
            expand_share: 0.5,
            expand_reach: 3.0,
            bridge_sigma: 1.0,
            retry_cut_off: false,
            one_to_many: true,
            one_to_many_density: 4.0,
            corner_vertices: true,
            max_corner_vertices: 1_000_000,
        }
    }
}
