//! The raster layer (traversability or elevation) as an embedded PNG, and its colour
//! scale for the legend.

use super::options::RasterLayer;
use super::svg::{num, View, NO_DATA};
use crate::export::finite_range;
use base64::Engine;
use smug_core::{GridLayer, World};
use std::fmt::Write as _;

/// The layer shown and its colour scale.
pub(super) enum RasterChoice<'a> {
    Traversability(&'a GridLayer),
    Elevation {
        layer: &'a GridLayer,
        low: f64,
        high: f64,
    },
}

impl<'a> RasterChoice<'a> {
    pub(super) fn for_world(world: &'a World, layer: RasterLayer) -> Self {
        match (&world.traversability, layer) {
            (Some(t), RasterLayer::Auto | RasterLayer::Traversability) => Self::Traversability(t),
            _ => {
                let (low, high) = finite_range(&world.elevation.data).unwrap_or((0.0, 0.0));
                Self::Elevation {
                    layer: &world.elevation,
                    low,
                    high,
                }
            }
        }
    }

    pub(super) fn layer(&self) -> &GridLayer {
        match self {
            Self::Traversability(layer) | Self::Elevation { layer, .. } => layer,
        }
    }

    pub(super) fn colour(&self, value: f32) -> [u8; 3] {
        if !value.is_finite() {
            return NO_DATA;
        }
        match *self {
            Self::Traversability(_) => traversability_colour(f64::from(value)),
            Self::Elevation { low, high, .. } => {
                let u = if high > low {
                    (f64::from(value) - low) / (high - low)
                } else {
                    0.0
                };
                elevation_colour(u)
            }
        }
    }

    /// The legend's colour bar for this layer.
    pub(super) fn colour_bar(&self) -> ColourBar {
        let stops =
            |f: fn(f64) -> [u8; 3]| (0..=8).map(|k| k as f64 / 8.0).map(|u| (u, f(u))).collect();
        match *self {
            Self::Traversability(_) => ColourBar {
                stops: stops(traversability_colour),
                low: "0".into(),
                high: "1".into(),
                name: "traversability",
            },
            Self::Elevation { low, high, .. } => ColourBar {
                stops: stops(elevation_colour),
                low: format!("{} m", num(low)),
                high: format!("{} m", num(high)),
                name: "elevation",
            },
        }
    }
}

/// A legend colour bar: gradient stops `(fraction, colour)`, end labels and the layer name.
pub(super) struct ColourBar {
    pub(super) stops: Vec<(f64, [u8; 3])>,
    pub(super) low: String,
    pub(super) high: String,
    pub(super) name: &'static str,
}

/// Red (0) → yellow (0.5) → green (1).
pub(super) fn traversability_colour(t: f64) -> [u8; 3] {
    ramp(
        t,
        &[
            (0.0, [215, 48, 39]),
            (0.5, [254, 224, 139]),
            (1.0, [26, 152, 80]),
        ],
    )
}

/// Light sand (low) → warm grey → dark (high): tall obstacles come out dark.
pub(super) fn elevation_colour(u: f64) -> [u8; 3] {
    ramp(
        u,
        &[
            (0.0, [246, 241, 228]),
            (0.6, [168, 156, 138]),
            (1.0, [72, 66, 60]),
        ],
    )
}

/// Piecewise-linear colour ramp through `stops` (sorted by position).
pub(super) fn ramp(u: f64, stops: &[(f64, [u8; 3])]) -> [u8; 3] {
    let u = if u.is_nan() { 0.0 } else { u.clamp(0.0, 1.0) };
    let upper = stops
        .iter()
        .position(|&(p, _)| p >= u)
        .unwrap_or(stops.len() - 1);
    if upper == 0 {
        return stops[0].1;
    }
    let ((p0, c0), (p1, c1)) = (stops[upper - 1], stops[upper]);
    let t = if p1 > p0 { (u - p0) / (p1 - p0) } else { 0.0 };
    std::array::from_fn(|k| {
        (f64::from(c0[k]) + t * (f64::from(c1[k]) - f64::from(c0[k]))).round() as u8
    })
}

