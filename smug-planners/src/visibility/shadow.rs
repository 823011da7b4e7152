//! The candidate corners a point may see, by a shadowcast that steps over runs of
//! cells instead of cells: blocked cells are found 64 at a time in bit rows (one set
//! per axis), a run of blocked cells casts one shadow, and the corners of a lit
//! stretch come from per-line sorted lists. Its cost grows with the shadows and the
//! corners it meets, not with the lit area (the cell-by-cell shadowcast,
//! [`Grid::visible_cells`], visits millions of cells from a corner of an open
//! 2000 × 2000 map).
//!
//! What it returns is a superset of [`Grid::visible_cells`]'s corners: every corner of
//! a free cell in a lit stretch of a scanned column.

use super::geometry::{push_uncut, slopes_into, Grid, Pt, EPS};

/// Bit rows of the blocked cells along both axes, and the corners on each vertex line.
#[derive(Clone, Debug)]
pub struct Lines {
    words_x: usize,
    words_y: usize,
    /// Row `y`'s cells along x, 64 per word (bit set: blocked).
    rows: Vec<u64>,
    /// Column `x`'s cells along y.
    cols: Vec<u64>,
    /// Corners on vertex column `x` (`0..=nx`): `(y, corner id)` sorted by `y`.
    on_x: Vec<Vec<(u32, u32)>>,
    /// Corners on vertex row `y` (`0..=ny`): `(x, corner id)` sorted by `x`.
    on_y: Vec<Vec<(u32, u32)>>,
}

impl Lines {
    /// The lines of `grid`.
    pub fn new(grid: &Grid) -> Self {
        let (nx, ny) = (grid.nx, grid.ny);
        let (words_x, words_y) = (nx.div_ceil(64).max(1), ny.div_ceil(64).max(1));
        let mut rows = vec![0u64; words_x * ny];
        let mut cols = vec![0u64; words_y * nx];
        for y in 0..ny {
            for x in 0..nx {
                if grid.blocked(x as i64, y as i64) {
                    rows[y * words_x + x / 64] |= 1 << (x % 64);
                    cols[x * words_y + y / 64] |= 1 << (y % 64);
                }
            }
        }
        let mut on_x = vec![Vec::new(); nx + 1];
        let mut on_y = vec![Vec::new(); ny + 1];
        for (id, c) in grid.corners.iter().enumerate() {
            let (x, y) = (c.at[0] as usize, c.at[1] as usize);
            on_x[x].push((y as u32, id as u32));
            on_y[y].push((x as u32, id as u32));
        }
        for list in on_x.iter_mut().chain(on_y.iter_mut()) {
            list.sort_unstable();
        }
        Self {
            words_x,
            words_y,
            rows,
            cols,
            on_x,
            on_y,
        }
    }

    /// Where line `line`'s bits start and its cells (`along_y`: the line is a column
    /// `x` and `w` is `y`; else a row); `None` off the grid.
    fn line(&self, along_y: bool, line: i64) -> (Option<usize>, i64) {
        let (lines, words, n) = if along_y {
            (self.on_x.len() - 1, self.words_y, self.on_y.len() - 1)
        } else {
            (self.on_y.len() - 1, self.words_x, self.on_x.len() - 1)
        };
        let start = (0..lines as i64)
            .contains(&line)
            .then(|| line as usize * words);
        (start, n as i64)
    }

    fn bits(&self, along_y: bool) -> &[u64] {
        if along_y {
            &self.cols
        } else {
            &self.rows
        }
    }

    /// True when cell `w` of line `line` is blocked (off the grid counts as blocked).
    fn blocked(&self, along_y: bool, line: i64, w: i64) -> bool {
        match self.line(along_y, line) {
            (Some(start), n) if (0..n).contains(&w) => {
                let w = w as usize;
                self.bits(along_y)[start + w / 64] >> (w % 64) & 1 == 1
            }
            _ => true,
        }
    }

    /// The first cell at or after `w` (in `0..n`) of the line at `start` that is
    /// blocked (`want_blocked`) or free; `n` when none is.
    fn first(&self, along_y: bool, start: usize, n: i64, w: i64, want_blocked: bool) -> i64 {
        let bits = self.bits(along_y);
        let mut k = w as usize;
        while (k as i64) < n {
            let word = bits[start + k / 64];
            let rest = if want_blocked { word } else { !word } >> (k % 64);
            if rest != 0 {
                return ((k + rest.trailing_zeros() as usize) as i64).min(n);
            }
            k = (k / 64 + 1) * 64;
        }
        n
    }

