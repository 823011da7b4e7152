//! SVG pictures of worlds, in the style of the paper's figures: the traversability (or
//! elevation) layer as an embedded raster, obstacles and missing data dark, the targets
//! with their labels, every pose of interest as a small arrow, the start and end poses,
//! a scale bar and a legend. [`RenderOptions`] also takes polylines and highlighted PoIs
//! so a plan can be drawn over the world.
//!
//! North is up: world y grows upwards, SVG y downwards; [`render_svg`] flips.

use crate::export::{finite_range, image_rows};
use base64::Engine;
use smug_core::{GridLayer, Pose2, World};
use std::fmt::Write as _;

/// Which layer the raster shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RasterLayer {
    /// Traversability when the world has it, elevation otherwise.
    #[default]
    Auto,
    /// The elevation (light = low, dark = high).
    Elevation,
    /// The traversability (green = 1, red = 0); falls back to elevation without one.
    Traversability,
}

/// What to draw and how big.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Title above the map.
    pub title: Option<String>,
    /// Polylines of world points `[x, y]` drawn over the map (e.g. a plan's paths).
    pub paths: Vec<Vec<[f64; 2]>>,
    /// PoIs to emphasise, as `(target index, PoI index)` in the world's mission.
    pub highlighted_pois: Vec<(usize, usize)>,
    /// The layer shown as raster.
    pub layer: RasterLayer,
    /// Length of the map's longer side in the picture, pixels.
    pub map_size_px: f64,
    /// Draw the legend beside the map.
    pub legend: bool,
    /// Draw the scale bar under the map.
    pub scale_bar: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            title: None,
            paths: Vec::new(),
            highlighted_pois: Vec::new(),
            layer: RasterLayer::Auto,
            map_size_px: 800.0,
            legend: true,
            scale_bar: true,
        }
    }
}

const MARGIN: f64 = 20.0;
const TITLE_HEIGHT: f64 = 32.0;
const FOOTER_HEIGHT: f64 = 44.0;
const LEGEND_WIDTH: f64 = 200.0;
const LEGEND_ROW: f64 = 22.0;

const NO_DATA: [u8; 3] = [28, 28, 30];
const POI_COLOUR: &str = "#1f4e9c";
const HIGHLIGHT_COLOUR: &str = "#ff7f0e";
const TARGET_COLOUR: &str = "#6a1b9a";
const START_COLOUR: &str = "#2ca02c";
const END_COLOUR: &str = "#d62728";
const PATH_COLOUR: &str = "#0072b2";

/// Maps world coordinates to picture coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
struct View {
    /// World x of the map's left edge.
    min_x: f64,
    /// World y of the map's top edge.
    max_y: f64,
    /// Pixels per metre.
    scale: f64,
    /// Picture x of the map's left edge.
    left: f64,
    /// Picture y of the map's top edge.
    top: f64,
    /// Map width and height in pixels.
    size: [f64; 2],
}

impl View {
    fn new(world: &World, options: &RenderOptions, top: f64) -> Self {
        let bounds = world.bounds();
        let [w, h] = bounds.extent();
        let longest = w.max(h);
        let scale = if longest > 0.0 && longest.is_finite() {
            options.map_size_px.max(1.0) / longest
        } else {
            1.0
        };
        Self {
            min_x: bounds.min[0],
            max_y: bounds.max[1],
            scale,
            left: MARGIN,
            top,
            size: [w * scale, h * scale],
        }
    }

    fn point(&self, x: f64, y: f64) -> [f64; 2] {
        [
            self.left + (x - self.min_x) * self.scale,
            self.top + (self.max_y - y) * self.scale,
        ]
    }

    fn bottom(&self) -> f64 {
        self.top + self.size[1]
    }
}

