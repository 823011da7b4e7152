//! The grid map generators: reproducible per seed, and each family has its shape
//! (density, one-cell doors, one-cell corridors, large obstacles).

use smug_worlds::grid_gen::{generate, GridFamily, GridParams};
use smug_worlds::movingai::MovingAiMap;

fn map(family: GridFamily, w: usize, h: usize, seed: u64) -> MovingAiMap {
    generate(&GridParams::new(family, w, h, seed)).unwrap()
}

/// The passable cells 4-connected to the first passable cell.
fn reachable_from_first(m: &MovingAiMap) -> usize {
    let Some(first) = m.passable.iter().position(|&p| p) else {
        return 0;
    };
    let mut seen = vec![false; m.passable.len()];
    let mut stack = vec![first];
    seen[first] = true;
    let mut count = 0;
    while let Some(i) = stack.pop() {
        count += 1;
        let (x, y) = (i % m.width, i / m.width);
        let mut visit = |nx: usize, ny: usize| {
            let j = ny * m.width + nx;
            if m.is_passable(nx, ny) && !seen[j] {
                seen[j] = true;
                stack.push(j);
            }
        };
        visit(x + 1, y);
        visit(x, y + 1);
        if x > 0 {
            visit(x - 1, y);
        }
        if y > 0 {
            visit(x, y - 1);
        }
    }
    count
}

#[test]
fn a_seed_gives_the_same_map_and_other_seeds_other_maps() {
    for family in GridFamily::ALL {
        let a = map(family, 40, 30, 7);
        assert_eq!(a, map(family, 40, 30, 7), "{family}");
        assert_eq!((a.width, a.height, a.passable.len()), (40, 30, 1200));
        for seed in [8, 9, 1000] {
            assert_ne!(a, map(family, 40, 30, seed), "{family}: seeds 7 and {seed}");
        }
        assert_eq!(family.name().parse::<GridFamily>().unwrap(), family);
    }
}

#[test]
fn random_maps_have_the_requested_density() {
    for (density, w, h) in [(0.1, 32, 32), (0.2, 32, 32), (0.35, 50, 20), (0.0, 8, 8)] {
        for seed in 1..4 {
            let params = GridParams {
                density,
                ..GridParams::new(GridFamily::Random, w, h, seed)
            };
            let m = generate(&params).unwrap();
            let blocked = m.passable.len() - m.passable_count();
            let expected = (density * (w * h) as f64).round() as usize;
            assert_eq!(blocked, expected, "density {density}, seed {seed}");
        }
    }
}

#[test]
fn rooms_are_joined_by_one_cell_doors_and_all_reachable() {
    let room = GridParams::DEFAULT_ROOM_SIZE;
    for seed in 1..6 {
        let m = map(GridFamily::Rooms, 64, 48, seed);
        assert_eq!(reachable_from_first(&m), m.passable_count(), "seed {seed}");
        let wall = |c: usize| (c + 1).is_multiple_of(room + 1);
        let mut doors = 0;
        for y in 0..m.height {
            for x in 0..m.width {
                let (wall_x, wall_y) = (wall(x) && x + 1 < m.width, wall(y) && y + 1 < m.height);
                if !(wall_x || wall_y) || !m.is_passable(x, y) {
                    continue;
                }
                doors += 1;
                assert!(
                    !(wall_x && wall_y),
                    "seed {seed}: wall crossing ({x}, {y}) open"
                );
                // A door is one cell: the wall cells beside it along the wall are blocked,
                // the room cells on either side across it are free.
                let (along, across) = if wall_x {
                    (
                        [(x, y.wrapping_sub(1)), (x, y + 1)],
                        [(x - 1, y), (x + 1, y)],
                    )
                } else {
                    (
                        [(x.wrapping_sub(1), y), (x + 1, y)],
                        [(x, y - 1), (x, y + 1)],
                    )
                };
                for (a, b) in along {
                    assert!(
                        !m.is_passable(a, b),
                        "seed {seed}: door at ({x}, {y}) wider"
                    );
                }
                for (a, b) in across {
                    assert!(
                        m.is_passable(a, b),
                        "seed {seed}: door at ({x}, {y}) leads nowhere"
                    );
                }
            }
        }
        // 8 × 6 rooms: a spanning tree has 47 doors, there are 82 walls.
        assert!((47..=82).contains(&doors), "seed {seed}: {doors} doors");
    }
}

#[test]
fn mazes_have_one_cell_corridors_and_are_connected() {
    for (w, h, seed) in [(33, 33, 1), (32, 21, 2), (9, 51, 3)] {
        let m = map(GridFamily::Maze, w, h, seed);
        assert_eq!(reachable_from_first(&m), m.passable_count(), "{w}×{h}");
        for y in 0..h - 1 {
            for x in 0..w - 1 {
                let square = [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)];
                assert!(
                    !square.iter().all(|&(a, b)| m.is_passable(a, b)),
                    "{w}×{h}: a 2×2 open square at ({x}, {y})"
                );
            }
        }
        // Every junction (even x and y) is a corridor cell: the maze spans the map.
        let junctions = w.div_ceil(2) * h.div_ceil(2);
        assert_eq!(
            (0..h)
                .step_by(2)
                .flat_map(|y| (0..w).step_by(2).map(move |x| (x, y)))
                .filter(|&(x, y)| m.is_passable(x, y))
                .count(),
            junctions
        );
        // A perfect maze is a tree: 2 · junctions − 1 corridor cells.
        assert_eq!(m.passable_count(), 2 * junctions - 1, "{w}×{h}");
    }
}

