//! `clearance-2d`: a disc robot of radius `radius` on a flat map: valid when the disc
//! lies inside the map and touches no obstacle cell (a cell without elevation data or
//! higher than the lowest ground by more than `obstacle_height`). A 2D distance field
//! accepts most states at once; near obstacles the cells around the disc decide exactly.

use crate::edt::squared_edt_2d;
use serde::{Deserialize, Serialize};
use smug_core::Counter;
use smug_core::{
    BuildContext, Counters, DiscOnGrid, Error, GridGeometry, Pose2, StateValidityChecker, World,
};

mod segment;

/// Parameters of the disc checker.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Clearance2dParams {
    /// Disc radius, metres.
    pub radius: f64,
    /// Cells higher than the lowest ground by more than this are obstacles, metres.
    pub obstacle_height: f64,
}

impl Default for Clearance2dParams {
    fn default() -> Self {
        Self {
            radius: 0.3,
            obstacle_height: 0.3,
        }
    }
}

/// Disc-vs-obstacle-cells validity.
pub struct Clearance2dChecker {
    geometry: GridGeometry,
    obstacles: Vec<bool>,
    /// Distance (metres) from each cell centre to the nearest obstacle cell centre.
    distance: Vec<f64>,
    radius: f64,
    checks: Counter,
    exact_checks: Counter,
    segment_checks: Counter,
}

impl Clearance2dChecker {
    /// A checker for a disc of `params.radius` on `world`'s elevation layer.
    pub fn new(world: &World, params: Clearance2dParams) -> Result<Self, Error> {
        if !(params.radius.is_finite() && params.radius >= 0.0) {
            return Err(Error::invalid_param(
                "validity",
                format!("radius must be ≥ 0, got {}", params.radius),
            ));
        }
        let e = &world.elevation;
        let ground = e
            .data
            .iter()
            .filter(|v| v.is_finite())
            .fold(f32::INFINITY, |a, &b| a.min(b));
        let limit = ground as f64 + params.obstacle_height;
        let obstacles: Vec<bool> = e
            .data
            .iter()
            .map(|&h| h.is_nan() || h as f64 > limit)
            .collect();
        let res = e.geometry.resolution;
        let distance = squared_edt_2d(&obstacles, e.geometry.size)
            .into_iter()
            .map(|d| d.sqrt() * res)
            .collect();
        Ok(Self {
            geometry: e.geometry,
            obstacles,
            distance,
            radius: params.radius,
            checks: Counter::new(),
            exact_checks: Counter::new(),
            segment_checks: Counter::new(),
        })
    }

    /// A lower bound of the distance from `(x, y)` to the nearest obstacle square, from
    /// the distance field (`None` off the grid).
    fn obstacle_distance_bound(&self, x: f64, y: f64) -> Option<f64> {
        let [i, j] = self.geometry.cell_of(x, y)?;
        let [cx, cy] = self.geometry.center_of(i, j);
        Some(
            self.distance[self.geometry.index(i, j)]
                - (x - cx).hypot(y - cy)
                - std::f64::consts::FRAC_1_SQRT_2 * self.geometry.resolution,
        )
    }

    /// The gaps `(dx, dy)` from `(x, y)` to the obstacle squares whose cells lie within
    /// `reach` of it along both axes, row by row (one exact check).
    fn obstacle_gaps(&self, x: f64, y: f64, reach: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.exact_checks.increment();
        let g = &self.geometry;
        let res = g.resolution;
        let lo = |v: f64, o: f64| ((v - reach - o) / res).floor().max(0.0) as usize;
        let hi = |v: f64, o: f64, n: usize| (((v + reach - o) / res).floor() as usize).min(n - 1);
        let columns = lo(x, g.origin[0])..=hi(x, g.origin[0], g.size[0]);
        (lo(y, g.origin[1])..=hi(y, g.origin[1], g.size[1]))
            .flat_map(move |j| columns.clone().map(move |i| (i, j)))
            .filter(|&(i, j)| self.obstacles[g.index(i, j)])
            .map(move |(i, j)| {
                let x0 = g.origin[0] + i as f64 * res;
                let y0 = g.origin[1] + j as f64 * res;
                let dx = (x0 - x).max(0.0).max(x - (x0 + res));
                let dy = (y0 - y).max(0.0).max(y - (y0 + res));
                (dx, dy)
            })
    }