/// The SVG picture of `world` (see the [module documentation](self)).
pub fn render_svg(world: &World, options: &RenderOptions) -> String {
    let title_height = if options.title.is_some() {
        TITLE_HEIGHT
    } else {
        0.0
    };
    let view = View::new(world, options, MARGIN + title_height);
    let raster = RasterChoice::for_world(world, options.layer);
    let legend_rows = legend_rows(world, options);
    let legend_height = LEGEND_ROW * (legend_rows.len() as f64 + 3.0);
    let width = view.left
        + view.size[0]
        + if options.legend {
            MARGIN + LEGEND_WIDTH
        } else {
            0.0
        }
        + MARGIN;
    let height = (view.bottom() + FOOTER_HEIGHT).max(view.top + legend_height) + MARGIN;

    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="Helvetica, Arial, sans-serif">"#,
        w = num(width),
        h = num(height)
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    if let Some(title) = &options.title {
        let _ = writeln!(
            svg,
            r#"<text class="title" x="{}" y="{}" font-size="18" font-weight="bold">{}</text>"#,
            num(MARGIN),
            num(MARGIN + 18.0),
            escape(title)
        );
    }
    draw_raster(&mut svg, world, &raster, &view);
    draw_paths(&mut svg, &options.paths, &view);
    draw_pois(&mut svg, world, &options.highlighted_pois, &view);
    draw_targets(&mut svg, world, &view);
    draw_start_and_end(&mut svg, world, &view);
    if options.scale_bar {
        draw_scale_bar(&mut svg, world, &view);
    }
    if options.legend {
        let left = view.left + view.size[0] + MARGIN;
        draw_legend(&mut svg, &raster, &legend_rows, left, view.top);
    }
    svg.push_str("</svg>\n");
    svg
}

/// The layer shown and its colour scale.
enum RasterChoice<'a> {
    Traversability(&'a GridLayer),
    Elevation {
        layer: &'a GridLayer,
        low: f64,
        high: f64,
    },
}

