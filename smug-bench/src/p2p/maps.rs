//! The maps `smug bench p2p` runs: the MovingAI benchmark maps from a data folder the
//! user downloads (`--data DIR`, else `$SMUG_DATA/movingai`), and maps of every
//! generated family with scenarios drawn by our own octile Dijkstra (`--generated`).

use crate::error::{bail, ResultExt as _};
use smug_worlds::grid_gen::{generate, GridFamily, GridParams};
use smug_worlds::movingai::{generate_scenarios, write_map, write_scenarios};
use std::path::{Path, PathBuf};

/// The MovingAI maps of the benchmark: (map, scenario file) under the data folder
/// (maps missing from it are skipped, and said so).
pub const MOVINGAI_MAPS: [(&str, &str); 7] = [
    (
        "mapf/random-32-32-10.map",
        "mapf/random-32-32-10-random-1.scen",
    ),
    (
        "mapf/random-32-32-20.map",
        "mapf/random-32-32-20-random-1.scen",
    ),
    ("dao/arena2.map", "dao/arena2.map.scen"),
    ("room/8room_000.map", "room/8room_000.map.scen"),
    ("street/Berlin_0_512.map", "street/Berlin_0_512.map.scen"),
    (
        "random/random512-10-0.map",
        "random/random512-10-0.map.scen",
    ),
    ("maze/maze512-1-0.map", "maze/maze512-1-0.map.scen"),
];

/// The environment variable naming the folder that holds `movingai/`.
pub const DATA_VARIABLE: &str = "SMUG_DATA";

/// One map to bench: its name (the `--maps` key), `.map` and `.scen` files.
pub struct BenchMap {
    /// The file stem, used by `--maps`.
    pub name: String,
    /// The `.map` file.
    pub map: PathBuf,
    /// The `.scen` file.
    pub scen: PathBuf,
}

/// The MovingAI data folder: `--data DIR`, else `$SMUG_DATA/movingai`, else an error
/// saying what to download and where.
pub fn movingai_dir(data: Option<&Path>) -> crate::Result<PathBuf> {
    if let Some(dir) = data {
        return Ok(dir.to_path_buf());
    }
    match std::env::var_os(DATA_VARIABLE) {
        Some(root) if !root.is_empty() => Ok(PathBuf::from(root).join("movingai")),
        _ => bail!("{}", missing_data_message()),
    }
}

fn missing_data_message() -> String {
    let files: Vec<String> = MOVINGAI_MAPS
        .iter()
        .map(|(map, scen)| format!("{map} + {scen}"))
        .collect();
    format!(
        "no MovingAI data: pass --data DIR or set {DATA_VARIABLE} (read as \
         ${DATA_VARIABLE}/movingai), or bench generated maps with --generated (or --maps \
         lunar). DIR holds maps of the MovingAI 2D pathfinding benchmark sets (Nathan \
         Sturtevant, published at https://movingai.com/benchmarks/grids.html and \
         https://movingai.com/benchmarks/mapf.html): {}",
        files.join(", ")
    )
}

/// The MovingAI maps under `dir` whose stem `wants` accepts.
pub fn movingai_maps(dir: &Path, wants: impl Fn(&str) -> bool) -> Vec<BenchMap> {
    MOVINGAI_MAPS
        .iter()
        .map(|(map, scen)| BenchMap {
            name: smug_worlds::map_file::file_stem(Path::new(map)),
            map: dir.join(map),
            scen: dir.join(scen),
        })
        .filter(|m| wants(&m.name))
        .collect()
}

/// True when `name` is one of the MovingAI maps.
pub fn is_movingai(name: &str) -> bool {
    MOVINGAI_MAPS
        .iter()
        .any(|(map, _)| smug_worlds::map_file::file_stem(Path::new(map)) == name)
}

/// The generated maps of `--generated`, all with seed 1: random obstacles at 10% and
/// 20%, rooms, a maze, open terrain, and a 2000 × 2000 map of polygons (4 M cells,
/// rasterised diagonal edges).
pub fn generated_params() -> Vec<GridParams> {
    let with_density = |family, size, density| GridParams {
        density,
        ..GridParams::new(family, size, size, 1)
    };
    vec![
        with_density(GridFamily::Random, 32, 0.1),
        with_density(GridFamily::Random, 32, 0.2),
        GridParams::new(GridFamily::Rooms, 64, 64, 1),
        GridParams::new(GridFamily::Maze, 33, 33, 1),
        with_density(GridFamily::Terrain, 64, 0.2),
        with_density(GridFamily::Polygons, 2000, 0.2),
    ]
}

/// The name of a generated map: family, size, density or room size, seed.
pub fn generated_name(params: &GridParams) -> String {
    let detail = match params.family {
        GridFamily::Random | GridFamily::Terrain | GridFamily::Polygons => {
            format!("-d{}", (params.density * 100.0).round())
        }
        GridFamily::Rooms => format!("-r{}", params.room_size),
        GridFamily::Maze => String::new(),
    };
    format!(
        "{}-{}x{}{detail}-s{}",
        params.family, params.width, params.height, params.seed
    )
}

/// Generates every `--generated` map `wants` accepts into `scratch`, with `scenarios`
/// scenarios each.
pub fn generated_maps(
    scratch: &Path,
    scenarios: usize,
    wants: impl Fn(&str) -> bool,
) -> crate::Result<Vec<BenchMap>> {
    let mut maps = Vec::new();
    for params in generated_params() {
        let name = generated_name(&params);
        if !wants(&name) {
            continue;
        }
        let grid = generate(&params)?;
        let map = scratch.join(format!("{name}.map"));
        let scen = scratch.join(format!("{name}.map.scen"));
        let drawn = generate_scenarios(&grid, &format!("{name}.map"), scenarios, params.seed)
            .with_context(|| name.clone())?;
        write_map(&map, &grid)?;
        write_scenarios(&scen, &drawn)?;
        maps.push(BenchMap { name, map, scen });
    }
    Ok(maps)
}
