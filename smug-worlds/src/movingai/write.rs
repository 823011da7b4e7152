//! Writers of MovingAI `.map` and `.scen` files (read back unchanged by
//! [`super::parse_map`] and [`super::parse_scenarios`]) and of a grid as map_server
//! YAML + PGM.

use super::{check_resolution, read_map, MovingAiError, MovingAiMap, Scenario};
use crate::export::{write_map_yaml, write_pgm, ExportError, FREE_VALUE, OCCUPIED_VALUE};
use crate::map_file::MapYaml;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The text of a `.map` file for `map`: passable cells `.`, blocked ones `@`, LF line
/// ends.
pub fn format_map(map: &MovingAiMap) -> String {
    let mut text = format!(
        "type octile\nheight {}\nwidth {}\nmap\n",
        map.height, map.width
    );
    for row in map.passable.chunks(map.width.max(1)) {
        text.extend(row.iter().map(|&free| if free { '.' } else { '@' }));
        text.push('\n');
    }
    text
}

/// The text of a `.scen` file: `version 1`, then one tab-separated line per scenario,
/// the optimal length with 8 decimals (as MovingAI's files).
pub fn format_scenarios(scenarios: &[Scenario]) -> String {
    let mut text = String::from("version 1\n");
    for s in scenarios {
        // Writing to a String cannot fail.
        let _ = writeln!(
            text,
            "{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{:.8}",
            s.bucket,
            s.map,
            s.width,
            s.height,
            s.start[0],
            s.start[1],
            s.goal[0],
            s.goal[1],
            s.optimal_length
        );
    }
    text
}

/// Writes `map` as a `.map` file at `path`, creating its folder.
pub fn write_map(path: &Path, map: &MovingAiMap) -> Result<(), MovingAiError> {
    write_text(path, &format_map(map))
}

/// Writes `scenarios` as a `.scen` file at `path`, creating its folder.
pub fn write_scenarios(path: &Path, scenarios: &[Scenario]) -> Result<(), MovingAiError> {
    write_text(path, &format_scenarios(scenarios))
}

/// Writes `grid` as the map_server YAML `out_yaml` and a PGM beside it (same stem), at
/// `resolution` metres per cell with origin `[0, 0]`, `comment` as the YAML's first
/// line. Passable cells are free, blocked ones occupied. Returns the PGM's path.
pub fn grid_to_map_yaml(
    grid: &MovingAiMap,
    out_yaml: &Path,
    resolution: f64,
    comment: &str,
) -> Result<PathBuf, MovingAiError> {
    check_resolution(resolution, out_yaml)?;
    let dir = out_yaml.parent().unwrap_or(Path::new(""));
    create_dir(dir)?;
    let pgm_name = format!("{}.pgm", crate::map_file::file_stem(out_yaml));
    let pgm_path = dir.join(&pgm_name);
    let pixels: Vec<u8> = grid
        .passable
        .iter()
        .map(|&free| if free { FREE_VALUE } else { OCCUPIED_VALUE })
        .collect();
    write_pgm(&pgm_path, [grid.width, grid.height], &pixels)?;
    let yaml = MapYaml::new(pgm_name, resolution, [0.0, 0.0]);
    write_map_yaml(out_yaml, &yaml, comment)?;
    Ok(pgm_path)
}

fn create_dir(dir: &Path) -> Result<(), ExportError> {
    if dir.as_os_str().is_empty() {
        return Ok(());
    }
    std::fs::create_dir_all(dir).map_err(|source| ExportError::Write {
        path: dir.to_path_buf(),
        source,
    })
}

fn write_text(path: &Path, text: &str) -> Result<(), MovingAiError> {
    create_dir(path.parent().unwrap_or(Path::new("")))?;
    smug_core::output::write_atomic(path, text.as_bytes()).map_err(|source| {
        ExportError::Write {
            path: path.to_path_buf(),
            source,
        }
        .into()
    })
}

/// Converts the MovingAI map `map` into `out_yaml` and a PGM beside it (same stem),
/// at `resolution` metres per cell with origin `[0, 0]` (see the
/// [module documentation](super) for the coordinates). Passable cells are free,
/// blocked ones occupied. Returns the PGM's path.
pub fn convert_movingai(
    map: &Path,
    out_yaml: &Path,
    resolution: f64,
) -> Result<PathBuf, MovingAiError> {
    check_resolution(resolution, map)?;
    let grid = read_map(map)?;
    grid_to_map_yaml(
        &grid,
        out_yaml,
        resolution,
        &format!("converted from MovingAI map {}", map.display()),
    )
}
