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
    let mut d: Vec<f64> = sites
        .iter()
        .map(|&s| if s { 0.0 } else { f64::INFINITY })
        .collect();
    let [nx, ny, nz] = size;
    assert_eq!(d.len(), nx * ny * nz, "grid size mismatch");
    let mut envelope = Envelope1d::default();
    let mut line = Vec::new();
    let strides = [1, nx, nx * ny];
    for axis in 0..3 {
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

/// Squared distances (cells²) to the nearest `true` cell of a 2D grid (x fastest).
pub fn squared_edt_2d(sites: &[bool], size: [usize; 2]) -> Vec<f64> {
    squared_edt_3d(sites, [size[0], size[1], 1])
}

/// Index of the first cell of every line along `axis`.
fn line_starts(size: [usize; 3], axis: usize) -> impl Iterator<Item = usize> {
    let [nx, ny, nz] = size;
    (0..nz)
        .flat_map(move |k| (0..ny).flat_map(move |j| (0..nx).map(move |i| (i, j, k))))
        .filter(move |&(i, j, k)| match axis {
            0 => i == 0,
            1 => j == 0,
            _ => k == 0,
        })
        .map(move |(i, j, k)| (k * ny + j) * nx + i)
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
