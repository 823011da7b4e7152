//! TSPLIB's distance functions, rounded exactly as TSPLIB95 defines them.

/// How distances are computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum WeightType {
    Explicit,
    Euc2d,
    Ceil2d,
    Man2d,
    Max2d,
    Geo,
    Att,
}

/// The dense matrix of TSPLIB distances between the coordinates.
pub(crate) fn coordinate_matrix(kind: WeightType, coords: &[(f64, f64)]) -> Vec<f64> {
    let n = coords.len();
    (0..n * n)
        .map(|k| {
            let (i, j) = (k / n, k % n);
            if i == j {
                0.0
            } else {
                distance(kind, coords[i], coords[j])
            }
        })
        .collect()
}

/// TSPLIB's `nint`: round half up.
fn nint(x: f64) -> f64 {
    (x + 0.5).floor()
}

/// The TSPLIB distance between two nodes.
fn distance(kind: WeightType, a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (a.0 - b.0, a.1 - b.1);
    match kind {
        WeightType::Euc2d => nint(dx.hypot(dy)),
        WeightType::Ceil2d => dx.hypot(dy).ceil(),
        WeightType::Man2d => nint(dx.abs() + dy.abs()),
        WeightType::Max2d => nint(dx.abs()).max(nint(dy.abs())),
        WeightType::Att => {
            let r = ((dx * dx + dy * dy) / 10.0).sqrt();
            let t = nint(r);
            if t < r {
                t + 1.0
            } else {
                t
            }
        }
        WeightType::Geo => geo_distance(a, b),
        WeightType::Explicit => 0.0,
    }
}

/// TSPLIB GEO: coordinates are `DDD.MM` (degrees and minutes) latitude, longitude; the
/// distance is in whole kilometres on the TSPLIB sphere (degrees truncated, as TSPLIB's
/// reference code does).
fn geo_distance(a: (f64, f64), b: (f64, f64)) -> f64 {
    // TSPLIB's truncated π, on purpose: the published GEO optima depend on it.
    #[allow(clippy::approx_constant)]
    const PI: f64 = 3.141592;
    const RRR: f64 = 6378.388;
    let radians = |x: f64| {
        let degrees = x.trunc();
        PI * (degrees + 5.0 * (x - degrees) / 3.0) / 180.0
    };
    let (lat_a, lon_a, lat_b, lon_b) = (radians(a.0), radians(a.1), radians(b.0), radians(b.1));
    let q1 = (lon_a - lon_b).cos();
    let q2 = (lat_a - lat_b).cos();
    let q3 = (lat_a + lat_b).cos();
    let cosine = (0.5 * ((1.0 + q1) * q2 - (1.0 - q1) * q3)).clamp(-1.0, 1.0);
    (RRR * cosine.acos() + 1.0).trunc()
}
