//! Exact Euclidean distance transforms in linear time (Felzenszwalb & Huttenlocher 2012):
//! the 1D lower envelope of parabolas, applied separably along each axis.

/// Squared distance (in cells²) from every cell to the nearest site, for a 1D array
/// `f` holding 0 at sites, `INFINITY` elsewhere (or any finite costs: the result is
/// `min_q (p − q)² + f(q)`). Scratch buffers are reused across calls.
#[derive(Debug, Default)]
pub struct Envelope1d {
    vertices: Vec<usize>,
    boundaries: Vec<f64>,
    out: Vec<f64>,
}

impl Envelope1d {
    /// Transforms `f` in place.
    pub fn transform(&mut self, f: &mut [f64]) {
        let n = f.len();
        let Some(first) = f.iter().position(|v| v.is_finite()) else {
            return;
        };
        self.vertices.clear();
        self.boundaries.clear();
        self.vertices.push(first);
        self.boundaries.push(f64::NEG_INFINITY);
        for q in first + 1..n {
            if !f[q].is_finite() {
                continue;
            }
            let mut s = self.intersection(f, q);
            while s <= *self.boundaries.last().expect("never empty") {
                self.vertices.pop();
                self.boundaries.pop();
                s = self.intersection(f, q);
            }
            self.vertices.push(q);
            self.boundaries.push(s);
        }
        self.out.clear();
        let mut k = 0;
        for p in 0..n {
            while k + 1 < self.vertices.len() && self.boundaries[k + 1] < p as f64 {
                k += 1;
            }
            let v = self.vertices[k];
            let d = p as f64 - v as f64;
            self.out.push(d * d + f[v]);
        }
        f.copy_from_slice(&self.out);
    }

    /// Where the parabola of `q` overtakes the one of the envelope's last vertex.
    fn intersection(&self, f: &[f64], q: usize) -> f64 {
        let v = *self.vertices.last().expect("never empty");
        let (qf, vf) = (q as f64, v as f64);
        ((f[q] + qf * qf) - (f[v] + vf * vf)) / (2.0 * (qf - vf))
    }
}

/// Squared distances (cells²) to the nearest `true` cell of a 3D grid of `size`
/// (x fastest); `INFINITY` everywhere when there is no site.
pub fn squared_edt_3d(sites: &[bool], size: [usize; 3]) -> Vec<f64> {
    let [nx, ny, nz] = size;
    assert_eq!(sites.len(), nx * ny * nz, "grid size mismatch");
    // Along x the input is sites or nothing: the nearest site by two sweeps gives what
    // the envelope would, cheaper.
    let mut d = vec![f64::INFINITY; sites.len()];
    if nx > 0 {
        for (row_sites, row) in sites.chunks_exact(nx).zip(d.chunks_exact_mut(nx)) {
            squared_distances_to_sites(row_sites, row);
        }
    }
    let mut envelope = Envelope1d::default();
    let mut line = Vec::new();
    let strides = [1, nx, nx * ny];
    for axis in 1..3 {
        let (len, stride) = (size[axis], strides[axis]);
        for start in line_starts(size, axis) {
            line.clear();
            line.extend((0..len).map(|k| d[start + k * stride]));
            envelope.transform(&mut line);
            for (k, v) in line.iter().enumerate() {
                d[start + k * stride] = *v;
            }
        }
    }
    d
}

/// Index of the first cell of every line along `axis`, in increasing order: the cells
/// of the other two axes, without visiting the grid.
fn line_starts(size: [usize; 3], axis: usize) -> impl Iterator<Item = usize> {
    let [nx, ny, nz] = size;
    let strides = [1, nx, nx * ny];
    // The two other axes, slower one first.
    let (outer, inner) = match axis {
        0 => (2, 1),
        1 => (2, 0),
        _ => (1, 0),
    };
    let (outer_len, inner_len) = ([nx, ny, nz][outer], [nx, ny, nz][inner]);
    (0..outer_len)
        .flat_map(move |a| (0..inner_len).map(move |b| a * strides[outer] + b * strides[inner]))
}

/// Squared distance (cells²) from every cell of a line to its nearest site, into
/// `out` (left as it is, `INFINITY`, on a line without sites).
fn squared_distances_to_sites(sites: &[bool], out: &mut [f64]) {
    let mut last_site = None;
    for (p, (&site, d)) in sites.iter().zip(out.iter_mut()).enumerate() {
        if site {
            last_site = Some(p);
        }
        if let Some(q) = last_site {
            *d = squared(p - q);
        }
    }
    let mut next_site = None;
    for (p, (&site, d)) in sites.iter().zip(out.iter_mut()).enumerate().rev() {
        if site {
            next_site = Some(p);
        }
        if let Some(q) = next_site {
            *d = d.min(squared(q - p));
        }
    }
}

/// `n²` as a float (exact for the grid sizes in use).
fn squared(n: usize) -> f64 {
    let n = n as f64;
    n * n
}

/// Squared distances (cells²) to the nearest `true` cell of a 2D grid (x fastest).
pub fn squared_edt_2d(sites: &[bool], size: [usize; 2]) -> Vec<f64> {
    squared_edt_3d(sites, [size[0], size[1], 1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn brute_force(sites: &[bool], size: [usize; 3]) -> Vec<f64> {
        let [nx, ny, nz] = size;
        let coords = |idx: usize| {
            [
                (idx % nx) as f64,
                ((idx / nx) % ny) as f64,
                (idx / (nx * ny)) as f64,
            ]
        };
        (0..nx * ny * nz)
            .map(|p| {
                let a = coords(p);
                sites
                    .iter()
                    .enumerate()
                    .filter(|(_, &s)| s)
                    .map(|(q, _)| {
                        let b = coords(q);
                        (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>()
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect()
    }

    proptest! {
        #[test]
        fn edt_equals_brute_force_on_random_grids(
            nx in 1usize..9, ny in 1usize..9, nz in 1usize..6, density in 0.0f64..0.5, seed in any::<u64>()
        ) {
            use rand::{Rng, SeedableRng};
            let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
            let sites: Vec<bool> = (0..nx * ny * nz).map(|_| rng.random::<f64>() < density).collect();
            let fast = squared_edt_3d(&sites, [nx, ny, nz]);
            let slow = brute_force(&sites, [nx, ny, nz]);
            for (a, b) in fast.iter().zip(&slow) {
                prop_assert!(a == b || (a - b).abs() < 1e-9, "{a} vs {b}");
            }
        }
    }

    #[test]
    fn line_starts_are_the_cells_with_a_zero_coordinate_on_the_axis() {
        let size = [4, 3, 5];
        for axis in 0..3 {
            let expected: Vec<usize> = (0..4 * 3 * 5)
                .filter(|&idx| [idx % 4, (idx / 4) % 3, idx / 12][axis] == 0)
                .collect();
            assert_eq!(line_starts(size, axis).collect::<Vec<_>>(), expected);
        }
    }

    #[test]
    fn single_site_gives_squared_distances() {
        let mut sites = vec![false; 5 * 4];
        sites[5 + 2] = true; // cell (2, 1)
        let d = squared_edt_2d(&sites, [5, 4]);
        assert_eq!(d[0], 4.0 + 1.0);
        assert_eq!(d[3 * 5 + 4], 4.0 + 4.0);
        assert!(squared_edt_2d(&[false; 6], [3, 2])
            .iter()
            .all(|v| v.is_infinite()));
    }
}