    /// The distance from `(x, y)` to the nearest obstacle square, exactly when it is
    /// below `reach`, else `reach` (only the cells within `reach` are looked at).
    fn obstacle_distance_within(&self, x: f64, y: f64, reach: f64) -> f64 {
        // `hypot` only for gaps that are, within rounding, the nearest so far by squared
        // distance (cheap): the minimum is the same as over every gap's `hypot`, bit
        // for bit (a gap near the final minimum is near the running one when seen).
        let (mut nearest2, mut nearest) = (f64::INFINITY, reach);
        for (dx, dy) in self.obstacle_gaps(x, y, reach) {
            let d2 = dx * dx + dy * dy;
            if d2 <= nearest2 * (1.0 + 1e-9) {
                nearest2 = nearest2.min(d2);
                nearest = nearest.min(dx.hypot(dy));
            }
        }
        nearest
    }

    /// True when the disc at `(x, y)` touches an obstacle cell (checks the cells around it).
    fn touches_obstacle(&self, x: f64, y: f64) -> bool {
        let r = self.radius;
        self.obstacle_gaps(x, y, r)
            .any(|(dx, dy)| self.within_radius(dx * dx + dy * dy, || dx.hypot(dy)))
    }

    /// True when an obstacle square at squared distance `d2` touches the disc: squared
    /// distances decide all but near-ties, which the distance itself (`exact`) decides;
    /// a point robot touches what it lies on. The rule of every state and motion check.
    fn within_radius(&self, d2: f64, exact: impl Fn() -> f64) -> bool {
        let r = self.radius;
        let (low, high) = (r * r * (1.0 - 1e-9), r * r * (1.0 + 1e-9));
        d2 < low || (d2 <= high && exact() < r) || (r == 0.0 && exact() == 0.0)
    }

    /// True when the disc centred at `(x, y)` lies inside the map.
    fn inside_border(&self, [x, y]: [f64; 2]) -> bool {
        let b = self.geometry.bounds();
        let r = self.radius;
        x - r >= b.min[0] && x + r <= b.max[0] && y - r >= b.min[1] && y + r <= b.max[1]
    }
}

impl StateValidityChecker for Clearance2dChecker {
    fn is_valid(&self, state: &Pose2) -> bool {
        self.checks.increment();
        let (x, y, r) = (state.x, state.y, self.radius);
        if !self.inside_border([x, y]) {
            return false;
        }
        let Some(bound) = self.obstacle_distance_bound(x, y) else {
            return false;
        };
        bound > r || !self.touches_obstacle(x, y)
    }

    /// The disc's distance to the map border and to the nearest obstacle square, less
    /// its radius (exact near obstacles, from the distance field farther away).
    fn clearance(&self, state: &Pose2) -> Option<f64> {
        let b = self.geometry.bounds();
        let (x, y, r) = (state.x, state.y, self.radius);
        let border = (x - b.min[0])
            .min(b.max[0] - x)
            .min(y - b.min[1])
            .min(b.max[1] - y);
        let Some(bound) = self.obstacle_distance_bound(x, y) else {
            return Some(border.min(0.0) - r);
        };
        // Far from obstacles the distance field's bound is enough; nearer, the cells
        // within one cell beyond the disc are measured exactly.
        let reach = r + self.geometry.resolution;
        let obstacle = if bound >= reach {
            bound
        } else {
            self.obstacle_distance_within(x, y, reach).max(bound)
        };
        Some(border.min(obstacle) - r)
    }

    fn segment_valid(&self, a: &Pose2, b: &Pose2) -> Option<bool> {
        self.segment_checks.increment();
        Some(self.segment_clear(a, b))
    }

    fn disc_on_grid(&self) -> Option<DiscOnGrid> {
        Some(DiscOnGrid {
            radius: self.radius,
            geometry: self.geometry,
            blocked: self.obstacles.clone(),
        })
    }

    fn counters(&self) -> Counters {
        Counters::from([
            ("checks".to_string(), self.checks.total()),
            ("exact_checks".to_string(), self.exact_checks.total()),
            ("segment_checks".to_string(), self.segment_checks.total()),
        ])
    }
}

fn build_clearance(
    params: Clearance2dParams,
    ctx: &BuildContext,
) -> Result<Clearance2dChecker, Error> {
    Clearance2dChecker::new(ctx.world()?.as_ref(), params)
}

