//! Map import (YAML + PGM/PNG), world export round trips, the `map` plugin and the
//! MovingAI converter and readers on generated maps and the sample files in
//! `tests/data/` (every terrain character, CRLF, header and scenario corner cases).

use image::{ImageBuffer, Luma, LumaA, Rgb, Rgba};
use smug_core::{
    GridGeometry, GridLayer, LoadedConfig, Mission, Pipeline, Point3, Pose2, Scenario, World,
};
use smug_worlds::grid_gen::{generate, GridFamily, GridParams};
use smug_worlds::map_file::{load_map, MapFileError};
use smug_worlds::movingai::{
    generate_scenarios, read_map, read_scenarios, scenario_to_world, write_map, write_scenarios,
};
use smug_worlds::{convert_movingai, export_world};
use std::path::{Path, PathBuf};

/// A fresh, empty folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("map-io-{name}"));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

const YAML: &str = "image: map.pgm\nresolution: 0.5\norigin: [1.0, -2.0, 0.0]\n";

/// A 3×2 ASCII PGM: top row occupied / free / unknown, bottom row free / occupied / free.
const PGM_P2: &str = "P2\n# comment\n3 2\n255\n0 254 205\n254 0 254\n";

fn mission(pois: &[[f64; 2]]) -> Mission {
    Mission {
        start: Pose2::new(1.5, -1.5, 0.0),
        end: None,
        targets: vec![smug_core::Target {
            id: "stone-1".into(),
            position: Point3 {
                x: 2.0,
                y: -1.0,
                z: 0.0,
            },
            pois: pois.iter().map(|p| Pose2::new(p[0], p[1], 0.5)).collect(),
        }],
    }
}

fn heights(layer: &GridLayer) -> Vec<Option<f32>> {
    layer
        .data
        .iter()
        .map(|v| (!v.is_nan()).then_some(*v))
        .collect()
}

#[test]
fn ascii_pgm_maps_flip_rows_and_classify_like_map_server() {
    let dir = scratch("p2");
    write(&dir, "map.pgm", PGM_P2);
    let yaml = write(&dir, "map.yaml", YAML);
    let layers = load_map(&yaml, 1.5).unwrap();
    let g = layers.elevation.geometry;
    assert_eq!(g, GridGeometry::new([1.0, -2.0], 0.5, [3, 2]).unwrap());
    // Grid row 0 is the image's bottom row.
    assert_eq!(
        heights(&layers.elevation),
        [Some(0.0), Some(1.5), Some(0.0), Some(1.5), Some(0.0), None]
    );
    assert!(layers.traversability.is_none());
    assert_eq!(layers.elevation.nearest(1.2, -1.2), Some(1.5)); // top-left pixel
}

#[test]
fn binary_and_sixteen_bit_pgm_and_colour_png_agree() {
    let dir = scratch("formats");
    let expected = heights(&{
        write(&dir, "map.pgm", PGM_P2);
        load_map(&write(&dir, "map.yaml", YAML), 2.0)
            .unwrap()
            .elevation
    });
    let mut p5 = b"P5\n3 2\n255\n".to_vec();
    p5.extend([0u8, 254, 205, 254, 0, 254]);
    write(&dir, "map.pgm", &p5);
    let yaml = write(&dir, "map.yaml", YAML);
    assert_eq!(heights(&load_map(&yaml, 2.0).unwrap().elevation), expected);

    let mut p5_16 = b"P5\n3 2\n65535\n".to_vec();
    for v in [0u16, 65278, 52685, 65278, 0, 65278] {
        p5_16.extend(v.to_be_bytes());
    }
    write(&dir, "map.pgm", &p5_16);
    assert_eq!(heights(&load_map(&yaml, 2.0).unwrap().elevation), expected);

    let values = [[0u8, 254, 205], [254, 0, 254]];
    let rgb = ImageBuffer::from_fn(3, 2, |x, y| Rgb([values[y as usize][x as usize]; 3]));
    rgb.save(dir.join("map.png")).unwrap();
    let png_yaml = write(&dir, "png.yaml", YAML.replace("map.pgm", "map.png"));
    assert_eq!(
        heights(&load_map(&png_yaml, 2.0).unwrap().elevation),
        expected
    );

    // A transparent pixel is unknown.
    let rgba = ImageBuffer::from_fn(3, 2, |x, y| {
        let v = values[y as usize][x as usize];
        Rgba([v, v, v, if (x, y) == (1, 1) { 0 } else { 255 }])
    });
    rgba.save(dir.join("map.png")).unwrap();
    let layers = load_map(&png_yaml, 2.0).unwrap();
    assert!(layers.elevation.get(1, 0).is_nan());
}

