//! `indoor`: a procedural indoor world like the paper's (seeded): a 16 × 16 m flat
//! floor split into four rooms by walls with doors, shelves along the walls, and
//! gauges on the walls as targets, each with PoIs in front of it, facing it.

use crate::canvas::{geometry, raise_rectangle, world_rng};
use rand::Rng;
use serde::{Deserialize, Serialize};
use smug_core::rng::StageRng;
use smug_core::{Error, GridLayer, MemoryLimit, Mission, Point3, Pose2, Scenario, Target, World};

/// Parameters of the indoor world.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IndoorParams {
    /// World seed; absent: derived from the config seed.
    pub seed: Option<u64>,
    /// Side of the square floor, metres (paper: 16).
    pub size: f64,
    /// Cell size, metres.
    pub resolution: f64,
    /// Number of gauges (paper: 12), spread over the four rooms.
    pub targets: usize,
    /// PoIs per gauge (paper: 2), side by side in front of it.
    pub pois_per_target: usize,
    /// Distance of the PoIs from the wall, metres.
    pub inspection_distance: f64,
    /// Shelves per room.
    pub shelves_per_room: usize,
    /// Wall height, metres.
    pub wall_height: f64,
}

impl Default for IndoorParams {
    fn default() -> Self {
        Self {
            seed: None,
            size: 16.0,
            resolution: 0.1,
            targets: 12,
            pois_per_target: 2,
            inspection_distance: 1.1,
            shelves_per_room: 2,
            wall_height: 2.0,
        }
    }
}

const WALL: f64 = 0.2;
const DOOR: f64 = 1.3;

/// An axis-aligned rectangle `[min, max]`.
#[derive(Clone, Copy, Debug)]
struct Rect {
    min: [f64; 2],
    max: [f64; 2],
}

impl Rect {
    fn inflated(&self, margin: f64) -> Rect {
        Rect {
            min: [self.min[0] - margin, self.min[1] - margin],
            max: [self.max[0] + margin, self.max[1] + margin],
        }
    }

    fn contains(&self, p: [f64; 2]) -> bool {
        p[0] >= self.min[0] && p[0] <= self.max[0] && p[1] >= self.min[1] && p[1] <= self.max[1]
    }

    fn overlaps(&self, other: &Rect) -> bool {
        self.min[0] < other.max[0]
            && other.min[0] < self.max[0]
            && self.min[1] < other.max[1]
            && other.min[1] < self.max[1]
    }
}

/// One side of a room's interior: a point on it, its direction and inward normal.
#[derive(Clone, Copy, Debug)]
struct Side {
    start: [f64; 2],
    tangent: [f64; 2],
    normal: [f64; 2],
    length: f64,
}

impl Side {
    fn at(&self, t: f64) -> [f64; 2] {
        [
            self.start[0] + self.tangent[0] * t,
            self.start[1] + self.tangent[1] * t,
        ]
    }
}

fn room_sides(room: &Rect) -> [Side; 4] {
    let [x0, y0] = room.min;
    let [x1, y1] = room.max;
    [
        Side {
            start: [x0, y0],
            tangent: [1.0, 0.0],
            normal: [0.0, 1.0],
            length: x1 - x0,
        },
        Side {
            start: [x1, y0],
            tangent: [0.0, 1.0],
            normal: [-1.0, 0.0],
            length: y1 - y0,
        },
        Side {
            start: [x1, y1],
            tangent: [-1.0, 0.0],
            normal: [0.0, -1.0],
            length: x1 - x0,
        },
        Side {
            start: [x0, y1],
            tangent: [0.0, -1.0],
            normal: [1.0, 0.0],
            length: y1 - y0,
        },
    ]
}

/// Builds the indoor world and its mission from `params` with randomness from `rng`.
pub fn indoor_world(params: &IndoorParams, rng: &mut StageRng) -> Result<Scenario, Error> {
    indoor_world_within(params, rng, MemoryLimit::default())
}

