//! The scale bar under the map and the legend beside it.

use super::options::RenderOptions;
use super::raster::{ColourBar, RasterChoice};
use super::svg::{
    arrow_shape, escape, num, View, END_COLOUR, HIGHLIGHT_COLOUR, LEGEND_ROW, LEGEND_WIDTH,
    NO_DATA, PATH_COLOUR, POI_COLOUR, START_COLOUR, TARGET_COLOUR,
};
use smug_core::{Mission, World};
use std::fmt::Write as _;

/// The largest 1, 2 or 5 × 10^k not above `limit` (> 0).
pub(super) fn nice_length(limit: f64) -> f64 {
    let power = 10f64.powf(limit.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * power)
        .find(|&l| l <= limit)
        .unwrap_or(power)
}

pub(super) fn draw_scale_bar(svg: &mut String, world: &World, view: &View) {
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
pub(super) struct LegendRow {
    symbol: String,
    text: &'static str,
}

pub(super) fn legend_rows(mission: Option<&Mission>, options: &RenderOptions) -> Vec<LegendRow> {
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
    if mission.is_some_and(|m| m.end.is_some()) {
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

pub(super) fn draw_legend(
    svg: &mut String,
    raster: &RasterChoice,
    rows: &[LegendRow],
    left: f64,
    top: f64,
) {
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