#[test]
fn negate_and_scale_mode() {
    let dir = scratch("modes");
    write(&dir, "map.pgm", "P2\n3 1\n255\n0 255 128\n");
    let yaml = write(&dir, "map.yaml", format!("{YAML}negate: 1\n"));
    let e = load_map(&yaml, 1.0).unwrap().elevation;
    assert_eq!(heights(&e), [Some(0.0), Some(1.0), None]);

    let yaml = write(&dir, "map.yaml", format!("{YAML}mode: scale\n"));
    let layers = load_map(&yaml, 1.0).unwrap();
    assert_eq!(
        heights(&layers.elevation),
        [Some(1.0), Some(0.0), Some(0.0)]
    );
    let t = layers.traversability.unwrap().data;
    assert_eq!(&t[..2], &[0.0, 1.0]);
    assert!(t[2] > 0.0 && t[2] < 1.0, "{t:?}");
}

#[test]
fn elevation_and_traversability_images() {
    let dir = scratch("layers");
    write(&dir, "map.pgm", PGM_P2);
    let ground = ImageBuffer::from_fn(3, 2, |x, y| Luma([1000 * (x as u16 + 3 * y as u16)]));
    ground.save(dir.join("ground.png")).unwrap();
    let trav = ImageBuffer::from_fn(3, 2, |x, y| match (x, y) {
        (0, 0) => LumaA([9u8, 255]),
        (1, 0) => LumaA([255, 0]),
        _ => LumaA([51, 255]),
    });
    trav.save(dir.join("trav.png")).unwrap();
    let yaml = write(
        &dir,
        "map.yaml",
        format!(
            "{YAML}elevation_image: ground.png\nelevation_scale: 0.002\nelevation_offset: -1.0\n\
             traversability_image: trav.png\ntraversability_nodata: 9\n"
        ),
    );
    let layers = load_map(&yaml, 2.0).unwrap();
    // Image pixel (x, y) is grid cell (x, 1 − y); ground = −1 + 0.002 · 1000 · (x + 3y).
    let e = &layers.elevation;
    assert_eq!(e.get(0, 1), -1.0 + 2.0); // occupied: ground + obstacle height
    assert_eq!(e.get(1, 1), 1.0); // free: ground
    assert!(e.get(2, 1).is_nan()); // unknown
    assert_eq!(e.get(0, 0), 5.0); // free, ground −1 + 0.002·3000
    assert_eq!(e.get(1, 0), 9.0); // occupied: 7 + 2
    let t = layers.traversability.unwrap();
    assert!(t.get(0, 1).is_nan(), "nodata value");
    assert!(t.get(1, 1).is_nan(), "transparent");
    assert_eq!(t.get(2, 1), 0.2);

    let yaml = write(
        &dir,
        "surface.yaml",
        format!(
            "{YAML}elevation_image: ground.png\nelevation_scale: 0.002\nelevation_offset: -1.0\n\
             elevation_includes_obstacles: true\n"
        ),
    );
    assert_eq!(load_map(&yaml, 2.0).unwrap().elevation.get(1, 0), 7.0);
}

fn import_error(dir: &Path, yaml_text: &str) -> String {
    let yaml = write(dir, "bad.yaml", yaml_text);
    let err = load_map(&yaml, 2.0).unwrap_err().to_string();
    assert!(err.contains("bad.yaml"), "YAML file not named: {err}");
    err
}