    /// The maximal runs of blocked cells of line `line` within `w0..=w1` (clipped to
    /// it), off-grid cells blocked.
    fn blocked_runs(
        &self,
        along_y: bool,
        line: i64,
        w0: i64,
        w1: i64,
        mut run: impl FnMut(i64, i64),
    ) {
        let (Some(start), n) = self.line(along_y, line) else {
            run(w0, w1);
            return;
        };
        let mut w = w0;
        while w <= w1 {
            let b0 = if (0..n).contains(&w) {
                self.first(along_y, start, n, w, true)
            } else {
                w
            };
            if b0 > w1 {
                break;
            }
            let end = if b0 >= n {
                w1 + 1
            } else {
                self.first(along_y, start, n, b0.max(0), false)
            };
            let b1 = if end >= n { w1 } else { (end - 1).min(w1) };
            run(b0, b1);
            w = b1 + 1;
        }
    }

    /// The corners on vertex line `line` (`along_y`: a column) with `w` in `w0..=w1`.
    fn corners(&self, along_y: bool, line: i64, w0: i64, w1: i64, mut visit: impl FnMut(u32, i64)) {
        let lists = if along_y { &self.on_x } else { &self.on_y };
        if line < 0 || line as usize >= lists.len() || w1 < 0 {
            return;
        }
        let list = &lists[line as usize];
        let from = list.partition_point(|&(w, _)| (w as i64) < w0);
        for &(w, id) in &list[from..] {
            if w as i64 > w1 {
                break;
            }
            visit(id, w as i64);
        }
    }

    /// Every corner a point at `s` may see (a superset, see the module), possibly more
    /// than once, by shadowcasting in four cones (right, left, up, down) with slopes
    /// in `[−1, 1]`.
    pub fn visible_corners(&self, s: Pt, mut visit: impl FnMut(u32)) {
        for cone in 0..4 {
            self.shadowcast(s, cone, &mut visit);
        }
    }

    fn shadowcast(&self, s: Pt, cone: u8, visit: &mut impl FnMut(u32)) {
        // (u, w) coordinates of the cone: u along its axis, w across; cones 0 and 1 scan
        // columns (u = ±x, w = y), 2 and 3 rows (u = ±y, w = x).
        let (su, sw) = match cone {
            0 => (s[0], s[1]),
            1 => (-s[0], s[1]),
            2 => (s[1], s[0]),
            _ => (-s[1], s[0]),
        };
        let along_y = cone < 2;
        let mirrored = cone % 2 == 1;
        // The grid line of cells `iu`, and the two vertex lines bounding it.
        let cell_line = |iu: i64| if mirrored { -iu - 1 } else { iu };
        let vertex_lines = |iu: i64| {
            if mirrored {
                [-iu - 1, -iu]
            } else {
                [iu, iu + 1]
            }
        };
        let mut windows: Vec<(f64, f64)> = vec![(-1.0 - EPS, 1.0 + EPS)];
        let mut next: Vec<(f64, f64)> = Vec::new();
        let mut cuts: Vec<(f64, f64)> = Vec::new();
        let on_line = sw.fract() == 0.0;
        let mut iu = su.floor() as i64;
        let limit = ((self.on_x.len().max(self.on_y.len())) as i64) * 2 + 4;
        while !windows.is_empty() && iu.abs() <= limit {
            let u0 = (iu as f64).max(su) - su;
            let u1 = (iu + 1) as f64 - su;
            let line = cell_line(iu);
            next.clear();
            for &(lo, hi) in &windows {
                let wmin = sw + (lo * u0).min(lo * u1);
                let wmax = sw + (hi * u0).max(hi * u1);
                let (w0, w1) = ((wmin - EPS).floor() as i64, (wmax + EPS).floor() as i64);
                // A corner of a lit free cell: on a vertex line of the column, beside a
                // free cell of the stretch.
                let lit = |w: i64| (w0..=w1).contains(&w) && !self.blocked(along_y, line, w);
                for v in vertex_lines(iu) {
                    self.corners(along_y, v, w0, w1 + 1, |id, w| {
                        if lit(w - 1) || lit(w) {
                            visit(id);
                        }
                    });
                }
                cuts.clear();
                self.blocked_runs(along_y, line, w0, w1, |b0, b1| {
                    // The slopes of rays entering the run's interior: the extremes are
                    // at its first cell's lower corners and its last cell's upper ones.
                    cuts.extend(slopes_into(
                        [su, sw],
                        iu as f64,
                        [b0 as f64, b1 as f64 + 1.0],
                    ));
                    // A source on a grid line: the ray along it between two blocked
                    // cells (a zero-width gap no disc passes) is cut.
                    let w = sw as i64;
                    if on_line
                        && (b0..=b1).contains(&w)
                        && (w > b0 || self.blocked(along_y, line, w - 1))
                    {
                        cuts.push((-2.0 * EPS, 2.0 * EPS));
                    }
                });
                push_uncut(lo, hi, &mut cuts, &mut next);
            }
            std::mem::swap(&mut windows, &mut next);
            iu += 1;
        }
    }
}