/// [`indoor_world`] with grids that must fit `memory` (a run's limit).
pub fn indoor_world_within(
    params: &IndoorParams,
    rng: &mut StageRng,
    memory: MemoryLimit,
) -> Result<Scenario, Error> {
    let bad = |message: String| Error::invalid_param("world", message);
    if params.size.is_nan() || params.size < 8.0 {
        return Err(bad(format!(
            "size must be ≥ 8 m for four rooms, got {}",
            params.size
        )));
    }
    let s = params.size;
    let g = geometry([s, s], params.resolution, memory).map_err(|e| bad(e.to_string()))?;
    let mut floor = GridLayer::filled(g, 0.0);
    let h = params.wall_height;
    let half = s / 2.0;
    // Outer walls and the two inner walls.
    for (min, max) in [
        ([0.0, 0.0], [s, WALL]),
        ([0.0, s - WALL], [s, s]),
        ([0.0, 0.0], [WALL, s]),
        ([s - WALL, 0.0], [s, s]),
        ([half - WALL / 2.0, 0.0], [half + WALL / 2.0, s]),
        ([0.0, half - WALL / 2.0], [s, half + WALL / 2.0]),
    ] {
        raise_rectangle(&mut floor, min, max, h);
    }
    let doors = cut_doors(&mut floor, rng, s);
    let rooms = [
        Rect {
            min: [WALL, WALL],
            max: [half - WALL / 2.0, half - WALL / 2.0],
        },
        Rect {
            min: [half + WALL / 2.0, WALL],
            max: [s - WALL, half - WALL / 2.0],
        },
        Rect {
            min: [WALL, half + WALL / 2.0],
            max: [half - WALL / 2.0, s - WALL],
        },
        Rect {
            min: [half + WALL / 2.0, half + WALL / 2.0],
            max: [s - WALL, s - WALL],
        },
    ];
    let start = Pose2::new(rooms[0].min[0] + 2.0, rooms[0].min[1] + 2.0, 0.0);
    let mut blocked: Vec<Rect> = doors.iter().map(|d| d.inflated(1.0)).collect();
    blocked.push(Rect {
        min: [start.x - 1.2, start.y - 1.2],
        max: [start.x + 1.2, start.y + 1.2],
    });
    let mut targets = Vec::with_capacity(params.targets);
    for k in 0..params.targets {
        let room = &rooms[k % rooms.len()];
        let target = place_gauge(params, rng, room, &mut blocked, k).ok_or_else(|| {
            bad(format!(
                "cannot place gauge {} in room {}; use fewer targets",
                k + 1,
                k % 4 + 1
            ))
        })?;
        targets.push(target);
    }
    for room in &rooms {
        for _ in 0..params.shelves_per_room {
            if let Some(shelf) = place_shelf(rng, room, &blocked) {
                raise_rectangle(&mut floor, shelf.min, shelf.max, rng.random_range(0.9..1.8));
                blocked.push(shelf.inflated(0.3));
            }
        }
    }
    Ok(World::new("indoor", floor).with_mission(Mission {
        start,
        end: None,
        targets,
    }))
}

/// Cuts one door into each half of both inner walls; returns the door rectangles.
fn cut_doors(floor: &mut GridLayer, rng: &mut StageRng, s: f64) -> Vec<Rect> {
    let half = s / 2.0;
    let mut doors = Vec::new();
    for segment in [
        (WALL + 0.8, half - 0.8 - DOOR),
        (half + 0.8, s - WALL - 0.8 - DOOR),
    ] {
        let a = rng.random_range(segment.0..segment.1);
        doors.push(Rect {
            min: [half - WALL, a],
            max: [half + WALL, a + DOOR],
        });
        let b = rng.random_range(segment.0..segment.1);
        doors.push(Rect {
            min: [b, half - WALL],
            max: [b + DOOR, half + WALL],
        });
    }
    let g = floor.geometry;
    for j in 0..g.size[1] {
        for i in 0..g.size[0] {
            let c = g.center_of(i, j);
            if doors.iter().any(|d| d.contains(c)) {
                floor.set(i, j, 0.0);
            }
        }
    }
    doors
}

/// A shelf (0.5 m deep, 1.0–1.8 m long) against a side of `room`, clear of `blocked`.
fn place_shelf(rng: &mut StageRng, room: &Rect, blocked: &[Rect]) -> Option<Rect> {
    for _ in 0..200 {
        let side = room_sides(room)[rng.random_range(0..4)];
        let length = rng.random_range(1.0..1.8);
        let t = rng.random_range(0.0..(side.length - length).max(0.0));
        let a = side.at(t);
        let b = side.at(t + length);
        let depth = [side.normal[0] * 0.5, side.normal[1] * 0.5];
        let corners = [
            a,
            b,
            [a[0] + depth[0], a[1] + depth[1]],
            [b[0] + depth[0], b[1] + depth[1]],
        ];
        let shelf = Rect {
            min: [
                corners.iter().map(|c| c[0]).fold(f64::INFINITY, f64::min),
                corners.iter().map(|c| c[1]).fold(f64::INFINITY, f64::min),
            ],
            max: [
                corners
                    .iter()
                    .map(|c| c[0])
                    .fold(f64::NEG_INFINITY, f64::max),
                corners
                    .iter()
                    .map(|c| c[1])
                    .fold(f64::NEG_INFINITY, f64::max),
            ],
        };
        if !blocked.iter().any(|r| r.overlaps(&shelf)) {
            return Some(shelf);
        }
    }
    None
}