#[test]
fn malformed_maps_are_typed_errors_naming_the_file() {
    let dir = scratch("malformed");
    write(&dir, "map.pgm", PGM_P2);
    write(&dir, "broken.pgm", "P2\n3 2\n255\n0 1\n");
    write(&dir, "text.pgm", "hello, I am not an image");
    write(&dir, "notes.txt", "hello, I am not an image");
    ImageBuffer::from_fn(4, 2, |_, _| Luma([0u16]))
        .save(dir.join("wide.png"))
        .unwrap();
    ImageBuffer::from_fn(3, 2, |_, _| Rgb([0u8, 0, 0]))
        .save(dir.join("colour.png"))
        .unwrap();
    let cases: &[(String, &[&str])] = &[
        (YAML.replace("0.5", "-0.5"), &["resolution", "-0.5"]),
        (YAML.replace("0.5", ".nan"), &["resolution", "NaN"]),
        (YAML.replace("0.5", "0"), &["resolution"]),
        (YAML.replace("0.0]", "1.57]"), &["yaw must be 0"]),
        (
            YAML.replace("map.pgm", "absent.pgm"),
            &["absent.pgm", "cannot read"],
        ),
        (
            YAML.replace("map.pgm", "broken.pgm"),
            &["broken.pgm", "cannot decode"],
        ),
        (
            YAML.replace("map.pgm", "text.pgm"),
            &["text.pgm", "cannot decode"],
        ),
        (
            YAML.replace("map.pgm", "notes.txt"),
            &["notes.txt", "unknown image format"],
        ),
        (
            format!("{YAML}elevation_image: wide.png\n"),
            &["map.pgm", "3×2", "wide.png", "4×2"],
        ),
        (
            format!("{YAML}traversability_image: colour.png\n"),
            &["colour.png", "grayscale"],
        ),
        (
            format!("{YAML}resolutoin: 1\n"),
            &["unknown field `resolutoin`"],
        ),
        (
            "image: map.pgm\norigin: [0, 0, 0]\n".into(),
            &["missing field `resolution`"],
        ),
        ("{{{".into(), &["invalid map YAML"]),
    ];
    for (text, needles) in cases {
        let err = import_error(&dir, text);
        for needle in *needles {
            assert!(err.contains(needle), "`{needle}` missing from: {err}");
        }
    }
    let err = load_map(&dir.join("absent.yaml"), 2.0).unwrap_err();
    assert!(matches!(err, MapFileError::Read { .. }), "{err}");
}

/// A pipeline config loading `map.yaml` in `dir` (with a robot small enough for the
/// tiny test maps) with extra world `params`.
fn map_config(dir: &Path, params: &str) -> Result<Scenario, String> {
    let robot = "[robot]\nlength = 0.4\nwidth = 0.3\n";
    let text =
        format!("{robot}[world]\ntype = \"map\"\n[world.params]\nyaml = \"map.yaml\"\n{params}");
    let loaded =
        LoadedConfig::from_text(&text, "test.toml", dir, &[]).map_err(|e| e.to_string())?;
    let pipeline = Pipeline::assemble(&loaded).map_err(|e| e.to_string())?;
    let world = pipeline.world.unwrap().as_ref().clone();
    Ok(world.with_mission(pipeline.given_mission.unwrap()))
}

#[test]
fn map_plugin_loads_missions_and_checks_they_lie_inside() {
    let dir = scratch("plugin");
    write(&dir, "map.pgm", PGM_P2);
    write(&dir, "map.yaml", YAML);
    let inside = toml::to_string(&mission(&[[2.0, -1.0]])).unwrap();
    write(&dir, "inside.toml", &inside);
    let world = map_config(
        &dir,
        "mission_file = \"inside.toml\"\nobstacle_height = 0.75\n",
    )
    .unwrap();
    assert_eq!(world.world.name, "map");
    assert_eq!(world.mission, mission(&[[2.0, -1.0]]));
    assert_eq!(world.world.elevation.get(0, 1), 0.75);

    let outside = toml::to_string(&mission(&[[2.0, -1.0], [2.0, -1.0], [9.0, -1.0]])).unwrap();
    write(&dir, "outside.toml", &outside);
    let err = map_config(&dir, "mission_file = \"outside.toml\"\n").unwrap_err();
    assert!(
        err.contains("PoI 2 of target `stone-1` lies outside the map"),
        "{err}"
    );
    assert!(err.contains("map.yaml"), "{err}");

    let err = map_config(&dir, "").unwrap_err();
    assert!(err.contains("needs a `mission`"), "{err}");
    let err = map_config(&dir, "mission_file = \"nope.toml\"\n").unwrap_err();
    assert!(err.contains("nope.toml"), "{err}");
    let err = map_config(
        &dir,
        "mission_file = \"inside.toml\"\nobstacle_hieght = 1\n",
    )
    .unwrap_err();
    assert!(err.contains("obstacle_hieght"), "{err}");

    // The YAML's own `mission` key is used when the config gives none.
    write(&dir, "map.yaml", format!("{YAML}mission: inside.toml\n"));
    let world = map_config(&dir, "name = \"lab\"\n").unwrap();
    assert_eq!(
        (world.world.name.as_str(), world.mission.targets.len()),
        ("lab", 1)
    );
}

