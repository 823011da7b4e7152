//! The picture's geometry and SVG text helpers shared by every part of the drawing:
//! layout constants and colours, the world-to-picture [`View`], numbers, escaping,
//! labels and the PoI arrow.

use super::options::RenderOptions;
use smug_core::World;

pub(super) const MARGIN: f64 = 20.0;
pub(super) const TITLE_HEIGHT: f64 = 32.0;
pub(super) const FOOTER_HEIGHT: f64 = 44.0;
pub(super) const LEGEND_WIDTH: f64 = 200.0;
pub(super) const LEGEND_ROW: f64 = 22.0;

pub(super) const NO_DATA: [u8; 3] = [28, 28, 30];
pub(super) const POI_COLOUR: &str = "#1f4e9c";
pub(super) const HIGHLIGHT_COLOUR: &str = "#ff7f0e";
pub(super) const TARGET_COLOUR: &str = "#6a1b9a";
pub(super) const START_COLOUR: &str = "#2ca02c";
pub(super) const END_COLOUR: &str = "#d62728";
pub(super) const PATH_COLOUR: &str = "#0072b2";

/// Maps world coordinates to picture coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct View {
    /// World x of the map's left edge.
    pub(super) min_x: f64,
    /// World y of the map's top edge.
    pub(super) max_y: f64,
    /// Pixels per metre.
    pub(super) scale: f64,
    /// Picture x of the map's left edge.
    pub(super) left: f64,
    /// Picture y of the map's top edge.
    pub(super) top: f64,
    /// Map width and height in pixels.
    pub(super) size: [f64; 2],
}

impl View {
    pub(super) fn new(world: &World, options: &RenderOptions, top: f64) -> Self {
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

    pub(super) fn point(&self, x: f64, y: f64) -> [f64; 2] {
        [
            self.left + (x - self.min_x) * self.scale,
            self.top + (self.max_y - y) * self.scale,
        ]
    }

    pub(super) fn bottom(&self) -> f64 {
        self.top + self.size[1]
    }
}

/// An arrow along +x from the origin, `length` pixels long, for a `rotate` transform.
pub(super) fn arrow_shape(length: f64, colour: &str, width: f64) -> String {
    let head = (length * 0.45).max(5.0);
    format!(
        r#"<line x1="0" y1="0" x2="{b}" y2="0" stroke="{colour}" stroke-width="{width}" stroke-linecap="round"/><path d="M{l},0 L{b},{h} L{b},-{h} Z" fill="{colour}"/>"#,
        l = num(length),
        b = num(length - head),
        h = num(head * 0.55),
    )
}

/// A text label with a white halo so it stays readable on any background.
pub(super) fn label(x: f64, y: f64, text: &str, colour: &str) -> String {
    format!(
        r#"<text x="{}" y="{}" font-size="12" fill="{colour}" stroke="white" stroke-width="3" paint-order="stroke">{}</text>"#,
        num(x),
        num(y),
        escape(text)
    )
}

/// A number for SVG: at most two decimals, no trailing zeros.
pub(super) fn num(v: f64) -> String {
    let text = format!("{v:.2}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    match text {
        "-0" | "" => "0".to_string(),
        other => other.to_string(),
    }
}

/// `text` escaped for XML content and attributes.
pub(super) fn escape(text: &str) -> String {
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