#[test]
fn terrain_is_open_ground_with_a_few_large_obstacles() {
    for seed in 1..5 {
        let m = map(GridFamily::Terrain, 64, 64, seed);
        let share = 1.0 - m.passable_count() as f64 / m.passable.len() as f64;
        // Placement stops at the first obstacle that reaches 20%; one obstacle is at most
        // a 22 × 22 square (12% of the map).
        assert!((0.2..0.32).contains(&share), "seed {seed}: {share}");
        // Large: the blocked cells form a few big blobs, not scattered cells.
        let inverted = MovingAiMap {
            passable: m.passable.iter().map(|p| !p).collect(),
            ..m.clone()
        };
        let biggest = largest_component(&inverted);
        assert!(
            biggest >= 50,
            "seed {seed}: largest obstacle {biggest} cells"
        );
        assert!(
            largest_component(&m) as f64 > 0.6 * m.passable_count() as f64,
            "seed {seed}: ground split"
        );
    }
}

/// The size of the largest 4-connected set of passable cells.
fn largest_component(m: &MovingAiMap) -> usize {
    let mut rest = m.clone();
    let mut largest = 0;
    while rest.passable_count() > 0 {
        let before = rest.passable_count();
        let size = reachable_from_first(&rest);
        largest = largest.max(size);
        // Remove that component: flood again, marking cells blocked.
        let first = rest.passable.iter().position(|&p| p).unwrap();
        let mut stack = vec![first];
        while let Some(i) = stack.pop() {
            if !rest.passable[i] {
                continue;
            }
            rest.passable[i] = false;
            let (x, y) = (i % m.width, i / m.width);
            for (nx, ny) in [
                (x + 1, y),
                (x.wrapping_sub(1), y),
                (x, y + 1),
                (x, y.wrapping_sub(1)),
            ] {
                if rest.is_passable(nx, ny) {
                    stack.push(ny * m.width + nx);
                }
            }
        }
        assert_eq!(before - rest.passable_count(), size);
    }
    largest
}

#[test]
fn bad_parameters_are_errors() {
    let base = GridParams::new(GridFamily::Random, 8, 8, 1);
    let cases = [
        (GridParams { width: 0, ..base }, "size 0x8"),
        (
            GridParams {
                height: 5000,
                ..base
            },
            "1 to 4096",
        ),
        (
            GridParams {
                density: 1.0,
                ..base
            },
            "density",
        ),
        (
            GridParams {
                density: f64::NAN,
                ..base
            },
            "density",
        ),
        (
            GridParams {
                density: -0.1,
                ..base
            },
            "density",
        ),
        (
            GridParams {
                room_size: 0,
                family: GridFamily::Rooms,
                ..base
            },
            "room size",
        ),
    ];
    for (params, needle) in cases {
        let err = generate(&params).unwrap_err().to_string();
        assert!(err.contains(needle), "{err}");
    }
    let err = "forest".parse::<GridFamily>().unwrap_err().to_string();
    assert!(err.contains("unknown map family `forest`"), "{err}");
}

#[test]
fn tiny_maps_of_every_family_generate() {
    for family in GridFamily::ALL {
        for (w, h) in [(1, 1), (1, 5), (2, 2), (3, 1)] {
            let m = map(family, w, h, 1);
            assert_eq!(m.passable.len(), w * h, "{family} {w}×{h}");
        }
    }
}

#[test]
fn polygons_are_open_ground_with_staircase_edged_obstacles() {
    for seed in 1..4 {
        let m = map(GridFamily::Polygons, 200, 200, seed);
        let share = 1.0 - m.passable_count() as f64 / m.passable.len() as f64;
        // Placement stops at the first polygon that reaches 20%; one polygon covers at
        // most π·(200/12)² cells (2.2% of the map).
        assert!((0.2..0.23).contains(&share), "seed {seed}: {share}");
        // Rasterised diagonal edges: some blocked cell has a free cell diagonally
        // beside it with both cells between free and blocked (a staircase step).
        let steps = (1..199)
            .flat_map(|y| (1..199).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                !m.is_passable(x, y)
                    && m.is_passable(x + 1, y + 1)
                    && m.is_passable(x, y + 1) != m.is_passable(x + 1, y)
            })
            .count();
        assert!(steps > 100, "seed {seed}: {steps} staircase steps");
        assert!(
            largest_component(&m) as f64 > 0.9 * m.passable_count() as f64,
            "seed {seed}: ground split"
        );
    }
}
