//! SVG pictures of worlds, in the style of the paper's figures: the traversability (or
//! elevation) layer as an embedded raster, obstacles and missing data dark, the targets
//! with their labels, every pose of interest as a small arrow, the start and end poses,
//! a scale bar and a legend. [`RenderOptions`] also takes polylines and highlighted PoIs
//! so a plan can be drawn over the world.
//!
//! North is up: world y grows upwards, SVG y downwards; [`render_svg`] flips.

mod legend;
mod marks;
mod options;
mod raster;
mod svg;

pub use options::{RasterLayer, RenderOptions};

use legend::{draw_legend, draw_scale_bar, legend_rows};
use marks::{draw_paths, draw_pois, draw_start_and_end, draw_targets};
use raster::{draw_raster, RasterChoice};
use smug_core::{Mission, World};
use std::fmt::Write as _;
use svg::{escape, num, View, FOOTER_HEIGHT, LEGEND_ROW, LEGEND_WIDTH, MARGIN, TITLE_HEIGHT};

/// The SVG picture of `world` with `mission` (when given) drawn over it (see the
/// [module documentation](self)).
pub fn render_svg(world: &World, mission: Option<&Mission>, options: &RenderOptions) -> String {
    let title_height = if options.title.is_some() {
        TITLE_HEIGHT
    } else {
        0.0
    };
    let view = View::new(world, options, MARGIN + title_height);
    let raster = RasterChoice::for_world(world, options.layer);
    let legend_rows = legend_rows(mission, options);
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
    draw_paths(&mut svg, &options.paths, &options.path_colours, &view);
    if let Some(mission) = mission {
        draw_pois(&mut svg, mission, &options.highlighted_pois, &view);
        draw_targets(&mut svg, mission, &view);
        draw_start_and_end(&mut svg, mission, &view);
    }
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

#[cfg(test)]
mod tests {
    use super::legend::nice_length;
    use super::marks::svg_rotation;
    use super::raster::{ramp, raster_size, traversability_colour};
    use super::*;
    use smug_core::{GridGeometry, GridLayer};

    fn world() -> World {
        let g = GridGeometry::new([-2.0, 1.0], 0.5, [20, 10]).unwrap();
        World::new("w", GridLayer::filled(g, 0.0))
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
