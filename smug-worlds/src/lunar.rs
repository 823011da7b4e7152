//! `lunar`: a procedural lunar world like the paper's (seeded): gently sloped terrain,
//! two craters with steep rims, two large boulders, stones as targets (ToIs) with PoIs
//! on a circle around each, facing it, and small rocks a robot base clears but should
//! not step on.

use crate::canvas::{add_feature, geometry, raise_feature, world_rng};
use rand::Rng;
use serde::{Deserialize, Serialize};
use smug_core::rng::StageRng;
use smug_core::{
    Error, GridGeometry, GridLayer, MemoryLimit, Mission, Point3, Pose2, Scenario, Target, World,
};
use std::f64::consts::{PI, TAU};

/// Parameters of the lunar world.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LunarParams {
    /// World seed; absent: derived from the config seed.
    pub seed: Option<u64>,
    /// Extent `(x, y)` in metres (paper: 30 × 29).
    pub size: [f64; 2],
    /// Cell size in metres.
    pub resolution: f64,
    /// Number of stones to inspect (paper: 13).
    pub targets: usize,
    /// PoIs per stone, evenly spaced on a circle (paper: 10).
    pub pois_per_target: usize,
    /// Radius of the PoI circle around a stone, metres.
    pub inspection_distance: f64,
    /// Number of craters.
    pub craters: usize,
    /// Number of large boulders.
    pub boulders: usize,
    /// Number of small rocks.
    pub small_rocks: usize,
    /// Start pose; absent: near the lower-left corner.
    pub start: Option<Pose2>,
}

impl Default for LunarParams {
    fn default() -> Self {
        Self {
            seed: None,
            size: [30.0, 29.0],
            resolution: 0.1,
            targets: 13,
            pois_per_target: 10,
            inspection_distance: 1.3,
            craters: 2,
            boulders: 2,
            small_rocks: 150,
            start: None,
        }
    }
}

/// A disc that later features keep out of.
#[derive(Clone, Copy, Debug)]
struct KeepOut {
    center: [f64; 2],
    radius: f64,
}

/// Places discs at random without overlap.
struct Placer {
    size: [f64; 2],
    taken: Vec<KeepOut>,
}

impl Placer {
    /// A centre at least `margin` from the border whose disc of `radius` overlaps nothing.
    fn place(&mut self, rng: &mut StageRng, radius: f64, margin: f64) -> Option<[f64; 2]> {
        for _ in 0..4000 {
            let c = [
                rng.random_range(margin..(self.size[0] - margin).max(margin + 1e-9)),
                rng.random_range(margin..(self.size[1] - margin).max(margin + 1e-9)),
            ];
            let free = self
                .taken
                .iter()
                .all(|k| (k.center[0] - c[0]).hypot(k.center[1] - c[1]) >= k.radius + radius);
            if free {
                self.taken.push(KeepOut { center: c, radius });
                return Some(c);
            }
        }
        None
    }
}

/// Gently sloped ground: a tilt and a few long waves.
fn base_terrain(layer: &mut GridLayer, rng: &mut StageRng) {
    *layer = Ground::draw(rng).layer(layer.geometry);
}

/// The ground's tilt and its long waves.
struct Ground {
    /// Slope of the tilt, and the cosine and sine of its direction.
    tilt: f64,
    tilt_dir: (f64, f64),
    /// Per wave: amplitude, wave number, cosine and sine of its direction, phase.
    waves: Vec<(f64, f64, (f64, f64), f64)>,
}

impl Ground {
    /// A tilt and four waves drawn from `rng`.
    fn draw(rng: &mut StageRng) -> Self {
        let tilt_dir = rng.random_range(0.0..TAU);
        let tilt = rng.random_range(0.01..0.03);
        let waves: Vec<(f64, f64, f64, f64)> = (0..4)
            .map(|_| {
                (
                    rng.random_range(0.04..0.1),
                    TAU / rng.random_range(6.0..14.0),
                    rng.random_range(0.0..TAU),
                    rng.random_range(0.0..TAU),
                )
            })
            .collect();
        Self {
            tilt,
            // The directions' cosines and sines once, not per cell.
            tilt_dir: (tilt_dir.cos(), tilt_dir.sin()),
            waves: waves
                .into_iter()
                .map(|(amplitude, k, direction, phase)| {
                    (amplitude, k, (direction.cos(), direction.sin()), phase)
                })
                .collect(),
        }
    }

