//! Polygon maps for `smug bench modes`: generated (seeded star-shaped polygons on a
//! 2000 × 2000 cell map, cities in the free space) or read from a CRL
//! `MAP_POINTS_CITY_POINTS` text file (`--data`), rasterised to 2000 × 2000 square cells
//! into a world for a disc robot: one PoI per city, facing east.

use crate::error::{bail, ResultExt as _};
use rand::Rng;
use smug_core::mission::Target;
use smug_core::pose::Point3;
use smug_core::{GridGeometry, GridLayer, Mission, Pose2, Scenario, World};
use std::path::Path;

/// Cells along each side of a generated map (and of the raster of a `--data` map).
pub const SIDE: usize = 2000;

/// Height of a blocked cell above the ground, metres (a wall for the disc robot).
const WALL: f32 = 2.0;

/// Obstacles of a generated map.
const OBSTACLES: usize = 28;

/// Least distance, in cells, from a generated city to the nearest blocked cell.
const CLEARANCE: usize = 4;

/// Polygons and cities in map units (one unit per cell).
#[derive(Clone, Debug)]
pub struct PolygonMap {
    /// What the map is called in errors.
    pub name: String,
    /// The free region's outline (everything outside is blocked), if any.
    pub border: Option<Vec<[f64; 2]>>,
    /// Blocked polygons.
    pub obstacles: Vec<Vec<[f64; 2]>>,
    /// City positions; the start is `cities[start]`.
    pub cities: Vec<[f64; 2]>,
    /// The start city.
    pub start: usize,
    /// The end city of an open path, as the file gives it.
    pub end: Option<usize>,
    /// Where the raster's corner cell starts, map units.
    pub origin: [f64; 2],
    /// The raster's cell side, map units.
    pub cell: f64,
}

/// A seeded map of `OBSTACLES` star-shaped polygons (5 to 8 corners, 60 to 180
/// cells across) and `targets + 1` cities (the first is the start) at least
/// `CLEARANCE` cells from every blocked cell.
pub fn generated(targets: usize, seed: u64) -> crate::Result<PolygonMap> {
    let mut rng = smug_core::rng::stage_rng(seed, "bench-modes-polygons");
    let side = SIDE as f64;
    let mut obstacles = Vec::with_capacity(OBSTACLES);
    for _ in 0..OBSTACLES {
        let centre = [
            rng.random_range(100.0..side - 100.0),
            rng.random_range(100.0..side - 100.0),
        ];
        let radius = rng.random_range(60.0..180.0);
        let corners = rng.random_range(5..=8);
        let mut angles: Vec<f64> = (0..corners)
            .map(|_| rng.random_range(0.0..std::f64::consts::TAU))
            .collect();
        angles.sort_by(f64::total_cmp);
        obstacles.push(
            angles
                .iter()
                .map(|a| {
                    let r = radius * rng.random_range(0.6..1.0);
                    [centre[0] + r * a.cos(), centre[1] + r * a.sin()]
                })
                .collect(),
        );
    }
    let mut map = PolygonMap {
        name: format!("generated polygons, {targets} targets, seed {seed}"),
        border: None,
        obstacles,
        cities: Vec::new(),
        start: 0,
        end: None,
        origin: [0.0, 0.0],
        cell: 1.0,
    };
    let blocked = rasterise(&map);
    let clear = |x: usize, y: usize| {
        let (lo_x, lo_y) = (x.saturating_sub(CLEARANCE), y.saturating_sub(CLEARANCE));
        let (hi_x, hi_y) = ((x + CLEARANCE).min(SIDE - 1), (y + CLEARANCE).min(SIDE - 1));
        (lo_y..=hi_y).all(|j| (lo_x..=hi_x).all(|i| !blocked[j * SIDE + i]))
    };
    let mut tries = 0;
    while map.cities.len() < targets + 1 {
        tries += 1;
        if tries > 1_000_000 {
            bail!("{}: no room for {} cities", map.name, targets + 1);
        }
        let (x, y) = (rng.random_range(0..SIDE), rng.random_range(0..SIDE));
        if clear(x, y) {
            map.cities.push([x as f64 + 0.5, y as f64 + 0.5]);
        }
    }
    Ok(map)
}

