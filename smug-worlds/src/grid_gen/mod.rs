//! Seeded generators of grid maps in the families path-planning benchmarks use:
//! random obstacles, rooms joined by one-cell doors, mazes with one-cell corridors and
//! open terrain with a few large obstacles, and open ground with convex polygons.
//!
//! Every generator draws from one ChaCha8 stream ([`smug_core::rng::stage_rng`]) seeded
//! by [`GridParams::seed`], so a seed gives the same map bit for bit on every platform.
//! Maps are [`MovingAiMap`]s: write them with [`crate::movingai::write_map`].

mod maze;
mod polygons;
mod random;
mod rooms;
mod shapes;
mod terrain;

use crate::movingai::MovingAiMap;
use std::fmt;
use std::str::FromStr;

/// Largest width or height a generator accepts.
pub const MAX_SIDE: usize = 4096;

/// A family of generated grid maps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GridFamily {
    /// Cells blocked independently at random: exactly `round(density · cells)` of them.
    Random,
    /// Square rooms of `room_size` cells separated by one-cell walls, adjacent rooms
    /// joined by at most one one-cell door; every room is reachable.
    Rooms,
    /// A perfect maze: one-cell corridors between one-cell walls, every corridor cell
    /// reachable.
    Maze,
    /// Open ground with a few large discs and rectangles covering about `density` of it.
    Terrain,
    /// Open ground with random convex polygons (rasterised: their diagonal edges are
    /// staircases) covering about `density` of it.
    Polygons,
}

impl GridFamily {
    /// Every family, in documentation order.
    pub const ALL: [GridFamily; 5] = [
        Self::Random,
        Self::Rooms,
        Self::Maze,
        Self::Terrain,
        Self::Polygons,
    ];

    /// The family's name on the command line and in file names.
    pub fn name(self) -> &'static str {
        match self {
            Self::Random => "random",
            Self::Rooms => "rooms",
            Self::Maze => "maze",
            Self::Terrain => "terrain",
            Self::Polygons => "polygons",
        }
    }

    /// The obstacle density used when none is given (families that use one).
    pub fn default_density(self) -> f64 {
        match self {
            Self::Random => 0.1,
            Self::Terrain | Self::Polygons => 0.2,
            Self::Rooms | Self::Maze => 0.0,
        }
    }
}

impl fmt::Display for GridFamily {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for GridFamily {
    type Err = GridGenError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|f| f.name() == text)
            .ok_or_else(|| GridGenError::UnknownFamily(text.to_string()))
    }
}

/// What to generate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridParams {
    /// The family.
    pub family: GridFamily,
    /// Columns, 1 to [`MAX_SIDE`].
    pub width: usize,
    /// Rows, 1 to [`MAX_SIDE`].
    pub height: usize,
    /// Seed of every random choice.
    pub seed: u64,
    /// Blocked share of the cells, in `[0, 1)` (`random`, `terrain` and `polygons` only).
    pub density: f64,
    /// Interior side of a room in cells, ≥ 1 (`rooms` only).
    pub room_size: usize,
}

impl GridParams {
    /// Room side used when none is given.
    pub const DEFAULT_ROOM_SIZE: usize = 8;

    /// A `width` × `height` map of `family` with seed `seed` and the family's defaults.
    pub fn new(family: GridFamily, width: usize, height: usize, seed: u64) -> Self {
        Self {
            family,
            width,
            height,
            seed,
            density: family.default_density(),
            room_size: Self::DEFAULT_ROOM_SIZE,
        }
    }
}

/// Why a map could not be generated.
#[derive(Debug, thiserror::Error)]
pub enum GridGenError {
    /// The family name is not one of [`GridFamily::ALL`].
    #[error("unknown map family `{0}` (expected random, rooms, maze, terrain or polygons)")]
    UnknownFamily(String),
    /// A parameter is out of its domain.
    #[error("{0}")]
    Invalid(String),
}

/// Generates the map `params` describes.
pub fn generate(params: &GridParams) -> Result<MovingAiMap, GridGenError> {
    validate(params)?;
    let mut rng = smug_core::rng::stage_rng(params.seed, params.family.name());
    let (w, h) = (params.width, params.height);
    Ok(match params.family {
        GridFamily::Random => random::generate(w, h, params.density, &mut rng),
        GridFamily::Rooms => rooms::generate(w, h, params.room_size, &mut rng),
        GridFamily::Maze => maze::generate(w, h, &mut rng),
        GridFamily::Terrain => terrain::generate(w, h, params.density, &mut rng),
        GridFamily::Polygons => polygons::generate(w, h, params.density, &mut rng),
    })
}

fn validate(params: &GridParams) -> Result<(), GridGenError> {
    let invalid = |m: String| Err(GridGenError::Invalid(m));
    if !(1..=MAX_SIDE).contains(&params.width) || !(1..=MAX_SIDE).contains(&params.height) {
        return invalid(format!(
            "size {}x{}: width and height must be 1 to {MAX_SIDE}",
            params.width, params.height
        ));
    }
    if !(0.0..1.0).contains(&params.density) {
        return invalid(format!(
            "density must be at least 0 and below 1, got {}",
            params.density
        ));
    }
    if params.room_size == 0 {
        return invalid("room size must be at least 1".into());
    }
    Ok(())
}