    /// The height at `(x, y)`, wave by wave (what [`Ground::layer`] computes).
    #[cfg(test)]
    fn height_at(&self, x: f64, y: f64) -> f64 {
        let mut h = self.tilt * (x * self.tilt_dir.0 + y * self.tilt_dir.1);
        for &(amplitude, k, (cos, sin), phase) in &self.waves {
            h += amplitude * (k * (x * cos + y * sin) + phase).sin();
        }
        h
    }

    /// The heights of the cells of `g`. A wave's phase at a cell is a column's part
    /// plus a row's part, so its sine is `sin a · cos b + cos a · sin b` from a sine
    /// and a cosine per column and per row: two products per cell instead of a sine.
    fn layer(&self, g: GridGeometry) -> GridLayer {
        let [nx, ny] = g.size;
        // Per column (x) or row (y): each wave's part of the phase, as (sin, cos).
        let parts =
            |along: f64, axis: fn(&(f64, f64)) -> f64, with_phase: bool| -> Vec<(f64, f64)> {
                self.waves
                    .iter()
                    .map(|(_, k, direction, phase)| {
                        (k * along * axis(direction) + if with_phase { *phase } else { 0.0 })
                            .sin_cos()
                    })
                    .collect()
            };
        let columns: Vec<Vec<(f64, f64)>> = (0..nx)
            .map(|i| parts(g.center_of(i, 0)[0], |d| d.0, true))
            .collect();
        let rows: Vec<Vec<(f64, f64)>> = (0..ny)
            .map(|j| parts(g.center_of(0, j)[1], |d| d.1, false))
            .collect();
        // Each cell's height is its own: rows are filled side by side.
        GridLayer::from_fn_par(g, |i, j| {
            let [x, y] = g.center_of(i, j);
            let mut h = self.tilt * (x * self.tilt_dir.0 + y * self.tilt_dir.1);
            for (w, &(amplitude, ..)) in self.waves.iter().enumerate() {
                let ((sin_a, cos_a), (sin_b, cos_b)) = (columns[i][w], rows[j][w]);
                h += amplitude * (sin_a * cos_b + cos_a * sin_b);
            }
            h as f32
        })
    }
}

/// A bowl of `radius` and `depth` with a steep rim.
fn crater_profile(radius: f64, depth: f64, rim: f64) -> impl Fn(f64, f64) -> f64 {
    let width = 0.35;
    move |dx, dy| {
        let r = dx.hypot(dy);
        let bowl = if r < radius {
            -depth * (1.0 - (r / radius).powi(2))
        } else {
            0.0
        };
        bowl + rim * (-((r - radius) / width).powi(2)).exp()
    }
}

/// A steep-sided dome with a superelliptic footprint of semi-axes `a`, `b`, rotated by `angle`.
fn boulder_profile(a: f64, b: f64, height: f64, angle: f64) -> impl Fn(f64, f64) -> Option<f64> {
    let (s, c) = angle.sin_cos();
    move |dx, dy| {
        let (u, v) = (c * dx + s * dy, -s * dx + c * dy);
        let q = (u / a).powi(4) + (v / b).powi(4);
        (q < 1.0).then(|| height * (1.0 - q).powf(0.25))
    }
}

/// An irregular dome: its radius varies with the angle.
fn stone_profile(radius: f64, height: f64, phases: [f64; 2]) -> impl Fn(f64, f64) -> Option<f64> {
    move |dx, dy| {
        let theta = dy.atan2(dx);
        let edge = radius
            * (1.0
                + 0.25 * (3.0 * theta + phases[0]).sin()
                + 0.15 * (5.0 * theta + phases[1]).sin());
        let r = dx.hypot(dy);
        (r < edge).then(|| height * (1.0 - (r / edge).powi(2)).sqrt())
    }
}

/// `count` PoIs evenly spaced on a circle around `center`, facing it.
fn pois_around(center: [f64; 2], distance: f64, count: usize, offset: f64) -> Vec<Pose2> {
    (0..count)
        .map(|k| {
            let theta = offset + TAU * k as f64 / count as f64;
            Pose2::new(
                center[0] + distance * theta.cos(),
                center[1] + distance * theta.sin(),
                theta + PI,
            )
        })
        .collect()
}