/// The largest pixel replication factor for the raster, so that small grids stay crisp
/// in viewers that smooth scaled images.
pub(super) const MAX_UPSAMPLING: usize = 8;

/// The layer as a PNG of `size` = `[width, height]` pixels (cells are replicated or
/// skipped to fit), north up; `None` for an empty grid.
pub(super) fn raster_png(raster: &RasterChoice, size: [usize; 2]) -> Option<Vec<u8>> {
    let layer = raster.layer();
    let [nx, ny] = layer.geometry.size;
    let [width, height] = size;
    if nx == 0 || ny == 0 || width == 0 || height == 0 || layer.data.len() != nx * ny {
        return None;
    }
    // The cell of each pixel, north up (image rows run top down).
    let cell = |x: u32, y: u32| {
        let column = x as usize * nx / width;
        let row = y as usize * ny / height;
        (ny - 1 - row) * nx + column
    };
    let (w, h) = (u32::try_from(width).ok()?, u32::try_from(height).ok()?);
    let image = if width * height < nx * ny {
        // Thinned out: colour only the cells a pixel shows.
        image::RgbImage::from_fn(w, h, |x, y| {
            image::Rgb(raster.colour(layer.data[cell(x, y)]))
        })
    } else {
        let colours: Vec<[u8; 3]> = layer.data.iter().map(|&v| raster.colour(v)).collect();
        image::RgbImage::from_fn(w, h, |x, y| image::Rgb(colours[cell(x, y)]))
    };
    let mut png = std::io::Cursor::new(Vec::new());
    image.write_to(&mut png, image::ImageFormat::Png).ok()?;
    Some(png.into_inner())
}

/// The raster's size in pixels: about as fine as the picture. Small grids replicate
/// each cell up to [`MAX_UPSAMPLING`] times; grids with more than twice as many cells
/// as the picture has pixels are thinned out (nearest cell).
pub(super) fn raster_size(layer: &GridLayer, view: &View) -> [usize; 2] {
    let [nx, ny] = layer.geometry.size;
    let cells = nx.max(ny).max(1) as f64;
    let pixels = view.size[0].max(view.size[1]).max(1.0);
    if cells <= pixels {
        let factor = ((pixels / cells).floor() as usize).clamp(1, MAX_UPSAMPLING);
        [nx * factor, ny * factor]
    } else {
        let step = (cells / (2.0 * pixels)).ceil().max(1.0) as usize;
        [nx.div_ceil(step), ny.div_ceil(step)]
    }
}

pub(super) fn draw_raster(svg: &mut String, world: &World, raster: &RasterChoice, view: &View) {
    let layer = raster.layer();
    let b = layer.geometry.bounds();
    let [x, y] = view.point(b.min[0], b.max[1]);
    let [x1, y1] = view.point(b.max[0], b.min[1]);
    match raster_png(raster, raster_size(layer, view)) {
        Some(png) => {
            let _ = writeln!(
                svg,
                r#"<image class="raster" x="{}" y="{}" width="{}" height="{}" preserveAspectRatio="none" style="image-rendering:pixelated" href="data:image/png;base64,{}"/>"#,
                num(x),
                num(y),
                num(x1 - x),
                num(y1 - y),
                base64::engine::general_purpose::STANDARD.encode(png)
            );
        }
        None => svg.push_str("<!-- no raster: the layer has no cells or too few values -->\n"),
    }
    let b = world.bounds();
    let [x, y] = view.point(b.min[0], b.max[1]);
    let _ = writeln!(
        svg,
        r##"<rect class="border" x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#333" stroke-width="1"/>"##,
        num(x),
        num(y),
        num(view.size[0]),
        num(view.size[1])
    );
}