/// Reads a CRL `MAP_POINTS_CITY_POINTS` text map: `[MAP_POINTS]` (`id x y`),
/// `[MAP_BORDER]` and `[MAP_OBSTACLE]` sections (one point id a line),
/// `[CITY_POINTS]` (`id x y reward`), `START_INDEX` and `END_INDEX` in `[INFO]`;
/// other sections are skipped.
pub fn read_crl(path: &Path) -> crate::Result<PolygonMap> {
    let text = std::fs::read_to_string(path).with_context(|| path.display().to_string())?;
    let mut points: std::collections::HashMap<usize, [f64; 2]> = Default::default();
    let mut polygons: Vec<(bool, Vec<usize>)> = Vec::new();
    let mut cities: Vec<(usize, [f64; 2])> = Vec::new();
    let (mut start, mut end) = (0, None);
    let mut section = String::new();
    let bad =
        |line: usize, what: &str| crate::error::invalid!("{}:{}: {what}", path.display(), line + 1);
    for (number, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        if line.starts_with('[') {
            section = line.to_string();
            match section.as_str() {
                "[MAP_BORDER]" => polygons.push((true, Vec::new())),
                "[MAP_OBSTACLE]" => polygons.push((false, Vec::new())),
                _ => {}
            }
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        let number_at = |k: usize| -> crate::Result<f64> {
            fields
                .get(k)
                .and_then(|f| f.parse().ok())
                .ok_or_else(|| bad(number, "expected a number"))
        };
        match section.as_str() {
            "[INFO]" => {
                if let Some(value) = line.strip_prefix("START_INDEX=") {
                    start = value.parse().map_err(|_| bad(number, "bad START_INDEX"))?;
                } else if let Some(value) = line.strip_prefix("END_INDEX=") {
                    end = Some(value.parse().map_err(|_| bad(number, "bad END_INDEX"))?);
                }
            }
            "[MAP_POINTS]" => {
                points.insert(number_at(0)? as usize, [number_at(1)?, number_at(2)?]);
            }
            "[MAP_BORDER]" | "[MAP_OBSTACLE]" => {
                if let Some((_, ids)) = polygons.last_mut() {
                    ids.push(number_at(0)? as usize);
                }
            }
            "[CITY_POINTS]" => {
                cities.push((number_at(0)? as usize, [number_at(1)?, number_at(2)?]))
            }
            _ => {}
        }
    }
    cities.sort_by_key(|c| c.0);
    let corner = |id: &usize| {
        points
            .get(id)
            .copied()
            .ok_or_else(|| crate::error::invalid!("{}: no map point {id}", path.display()))
    };
    let mut border = None;
    let mut obstacles = Vec::new();
    for (is_border, ids) in &polygons {
        let polygon = ids.iter().map(corner).collect::<crate::Result<Vec<_>>>()?;
        if *is_border {
            border = Some(polygon);
        } else {
            obstacles.push(polygon);
        }
    }
    let cities: Vec<[f64; 2]> = cities.into_iter().map(|c| c.1).collect();
    // The raster covers the border (else every corner and city), square.
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    let outline: Vec<[f64; 2]> = match &border {
        Some(border) => border.clone(),
        None => obstacles.iter().flatten().chain(&cities).copied().collect(),
    };
    for p in &outline {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let cell = (hi[0] - lo[0]).max(hi[1] - lo[1]) / SIDE as f64;
    if !(cell.is_finite() && cell > 0.0) {
        bail!("{}: the map has no extent", path.display());
    }
    if cities.len() < 2 || start >= cities.len() || end.is_some_and(|e| e >= cities.len()) {
        bail!(
            "{}: needs two cities or more, and a start and end among them",
            path.display()
        );
    }
    Ok(PolygonMap {
        name: path
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into()),
        border,
        obstacles,
        cities,
        start,
        end,
        origin: lo,
        cell,
    })
}

/// True when `p` lies inside `polygon` (even-odd rule).
fn inside(polygon: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut within = false;
    let mut previous = polygon[polygon.len() - 1];
    for &corner in polygon {
        let ([x0, y0], [x1, y1]) = (previous, corner);
        if (y0 > p[1]) != (y1 > p[1]) && p[0] < x0 + (p[1] - y0) * (x1 - x0) / (y1 - y0) {
            within = !within;
        }
        previous = corner;
    }
    within
}

/// Blocked cells (row-major from the bottom row): a cell is blocked when its centre
/// is inside an obstacle or outside the border.
fn rasterise(map: &PolygonMap) -> Vec<bool> {
    let mut blocked = vec![false; SIDE * SIDE];
    let [x0, y0] = map.origin;
    let centre = |i: usize, j: usize| {
        [
            x0 + (i as f64 + 0.5) * map.cell,
            y0 + (j as f64 + 0.5) * map.cell,
        ]
    };
    if let Some(border) = &map.border {
        for j in 0..SIDE {
            for i in 0..SIDE {
                blocked[j * SIDE + i] = !inside(border, centre(i, j));
            }
        }
    }
    for polygon in map.obstacles.iter().filter(|p| p.len() >= 3) {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for c in polygon {
            for k in 0..2 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
        }
        let cells = |lo: f64, hi: f64, origin: f64| {
            let (lo, hi) = ((lo - origin) / map.cell, (hi - origin) / map.cell);
            (lo.floor().max(0.0) as usize)..(hi.ceil().max(0.0) as usize).min(SIDE)
        };
        for j in cells(lo[1], hi[1], y0) {
            for i in cells(lo[0], hi[0], x0) {
                if inside(polygon, centre(i, j)) {
                    blocked[j * SIDE + i] = true;
                }
            }
        }
    }
    blocked
}

/// The world of `map`: its raster as an elevation (walls `WALL` high) and a mission
/// from the start city through every other one, back to the start (`open` false) or
/// to the file's end city (`open`, when it names one).
pub fn world(map: &PolygonMap, open: bool) -> crate::Result<Scenario> {
    let blocked = rasterise(map);
    let geometry = GridGeometry::new(map.origin, map.cell, [SIDE, SIDE])
        .map_err(|e| crate::error::invalid!("{}: {e}", map.name))?;
    let elevation = GridLayer::from_fn(
        geometry,
        |i, j| if blocked[j * SIDE + i] { WALL } else { 0.0 },
    );
    let pose = |c: usize| Pose2::new(map.cities[c][0], map.cities[c][1], 0.0);
    let end = if open {
        map.end.filter(|&e| e != map.start)
    } else {
        None
    };
    let targets = (0..map.cities.len())
        .filter(|&c| c != map.start && Some(c) != end)
        .map(|c| Target {
            id: format!("city-{c}"),
            position: Point3 {
                x: map.cities[c][0],
                y: map.cities[c][1],
                z: 0.0,
            },
            pois: vec![pose(c)],
        })
        .collect();
    let mission = Mission {
        start: pose(map.start),
        end: end.map(pose),
        targets,
    };
    Ok(World::new(map.name.clone(), elevation).with_mission(mission))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_generated_map_is_reproducible_and_its_cities_are_clear() {
        let a = generated(20, 3).unwrap();
        let b = generated(20, 3).unwrap();
        assert_eq!(a.cities, b.cities);
        assert_eq!(a.cities.len(), 21);
        let blocked = rasterise(&a);
        assert!(blocked.iter().any(|&b| b), "some cells are blocked");
        for c in &a.cities {
            assert!(!blocked[c[1] as usize * SIDE + c[0] as usize]);
        }
        assert_ne!(generated(20, 4).unwrap().cities, a.cities);
    }

    #[test]
    fn a_crl_map_is_read_with_its_border_obstacles_and_cities() {
        let dir = std::env::temp_dir().join(format!("smug-crl-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("square.txt");
        std::fs::write(
            &file,
            "[INFO]\nFORMAT=MAP_POINTS_CITY_POINTS\nSTART_INDEX=0\nEND_INDEX=1\n\n[MAP_POINTS]\n\
             0 0 0\n1 2000 0\n2 2000 2000\n3 0 2000\n4 900 900\n5 1100 900\n6 1000 1100\n\n\
             [MAP_BORDER]\n0\n1\n2\n3\n\n[MAP_OBSTACLE]\n6\n5\n4\n\n[CITY_POINTS]\n\
             0 100 100 0\n1 1900 1900 0\n2 1000 1500 3\n",
        )
        .unwrap();
        let map = read_crl(&file).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(map.cities.len(), 3);
        assert_eq!((map.start, map.end), (0, Some(1)));
        assert_eq!(map.obstacles.len(), 1);
        let blocked = rasterise(&map);
        assert_eq!((map.origin, map.cell), ([0.0, 0.0], 1.0));
        assert!(blocked[1000 * SIDE + 1000], "inside the triangle");
        assert!(!blocked[100 * SIDE + 100]);
        let open = world(&map, true).unwrap();
        assert_eq!(open.mission.targets.len(), 1);
        assert!(open.mission.end.is_some());
        assert_eq!(world(&map, false).unwrap().mission.targets.len(), 2);
    }
}