/// Builds the lunar world and its mission from `params` with randomness from `rng`.
pub fn lunar_world(params: &LunarParams, rng: &mut StageRng) -> Result<Scenario, Error> {
    lunar_world_within(params, rng, MemoryLimit::default())
}

/// [`lunar_world`] with grids that must fit `memory` (a run's limit).
pub fn lunar_world_within(
    params: &LunarParams,
    rng: &mut StageRng,
    memory: MemoryLimit,
) -> Result<Scenario, Error> {
    let bad = |message: String| Error::invalid_param("world", message);
    if params.pois_per_target == 0
        || params.inspection_distance.is_nan()
        || params.inspection_distance <= 0.0
    {
        return Err(bad(
            "pois_per_target and inspection_distance must be > 0".into()
        ));
    }
    let g = geometry(params.size, params.resolution, memory).map_err(|e| bad(e.to_string()))?;
    let mut terrain = GridLayer::filled(g, 0.0);
    base_terrain(&mut terrain, rng);
    let start = params.start.unwrap_or(Pose2::new(2.0, 2.0, PI / 4.0));
    let mut placer = Placer {
        size: params.size,
        taken: vec![KeepOut {
            center: start.xy(),
            radius: 2.0,
        }],
    };
    let too_crowded = |what: &str| {
        bad(format!(
            "cannot place the {what} in a {}×{} m world; use a larger `size` or fewer features",
            params.size[0], params.size[1]
        ))
    };
    for _ in 0..params.craters {
        let radius = rng.random_range(2.0..3.0);
        let center = placer
            .place(rng, radius + 0.8, radius + 1.0)
            .ok_or_else(|| too_crowded("craters"))?;
        let profile = crater_profile(
            radius,
            rng.random_range(0.6..0.9),
            rng.random_range(0.3..0.45),
        );
        add_feature(&mut terrain, center, radius + 1.5, profile);
    }
    let ground = terrain.clone();
    for _ in 0..params.boulders {
        let (a, b) = (rng.random_range(1.0..1.5), rng.random_range(0.7..1.1));
        let center = placer
            .place(rng, a + 0.8, a + 1.0)
            .ok_or_else(|| too_crowded("boulders"))?;
        let profile = boulder_profile(a, b, rng.random_range(1.2..1.8), rng.random_range(0.0..PI));
        raise_feature(&mut terrain, &ground, center, a, profile);
    }
    let targets = place_stones(params, rng, &mut placer, &mut terrain, &ground)
        .ok_or_else(|| too_crowded("stones"))?;
    scatter_small_rocks(params, rng, &placer, &mut terrain);
    let mission = Mission {
        start,
        end: None,
        targets,
    };
    Ok(World::new("lunar", terrain).with_mission(mission))
}

/// Places the stones (ToIs) with their PoIs, shrinking the spacing if crowded.
fn place_stones(
    params: &LunarParams,
    rng: &mut StageRng,
    placer: &mut Placer,
    terrain: &mut GridLayer,
    ground: &GridLayer,
) -> Option<Vec<Target>> {
    let fixed = placer.taken.len();
    let mut spacing = params.inspection_distance + 0.7;
    'attempt: loop {
        placer.taken.truncate(fixed);
        let mut stones = Vec::with_capacity(params.targets);
        for _ in 0..params.targets {
            let margin = params.inspection_distance + 0.8;
            match placer.place(rng, spacing, margin) {
                Some(center) => stones.push(center),
                None if spacing > params.inspection_distance + 0.1 => {
                    spacing *= 0.9;
                    continue 'attempt;
                }
                None => return None,
            }
        }
        return Some(
            stones
                .into_iter()
                .enumerate()
                .map(|(k, center)| draw_stone(params, rng, terrain, ground, k, center))
                .collect(),
        );
    }
}

fn draw_stone(
    params: &LunarParams,
    rng: &mut StageRng,
    terrain: &mut GridLayer,
    ground: &GridLayer,
    k: usize,
    center: [f64; 2],
) -> Target {
    let radius = rng.random_range(0.2..0.4);
    let height = rng.random_range(0.2..0.6);
    let phases = [rng.random_range(0.0..TAU), rng.random_range(0.0..TAU)];
    raise_feature(
        terrain,
        ground,
        center,
        radius * 1.5,
        stone_profile(radius, height, phases),
    );
    let z = ground.nearest(center[0], center[1]).unwrap_or(0.0) + height;
    let offset = rng.random_range(0.0..TAU);
    Target {
        id: format!("stone-{:02}", k + 1),
        position: Point3 {
            x: center[0],
            y: center[1],
            z,
        },
        pois: pois_around(
            center,
            params.inspection_distance,
            params.pois_per_target,
            offset,
        ),
    }
}