fn sample_world() -> Scenario {
    let g = GridGeometry::new([-3.25, 10.5], 0.25, [40, 24]).unwrap();
    let mut elevation = GridLayer::from_fn(g, |i, j| {
        let [x, y] = g.center_of(i, j);
        (0.2 * (x * 0.7).sin() + 0.01 * y - 0.42) as f32
    });
    for i in 10..14 {
        for j in 5..9 {
            elevation.set(i, j, 1.8); // a block
        }
    }
    elevation.set(0, 0, f32::NAN);
    elevation.set(39, 23, f32::NAN);
    let mut traversability = GridLayer::from_fn(g, |i, j| ((i + j) % 11) as f32 / 10.0);
    traversability.set(3, 4, f32::NAN);
    let mut world = World::new("round-trip", elevation).with_mission(Mission {
        start: Pose2::new(-2.0, 11.0, 0.3),
        end: Some(Pose2::new(5.0, 15.0, -3.0)),
        targets: vec![
            smug_core::Target {
                id: "gauge \"a\"".into(),
                position: Point3 {
                    x: 0.1,
                    y: 12.0,
                    z: 0.5,
                },
                pois: vec![
                    Pose2::new(0.0, 11.5, 1.0),
                    Pose2::new(1.0 / 3.0, 12.5, -2.0),
                ],
            },
            smug_core::Target {
                id: "valve".into(),
                position: Point3 {
                    x: 4.0,
                    y: 14.0,
                    z: 0.0,
                },
                pois: vec![Pose2::new(4.5, 14.0, 3.1)],
            },
        ],
    });
    world.world.traversability = Some(traversability);
    world
}

#[test]
fn export_then_import_round_trips() {
    let dir = scratch("round-trip");
    let Scenario {
        world,
        mission: given,
    } = sample_world();
    let yaml = export_world(&world, Some(&given), &dir.join("out"), "rt").unwrap();
    assert_eq!(yaml, dir.join("out/rt.yaml"));
    for file in [
        "rt.pgm",
        "rt.elevation.png",
        "rt.traversability.png",
        "rt.mission.toml",
    ] {
        assert!(dir.join("out").join(file).is_file(), "{file} missing");
    }
    let layers = load_map(&yaml, 2.0).unwrap();
    let mission = smug_worlds::load_mission(layers.mission_file.as_ref().unwrap()).unwrap();
    assert_eq!(mission, given);
    let imported = layers.into_scenario("rt", mission, &yaml).unwrap().world;
    assert_eq!(imported.elevation.geometry, world.elevation.geometry);
    for (k, (a, b)) in world
        .elevation
        .data
        .iter()
        .zip(&imported.elevation.data)
        .enumerate()
    {
        assert_eq!(a.is_nan(), b.is_nan(), "cell {k}: {a} vs {b}");
        assert!(
            a.is_nan() || (a - b).abs() <= 0.0006,
            "cell {k}: {a} vs {b}"
        );
    }
    let (t0, t1) = (
        world.traversability.as_ref().unwrap(),
        imported.traversability.as_ref().unwrap(),
    );
    for (a, b) in t0.data.iter().zip(&t1.data) {
        assert_eq!(a.is_nan(), b.is_nan());
        assert!(
            a.is_nan() || (a - b).abs() <= 0.5 / 255.0 + 1e-6,
            "{a} vs {b}"
        );
    }
    // The occupancy image marks the block occupied and NaN cells unknown.
    let pgm = std::fs::read(dir.join("out/rt.pgm")).unwrap();
    let pixels = &pgm[pgm.len() - 40 * 24..];
    let pixel = |i: usize, j: usize| pixels[(23 - j) * 40 + i];
    assert_eq!((pixel(11, 6), pixel(0, 0), pixel(20, 20)), (0, 205, 254));
}

