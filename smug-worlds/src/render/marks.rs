//! The marks drawn over the raster: paths, poses of interest, targets, start and end.

use super::svg::{
    arrow_shape, escape, label, num, View, END_COLOUR, HIGHLIGHT_COLOUR, PATH_COLOUR, POI_COLOUR,
    START_COLOUR, TARGET_COLOUR,
};
use smug_core::{Mission, Pose2};
use std::fmt::Write as _;

/// Draws `paths`, path `k` in `colours[k]` (the default path colour where absent).
pub(super) fn draw_paths(
    svg: &mut String,
    paths: &[Vec<[f64; 2]>],
    colours: &[String],
    view: &View,
) {
    for (k, path) in paths.iter().enumerate().filter(|(_, p)| p.len() >= 2) {
        let colour = colours.get(k).map_or(PATH_COLOUR, String::as_str);
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
            r#"<polyline class="path" points="{}" fill="none" stroke="{colour}" stroke-width="2.5" stroke-linejoin="round" stroke-linecap="round"/>"#,
            points.join(" ")
        );
    }
}

/// SVG rotation (degrees, clockwise) of a world yaw (radians, counter-clockwise).
pub(super) fn svg_rotation(yaw: f64) -> f64 {
    -yaw.to_degrees()
}

pub(super) fn pose_transform(pose: &Pose2, view: &View) -> String {
    let [x, y] = view.point(pose.x, pose.y);
    format!(
        "translate({} {}) rotate({})",
        num(x),
        num(y),
        num(svg_rotation(pose.yaw))
    )
}

pub(super) fn draw_pois(
    svg: &mut String,
    mission: &Mission,
    highlighted: &[(usize, usize)],
    view: &View,
) {
    for (t, target) in mission.targets.iter().enumerate() {
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

pub(super) fn draw_targets(svg: &mut String, mission: &Mission, view: &View) {
    for target in &mission.targets {
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

pub(super) fn draw_start_and_end(svg: &mut String, mission: &Mission, view: &View) {
    let start = &mission.start;
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
    if let Some(end) = &mission.end {
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
