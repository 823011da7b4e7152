//! The geometric estimator's fitting window (the cell offsets within its radius, as
//! runs along x) and the least-squares plane fit of the heights in it.

use super::TerrainFeatures;
use smug_core::GridLayer;

/// Cells fitted side by side by [`Window::row_features`].
const LANES: usize = 2;

/// The fitting window: the cell offsets within the radius, as runs of consecutive
/// offsets along x, row by row — the cells (and the order) of the plain double loop
/// over the bounding square, with the distance test done once instead of per cell.
#[derive(Clone, Debug)]
pub(super) struct Window {
    runs: Vec<WindowRun>,
    /// `x` offset (metres) of each `di`, indexed by `di + reach`.
    x: Vec<f64>,
    pub(super) reach: isize,
    /// The fit of every cell of the window at height 0: the sums of `x` and `y` alone
    /// (`n`, `sx`, `sy`, `sxx`, `sxy`, `syy`) that a window inside the grid without a
    /// missing height accumulates, in the same order, hence to the same bits.
    shape: PlaneFit,
}

/// Consecutive window offsets `di_lo..=di_hi` in row `dj`.
#[derive(Clone, Copy, Debug)]
struct WindowRun {
    dj: isize,
    y: f64,
    di_lo: isize,
    di_hi: isize,
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
            shape,
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
                    fit.add(x, run.y, (z - z0) as f64);
                }
            }
        }
        fit.features()
    }

    /// The features of every cell of row `j`, in order of `i`: the same values as
    /// [`Window::features`] cell by cell. Cells whose windows lie inside the grid are
    /// fitted [`LANES`] at a time ([`Window::inner_fits`]), each lane's sums in the
    /// order of one cell alone, so that the processor overlaps the lanes' additions.
    pub(super) fn row_features(
        &self,
        elevation: &GridLayer,
        j: usize,
        mut emit: impl FnMut(usize, Option<TerrainFeatures>),
    ) {
        let [nx, ny] = elevation.geometry.size;
        let r = self.reach.max(0) as usize;
        let rows_inside = j >= r && j + r < ny;
        let mut i = 0;
        while i < nx {
            let lanes_inside = rows_inside && i >= r && i + LANES - 1 + r < nx;
            match lanes_inside
                .then(|| self.inner_fits(elevation, i, j))
                .flatten()
            {
                Some(fits) => {
                    for (lane, fit) in fits.iter().enumerate() {
                        emit(i + lane, fit.features());
                    }
                    i += LANES;
                }
                None => {
                    emit(i, self.features(elevation, i, j));
                    i += 1;
                }
            }
        }
    }

    /// The fits of cells `i .. i + LANES` of row `j`, whose windows lie inside the
    /// grid, as [`Window::inner_fit`] gives each; `None` when a lane's sums are not
    /// numbers (a missing height, say: the caller fits those cells one by one).
    fn inner_fits(&self, elevation: &GridLayer, i: usize, j: usize) -> Option<[PlaneFit; LANES]> {
        let nx = elevation.geometry.size[0];
        let r = self.reach;
        let z0: [f32; LANES] = std::array::from_fn(|lane| elevation.data[j * nx + i + lane]);
        let (mut sz, mut sxz, mut syz, mut szz) =
            ([0.0f64; LANES], [0.0; LANES], [0.0; LANES], [0.0; LANES]);
        let (mut low, mut high) = ([f64::INFINITY; LANES], [f64::NEG_INFINITY; LANES]);
        for run in &self.runs {
            let row = &elevation.data[(j as isize + run.dj) as usize * nx..][..nx];
            let lo = (i as isize + run.di_lo) as usize;
            let len = (run.di_hi - run.di_lo + 1) as usize;
            let cells = &row[lo..lo + len + LANES - 1];
            let xs = &self.x[(run.di_lo + r) as usize..][..len];
            for (k, &x) in xs.iter().enumerate() {
                for lane in 0..LANES {
                    let z = (cells[k + lane] - z0[lane]) as f64;
                    sz[lane] += z;
                    sxz[lane] += x * z;
                    syz[lane] += run.y * z;
                    szz[lane] += z * z;
                    low[lane] = low[lane].min(z);
                    high[lane] = high[lane].max(z);
                }
            }
        }
        if sz.iter().chain(&szz).any(|s| s.is_nan()) {
            return None;
        }
        Some(std::array::from_fn(|lane| PlaneFit {
            sz: sz[lane],
            sxz: sxz[lane],
            syz: syz[lane],
            szz: szz[lane],
            low: low[lane],
            high: high[lane],
            ..self.shape
        }))
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
        let mut fit = PlaneFit {
            low: f64::INFINITY,
            high: f64::NEG_INFINITY,
            ..self.shape
        };
        (fit.sz, fit.sxz, fit.syz, fit.szz) = (0.0, 0.0, 0.0, 0.0);
        for run in &self.runs {
            let row = &elevation.data[(j + run.dj) as usize * nx..][..nx];
            let cells = &row[(i + run.di_lo) as usize..=(i + run.di_hi) as usize];
            let xs = &self.x[(run.di_lo + r) as usize..=(run.di_hi + r) as usize];
            for (&z, &x) in cells.iter().zip(xs) {
                if z.is_nan() {
                    return None;
                }
                fit.add_height(x, run.y, (z - z0) as f64);
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
    fn features(&self) -> Option<TerrainFeatures> {
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
        // Σ(z − a − bx − cy)² expanded in the accumulated sums.
        let sse = self.szz + a * a * self.n + b * b * self.sxx + c * c * self.syy
            - 2.0 * a * self.sz
            - 2.0 * b * self.sxz
            - 2.0 * c * self.syz
            + 2.0 * a * b * self.sx
            + 2.0 * a * c * self.sy
            + 2.0 * b * c * self.sxy;
        Some(TerrainFeatures {
            slope: b.hypot(c).atan(),
            roughness: (sse.max(0.0) / self.n).sqrt(),
            step,
        })
    }
}

pub(super) fn det3(m: [[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}