#[test]
fn export_rejects_unusable_requests() {
    let dir = scratch("export-errors");
    let sample = sample_world();
    let err = export_world(&sample.world, Some(&sample.mission), &dir, "a/b")
        .unwrap_err()
        .to_string();
    assert!(err.contains("a/b"), "{err}");
    let blocker = write(&dir, "file", "x");
    let err = export_world(
        &sample.world,
        Some(&sample.mission),
        &blocker.join("sub"),
        "w",
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("cannot write"), "{err}");
}

/// The sample `.map` / `.scen` files of this crate's tests.
fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

/// A generated 32×32 map with 10% random obstacles and 200 scenarios, written as
/// `random.map` and `random.map.scen` into `dir`.
fn generated_random_map(dir: &Path) -> (PathBuf, PathBuf) {
    let params = GridParams::new(GridFamily::Random, 32, 32, 1);
    let grid = generate(&params).unwrap();
    let map = dir.join("random.map");
    let scen = dir.join("random.map.scen");
    write_map(&map, &grid).unwrap();
    let scenarios = generate_scenarios(&grid, "random.map", 200, 1).unwrap();
    write_scenarios(&scen, &scenarios).unwrap();
    (map, scen)
}

#[test]
fn movingai_conversion_keeps_cells_and_scenarios() {
    let dir = scratch("movingai");
    let (map_path, scen_path) = generated_random_map(&dir);
    let grid = read_map(&map_path).unwrap();
    assert_eq!((grid.width, grid.height), (32, 32));
    let resolution = 0.5;
    let yaml = dir.join("converted.yaml");
    let pgm = convert_movingai(&map_path, &yaml, resolution).unwrap();
    assert_eq!(pgm, dir.join("converted.pgm"));
    let layers = load_map(&yaml, 2.0).unwrap();
    let e = &layers.elevation;
    assert_eq!(e.geometry.size, [32, 32]);
    assert_eq!(e.geometry.bounds().max, [16.0, 16.0]);
    let mut blocked = 0;
    for y in 0..grid.height {
        for x in 0..grid.width {
            let [wx, wy] = scenario_to_world([x, y], grid.height, resolution);
            let z = e.nearest(wx, wy).unwrap();
            assert_eq!(z == 2.0, !grid.is_passable(x, y), "cell ({x}, {y})");
            blocked += usize::from(z == 2.0);
        }
    }
    assert_eq!(blocked, 102, "10% of 1024 cells");
    let scenarios = read_scenarios(&scen_path).unwrap();
    assert_eq!(scenarios.len(), 200);
    for s in &scenarios {
        assert_eq!((s.width, s.height, s.map.as_str()), (32, 32, "random.map"));
        for cell in [s.start, s.goal] {
            let [wx, wy] = scenario_to_world(cell, grid.height, resolution);
            assert_eq!(
                e.nearest(wx, wy),
                Some(0.0),
                "scenario cell {cell:?} not free"
            );
        }
    }
}

