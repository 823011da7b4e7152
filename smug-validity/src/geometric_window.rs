//! The geometric estimator's fitting window (the cell offsets within its radius, as
//! runs along x) and the least-squares plane fit of the heights in it.

use super::TerrainFeatures;
use smug_core::GridLayer;

/// The fitting window: the cell offsets within the radius, as runs of consecutive
/// offsets along x, row by row — the cells (and the order) of the plain double loop
/// over the bounding square, with the distance test done once instead of per cell.
#[derive(Clone, Debug)]
pub(super) struct Window {
    runs: Vec<WindowRun>,
    /// `x` offset (metres) of each `di`, indexed by `di + reach`.
    x: Vec<f64>,
    pub(super) reach: isize,
    /// Cell size, metres.
    resolution: f64,
    /// The fit of every cell of the window at height 0: the sums of `x` and `y` alone
    /// (`n`, `sx`, `sy`, `sxx`, `sxy`, `syy`) that a window inside the grid without a
    /// missing height accumulates, in the same order, hence to the same bits.
    shape: PlaneFit,
}

/// Consecutive window offsets `di_lo..=di_hi` in row `dj`.
#[derive(Clone, Copy, Debug)]
pub(super) struct WindowRun {
    pub(super) dj: isize,
    pub(super) y: f64,
    pub(super) di_lo: isize,
    pub(super) di_hi: isize,
}

impl Window {
    /// The cells within `radius` (metres) of a cell on a grid of `resolution`.
    pub(super) fn new(radius: f64, resolution: f64) -> Self {
        let reach = (radius / resolution).floor() as isize;
        let offset = |d: isize| d as f64 * resolution;
        let mut runs: Vec<WindowRun> = Vec::new();
        for dj in -reach..=reach {
            for di in -reach..=reach {
                if offset(di).hypot(offset(dj)) > radius + 1e-9 {
                    continue;
                }
                match runs.last_mut() {
                    Some(run) if run.dj == dj && run.di_hi + 1 == di => run.di_hi = di,
                    _ => runs.push(WindowRun {
                        dj,
                        y: offset(dj),
                        di_lo: di,
                        di_hi: di,
                    }),
                }
            }
        }
        let x: Vec<f64> = (-reach..=reach).map(offset).collect();
        let mut shape = PlaneFit::default();
        for run in &runs {
            for di in run.di_lo..=run.di_hi {
                shape.add(x[(di + reach) as usize], run.y, 0.0);
            }
        }
        Self {
            runs,
            x,
            reach,
            resolution,
            shape,
        }
    }

    /// The window's runs, row by row.
    pub(super) fn runs(&self) -> &[WindowRun] {
        &self.runs
    }

    /// Cell size, metres.
    pub(super) fn resolution(&self) -> f64 {
        self.resolution
    }

    /// The fit of a window inside the grid without a missing height, from its height
    /// sums and extremes (relative to the cell's height): the position sums are the
    /// window's [`shape`](Self::shape).
    pub(super) fn fit_from_heights(
        &self,
        sz: f64,
        sxz: f64,
        syz: f64,
        szz: f64,
        low: f64,
        high: f64,
    ) -> PlaneFit {
        PlaneFit {
            sz,
            sxz,
            syz,
            szz,
            low,
            high,
            ..self.shape
        }
    }

    /// The terrain features around cell `(i, j)`; `None` without enough data.
    pub(super) fn features(
        &self,
        elevation: &GridLayer,
        i: usize,
        j: usize,
    ) -> Option<TerrainFeatures> {
        let [nx, ny] = elevation.geometry.size;
        let z0 = elevation.get(i, j);
        if z0.is_nan() {
            return None;
        }
        let (i, j) = (i as isize, j as isize);
        if let Some(fit) = self.inner_fit(elevation, i, j, z0) {
            return fit.features();
        }
        let mut fit = PlaneFit::default();
        for run in &self.runs {
            let cj = j + run.dj;
            if cj < 0 || cj >= ny as isize {
                continue;
            }
            let lo = (i + run.di_lo).max(0);
            let hi = (i + run.di_hi).min(nx as isize - 1);
            if lo > hi {
                continue;
            }
            let row = &elevation.data[cj as usize * nx..][..nx];
            let cells = &row[lo as usize..=hi as usize];
            let xs = &self.x[(lo - i + self.reach) as usize..=(hi - i + self.reach) as usize];
            for (&z, &x) in cells.iter().zip(xs) {
                if !z.is_nan() {
                    fit.add(x, run.y, z as f64 - z0 as f64);
                }
            }
        }
        fit.features()
    }

    /// The fit around `(i, j)` (height `z0`) when the window lies inside the grid and
    /// holds no missing height: the heights' sums accumulated alone, the position sums
    /// taken from [`Window::shape`] (the same bits as accumulating everything cell by
    /// cell, in about half the arithmetic); `None` otherwise.
    fn inner_fit(&self, elevation: &GridLayer, i: isize, j: isize, z0: f32) -> Option<PlaneFit> {
        let [nx, ny] = elevation.geometry.size;
        let r = self.reach;
        if i < r || j < r || i + r >= nx as isize || j + r >= ny as isize {
            return None;
        }
        let mut fit = self.fit_from_heights(0.0, 0.0, 0.0, 0.0, f64::INFINITY, f64::NEG_INFINITY);
        for run in &self.runs {
            let row = &elevation.data[(j + run.dj) as usize * nx..][..nx];
            let cells = &row[(i + run.di_lo) as usize..=(i + run.di_hi) as usize];
            let xs = &self.x[(run.di_lo + r) as usize..=(run.di_hi + r) as usize];
            for (&z, &x) in cells.iter().zip(xs) {
                if z.is_nan() {
                    return None;
                }
                fit.add_height(x, run.y, z as f64 - z0 as f64);
            }
        }
        Some(fit)
    }
}

