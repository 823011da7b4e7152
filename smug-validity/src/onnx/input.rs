//! The model's input channels from the elevation: resampled to the model's training
//! resolution, each channel computed, NaN filled and normalised.

use serde::{Deserialize, Serialize};
use smug_core::{GridGeometry, GridLayer};

/// One input channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Channel {
    /// Terrain height, metres.
    Elevation,
    /// Gradient magnitude (rise over run) by central differences, one-sided at the
    /// border and beside NaN cells.
    Slope,
    /// |elevation − mean of the 3 × 3 neighbourhood's known cells|, metres.
    Roughness,
}

/// How each channel's values are scaled before the model sees them.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, tag = "kind", rename_all = "kebab-case")]
pub enum Normalisation {
    /// As computed.
    #[default]
    None,
    /// `(v − mean[c]) / std[c]`.
    MeanStd {
        /// Per channel.
        mean: Vec<f64>,
        /// Per channel, > 0.
        std: Vec<f64>,
    },
    /// `(v − min[c]) / (max[c] − min[c])`.
    MinMax {
        /// Per channel.
        min: Vec<f64>,
        /// Per channel, > min.
        max: Vec<f64>,
    },
}

impl Normalisation {
    /// What is wrong with it for `channels` channels, if anything.
    pub fn invalid(&self, channels: usize) -> Option<String> {
        let (a, b, names) = match self {
            Self::None => return None,
            Self::MeanStd { mean, std } => (mean, std, ("mean", "std")),
            Self::MinMax { min, max } => (min, max, ("min", "max")),
        };
        if a.len() != channels || b.len() != channels {
            return Some(format!(
                "normalisation: `{}` and `{}` need one value per input channel ({channels})",
                names.0, names.1
            ));
        }
        let bad = a.iter().zip(b).position(|(a, b)| match self {
            Self::MeanStd { .. } => !(a.is_finite() && b.is_finite() && *b > 0.0),
            _ => !(a.is_finite() && b.is_finite() && b > a),
        });
        bad.map(|c| {
            format!(
                "normalisation: channel {c}: need finite values with {} > 0 (std) or max > min",
                names.1
            )
        })
    }

    /// `v` of channel `c`, normalised.
    fn apply(&self, c: usize, v: f64) -> f64 {
        match self {
            Self::None => v,
            Self::MeanStd { mean, std } => (v - mean[c]) / std[c],
            Self::MinMax { min, max } => (v - min[c]) / (max[c] - min[c]),
        }
    }
}

/// The elevation on the model's grid: the map's own when `resolution` is `None` or
/// equal, else a grid of that cell size over the same extent, sampled bilinearly.
pub fn model_grid(elevation: &GridLayer, resolution: Option<f64>) -> GridLayer {
    let g = elevation.geometry;
    let Some(r) = resolution.filter(|r| (r - g.resolution).abs() > 1e-9 * g.resolution) else {
        return elevation.clone();
    };
    let size = g
        .size
        .map(|n| ((n as f64 * g.resolution / r).round() as usize).max(1));
    let geometry = GridGeometry {
        origin: g.origin,
        resolution: r,
        size,
    };
    resample(elevation, geometry)
}

/// `layer` sampled bilinearly at `geometry`'s cell centres (NaN where unknown).
pub fn resample(layer: &GridLayer, geometry: GridGeometry) -> GridLayer {
    GridLayer::from_fn(geometry, |i, j| {
        let [x, y] = geometry.center_of(i, j);
        layer.bilinear(x, y).map_or(f32::NAN, |v| v as f32)
    })
}

/// Channel `channel` of `elevation`, row-major (NaN where the elevation is).
pub fn channel_values(elevation: &GridLayer, channel: Channel) -> Vec<f64> {
    let [nx, ny] = elevation.geometry.size;
    let z = |i: usize, j: usize| f64::from(elevation.get(i, j));
    let mut out = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            out.push(match channel {
                Channel::Elevation => z(i, j),
                Channel::Slope => slope(elevation, i, j),
                Channel::Roughness => {
                    let around = neighbourhood(elevation, i, j);
                    (z(i, j) - around.iter().sum::<f64>() / around.len() as f64).abs()
                }
            });
        }
    }
    out
}