/// Small rocks: bumps of 4–12 cm, away from the start and the stones' PoI circles.
fn scatter_small_rocks(
    params: &LunarParams,
    rng: &mut StageRng,
    placer: &Placer,
    terrain: &mut GridLayer,
) {
    for _ in 0..params.small_rocks {
        let c = [
            rng.random_range(0.0..params.size[0]),
            rng.random_range(0.0..params.size[1]),
        ];
        let radius = rng.random_range(0.05..0.15);
        let height = rng.random_range(0.04..0.12);
        let near_start =
            (c[0] - placer.taken[0].center[0]).hypot(c[1] - placer.taken[0].center[1]) < 1.0;
        if !near_start {
            add_feature(terrain, c, radius, |dx, dy| {
                let r = dx.hypot(dy) / radius;
                if r < 1.0 {
                    height * (1.0 - r * r)
                } else {
                    0.0
                }
            });
        }
    }
}

smug_core::register_plugin!(
    smug_core::registry::WorldStage,
    name = "lunar",
    summary = "procedural lunar world: slopes, craters, boulders, stones (ToIs) with PoI circles",
    params = LunarParams,
    build = |params, ctx| Ok(Box::new(lunar_world_within(
        &params,
        &mut world_rng(params.seed, ctx),
        ctx.memory(),
    )?)),
);

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn paper_sized_world_is_seeded_and_complete() {
        let params = LunarParams::default();
        let a = lunar_world(&params, &mut StageRng::seed_from_u64(3)).unwrap();
        let b = lunar_world(&params, &mut StageRng::seed_from_u64(3)).unwrap();
        let c = lunar_world(&params, &mut StageRng::seed_from_u64(4)).unwrap();
        assert_eq!(a, b, "same seed, same world");
        assert_ne!(a.world.elevation, c.world.elevation);
        assert_eq!(a.world.elevation.geometry.size, [300, 290]);
        assert_eq!(a.mission.targets.len(), 13);
        assert!(a.mission.targets.iter().all(|t| t.pois.len() == 10));
        a.mission.validate().unwrap();
        let bounds = a.world.bounds();
        for t in &a.mission.targets {
            for p in &t.pois {
                assert!(bounds.contains(p.x, p.y));
                let facing = (t.position.y - p.y).atan2(t.position.x - p.x);
                assert!(smug_core::pose::angle_distance(facing, p.yaw) < 1e-9);
            }
            let top = a.world.height_at(t.position.x, t.position.y).unwrap();
            assert!(
                top > a.world.height_at(t.pois[0].x, t.pois[0].y).unwrap() + 0.1,
                "stone {} is not raised",
                t.id
            );
        }
    }

    #[test]
    fn the_ground_by_columns_and_rows_is_the_ground_wave_by_wave() {
        let g = GridGeometry::new([-3.0, 2.0], 0.1, [400, 300]).unwrap();
        for seed in 0..5 {
            let ground = Ground::draw(&mut StageRng::seed_from_u64(seed));
            let layer = ground.layer(g);
            for j in 0..300 {
                for i in 0..400 {
                    let [x, y] = g.center_of(i, j);
                    let direct = ground.height_at(x, y);
                    let by_parts = layer.get(i, j) as f64;
                    assert!(
                        (by_parts - direct).abs() < 1e-6,
                        "({i}, {j}): {by_parts} vs {direct}"
                    );
                }
            }
        }
    }

    #[test]
    fn scales_to_many_targets_and_refuses_impossible_ones() {
        let many = LunarParams {
            targets: 48,
            pois_per_target: 6,
            ..LunarParams::default()
        };
        let w = lunar_world(&many, &mut StageRng::seed_from_u64(1)).unwrap();
        assert_eq!(w.mission.targets.len(), 48);
        let crowded = LunarParams {
            targets: 400,
            ..LunarParams::default()
        };
        let err = lunar_world(&crowded, &mut StageRng::seed_from_u64(1))
            .unwrap_err()
            .to_string();
        assert!(err.contains("cannot place the stones"), "{err}");
    }
}
