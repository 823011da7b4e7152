//! `visibility`: exact shortest paths for a disc robot on a 2D occupancy grid under the
//! `path-length` objective on a holonomic SE(2) space.
//!
//! The free space of a disc of radius `r` is the grid's free area minus every blocked
//! cell inflated by `r`; the inflated cells' boundary is made of straight edges and
//! quarter circles of radius `r` around the convex corners of the blocked cells. A
//! shortest path is a chain of segments tangent to those circles, joined by arcs of
//! them (the tangent visibility graph, exact: no sampling, no discretisation). The
//! graph is built lazily, corner by corner (the corners a corner may see come from a
//! conservative shadowcast, each tangent segment's clearance is checked exactly against
//! the cells near it), and shared by every query of the mission; A* answers one goal
//! and one start with many goals ([`PointToPointPlanner::plan_many`]; the heuristic
//! is the distance to the nearest goal, Dijkstra beyond 64 goals).
//!
//! What is not exact: circles are planned with a radius 10⁻⁷ cell above the robot's
//! (a margin so that rounding never puts the returned path inside an inflated cell),
//! and the returned path follows each arc by its circumscribed polygon (its vertices
//! outside the circle, so the path stays valid), at most 0.05 rad per piece: at most
//! 0.021 % longer than the arc it replaces; [`Visibility::last_optimum`] gives the exact
//! length. The heading: the optimum for `w_t·length + w_r·d(yaw)` is the shortest
//! planar path plus one turn `w_r·d(yaw_s, yaw_g)`; the path keeps the start's heading
//! and turns on its last segment.
//!
//! The planner refuses, naming the config key, a robot that is not a disc on a 2D
//! grid (`validity.type` other than `clearance-2d`), a curved motion model
//! (`space.type`), an objective other than path length (`objective.type`), a terrain
//! world (a `[traversability]` layer). Discs of any radius are served: from about half
//! a cell on, arcs can pass near cells other than their corner's and are checked
//! exactly too (the crossings of the circle with each nearby cell's inflated square).

mod clearance;
mod clearance_bounds;
mod geometry;
mod search;
mod shadow;
mod staircase;
#[cfg(test)]
mod tests;

pub use geometry::Grid;
pub use search::{Route, TangentGraph, Visit};

use geometry::{Pt, EPS};
use serde::{Deserialize, Serialize};
use smug_core::{
    BuildContext, DiscOnGrid, Error, GridGeometry, NoPathReason, Objective, Path, PlannerOutcome,
    PlannerStats, PointToPointPlanner, Pose2, Proof, Result, StateValidityChecker, TimeBreakdown,
};
use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

/// Parameters of the `visibility` planner.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct VisibilityParams {
    /// Build the whole tangent graph when the planner is built (timed apart, as
    /// preprocessing) instead of corner by corner as queries reach them.
    pub build_all: bool,
    /// Keep every convex corner in the graph: no staircase corner is left out until a
    /// query needs it (a reference for the tests; slower on rasterised diagonals).
    pub all_corners: bool,
}

/// A goal the exact search did not reach: it covered everything the start reaches.
const PROVED_NONE: PlannerOutcome =
    PlannerOutcome::NoPath(NoPathReason::Proved(Proof::Disconnected));

/// Margin added to the robot's radius for the circles, grid units.
const RADIUS_MARGIN: f64 = 1e-7;

/// Largest arc piece of a returned path, radians (excess ≤ tan(δ/2)/(δ/2) − 1 = 0.021 %).
const ARC_STEP: f64 = 0.05;

/// The exact planner.
pub struct Visibility {
    graph: TangentGraph,
    geometry: GridGeometry,
    states: Arc<dyn StateValidityChecker>,
    objective: Arc<dyn Objective>,
    /// Robot radius, grid units.
    radius: f64,
    queries: u64,
    breakdown: TimeBreakdown,
    build_s: f64,
    last_optimum: Vec<Option<f64>>,
}

/// Why the planner cannot serve a pipeline: the config key and the reason.
fn refuse(key: &str, reason: impl std::fmt::Display) -> Error {
    Error::invalid_param(
        "planner",
        format!("`visibility` cannot plan here: {reason} (`{key}`); use `lazy-prm-star`"),
    )
}