/// The known elevations of the 3 × 3 neighbourhood of `(i, j)` (the cell included).
fn neighbourhood(elevation: &GridLayer, i: usize, j: usize) -> Vec<f64> {
    let [nx, ny] = elevation.geometry.size;
    let mut values = Vec::with_capacity(9);
    for jj in j.saturating_sub(1)..(j + 2).min(ny) {
        for ii in i.saturating_sub(1)..(i + 2).min(nx) {
            let v = f64::from(elevation.get(ii, jj));
            if !v.is_nan() {
                values.push(v);
            }
        }
    }
    values
}

/// The gradient magnitude at `(i, j)`.
fn slope(elevation: &GridLayer, i: usize, j: usize) -> f64 {
    let [nx, ny] = elevation.geometry.size;
    let r = elevation.geometry.resolution;
    let z = |i: usize, j: usize| f64::from(elevation.get(i, j));
    let derivative = |before: Option<f64>, here: f64, after: Option<f64>| match (before, after) {
        (Some(b), Some(a)) => (a - b) / (2.0 * r),
        (None, Some(a)) => (a - here) / r,
        (Some(b), None) => (here - b) / r,
        (None, None) => 0.0,
    };
    let known = |v: f64| (!v.is_nan()).then_some(v);
    let dx = derivative(
        i.checked_sub(1).and_then(|i| known(z(i, j))),
        z(i, j),
        (i + 1 < nx).then(|| z(i + 1, j)).and_then(known),
    );
    let dy = derivative(
        j.checked_sub(1).and_then(|j| known(z(i, j))),
        z(i, j),
        (j + 1 < ny).then(|| z(i, j + 1)).and_then(known),
    );
    dx.hypot(dy)
}

/// The model's input planes: each channel normalised, NaN replaced by `nan_fill`
/// (after normalisation), as `f32`, channel-major then row-major.
pub fn input_planes(
    elevation: &GridLayer,
    channels: &[Channel],
    normalisation: &Normalisation,
    nan_fill: f64,
) -> Vec<f32> {
    let mut planes = Vec::with_capacity(channels.len() * elevation.data.len());
    for (c, &channel) in channels.iter().enumerate() {
        planes.extend(channel_values(elevation, channel).into_iter().map(|v| {
            if v.is_nan() {
                nan_fill as f32
            } else {
                normalisation.apply(c, v) as f32
            }
        }));
    }
    planes
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp() -> GridLayer {
        let g = GridGeometry::new([0.0, 0.0], 0.5, [4, 3]).unwrap();
        GridLayer::from_fn(g, |i, _| i as f32) // rises 1 m per 0.5 m along x
    }

    #[test]
    fn a_ramp_has_slope_2_and_no_roughness_inside() {
        let z = ramp();
        let slope = channel_values(&z, Channel::Slope);
        assert!(slope.iter().all(|s| (s - 2.0).abs() < 1e-12), "{slope:?}");
        let rough = channel_values(&z, Channel::Roughness);
        assert!(
            rough[5].abs() < 1e-12 && rough[6].abs() < 1e-12,
            "{rough:?}"
        );
        assert!(
            (rough[0] - 0.5).abs() < 1e-12,
            "the border mean is one-sided"
        );
    }

    #[test]
    fn planes_are_normalised_channel_major_and_nan_filled() {
        let mut z = ramp();
        z.set(1, 0, f32::NAN);
        let norm = Normalisation::MeanStd {
            mean: vec![1.0, 0.0],
            std: vec![2.0, 1.0],
        };
        let planes = input_planes(&z, &[Channel::Elevation, Channel::Slope], &norm, -9.0);
        assert_eq!(planes.len(), 24);
        assert_eq!(&planes[..4], &[-0.5, -9.0, 0.5, 1.0]);
        assert!(
            (planes[16] - 2.0).abs() < 1e-6,
            "slope of cell (0, 1): one-sided in x"
        );
        assert!(norm.invalid(2).is_none());
        assert!(norm.invalid(1).is_some());
        let flat = Normalisation::MinMax {
            min: vec![1.0],
            max: vec![1.0],
        };
        assert!(flat.invalid(1).is_some());
    }

    #[test]
    fn the_model_grid_resamples_only_when_the_resolution_differs() {
        let z = ramp();
        assert_eq!(model_grid(&z, None), z);
        assert_eq!(model_grid(&z, Some(0.5)), z);
        let coarse = model_grid(&z, Some(1.0));
        assert_eq!(coarse.geometry.size, [2, 2]);
        assert!((coarse.get(0, 0) - 0.5).abs() < 1e-6, "{coarse:?}");
    }
}
