//! Drawing terrain features onto an elevation layer.

use rand::SeedableRng;
use smug_core::rng::StageRng;
use smug_core::{BuildContext, GridGeometry, GridLayer, MemoryLimit};

/// The RNG of a procedural world: its own `seed` if given, else the config seed's
/// `world` stream.
pub(crate) fn world_rng(seed: Option<u64>, ctx: &BuildContext) -> StageRng {
    match seed {
        Some(seed) => StageRng::seed_from_u64(seed),
        None => ctx.rng("world"),
    }
}

/// Cells whose centres lie within `radius` of `(cx, cy)`, as index ranges.
fn cells_near(
    g: &GridGeometry,
    cx: f64,
    cy: f64,
    radius: f64,
) -> (std::ops::Range<usize>, std::ops::Range<usize>) {
    let to_index = |v: f64, origin: f64, n: usize| {
        (((v - origin) / g.resolution).floor().max(0.0) as usize).min(n)
    };
    let i0 = to_index(cx - radius, g.origin[0], g.size[0]);
    let i1 = (to_index(cx + radius, g.origin[0], g.size[0]) + 1).min(g.size[0]);
    let j0 = to_index(cy - radius, g.origin[1], g.size[1]);
    let j1 = (to_index(cy + radius, g.origin[1], g.size[1]) + 1).min(g.size[1]);
    (i0..i1, j0..j1)
}

/// Adds `f(dx, dy)` (offsets from the centre) to every cell within `radius`.
pub(crate) fn add_feature(
    layer: &mut GridLayer,
    center: [f64; 2],
    radius: f64,
    f: impl Fn(f64, f64) -> f64,
) {
    let g = layer.geometry;
    let (is, js) = cells_near(&g, center[0], center[1], radius);
    for j in js {
        for i in is.clone() {
            let [x, y] = g.center_of(i, j);
            let delta = f(x - center[0], y - center[1]);
            if delta != 0.0 {
                let v = layer.get(i, j) + delta as f32;
                layer.set(i, j, v);
            }
        }
    }
}

/// Raises every cell within `radius` to `base(x, y) + f(dx, dy)` where that is higher.
pub(crate) fn raise_feature(
    layer: &mut GridLayer,
    base: &GridLayer,
    center: [f64; 2],
    radius: f64,
    f: impl Fn(f64, f64) -> Option<f64>,
) {
    let g = layer.geometry;
    let (is, js) = cells_near(&g, center[0], center[1], radius);
    for j in js {
        for i in is.clone() {
            let [x, y] = g.center_of(i, j);
            if let Some(h) = f(x - center[0], y - center[1]) {
                let top = base.get(i, j) + h as f32;
                if top > layer.get(i, j) {
                    layer.set(i, j, top);
                }
            }
        }
    }
}

/// Raises every cell whose centre lies in the rectangle `[min, max]` to at least `height`.
pub(crate) fn raise_rectangle(layer: &mut GridLayer, min: [f64; 2], max: [f64; 2], height: f64) {
    let g = layer.geometry;
    for j in 0..g.size[1] {
        for i in 0..g.size[0] {
            let [x, y] = g.center_of(i, j);
            if x >= min[0]
                && x <= max[0]
                && y >= min[1]
                && y <= max[1]
                && layer.get(i, j) < height as f32
            {
                layer.set(i, j, height as f32);
            }
        }
    }
}

/// Why a procedural world's size and resolution make no grid.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub(crate) enum CanvasError {
    /// The size is not positive and finite.
    #[error("size must be positive, got {0:?}")]
    Size([f64; 2]),
    /// The resolution is not positive and finite.
    #[error("resolution must be > 0, got {0}")]
    Resolution(f64),
    /// More than 10⁸ cells.
    #[error("size {size:?} at {resolution} m has too many cells")]
    TooManyCells {
        /// The size, metres.
        size: [f64; 2],
        /// The resolution, metres.
        resolution: f64,
    },
    /// The grid itself is refused (e.g. above the memory limit).
    #[error(transparent)]
    Grid(#[from] smug_core::GridError),
}

/// A geometry of `size` metres at `resolution`, origin at (0, 0), within `memory`.
pub(crate) fn geometry(
    size: [f64; 2],
    resolution: f64,
    memory: MemoryLimit,
) -> Result<GridGeometry, CanvasError> {
    if !(size[0] > 0.0 && size[1] > 0.0 && size[0].is_finite() && size[1].is_finite()) {
        return Err(CanvasError::Size(size));
    }
    if !(resolution > 0.0 && resolution.is_finite()) {
        return Err(CanvasError::Resolution(resolution));
    }
    let cells = [
        (size[0] / resolution).round(),
        (size[1] / resolution).round(),
    ];
    if cells[0] * cells[1] > 1e8 {
        return Err(CanvasError::TooManyCells { size, resolution });
    }
    GridGeometry::new_within(
        [0.0, 0.0],
        resolution,
        [cells[0].max(1.0) as usize, cells[1].max(1.0) as usize],
        memory,
    )
    .map_err(CanvasError::from)
}