smug_core::register_plugin!(
    smug_core::registry::ValidityStage,
    name = "clearance-2d",
    summary = "a disc robot of radius r on a flat map (wheeled robots, comparisons with OMPL)",
    params = Clearance2dParams,
    build = |params, ctx| Ok(Box::new(build_clearance(params, ctx)?)),
);

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use smug_core::GridLayer;

    /// A 10×10 map at 1 m with a few blocked cells.
    fn world() -> World {
        let g = GridGeometry::new([0.0, 0.0], 1.0, [10, 10]).unwrap();
        let blocked = [(3, 3), (4, 3), (7, 8), (0, 9)];
        let elevation =
            GridLayer::from_fn(g, |i, j| if blocked.contains(&(i, j)) { 2.0 } else { 0.0 });
        World::new("grid", elevation)
    }

    proptest! {
        #[test]
        fn agrees_with_brute_force_disc_vs_squares(x in 0.0f64..10.0, y in 0.0f64..10.0, r in 0.0f64..1.5) {
            let w = world();
            let checker = Clearance2dChecker::new(&w, Clearance2dParams { radius: r, obstacle_height: 1.0 }).unwrap();
            let inside = x - r >= 0.0 && x + r <= 10.0 && y - r >= 0.0 && y + r <= 10.0;
            let clear = [(3, 3), (4, 3), (7, 8), (0, 9)].iter().all(|&(i, j)| {
                let dx = (i as f64 - x).max(0.0).max(x - (i as f64 + 1.0));
                let dy = (j as f64 - y).max(0.0).max(y - (j as f64 + 1.0));
                dx.hypot(dy) >= r && !(dx == 0.0 && dy == 0.0)
            });
            prop_assert_eq!(checker.is_valid(&Pose2::new(x, y, 0.0)), inside && clear);
        }

        #[test]
        fn the_segment_test_is_exact(
            a in (0.0f64..10.0, 0.0f64..10.0), b in (0.0f64..10.0, 0.0f64..10.0),
            r in 0.0f64..1.5,
        ) {
            let w = world();
            let checker = Clearance2dChecker::new(&w, Clearance2dParams { radius: r, obstacle_height: 1.0 }).unwrap();
            let (a, b) = (Pose2::new(a.0, a.1, 0.0), Pose2::new(b.0, b.1, 1.0));
            let verdict = checker.segment_valid(&a, &b).unwrap();
            prop_assert_eq!(verdict, checker.segment_valid(&b, &a).unwrap());
            // Dense points, `step` apart: all valid when the segment is; when it is not,
            // one of them comes within half a step of contact.
            let steps = 4000;
            let step = a.xy_distance(&b) / steps as f64;
            let points = (0..=steps).map(|k| {
                let t = k as f64 / steps as f64;
                Pose2::new(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), 0.0)
            });
            if verdict {
                for p in points {
                    prop_assert!(checker.is_valid(&p), "{:?} on a clear segment", p);
                }
            } else {
                let nearest = points
                    .map(|p| checker.clearance(&p).unwrap())
                    .fold(f64::INFINITY, f64::min);
                prop_assert!(nearest <= 0.5 * step + 1e-9, "blocked, yet {} clear", nearest);
            }
        }

        #[test]
        fn clearance_is_a_safe_radius(
            x in 0.0f64..10.0, y in 0.0f64..10.0, r in 0.0f64..1.5,
            angle in -3.2f64..3.2, share in 0.0f64..1.0, yaw in -3.0f64..3.0,
        ) {
            let w = world();
            let checker = Clearance2dChecker::new(&w, Clearance2dParams { radius: r, obstacle_height: 1.0 }).unwrap();
            let p = Pose2::new(x, y, 0.0);
            let c = checker.clearance(&p).unwrap();
            // Positive clearance: valid; invalid: no positive clearance.
            if c > 1e-12 {
                prop_assert!(checker.is_valid(&p));
            }
            if !checker.is_valid(&p) {
                prop_assert!(c <= 1e-12, "invalid with clearance {}", c);
            }
            // Every state within the clearance, with any yaw, is valid.
            if c > 1e-9 {
                let d = share * c * (1.0 - 1e-9);
                let q = Pose2::new(x + d * angle.cos(), y + d * angle.sin(), yaw);
                prop_assert!(checker.is_valid(&q), "{:?} within {} of {:?}", q, c, p);
            }
        }
    }
}
