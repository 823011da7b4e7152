//! SVG rendering: structure, markers, the embedded raster and world → picture coordinates.

use base64::Engine;
use smug_core::{GridGeometry, GridLayer, Mission, Point3, Pose2, Scenario, Target, World};
use smug_worlds::render::RasterLayer;
use smug_worlds::{render_svg, RenderOptions};

fn world() -> Scenario {
    // 10 × 5 m, 0.5 m cells, origin at (0, 0).
    let g = GridGeometry::new([0.0, 0.0], 0.5, [20, 10]).unwrap();
    let mut elevation = GridLayer::filled(g, 0.0);
    elevation.set(2, 1, f32::NAN);
    elevation.set(5, 5, 2.0);
    let mut world = World::new("test <world>", elevation).with_mission(Mission {
        start: Pose2::new(1.0, 1.0, 0.0),
        end: Some(Pose2::new(9.0, 4.0, 1.0)),
        targets: vec![
            Target {
                id: "stone & co".into(),
                position: Point3 {
                    x: 5.0,
                    y: 2.5,
                    z: 0.0,
                },
                pois: vec![Pose2::new(4.0, 2.5, 0.0), Pose2::new(6.0, 2.5, 3.0)],
            },
            Target {
                id: "gauge".into(),
                position: Point3 {
                    x: 8.0,
                    y: 1.0,
                    z: 0.0,
                },
                pois: vec![Pose2::new(8.0, 2.0, -1.57)],
            },
        ],
    });
    world.world.traversability = Some(GridLayer::from_fn(
        g,
        |i, _| {
            if i == 0 {
                f32::NAN
            } else {
                1.0
            }
        },
    ));
    world
}

/// Checks that tags nest properly (enough to catch broken markup).
fn assert_well_formed(svg: &str) {
    let mut open: Vec<&str> = Vec::new();
    let mut rest = svg;
    while let Some(start) = rest.find('<') {
        let end = start + rest[start..].find('>').expect("unclosed tag");
        let tag = &rest[start + 1..end];
        rest = &rest[end + 1..];
        if tag.starts_with("!--") || tag.ends_with('/') {
            continue;
        }
        if let Some(closing) = tag.strip_prefix('/') {
            assert_eq!(open.pop(), Some(closing), "mismatched </{closing}>");
        } else {
            open.push(tag.split_whitespace().next().unwrap());
        }
    }
    assert!(open.is_empty(), "unclosed: {open:?}");
}

fn embedded_png(svg: &str) -> image::RgbImage {
    let start = svg.find("data:image/png;base64,").unwrap() + "data:image/png;base64,".len();
    let end = start + svg[start..].find('"').unwrap();
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(&svg[start..end])
        .unwrap();
    image::load_from_memory(&bytes).unwrap().to_rgb8()
}

/// The colour of the cell in `column` and image `row` (top row 0) of an 8× raster.
fn cell(png: &image::RgbImage, column: u32, row: u32) -> [u8; 3] {
    let colour = png.get_pixel(8 * column, 8 * row).0;
    assert_eq!(png.get_pixel(8 * column + 7, 8 * row + 7).0, colour);
    colour
}

#[test]
fn renders_every_element_of_the_world_and_the_overlay() {
    let options = RenderOptions {
        title: Some("A <title>".into()),
        paths: vec![vec![[1.0, 1.0], [4.0, 2.5], [8.0, 2.0]]],
        highlighted_pois: vec![(0, 1), (7, 7)],
        ..RenderOptions::default()
    };
    let scenario = world();
    let svg = render_svg(&scenario.world, Some(&scenario.mission), &options);
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    assert_well_formed(&svg);
    for needle in [
        "<image class=\"raster\"",
        "A &lt;title&gt;",
        "stone &amp; co",
        ">gauge<",
        "class=\"start\"",
        "class=\"end\"",
        "class=\"scale-bar\"",
        "class=\"legend\"",
        "traversability",
        "selected pose of interest",
        "<polyline class=\"path\"",
    ] {
        assert!(svg.contains(needle), "`{needle}` missing");
    }
    assert_eq!(svg.matches("class=\"toi\"").count(), 2);
    assert_eq!(svg.matches("class=\"poi\"").count(), 2);
    assert_eq!(svg.matches("class=\"poi highlighted\"").count(), 1);
    // 800 px for 10 m: 80 px/m; the map's top-left corner is at (20, 52) below the title.
    assert!(svg.contains("translate(100 372) rotate(0)"), "start pose");
    assert!(svg.contains("points=\"100,372 340,252 660,292\""), "path");
    assert!(svg.contains(">2 m</text>"), "scale bar");
}

#[test]
fn the_raster_is_north_up_with_missing_data_dark() {
    let world = world();
    let svg = render_svg(
        &world.world,
        Some(&world.mission),
        &RenderOptions::default(),
    );
    let png = embedded_png(&svg);
    // 20 × 10 cells drawn 800 × 400 px: each cell is replicated 8 × 8 (the maximum).
    assert_eq!(png.dimensions(), (160, 80));
    // Traversability: column 0 is NaN (dark), the rest 1 (green).
    assert!(cell(&png, 0, 3).iter().all(|&c| c < 40));
    assert_eq!(cell(&png, 5, 3), [26, 152, 80]);

    let options = RenderOptions {
        layer: RasterLayer::Elevation,
        legend: false,
        scale_bar: false,
        ..RenderOptions::default()
    };
    let svg = render_svg(&world.world, Some(&world.mission), &options);
    assert!(!svg.contains("class=\"legend\"") && !svg.contains("class=\"scale-bar\""));
    let png = embedded_png(&svg);
    // Cell (2, 1) is NaN: image row 10 − 1 − 1 = 8. Cell (5, 5), the highest, is darkest.
    assert!(cell(&png, 2, 8).iter().all(|&c| c < 40));
    let (floor, top) = (cell(&png, 8, 8), cell(&png, 5, 4));
    assert!(floor[0] > 200 && top[0] < 100, "{floor:?} {top:?}");
}

#[test]
fn degenerate_worlds_render_without_panicking() {
    let g = GridGeometry::new([0.0, 0.0], 1.0, [1, 1]).unwrap();
    let mut world = World::new("one cell", GridLayer::filled(g, f32::NAN)).with_mission(Mission {
        start: Pose2::new(0.5, 0.5, 0.0),
        end: None,
        targets: Vec::new(),
    });
    assert_well_formed(&render_svg(
        &world.world,
        Some(&world.mission),
        &RenderOptions::default(),
    ));
    // A world without a mission: the map alone.
    let bare = render_svg(&world.world, None, &RenderOptions::default());
    assert_well_formed(&bare);
    assert!(!bare.contains("class=\"start\""));
    world.world.elevation =
        GridLayer::filled(GridGeometry::new([0.0, 0.0], 1.0, [0, 0]).unwrap(), 0.0);
    let svg = render_svg(
        &world.world,
        Some(&world.mission),
        &RenderOptions::default(),
    );
    assert_well_formed(&svg);
    assert!(!svg.contains("<image"));
}
