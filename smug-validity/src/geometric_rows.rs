//! The geometric estimator's row sums: the fit of a cell whose window lies inside the
//! grid with finite heights, added from its window's runs (about `2r + 1` of them)
//! instead of from its cells (about `π r²`).
//!
//! Every run of the window is centred on the cell's column (the window is symmetric),
//! so the sums of a run of half-width `h` around column `i` of row `cj` serve every
//! cell of column `i` whose window holds that run. They are taken relative to the
//! row's own height at column `i` ([`RunSums`]) and moved to the cell's height when
//! added, so every sum stays as local as the window; nothing runs along a whole row.
//! A window that leaves the grid or holds a missing or infinite height is fitted cell
//! by cell as before ([`Window::features`]).

use super::window::{ShapeSolver, Window};
use super::TerrainFeatures;
use smug_core::{CellRect, GridLayer};

/// Columns whose row sums are computed together (the sums of a tile stay in cache).
const TILE_COLUMNS: usize = 64;

/// The window's runs as half-widths, when every run is centred on the cell.
#[derive(Clone, Debug)]
pub(super) struct RowRuns {
    /// The distinct half-widths, ascending.
    half_widths: Vec<usize>,
    /// Per run of the window (in its order): row offset, `y` offset and the index of
    /// its half-width in `half_widths`.
    runs: Vec<(isize, f64, usize)>,
    /// The window's plane solver (`None`: too few cells for a plane).
    solver: Option<ShapeSolver>,
}

impl RowRuns {
    /// The window's runs; `None` when some run is not centred (never for a window of
    /// cells within a radius, which is symmetric).
    pub(super) fn new(window: &Window) -> Option<Self> {
        let mut half_widths: Vec<usize> = Vec::new();
        for run in window.runs() {
            if run.di_lo != -run.di_hi {
                return None;
            }
            half_widths.push(run.di_hi as usize);
        }
        half_widths.sort_unstable();
        half_widths.dedup();
        let runs = window
            .runs()
            .iter()
            .map(|run| {
                let h = half_widths.binary_search(&(run.di_hi as usize)).ok()?;
                Some((run.dj, run.y, h))
            })
            .collect::<Option<_>>()?;
        Some(Self {
            half_widths,
            runs,
            solver: ShapeSolver::new(window),
        })
    }

    /// The features of every cell of `rect`: the row-sum fit where the window lies
    /// inside the grid with finite heights, the cell-by-cell fit elsewhere. A cell's
    /// features depend on the cell alone, not on the rectangle it is computed in.
    pub(super) fn rect_features(
        &self,
        window: &Window,
        elevation: &GridLayer,
        rect: CellRect,
        mut emit: impl FnMut(usize, usize, Option<TerrainFeatures>),
    ) {
        let [nx, ny] = elevation.geometry.size;
        let r = window.reach.max(0) as usize;
        // Cells whose window lies inside the grid.
        let (inner_i0, inner_i1) = (r, nx.saturating_sub(r));
        let (inner_j0, inner_j1) = (r, ny.saturating_sub(r));
        let mut tile = Tile::default();
        let mut row = RowFits::default();
        let mut i0 = rect.i0;
        while i0 < rect.i1 {
            let i1 = (i0 + TILE_COLUMNS).min(rect.i1);
            let columns = (i0.max(inner_i0), i1.min(inner_i1));
            let rows = (rect.j0.max(inner_j0), rect.j1.min(inner_j1));
            let inner = columns.0 < columns.1 && rows.0 < rows.1;
            if inner {
                tile.fill(self, elevation, columns, (rows.0 - r, rows.1 + r));
            }
            for j in rect.j0..rect.j1 {
                let fitted = inner && (rows.0..rows.1).contains(&j);
                if fitted {
                    row.fit(self, &tile, elevation, j);
                }
                for i in i0..i1 {
                    let fit = fitted && (columns.0..columns.1).contains(&i);
                    let features = fit
                        .then(|| row.features(window, self.solver.as_ref(), i - columns.0))
                        .flatten()
                        .unwrap_or_else(|| window.features(elevation, i, j));
                    emit(i, j, features);
                }
            }
            i0 = i1;
        }
    }
}