/// A gauge on a wall of `room` with PoIs in front of it, clear of `blocked`.
fn place_gauge(
    params: &IndoorParams,
    rng: &mut StageRng,
    room: &Rect,
    blocked: &mut Vec<Rect>,
    k: usize,
) -> Option<Target> {
    let spread = 0.8;
    for _ in 0..500 {
        let side = room_sides(room)[rng.random_range(0..4)];
        let margin = 1.2;
        if side.length <= 2.0 * margin {
            continue;
        }
        let t = rng.random_range(margin..side.length - margin);
        let on_wall = side.at(t);
        let front = [
            on_wall[0] + side.normal[0] * params.inspection_distance,
            on_wall[1] + side.normal[1] * params.inspection_distance,
        ];
        let zone = Rect {
            min: [
                front[0].min(on_wall[0]) - spread / 2.0 - 0.3,
                front[1].min(on_wall[1]) - spread / 2.0 - 0.3,
            ],
            max: [
                front[0].max(on_wall[0]) + spread / 2.0 + 0.3,
                front[1].max(on_wall[1]) + spread / 2.0 + 0.3,
            ],
        };
        if blocked.iter().any(|r| r.overlaps(&zone)) {
            continue;
        }
        blocked.push(zone);
        let yaw = (-side.normal[1]).atan2(-side.normal[0]);
        let n = params.pois_per_target;
        let pois = (0..n)
            .map(|p| {
                let lateral = if n == 1 {
                    0.0
                } else {
                    spread * (p as f64 / (n - 1) as f64 - 0.5)
                };
                Pose2::new(
                    front[0] + side.tangent[0] * lateral,
                    front[1] + side.tangent[1] * lateral,
                    yaw,
                )
            })
            .collect();
        return Some(Target {
            id: format!("gauge-{:02}", k + 1),
            position: Point3 {
                x: on_wall[0],
                y: on_wall[1],
                z: 1.0,
            },
            pois,
        });
    }
    None
}

smug_core::register_plugin!(
    smug_core::registry::WorldStage,
    name = "indoor",
    summary = "procedural indoor world: four rooms with doors, shelves, gauges (ToIs) on the walls",
    params = IndoorParams,
    build = |params, ctx| Ok(Box::new(indoor_world_within(
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
    fn every_seed_gives_a_complete_world() {
        for seed in 0..40 {
            let w =
                indoor_world(&IndoorParams::default(), &mut StageRng::seed_from_u64(seed)).unwrap();
            assert_eq!(w.mission.targets.len(), 12, "seed {seed}");
        }
    }

    #[test]
    fn paper_sized_world_has_rooms_doors_and_gauges() {
        let params = IndoorParams::default();
        let w = indoor_world(&params, &mut StageRng::seed_from_u64(2)).unwrap();
        assert_eq!(
            w,
            indoor_world(&params, &mut StageRng::seed_from_u64(2)).unwrap()
        );
        assert_eq!(w.world.elevation.geometry.size, [160, 160]);
        assert_eq!(w.mission.targets.len(), 12);
        assert!(w.mission.targets.iter().all(|t| t.pois.len() == 2));
        w.mission.validate().unwrap();
        // Walls are high, the start is on the floor, every PoI is on the floor.
        assert_eq!(w.world.height_at(8.0, 0.1), Some(2.0));
        assert_eq!(
            w.world.height_at(w.mission.start.x, w.mission.start.y),
            Some(0.0)
        );
        for t in &w.mission.targets {
            for p in &t.pois {
                assert_eq!(
                    w.world.height_at(p.x, p.y),
                    Some(0.0),
                    "{} PoI on an obstacle",
                    t.id
                );
            }
        }
        let doors_cut = (0..160)
            .filter(|&j| w.world.elevation.get(80, j) == 0.0)
            .count();
        assert!(
            doors_cut >= 2 * 12,
            "the inner wall has {doors_cut} open cells"
        );
    }
}