#[test]
fn every_sample_and_generated_movingai_file_parses() {
    let dir = scratch("movingai-families");
    let mut pairs = vec![
        (
            data_dir().join("every-terrain.map"),
            data_dir().join("tabs.scen"),
        ),
        (
            data_dir().join("crlf.map"),
            data_dir().join("spaces-crlf.scen"),
        ),
    ];
    for family in GridFamily::ALL {
        let grid = generate(&GridParams::new(family, 45, 30, 2)).unwrap();
        let map = dir.join(format!("{family}.map"));
        write_map(&map, &grid).unwrap();
        let scen = dir.join(format!("{family}.map.scen"));
        let name = format!("{family}.map");
        write_scenarios(&scen, &generate_scenarios(&grid, &name, 50, 2).unwrap()).unwrap();
        pairs.push((map, scen));
    }
    for (map, scen) in &pairs {
        let grid = read_map(map).unwrap();
        let scenarios = read_scenarios(scen).unwrap();
        assert!(!scenarios.is_empty(), "{}", scen.display());
        for s in &scenarios {
            let name = scen.display();
            assert_eq!((s.width, s.height), (grid.width, grid.height), "{name}");
            assert!(grid.is_passable(s.start[0], s.start[1]), "{name}: {s:?}");
            assert!(grid.is_passable(s.goal[0], s.goal[1]), "{name}: {s:?}");
            let length = smug_worlds::movingai::octile_length(&grid, s.start, s.goal);
            assert!(
                (length.unwrap() - s.optimal_length).abs() < 1e-6,
                "{name}: {s:?}"
            );
        }
    }
}

#[test]
fn sample_files_cover_the_reader_corner_cases() {
    // Every terrain character: `.`, `G` and `S` passable; `@`, `O`, `T` and `W` blocked.
    let terrain = read_map(&data_dir().join("every-terrain.map")).unwrap();
    let rows: Vec<String> = (0..terrain.height)
        .map(|y| {
            (0..terrain.width)
                .map(|x| if terrain.is_passable(x, y) { '.' } else { '#' })
                .collect()
        })
        .collect();
    assert_eq!(rows, [".....", "##.##", "....."]);
    // CRLF line ends read like LF ones.
    let crlf = read_map(&data_dir().join("crlf.map")).unwrap();
    assert_eq!(crlf.passable, [true, false, true, true, true, true]);
    let spaced = read_scenarios(&data_dir().join("spaces-crlf.scen")).unwrap();
    assert_eq!(
        (spaced[0].start, spaced[0].goal, spaced[0].optimal_length),
        ([0, 0], [2, 0], 4.0)
    );
    // Header lines in either order; blank lines after the rows are fine.
    let w = read_map(&data_dir().join("width-first.map")).unwrap();
    assert_eq!(
        (w.width, w.height, w.passable.clone()),
        (2, 1, vec![true, false])
    );
    assert_eq!(
        read_map(&data_dir().join("trailing-blank-lines.map"))
            .unwrap()
            .passable_count(),
        4
    );
    let errors = [
        (
            "no-width.map",
            "no-width.map:3: the header needs `height` and `width`",
        ),
        ("no-version.scen", "no-version.scen:1: expected `version 1`"),
        ("short-line.scen", "short-line.scen:2: expected 9 fields"),
    ];
    for (file, needle) in errors {
        let path = data_dir().join(file);
        let err = if file.ends_with(".map") {
            read_map(&path).unwrap_err().to_string()
        } else {
            read_scenarios(&path).unwrap_err().to_string()
        };
        assert!(err.contains(needle), "{err}");
    }
    let missing = read_map(&data_dir().join("absent.map"))
        .unwrap_err()
        .to_string();
    assert!(missing.contains("absent.map: cannot read"), "{missing}");
}

#[test]
fn movingai_converter_rejects_bad_input() {
    let dir = scratch("movingai-bad");
    let map = write(
        &dir,
        "bad.map",
        "type octile\nheight 2\nwidth 2\nmap\n..\n.?\n",
    );
    let err = convert_movingai(&map, &dir.join("out.yaml"), 1.0)
        .unwrap_err()
        .to_string();
    assert!(err.contains("bad.map:6: unknown terrain `?`"), "{err}");
    let good = write(&dir, "good.map", "type octile\nheight 1\nwidth 1\nmap\n.\n");
    for resolution in [0.0, -1.0, f64::NAN] {
        let err = convert_movingai(&good, &dir.join("out.yaml"), resolution)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("good.map") && err.contains("resolution"),
            "{err}"
        );
    }
    assert!(!dir.join("out.yaml").exists());
}