/// Sums of the centred runs `z[i − h ..= i + h]` of one row for a tile's columns
/// `i`, relative to `z[i]`, one array per quantity (the loops run over columns).
#[derive(Clone, Debug, Default)]
struct RunSums {
    /// Σ (z − z[i]).
    s: Vec<f64>,
    /// Σ k · (z[i + k] − z[i]).
    t: Vec<f64>,
    /// Σ (z − z[i])².
    q: Vec<f64>,
    /// The lowest height.
    low: Vec<f32>,
    /// The highest height.
    high: Vec<f32>,
}

impl RunSums {
    /// The runs of half-width 0 around heights `zc` (the heights alone).
    fn centre(&mut self, zc: &[f32]) {
        let n = zc.len();
        for v in [&mut self.s, &mut self.t, &mut self.q] {
            v.clear();
            v.resize(n, 0.0);
        }
        self.low.clear();
        self.low.extend_from_slice(zc);
        self.high.clear();
        self.high.extend_from_slice(zc);
    }

    /// Widens every run by one cell on each side: `left[c]` and `right[c]` lie at
    /// distance `h` from the centre `zc[c]`. A height that is not a finite number
    /// makes `q` (or the centre's offset) not finite, which the fit checks.
    fn widen(&mut self, zc: &[f32], h: usize, left: &[f32], right: &[f32]) {
        let h = h as f64;
        let n = zc.len();
        let (s, t, q) = (&mut self.s[..n], &mut self.t[..n], &mut self.q[..n]);
        let (low, high) = (&mut self.low[..n], &mut self.high[..n]);
        let (left, right) = (&left[..n], &right[..n]);
        for c in 0..n {
            let (a, b) = (
                left[c] as f64 - zc[c] as f64,
                right[c] as f64 - zc[c] as f64,
            );
            s[c] += a + b;
            t[c] += h * (b - a);
            q[c] += a * a + b * b;
            low[c] = if left[c] < low[c] { left[c] } else { low[c] };
            low[c] = if right[c] < low[c] { right[c] } else { low[c] };
            high[c] = if left[c] > high[c] { left[c] } else { high[c] };
            high[c] = if right[c] > high[c] {
                right[c]
            } else {
                high[c]
            };
        }
    }
}

/// The row sums of a tile's columns, for every row its cells' windows reach.
#[derive(Default)]
struct Tile {
    /// The tile's columns `i0..i1` and rows `j0..j1`.
    columns: (usize, usize),
    rows: (usize, usize),
    /// `sums[(cj − j0) · half_widths + k]`: the runs of the `k`-th half-width.
    sums: Vec<RunSums>,
}

impl Tile {
    /// Computes the run sums of rows `rows` over columns `columns` (whose runs, of
    /// every half-width, lie inside the grid).
    fn fill(
        &mut self,
        runs: &RowRuns,
        elevation: &GridLayer,
        columns: (usize, usize),
        rows: (usize, usize),
    ) {
        let nx = elevation.geometry.size[0];
        let per_row = runs.half_widths.len();
        self.columns = columns;
        self.rows = rows;
        self.sums
            .resize_with((rows.1 - rows.0) * per_row, RunSums::default);
        let h_max = runs.half_widths.last().copied().unwrap_or(0);
        let mut acc = RunSums::default();
        let (i0, i1) = columns;
        for cj in rows.0..rows.1 {
            let row = &elevation.data[cj * nx..][..nx];
            let zc = &row[i0..i1];
            acc.centre(zc);
            let mut k = 0;
            for h in 0..=h_max {
                if h > 0 {
                    acc.widen(zc, h, &row[i0 - h..i1 - h], &row[i0 + h..i1 + h]);
                }
                if runs.half_widths[k] == h {
                    self.sums[(cj - rows.0) * per_row + k].clone_from(&acc);
                    k += 1;
                }
            }
        }
    }