impl<'a> RasterChoice<'a> {
    fn for_world(world: &'a World, layer: RasterLayer) -> Self {
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

    fn layer(&self) -> &GridLayer {
        match self {
            Self::Traversability(layer) | Self::Elevation { layer, .. } => layer,
        }
    }

    fn colour(&self, value: f32) -> [u8; 3] {
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
    fn colour_bar(&self) -> ColourBar {
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
struct ColourBar {
    stops: Vec<(f64, [u8; 3])>,
    low: String,
    high: String,
    name: &'static str,
}

/// Red (0) → yellow (0.5) → green (1).
fn traversability_colour(t: f64) -> [u8; 3] {
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
fn elevation_colour(u: f64) -> [u8; 3] {
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
fn ramp(u: f64, stops: &[(f64, [u8; 3])]) -> [u8; 3] {
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
const MAX_UPSAMPLING: usize = 8;

/// The layer as a PNG of `size` = `[width, height]` pixels (cells are replicated or
/// skipped to fit), north up; `None` for an empty grid.
fn raster_png(raster: &RasterChoice, size: [usize; 2]) -> Option<Vec<u8>> {
    let layer = raster.layer();
    let [nx, ny] = layer.geometry.size;
    let [width, height] = size;
    if nx == 0 || ny == 0 || width == 0 || height == 0 || layer.data.len() != nx * ny {
        return None;
    }
    let colours = image_rows(layer.geometry, |k| raster.colour(layer.data[k]));
    let image = image::RgbImage::from_fn(
        u32::try_from(width).ok()?,
        u32::try_from(height).ok()?,
        |x, y| {
            let column = x as usize * nx / width;
            let row = y as usize * ny / height;
            image::Rgb(colours[row * nx + column])
        },
    );
    let mut png = std::io::Cursor::new(Vec::new());
    image.write_to(&mut png, image::ImageFormat::Png).ok()?;
    Some(png.into_inner())
}

/// The raster's size in pixels: about as fine as the picture. Small grids replicate
/// each cell up to [`MAX_UPSAMPLING`] times; grids with more than twice as many cells
/// as the picture has pixels are thinned out (nearest cell).
fn raster_size(layer: &GridLayer, view: &View) -> [usize; 2] {
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

fn draw_raster(svg: &mut String, world: &World, raster: &RasterChoice, view: &View) {
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

fn draw_paths(svg: &mut String, paths: &[Vec<[f64; 2]>], view: &View) {
    for path in paths.iter().filter(|p| p.len() >= 2) {
        let points: Vec<String> = path
            .iter()
            .filter(|p| p[0].is_finite() && p[1].is_finite())
            .map(|p| {
                let [x, y] = view.point(p[0], p[1]);
                format!("{},{}", num(x), num(y))
            })
            .collect();
        let _ = writeln!(
            svg,
            r#"<polyline class="path" points="{}" fill="none" stroke="{PATH_COLOUR}" stroke-width="2.5" stroke-linejoin="round" stroke-linecap="round"/>"#,
            points.join(" ")
        );
    }
}

/// An arrow along +x from the origin, `length` pixels long, for a `rotate` transform.
fn arrow_shape(length: f64, colour: &str, width: f64) -> String {
    let head = (length * 0.45).max(5.0);
    format!(
        r#"<line x1="0" y1="0" x2="{b}" y2="0" stroke="{colour}" stroke-width="{width}" stroke-linecap="round"/><path d="M{l},0 L{b},{h} L{b},-{h} Z" fill="{colour}"/>"#,
        l = num(length),
        b = num(length - head),
        h = num(head * 0.55),
    )
}

/// SVG rotation (degrees, clockwise) of a world yaw (radians, counter-clockwise).
fn svg_rotation(yaw: f64) -> f64 {
    -yaw.to_degrees()
}

fn pose_transform(pose: &Pose2, view: &View) -> String {
    let [x, y] = view.point(pose.x, pose.y);
    format!(
        "translate({} {}) rotate({})",
        num(x),
        num(y),
        num(svg_rotation(pose.yaw))
    )
}

fn draw_pois(svg: &mut String, world: &World, highlighted: &[(usize, usize)], view: &View) {
    for (t, target) in world.mission.targets.iter().enumerate() {
        for (p, pose) in target.pois.iter().enumerate() {
            let bright = highlighted.contains(&(t, p));
            let (class, shape) = if bright {
                ("poi highlighted", arrow_shape(22.0, HIGHLIGHT_COLOUR, 3.0))
            } else {
                ("poi", arrow_shape(14.0, POI_COLOUR, 1.6))
            };
            let _ = writeln!(
                svg,
                r#"<g class="{class}" transform="{}"><title>{} PoI {p}</title>{shape}</g>"#,
                pose_transform(pose, view),
                escape(&target.id)
            );
        }
    }
}

fn draw_targets(svg: &mut String, world: &World, view: &View) {
    for target in &world.mission.targets {
        let [x, y] = view.point(target.position.x, target.position.y);
        let _ = writeln!(
            svg,
            r#"<g class="toi"><circle cx="{x}" cy="{y}" r="5.5" fill="white" stroke="{TARGET_COLOUR}" stroke-width="2.5"/>{}</g>"#,
            label(x + 8.0, y - 7.0, &target.id, TARGET_COLOUR),
            x = num(x),
            y = num(y),
        );
    }
}

fn draw_start_and_end(svg: &mut String, world: &World, view: &View) {
    let start = &world.mission.start;
    let [x, y] = view.point(start.x, start.y);
    let _ = writeln!(
        svg,
        r#"<g class="start"><g transform="{}">{}</g><circle cx="{}" cy="{}" r="7" fill="{START_COLOUR}" stroke="white" stroke-width="1.5"/>{}</g>"#,
        pose_transform(start, view),
        arrow_shape(20.0, START_COLOUR, 2.5),
        num(x),
        num(y),
        label(x + 9.0, y + 16.0, "start", START_COLOUR)
    );
    if let Some(end) = &world.mission.end {
        let [x, y] = view.point(end.x, end.y);
        let _ = writeln!(
            svg,
            r#"<g class="end"><g transform="{}">{}</g><rect x="{}" y="{}" width="12" height="12" fill="{END_COLOUR}" stroke="white" stroke-width="1.5"/>{}</g>"#,
            pose_transform(end, view),
            arrow_shape(20.0, END_COLOUR, 2.5),
            num(x - 6.0),
            num(y - 6.0),
            label(x + 9.0, y + 16.0, "end", END_COLOUR)
        );
    }
}

/// A text label with a white halo so it stays readable on any background.
fn label(x: f64, y: f64, text: &str, colour: &str) -> String {
    format!(
        r#"<text x="{}" y="{}" font-size="12" fill="{colour}" stroke="white" stroke-width="3" paint-order="stroke">{}</text>"#,
        num(x),
        num(y),
        escape(text)
    )
}

/// The largest 1, 2 or 5 × 10^k not above `limit` (> 0).
fn nice_length(limit: f64) -> f64 {
    let power = 10f64.powf(limit.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * power)
        .find(|&l| l <= limit)
        .unwrap_or(power)
}

fn draw_scale_bar(svg: &mut String, world: &World, view: &View) {
    let [w, h] = world.bounds().extent();
    let g = world.elevation.geometry;
    let summary = format!(
        "{} × {} m · {}×{} cells of {} m",
        num(w),
        num(h),
        g.size[0],
        g.size[1],
        num(g.resolution)
    );
    let y = view.bottom() + 22.0;
    if w > 0.0 && w.is_finite() {
        let metres = nice_length(w / 4.0);
        let length = metres * view.scale;
        let (x0, x1) = (view.left, view.left + length);
        let _ = writeln!(
            svg,
            r##"<g class="scale-bar"><path d="M{x0},{t} L{x0},{y} L{x1},{y} L{x1},{t}" fill="none" stroke="#111" stroke-width="2"/><text x="{lx}" y="{ly}" font-size="12" text-anchor="middle">{m} m</text></g>"##,
            x0 = num(x0),
            x1 = num(x1),
            y = num(y),
            t = num(y - 6.0),
            lx = num((x0 + x1) / 2.0),
            ly = num(y - 9.0),
            m = num(metres),
        );
    }
    let _ = writeln!(
        svg,
        r##"<text class="summary" x="{}" y="{}" font-size="11" fill="#555" text-anchor="end">{}</text>"##,
        num(view.left + view.size[0]),
        num(y),
        escape(&summary)
    );
}

/// A legend entry: its symbol (drawn around the origin) and its text.
struct LegendRow {
    symbol: String,
    text: &'static str,
}

fn legend_rows(world: &World, options: &RenderOptions) -> Vec<LegendRow> {
    let mut rows = vec![
        LegendRow {
            symbol: format!(
                r##"<rect x="-7" y="-7" width="14" height="14" fill="rgb({},{},{})" stroke="#333"/>"##,
                NO_DATA[0], NO_DATA[1], NO_DATA[2]
            ),
            text: "obstacle / no data",
        },
        LegendRow {
            symbol: format!(
                r#"<circle r="5.5" fill="white" stroke="{TARGET_COLOUR}" stroke-width="2.5"/>"#
            ),
            text: "target (ToI)",
        },
        LegendRow {
            symbol: format!(
                r#"<g transform="translate(-7 0)">{}</g>"#,
                arrow_shape(14.0, POI_COLOUR, 1.6)
            ),
            text: "pose of interest",
        },
    ];
    if !options.highlighted_pois.is_empty() {
        rows.push(LegendRow {
            symbol: format!(
                r#"<g transform="translate(-9 0)">{}</g>"#,
                arrow_shape(18.0, HIGHLIGHT_COLOUR, 3.0)
            ),
            text: "selected pose of interest",
        });
    }
    rows.push(LegendRow {
        symbol: format!(
            r#"<circle r="7" fill="{START_COLOUR}" stroke="white" stroke-width="1.5"/>"#
        ),
        text: "start",
    });
    if world.mission.end.is_some() {
        rows.push(LegendRow {
            symbol: format!(r#"<rect x="-6" y="-6" width="12" height="12" fill="{END_COLOUR}"/>"#),
            text: "end",
        });
    }
    if options.paths.iter().any(|p| p.len() >= 2) {
        rows.push(LegendRow {
            symbol: format!(
                r#"<line x1="-9" y1="0" x2="9" y2="0" stroke="{PATH_COLOUR}" stroke-width="2.5"/>"#
            ),
            text: "path",
        });
    }
    rows
}

fn draw_legend(svg: &mut String, raster: &RasterChoice, rows: &[LegendRow], left: f64, top: f64) {
    let ColourBar {
        stops,
        low,
        high,
        name,
    } = raster.colour_bar();
    let _ = writeln!(svg, r#"<g class="legend" font-size="12">"#);
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="{}" font-weight="bold">{name}</text>"#,
        num(left),
        num(top + 12.0)
    );
    let mut gradient = String::new();
    for (u, c) in stops {
        let _ = write!(
            gradient,
            r#"<stop offset="{}" stop-color="rgb({},{},{})"/>"#,
            num(u),
            c[0],
            c[1],
            c[2]
        );
    }
    let bar_y = top + 20.0;
    let _ = writeln!(
        svg,
        r##"<defs><linearGradient id="smug-colour-bar">{gradient}</linearGradient></defs><rect x="{x}" y="{y}" width="{w}" height="12" fill="url(#smug-colour-bar)" stroke="#333"/><text x="{x}" y="{ty}" font-size="11">{low}</text><text x="{xr}" y="{ty}" font-size="11" text-anchor="end">{high}</text>"##,
        x = num(left),
        y = num(bar_y),
        w = num(LEGEND_WIDTH - 20.0),
        xr = num(left + LEGEND_WIDTH - 20.0),
        ty = num(bar_y + 26.0),
        low = escape(&low),
        high = escape(&high),
    );
    for (k, row) in rows.iter().enumerate() {
        let y = bar_y + 2.0 * LEGEND_ROW + 12.0 + k as f64 * LEGEND_ROW;
        let _ = writeln!(
            svg,
            r#"<g transform="translate({} {})">{}</g><text x="{}" y="{}">{}</text>"#,
            num(left + 10.0),
            num(y),
            row.symbol,
            num(left + 28.0),
            num(y + 4.0),
            row.text
        );
    }
    svg.push_str("</g>\n");
}

/// A number for SVG: at most two decimals, no trailing zeros.
fn num(v: f64) -> String {
    let text = format!("{v:.2}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    match text {
        "-0" | "" => "0".to_string(),
        other => other.to_string(),
    }
}

/// `text` escaped for XML content and attributes.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use smug_core::{GridGeometry, Mission};

    fn world() -> World {
        let g = GridGeometry::new([-2.0, 1.0], 0.5, [20, 10]).unwrap();
        World::new(
            "w",
            GridLayer::filled(g, 0.0),
            Mission {
                start: Pose2::new(0.0, 2.0, 0.0),
                end: None,
                targets: Vec::new(),
            },
        )
    }

    #[test]
    fn view_puts_north_up() {
        let w = world();
        let view = View::new(&w, &RenderOptions::default(), 30.0);
        assert_eq!(view.scale, 80.0);
        assert_eq!(view.point(-2.0, 6.0), [MARGIN, 30.0]);
        assert_eq!(view.point(8.0, 1.0), [MARGIN + 800.0, 30.0 + 400.0]);
        assert_eq!(svg_rotation(std::f64::consts::FRAC_PI_2), -90.0);
    }

    #[test]
    fn raster_size_follows_the_picture() {
        let w = world();
        let view = View::new(&w, &RenderOptions::default(), 30.0);
        assert_eq!(raster_size(&w.elevation, &view), [160, 80]);
        let big = GridGeometry::new([0.0, 0.0], 0.01, [4001, 2000]).unwrap();
        let layer = GridLayer::filled(big, 0.0);
        assert_eq!(raster_size(&layer, &view), [1334, 667]);
    }

    #[test]
    fn helpers_format_and_escape() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(2.345), "2.35");
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
        assert_eq!(nice_length(7.3), 5.0);
        assert_eq!(nice_length(0.3), 0.2);
        assert_eq!(nice_length(1.0), 1.0);
        assert_eq!(
            ramp(0.5, &[(0.0, [0, 0, 0]), (1.0, [200, 100, 0])]),
            [100, 50, 0]
        );
        assert_eq!(traversability_colour(1.0), [26, 152, 80]);
    }
}
