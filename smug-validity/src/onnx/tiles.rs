//! Running a fully convolutional model over a large map in square tiles: each tile is
//! cut with `overlap` cells of context on every side (beyond the map: padding), and
//! only its centre is kept, so the result equals one run over the whole map whenever
//! the model's receptive radius is at most `overlap` cells.

use serde::{Deserialize, Serialize};

/// What the model sees beyond the map's border.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Padding {
    /// The nearest border cell's value (per channel).
    #[default]
    Edge,
    /// Zero (after normalisation).
    Zero,
}

/// How a map is cut into tiles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tiling {
    /// Side of a tile's kept centre, cells.
    pub tile: usize,
    /// Context cells on each side.
    pub overlap: usize,
    /// Padding beyond the map.
    pub padding: Padding,
}

impl Tiling {
    /// Side of the window the model is run on.
    pub fn window(&self) -> usize {
        self.tile + 2 * self.overlap
    }
}

/// A model's output for one window: its side (square, centred in the window) and
/// values, row-major.
pub struct WindowOutput {
    /// Side, cells (the window's, or less for a model without padding).
    pub side: usize,
    /// Values.
    pub values: Vec<f32>,
}

/// Why a window's output cannot be placed.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
pub enum TileError<E> {
    /// The model failed.
    #[error(transparent)]
    Model(E),
    /// The output is larger than the window, trims unevenly or more than the overlap.
    #[error(
        "the model turns a {window}×{window} window into {side}×{side}: \
         it may trim at most `overlap` = {overlap} cells per side"
    )]
    OutputSize {
        /// Window side.
        window: usize,
        /// Output side.
        side: usize,
        /// The overlap.
        overlap: usize,
    },
}

/// Runs `run` on every window of `planes` (`channels` planes of `size = [nx, ny]`,
/// row-major) and returns the output for every map cell, row-major.
pub fn run_tiled<E>(
    planes: &[f32],
    channels: usize,
    size: [usize; 2],
    tiling: Tiling,
    mut run: impl FnMut(&[f32]) -> Result<WindowOutput, E>,
) -> Result<Vec<f32>, TileError<E>> {
    let [nx, ny] = size;
    let side = tiling.window();
    let mut out = vec![f32::NAN; nx * ny];
    for tj in (0..ny).step_by(tiling.tile) {
        for ti in (0..nx).step_by(tiling.tile) {
            let window = cut_window(planes, channels, size, [ti, tj], tiling);
            let output = run(&window).map_err(TileError::Model)?;
            let trim = side.saturating_sub(output.side) / 2;
            let uneven = (side.max(output.side) - output.side) % 2 != 0;
            if output.side > side
                || uneven
                || trim > tiling.overlap
                || output.values.len() < output.side * output.side
            {
                return Err(TileError::OutputSize {
                    window: side,
                    side: output.side,
                    overlap: tiling.overlap,
                });
            }
            let offset = tiling.overlap - trim;
            for j in tj..(tj + tiling.tile).min(ny) {
                for i in ti..(ti + tiling.tile).min(nx) {
                    let (a, b) = (i - ti + offset, j - tj + offset);
                    out[j * nx + i] = output.values[b * output.side + a];
                }
            }
        }
    }
    Ok(out)
}

/// The window whose kept centre starts at map cell `corner`, channel-major.
fn cut_window(
    planes: &[f32],
    channels: usize,
    [nx, ny]: [usize; 2],
    corner: [usize; 2],
    tiling: Tiling,
) -> Vec<f32> {
    let side = tiling.window();
    let mut window = Vec::with_capacity(channels * side * side);
    let cell = |start: usize, k: usize, n: usize| -> Option<usize> {
        let at = (start + k).checked_sub(tiling.overlap);
        match (at, tiling.padding) {
            (Some(at), _) if at < n => Some(at),
            (_, Padding::Zero) => None,
            (Some(_), Padding::Edge) => Some(n - 1),
            (None, Padding::Edge) => Some(0),
        }
    };
    for c in 0..channels {
        let plane = &planes[c * nx * ny..(c + 1) * nx * ny];
        for b in 0..side {
            for a in 0..side {
                window.push(match (cell(corner[0], a, nx), cell(corner[1], b, ny)) {
                    (Some(i), Some(j)) => plane[j * nx + i],
                    _ => 0.0,
                });
            }
        }
    }
    window
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 × 3 box sum with zero padding inside the window (a model's 'same' conv).
    fn box_sum(window: &[f32], side: usize) -> WindowOutput {
        let at = |i: isize, j: isize| {
            let inside = (0..side as isize).contains(&i) && (0..side as isize).contains(&j);
            if inside {
                window[j as usize * side + i as usize]
            } else {
                0.0
            }
        };
        let mut values = Vec::with_capacity(side * side);
        for j in 0..side as isize {
            for i in 0..side as isize {
                values.push(
                    (-1..=1)
                        .flat_map(|dj| (-1..=1).map(move |di| (di, dj)))
                        .map(|(di, dj)| at(i + di, j + dj))
                        .sum(),
                );
            }
        }
        WindowOutput { side, values }
    }

    #[test]
    fn tiles_with_enough_overlap_equal_one_window_over_the_map() {
        let size = [7, 5];
        let planes: Vec<f32> = (0..35).map(|k| ((k * 37) % 11) as f32).collect();
        for padding in [Padding::Edge, Padding::Zero] {
            let whole = Tiling {
                tile: 7,
                overlap: 1,
                padding,
            };
            let expected =
                run_tiled(&planes, 1, size, whole, |w| Ok::<_, ()>(box_sum(w, 9))).unwrap();
            let small = Tiling {
                tile: 2,
                overlap: 1,
                padding,
            };
            let tiled = run_tiled(&planes, 1, size, small, |w| Ok::<_, ()>(box_sum(w, 4))).unwrap();
            assert_eq!(tiled, expected, "{padding:?}");
        }
        // Zero padding: a corner cell sums its 4 in-map neighbours only.
        let whole = Tiling {
            tile: 7,
            overlap: 1,
            padding: Padding::Zero,
        };
        let out = run_tiled(&planes, 1, size, whole, |w| Ok::<_, ()>(box_sum(w, 9))).unwrap();
        assert_eq!(out[0], planes[0] + planes[1] + planes[7] + planes[8]);
    }

    #[test]
    fn a_trimming_model_is_placed_by_its_margin_and_too_much_trim_is_an_error() {
        let planes: Vec<f32> = (0..16).map(|k| k as f32).collect();
        let tiling = Tiling {
            tile: 2,
            overlap: 1,
            padding: Padding::Edge,
        };
        // 'valid' identity: drops one cell per side, keeps the centre.
        let centre = |w: &[f32]| {
            let values = [w[5], w[6], w[9], w[10]].to_vec();
            Ok::<_, ()>(WindowOutput { side: 2, values })
        };
        assert_eq!(
            run_tiled(&planes, 1, [4, 4], tiling, centre).unwrap(),
            planes
        );
        let tiny = |_: &[f32]| {
            Ok::<_, ()>(WindowOutput {
                side: 1,
                values: vec![0.0],
            })
        };
        assert!(matches!(
            run_tiled(&planes, 1, [4, 4], tiling, tiny),
            Err(TileError::OutputSize {
                window: 4,
                side: 1,
                overlap: 1
            })
        ));
    }
}