    /// The run sums of row `cj`'s `k`-th half-width.
    fn run(&self, cj: usize, k: usize, per_row: usize) -> &RunSums {
        &self.sums[(cj - self.rows.0) * per_row + k]
    }
}

/// The height sums of the fits of one row of a tile's cells (relative to each
/// cell's height), added run by run in the window's order.
#[derive(Default)]
struct RowFits {
    sz: Vec<f64>,
    /// Σ k · (z − z0), in cells (times the resolution: Σ x · (z − z0)).
    skz: Vec<f64>,
    syz: Vec<f64>,
    szz: Vec<f64>,
    low: Vec<f32>,
    high: Vec<f32>,
    z0: Vec<f32>,
}

impl RowFits {
    /// Adds up the fits of row `j`'s cells over the tile's columns.
    fn fit(&mut self, runs: &RowRuns, tile: &Tile, elevation: &GridLayer, j: usize) {
        let nx = elevation.geometry.size[0];
        let (i0, i1) = tile.columns;
        let n = i1 - i0;
        for v in [&mut self.sz, &mut self.skz, &mut self.syz, &mut self.szz] {
            v.clear();
            v.resize(n, 0.0);
        }
        self.low.clear();
        self.low.resize(n, f32::INFINITY);
        self.high.clear();
        self.high.resize(n, f32::NEG_INFINITY);
        self.z0.clear();
        self.z0
            .extend_from_slice(&elevation.data[j * nx + i0..j * nx + i1]);
        let per_row = runs.half_widths.len();
        for &(dj, y, k) in &runs.runs {
            let cj = (j as isize + dj) as usize;
            let zc = &elevation.data[cj * nx + i0..cj * nx + i1];
            let count = (2 * runs.half_widths[k] + 1) as f64;
            self.add_run(tile.run(cj, k, per_row), zc, count, y);
        }
    }

    /// Adds a run of `count` heights at `y` centred on heights `zc` to every cell.
    fn add_run(&mut self, run: &RunSums, zc: &[f32], count: f64, y: f64) {
        let n = self.z0.len();
        let (sz, skz, syz, szz) = (
            &mut self.sz[..n],
            &mut self.skz[..n],
            &mut self.syz[..n],
            &mut self.szz[..n],
        );
        let (low, high, z0) = (&mut self.low[..n], &mut self.high[..n], &self.z0[..n]);
        let (rs, rt, rq, rlow, rhigh) = (
            &run.s[..n],
            &run.t[..n],
            &run.q[..n],
            &run.low[..n],
            &run.high[..n],
        );
        let zc = &zc[..n];
        for c in 0..n {
            let e = zc[c] as f64 - z0[c] as f64;
            let s = rs[c] + count * e;
            sz[c] += s;
            // Σ k · e over a centred run is 0.
            skz[c] += rt[c];
            syz[c] += y * s;
            szz[c] += rq[c] + e * (2.0 * rs[c] + count * e);
            low[c] = if rlow[c] < low[c] { rlow[c] } else { low[c] };
            high[c] = if rhigh[c] > high[c] {
                rhigh[c]
            } else {
                high[c]
            };
        }
    }

    /// The features of the `c`-th cell; `None` when its window holds a height that
    /// is not a finite number (its sums are not all finite).
    fn features(
        &self,
        window: &Window,
        solver: Option<&ShapeSolver>,
        c: usize,
    ) -> Option<Option<TerrainFeatures>> {
        let (sz, szz) = (self.sz[c], self.szz[c]);
        if !(sz.is_finite()
            && szz.is_finite()
            && self.syz[c].is_finite()
            && self.skz[c].is_finite())
        {
            return None;
        }
        let z0 = self.z0[c] as f64;
        let fit = window.fit_from_heights(
            sz,
            window.resolution() * self.skz[c],
            self.syz[c],
            szz,
            self.low[c] as f64 - z0,
            self.high[c] as f64 - z0,
        );
        Some(match solver {
            Some(solver) => Some(fit.features_solved(solver)),
            None => fit.features(),
        })
    }
}