impl Visibility {
    /// The planner for the disc and grid of `disc`, costs by `objective` (which must be
    /// an SE(2) length), states checked by `states` (for start and goal).
    pub fn new(
        params: VisibilityParams,
        disc: DiscOnGrid,
        states: Arc<dyn StateValidityChecker>,
        objective: Arc<dyn Objective>,
    ) -> Result<Self> {
        if objective.se2_length_weights().is_none() {
            return Err(refuse(
                "objective.type",
                "the objective is not the path length on a holonomic space",
            ));
        }
        let g = disc.geometry;
        let radius = disc.radius / g.resolution;
        if !(radius.is_finite() && radius >= 0.0) {
            return Err(refuse(
                "validity.params.radius",
                format!("the disc's radius must be ≥ 0, got {} m", disc.radius),
            ));
        }
        if disc.blocked.len() != g.len() {
            return Err(Error::InvalidInput(format!(
                "visibility: {} occupancy flags for a {}×{} grid",
                disc.blocked.len(),
                g.size[0],
                g.size[1]
            )));
        }
        let started = Instant::now();
        let grid = Grid::new(g.size[0], g.size[1], disc.blocked);
        let r = radius + 2.0 * RADIUS_MARGIN;
        let mut graph = TangentGraph::new(grid, r, radius + RADIUS_MARGIN, !params.all_corners);
        if params.build_all {
            graph.build_all();
        }
        Ok(Self {
            graph,
            geometry: g,
            states,
            objective,
            radius,
            queries: 0,
            breakdown: TimeBreakdown::default(),
            build_s: started.elapsed().as_secs_f64(),
            last_optimum: Vec::new(),
        })
    }

    /// The exact planar lengths (metres, arcs exact) of the last query's shortest
    /// paths, one per goal (`None`: no path).
    pub fn last_optimum(&self) -> &[Option<f64>] {
        &self.last_optimum
    }

    /// Seconds spent building the graph before the first query (with `build_all`).
    pub fn preprocessing_s(&self) -> f64 {
        self.build_s
    }

    fn to_grid(&self, p: &Pose2) -> Pt {
        let g = &self.geometry;
        [
            (p.x - g.origin[0]) / g.resolution,
            (p.y - g.origin[1]) / g.resolution,
        ]
    }

    fn to_world(&self, p: Pt, yaw: f64) -> Pose2 {
        let g = &self.geometry;
        Pose2::new(
            g.origin[0] + p[0] * g.resolution,
            g.origin[1] + p[1] * g.resolution,
            yaw,
        )
    }

    /// The polygon circumscribing the arc of a visit: its vertices outside the circle
    /// (the path stays valid), pieces of at most `step` radians.
    fn arc_points(&self, v: &Visit, step_max: f64) -> Vec<Pt> {
        let r = self.graph.r;
        let corner = self.graph.grid.corners[v.corner as usize];
        let span = v.rel_out - v.rel_in;
        let mut points = vec![corner.point(r, v.rel_in)];
        if span.abs() > EPS {
            let pieces = (span.abs() / step_max).ceil().max(1.0) as usize;
            let step = span / pieces as f64;
            let out = r / (step / 2.0).cos();
            // The piece vertices by rotating one unit vector (a sine and a cosine per
            // arc, not per piece).
            let first = corner.q0 + v.rel_in + 0.5 * step;
            let (mut sin, mut cos) = first.sin_cos();
            let (ds, dc) = step.sin_cos();
            points.reserve(pieces + 1);
            for _ in 0..pieces {
                points.push([corner.at[0] + out * cos, corner.at[1] + out * sin]);
                (cos, sin) = (cos * dc - sin * ds, sin * dc + cos * ds);
            }
        }
        points.push(corner.point(r, v.rel_out));
        points
    }

    /// The polyline of a route: arcs by circumscribed polygons (finer where a disc of
    /// half a cell or more passes close to another cell), headings the start's but the
    /// last.
    fn path_of(&self, start: &Pose2, goal: &Pose2, route: &Route) -> Path {
        let mut points: Vec<Pt> = vec![self.to_grid(start)];
        for v in &route.visits {
            let mut step = ARC_STEP;
            let mut arc = self.arc_points(v, step);
            while self.graph.big
                && step > 1e-5
                && !arc
                    .windows(2)
                    .all(|w| self.graph.grid.segment_clear(w[0], w[1], self.radius))
            {
                step /= 4.0;
                arc = self.arc_points(v, step);
            }
            points.extend(arc);
        }
        points.push(self.to_grid(goal));
        let mut states: Vec<Pose2> = Vec::with_capacity(points.len());
        for (k, p) in points.iter().enumerate() {
            let last = k + 1 == points.len();
            let yaw = if last { goal.yaw } else { start.yaw };
            let pose = self.to_world(*p, yaw);
            let single = states.len() == 1;
            match states.last_mut() {
                Some(prev) if prev.xy_distance(&pose) < 1e-12 && !(last && single) => {
                    if last {
                        *prev = *goal;
                    }
                }
                _ => states.push(if k == 0 {
                    *start
                } else if last {
                    *goal
                } else {
                    pose
                }),
            }
        }
        Path::new(states, self.objective.as_ref())
    }
}