/// Least-squares fit of `z = a + b·x + c·y`, accumulated point by point.
#[derive(Clone, Copy, Debug)]
pub(super) struct PlaneFit {
    n: f64,
    sx: f64,
    sy: f64,
    sz: f64,
    sxx: f64,
    sxy: f64,
    syy: f64,
    sxz: f64,
    syz: f64,
    szz: f64,
    /// The lowest `z` added (`INFINITY` before any number).
    low: f64,
    /// The highest `z` added (`-INFINITY` before any number).
    high: f64,
}

impl Default for PlaneFit {
    fn default() -> Self {
        Self {
            n: 0.0,
            sx: 0.0,
            sy: 0.0,
            sz: 0.0,
            sxx: 0.0,
            sxy: 0.0,
            syy: 0.0,
            sxz: 0.0,
            syz: 0.0,
            szz: 0.0,
            low: f64::INFINITY,
            high: f64::NEG_INFINITY,
        }
    }
}

impl PlaneFit {
    fn add(&mut self, x: f64, y: f64, z: f64) {
        self.n += 1.0;
        self.sx += x;
        self.sy += y;
        self.sz += z;
        self.sxx += x * x;
        self.sxy += x * y;
        self.syy += y * y;
        self.sxz += x * z;
        self.syz += y * z;
        self.szz += z * z;
        self.low = self.low.min(z);
        self.high = self.high.max(z);
    }

    /// The height sums of [`add`](Self::add) alone (the position sums are known).
    fn add_height(&mut self, x: f64, y: f64, z: f64) {
        self.sz += z;
        self.sxz += x * z;
        self.syz += y * z;
        self.szz += z * z;
        self.low = self.low.min(z);
        self.high = self.high.max(z);
    }

    /// Solves the 3×3 normal equations (Cramer's rule); flat when under-determined.
    pub(super) fn features(&self) -> Option<TerrainFeatures> {
        if self.n == 0.0 {
            return None;
        }
        // No number among the heights (all NaN): no step either.
        let step = if self.low > self.high {
            f64::NAN
        } else {
            self.high - self.low
        };
        let m = [
            [self.n, self.sx, self.sy],
            [self.sx, self.sxx, self.sxy],
            [self.sy, self.sxy, self.syy],
        ];
        let rhs = [self.sz, self.sxz, self.syz];
        let det = det3(m);
        let (a, b, c) = if self.n >= 3.0 && det.abs() > 1e-12 {
            let solve = |k: usize| {
                let mut mk = m;
                for (row, value) in mk.iter_mut().zip(rhs) {
                    row[k] = value;
                }
                det3(mk) / det
            };
            (solve(0), solve(1), solve(2))
        } else {
            (self.sz / self.n, 0.0, 0.0)
        };
        Some(self.features_of_plane(a, b, c, step))
    }

    /// The features of a fit over a window of `solver`'s shape (the same position
    /// sums), its plane solved with the shape's inverse normal matrix.
    pub(super) fn features_solved(&self, solver: &ShapeSolver) -> TerrainFeatures {
        let rhs = [self.sz, self.sxz, self.syz];
        let [a, b, c] = solver
            .inverse
            .map(|row| row[0] * rhs[0] + row[1] * rhs[1] + row[2] * rhs[2]);
        self.features_of_plane(a, b, c, self.high - self.low)
    }

    /// The features of the plane `z = a + b·x + c·y` fitted to the sums.
    fn features_of_plane(&self, a: f64, b: f64, c: f64, step: f64) -> TerrainFeatures {
        // Σ(z − a − bx − cy)² expanded in the accumulated sums.
        let sse = self.szz + a * a * self.n + b * b * self.sxx + c * c * self.syy
            - 2.0 * a * self.sz
            - 2.0 * b * self.sxz
            - 2.0 * c * self.syz
            + 2.0 * a * b * self.sx
            + 2.0 * a * c * self.sy
            + 2.0 * b * c * self.sxy;
        TerrainFeatures {
            slope: (b * b + c * c).sqrt().atan(),
            roughness: (sse.max(0.0) / self.n).sqrt(),
            step,
        }
    }
}

/// The inverse of a window shape's normal matrix: the plane of a fit over a whole
/// window is this matrix times the fit's height sums.
#[derive(Clone, Copy, Debug)]
pub(super) struct ShapeSolver {
    inverse: [[f64; 3]; 3],
}

impl ShapeSolver {
    /// The solver of `window`'s shape; `None` when [`PlaneFit::features`] would
    /// fit a flat plane (too few cells, or a singular matrix).
    pub(super) fn new(window: &Window) -> Option<Self> {
        let f = &window.shape;
        let m = [
            [f.n, f.sx, f.sy],
            [f.sx, f.sxx, f.sxy],
            [f.sy, f.sxy, f.syy],
        ];
        let det = det3(m);
        if !(f.n >= 3.0 && det.abs() > 1e-12) {
            return None;
        }
        // The adjugate's entry (r, k) is the cofactor (k, r).
        let cofactor = |k: usize, r: usize| {
            let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
            let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
            m[k1][r1] * m[k2][r2] - m[k1][r2] * m[k2][r1]
        };
        let inverse = std::array::from_fn(|r| std::array::from_fn(|k| cofactor(k, r) / det));
        Some(Self { inverse })
    }
}

pub(super) fn det3(m: [[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}