impl PointToPointPlanner for Visibility {
    fn plan(&mut self, start: &Pose2, goal: &Pose2) -> Result<PlannerOutcome> {
        let mut outcomes = self.plan_many(start, std::slice::from_ref(goal))?;
        Ok(outcomes.pop().unwrap_or(PROVED_NONE))
    }

    fn plan_many(&mut self, start: &Pose2, goals: &[Pose2]) -> Result<Vec<PlannerOutcome>> {
        self.queries += goals.len() as u64;
        self.last_optimum = vec![None; goals.len()];
        let started = Instant::now();
        if !self.states.is_valid(start) {
            return Ok(vec![PlannerOutcome::InvalidStart; goals.len()]);
        }
        let reach = self.graph.r_check + 1.0;
        let s = self.to_grid(start);
        let clear_s = self.graph.grid.clearance(s, reach);
        let mut asked = Vec::new();
        let mut index = Vec::with_capacity(goals.len());
        for goal in goals {
            if self.states.is_valid(goal) {
                let g = self.to_grid(goal);
                index.push(Some(asked.len()));
                asked.push((g, self.graph.grid.clearance(g, reach)));
            } else {
                index.push(None);
            }
        }
        let routes = if asked.is_empty() {
            Vec::new()
        } else {
            self.graph.shortest(s, clear_s, &asked)
        };
        let res = self.geometry.resolution;
        let mut outcomes = Vec::with_capacity(goals.len());
        for (k, goal) in goals.iter().enumerate() {
            outcomes.push(match index[k] {
                None => PlannerOutcome::InvalidGoal,
                Some(i) => match &routes[i] {
                    None => PROVED_NONE,
                    Some(route) => {
                        self.last_optimum[k] = Some(route.length * res);
                        PlannerOutcome::Exact(self.path_of(start, goal, route))
                    }
                },
            });
        }
        self.breakdown.astar_s += started.elapsed().as_secs_f64();
        Ok(outcomes)
    }

    fn answers_many(&self) -> bool {
        true
    }

    fn stats(&self) -> PlannerStats {
        let c = &self.graph.counts;
        PlannerStats {
            queries: self.queries,
            vertices: c.departures,
            edges: c.departures,
            breakdown: TimeBreakdown {
                sampling_s: self.build_s,
                ..self.breakdown
            },
            counters: BTreeMap::from([
                ("corners".to_string(), self.graph.grid.corners.len() as u64),
                (
                    "corners_hidden".to_string(),
                    self.graph.hidden_count() as u64,
                ),
                ("corners_built".to_string(), c.corners_built),
                ("segment_checks".to_string(), c.segment_checks),
                ("expansions".to_string(), c.expansions),
                ("pruned_tangents".to_string(), c.pruned),
                ("radius_millicells".to_string(), (self.radius * 1e3) as u64),
            ]),
        }
    }
}

/// The exact planner for the pipeline of `ctx`: `Ok(Err(refusal))` when it does not
/// apply (naming the config key), `Err` for any other failure.
pub(crate) fn build_exact(
    params: VisibilityParams,
    ctx: &BuildContext,
) -> Result<std::result::Result<Visibility, Error>> {
    let space = ctx.space();
    if !space.is_holonomic() {
        return Ok(Err(refuse(
            "space.type",
            "the motion model is curved (a car), not straight holonomic motions",
        )));
    }
    let world = ctx.world()?;
    if world.traversability.is_some() {
        return Ok(Err(refuse(
            "traversability.type",
            "a terrain world (it has a traversability layer); the exact planner plans on flat occupancy maps",
        )));
    }
    let states = ctx.state_validity()?;
    let Some(disc) = states.disc_on_grid() else {
        return Ok(Err(refuse(
            "validity.type",
            "the robot is not a disc on a 2D occupancy map (use `clearance-2d`)",
        )));
    };
    let objective = ctx.objective();
    if objective.se2_length_weights().is_none() {
        return Ok(Err(refuse(
            "objective.type",
            "the objective is not the path length on a holonomic space",
        )));
    }
    Visibility::new(params, disc, states, objective).map(Ok)
}

fn build_planner(params: VisibilityParams, ctx: &BuildContext) -> Result<Visibility> {
    build_exact(params, ctx)?
}

smug_core::register_plugin!(
    smug_core::registry::PlannerStage,
    name = "visibility",
    summary =
        "exact shortest paths of a disc on a 2D grid (tangent visibility graph), path length only",
    params = VisibilityParams,
    build = |params, ctx| Ok(Box::new(build_planner(params, ctx)?)),
);
