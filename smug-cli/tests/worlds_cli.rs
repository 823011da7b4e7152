//! End-to-end tests of `smug worlds`: generate, convert, show, export, and bad maps.

mod common;

use common::*;
use std::path::{Path, PathBuf};
use std::process::Output;

/// A fresh, empty folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("worlds-cli-{name}"));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(path: &Path) -> &str {
    path.to_str().unwrap()
}

fn assert_ok(out: &Output) {
    assert_eq!(out.status.code(), Some(0), "stderr: {}", stderr(out));
}

/// Generates a 32×32 map with 10% random obstacles as `dir/grid.map`.
fn generated_map(dir: &Path) -> PathBuf {
    let map = dir.join("grid.map");
    assert_ok(&smug(&[
        "worlds",
        "generate",
        "random",
        "--size",
        "32x32",
        "--seed",
        "1",
        "--out",
        text(&map),
    ]));
    map
}

const MISSION: &str = r#"start = { x = 1.5, y = 1.5, yaw = 0.0 }
[[targets]]
id = "rock-a"
position = { x = 10.0, y = 10.0 }
pois = [{ x = 9.5, y = 10.5, yaw = 1.0 }, { x = 10.5, y = 9.5, yaw = -2.0 }]
"#;

#[test]
fn convert_a_movingai_map_then_show_and_export_it() {
    let dir = scratch("convert");
    let map = generated_map(&dir);
    let yaml = dir.join("random.yaml");
    let out = smug(&[
        "worlds",
        "convert-movingai",
        text(&map),
        text(&yaml),
        "--resolution",
        "0.5",
    ]);
    assert_ok(&out);
    assert!(dir.join("random.pgm").is_file());

    let svg = dir.join("pictures/random.svg");
    assert_ok(&smug(&["worlds", "show", text(&yaml), "--out", text(&svg)]));
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.len() > 2000, "{} bytes", picture.len());
    for needle in ["<image", "data:image/png;base64,", "class=\"legend\""] {
        assert!(picture.contains(needle), "`{needle}` missing");
    }
    // A map without a mission is drawn alone: no start is invented.
    assert!(!picture.contains("class=\"start\""));

    let mission = dir.join("mission.toml");
    std::fs::write(&mission, MISSION).unwrap();
    let with_mission = smug(&[
        "worlds",
        "show",
        text(&yaml),
        "--mission",
        text(&mission),
        "--out",
        text(&svg),
        "--title",
        "random 32",
    ]);
    assert_ok(&with_mission);
    assert!(String::from_utf8_lossy(&with_mission.stdout).contains("1 targets, 2 poses"));
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(picture.matches("class=\"poi\"").count(), 2);
    assert!(picture.contains("class=\"start\""));
    assert!(picture.contains("rock-a") && picture.contains("random 32"));

    let export_dir = dir.join("export");
    let out = smug(&[
        "worlds",
        "export",
        text(&yaml),
        "--mission",
        text(&mission),
        "--out",
        text(&export_dir),
    ]);
    assert_ok(&out);
    for file in [
        "random.yaml",
        "random.pgm",
        "random.elevation.png",
        "random.mission.toml",
    ] {
        assert!(export_dir.join(file).is_file(), "{file} missing");
    }
    // The exported YAML names its mission: `show` picks it up.
    let again = smug(&[
        "worlds",
        "show",
        text(&export_dir.join("random.yaml")),
        "--out",
        text(&svg),
    ]);
    assert_ok(&again);
    assert!(std::fs::read_to_string(&svg).unwrap().contains("rock-a"));
}

#[test]
fn show_builds_configs_and_plugins() {
    let dir = scratch("show");
    let svg = dir.join("demo.svg");
    assert_ok(&smug(&[
        "worlds",
        "show",
        "configs/flat-demo.toml",
        "--out",
        text(&svg),
    ]));
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(picture.matches("class=\"toi\"").count(), 3);
    assert!(picture.contains("flat-demo"));

    // A plugin name with its defaults: `flat` needs a mission.
    assert_bad_input(
        &smug(&["worlds", "show", "flat", "--out", text(&svg)]),
        &["world plugin `flat`", "mission"],
    );
    let mission = dir.join("mission.toml");
    std::fs::write(&mission, MISSION).unwrap();
    let set = format!("world.params.mission_file={:?}", text(&mission));
    assert_ok(&smug(&[
        "worlds",
        "show",
        "flat",
        "--set",
        &set,
        "--set",
        "world.params.size=[12.0, 12.0]",
        "--seed",
        "3",
        "--out",
        text(&svg),
    ]));
    assert_bad_input(
        &smug(&["worlds", "show", "no-such-world", "--out", text(&svg)]),
        &["unknown world plugin `no-such-world`", "flat"],
    );
    assert_bad_input(
        &smug(&[
            "worlds",
            "show",
            "configs/flat-demo.toml",
            "--mission",
            text(&dir.join("nope.toml")),
            "--out",
            text(&svg),
        ]),
        &["nope.toml", "cannot read mission"],
    );
}

/// Writes a map folder: a 4×3 occupancy PGM and `yaml_text` as `bad.yaml`.
fn bad_map(name: &str, yaml_text: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(name);
    std::fs::write(
        dir.join("map.pgm"),
        "P2\n4 3\n255\n0 254 254 254\n254 254 254 254\n254 254 205 0\n",
    )
    .unwrap();
    std::fs::write(dir.join("small.pgm"), "P2\n3 3\n255\n1 2 3\n4 5 6\n7 8 9\n").unwrap();
    let yaml = dir.join("bad.yaml");
    std::fs::write(&yaml, yaml_text).unwrap();
    (dir, yaml)
}

#[test]
fn malformed_maps_exit_2_naming_the_file_and_the_problem() {
    let good = "image: map.pgm\nresolution: 0.5\norigin: [0.0, 0.0, 0.0]\n";
    let cases: &[(&str, String, &[&str])] = &[
        (
            "size",
            format!("{good}traversability_image: small.pgm\n"),
            &["bad.yaml", "small.pgm", "3×3", "4×3", "sizes differ"],
        ),
        (
            "missing",
            good.replace("map.pgm", "gone.pgm"),
            &["bad.yaml", "gone.pgm", "cannot read"],
        ),
        (
            "nan",
            good.replace("0.5", ".nan"),
            &["bad.yaml", "resolution", "NaN"],
        ),
        (
            "negative",
            good.replace("0.5", "-0.5"),
            &["bad.yaml", "resolution", "-0.5"],
        ),
        (
            "yaw",
            good.replace("0.0]", "0.3]"),
            &["bad.yaml", "yaw must be 0"],
        ),
    ];
    for (name, yaml_text, needles) in cases {
        let (dir, yaml) = bad_map(name, yaml_text);
        let svg = dir.join("out.svg");
        assert_bad_input(
            &smug(&["worlds", "show", text(&yaml), "--out", text(&svg)]),
            needles,
        );
        assert!(!svg.exists(), "{name}: picture written despite the error");
    }
    let (dir, yaml) = bad_map("outside", good);
    let mission = dir.join("mission.toml");
    std::fs::write(&mission, MISSION).unwrap();
    assert_bad_input(
        &smug(&[
            "worlds",
            "export",
            text(&yaml),
            "--mission",
            text(&mission),
            "--out",
            text(&dir),
        ]),
        &["bad.yaml", "PoI 0 of target `rock-a` lies outside the map"],
    );
}

#[test]
fn bad_movingai_input_exits_2() {
    let dir = scratch("bad-movingai");
    let map = dir.join("bad.map");
    std::fs::write(&map, "type octile\nheight 2\nwidth 3\nmap\n...\n..\n").unwrap();
    let out_yaml = dir.join("out.yaml");
    assert_bad_input(
        &smug(&["worlds", "convert-movingai", text(&map), text(&out_yaml)]),
        &["bad.map:6", "row has 2 cells", "width 3"],
    );
    let good = generated_map(&dir);
    for resolution in ["-1", "nan", "0"] {
        assert_bad_input(
            &smug(&[
                "worlds",
                "convert-movingai",
                text(&good),
                text(&out_yaml),
                "--resolution",
                resolution,
            ]),
            &["grid.map", "resolution"],
        );
    }
    assert!(!out_yaml.exists());
}

#[test]
fn generate_writes_a_map_scenarios_and_a_map_yaml() {
    let dir = scratch("generate");
    let map = dir.join("maze.map");
    let out = smug(&[
        "worlds",
        "generate",
        "maze",
        "--size",
        "21x15",
        "--seed",
        "4",
        "--out",
        text(&map),
        "--scen",
        "30",
        "--yaml",
        "--resolution",
        "0.5",
    ]);
    assert_ok(&out);
    assert!(
        stdout(&out).contains("maze 21×15 map, seed 4"),
        "{}",
        stdout(&out)
    );
    let grid = std::fs::read_to_string(&map).unwrap();
    assert!(
        grid.starts_with("type octile\nheight 15\nwidth 21\nmap\n"),
        "{grid}"
    );
    assert_eq!(grid.lines().count(), 4 + 15);
    let scen = std::fs::read_to_string(dir.join("maze.map.scen")).unwrap();
    assert!(scen.starts_with("version 1\n"));
    assert_eq!(scen.lines().count(), 1 + 30);
    assert!(
        scen.lines()
            .nth(1)
            .unwrap()
            .contains("\tmaze.map\t21\t15\t"),
        "{scen}"
    );
    let yaml = std::fs::read_to_string(dir.join("maze.yaml")).unwrap();
    assert!(yaml.contains("generated by `smug worlds generate maze --size 21x15 --seed 4`"));
    assert!(
        yaml.contains("resolution: 0.5") && dir.join("maze.pgm").is_file(),
        "{yaml}"
    );
    // The YAML is a usable world.
    let svg = dir.join("maze.svg");
    assert_ok(&smug(&[
        "worlds",
        "show",
        text(&dir.join("maze.yaml")),
        "--out",
        text(&svg),
    ]));
    // Same seed, same bytes; another seed, another map.
    let again = dir.join("again.map");
    let args = [
        "worlds",
        "generate",
        "maze",
        "--size",
        "21x15",
        "--out",
        text(&again),
    ];
    assert_ok(&smug(&[&args[..], &["--seed", "4"]].concat()));
    assert_eq!(std::fs::read_to_string(&again).unwrap(), grid);
    assert_ok(&smug(&[&args[..], &["--seed", "5"]].concat()));
    assert_ne!(std::fs::read_to_string(&again).unwrap(), grid);
}

#[test]
fn bad_generate_input_exits_2() {
    let dir = scratch("generate-bad");
    let out = dir.join("x.map");
    let run = |extra: &[&str]| {
        let mut args = vec!["worlds", "generate"];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--out", text(&out)]);
        smug(&args)
    };
    assert_bad_input(
        &run(&["maze", "--size", "8x8", "--density", "0.2"]),
        &["--density applies to the random and terrain families, not maze"],
    );
    assert_bad_input(
        &run(&["random", "--size", "8x8", "--room-size", "3"]),
        &["--room-size applies to the rooms family, not random"],
    );
    assert_bad_input(
        &run(&["random", "--size", "8x8", "--density", "1.5"]),
        &["density must be at least 0 and below 1, got 1.5"],
    );
    assert_bad_input(
        &run(&["random", "--size", "0x8"]),
        &["size 0x8", "1 to 4096"],
    );
    assert_bad_input(
        &run(&["rooms", "--size", "8x8", "--room-size", "0"]),
        &["room size must be at least 1"],
    );
    assert!(!out.exists(), "a map was written despite the errors");
    // Usage errors (clap) also exit 2.
    for args in [
        &["forest", "--size", "8x8"][..],
        &["random", "--size", "8by8"][..],
    ] {
        let bad = run(args);
        assert_eq!(bad.status.code(), Some(2), "{args:?}");
    }
    assert!(stderr(&run(&["forest", "--size", "8x8"])).contains("unknown map family `forest`"));
    assert!(stderr(&run(&["random", "--size", "8by8"])).contains("expected WIDTHxHEIGHT"));
}

/// The command documented in `configs/maps/README.md` for the imported-map example.
/// The commands that made the tracked example maps (`configs/maps/`), with the stem of
/// their files.
const CONFIG_MAPS: [(&[&str], &str); 2] = [
    (
        &[
            "worlds",
            "generate",
            "random",
            "--size",
            "32x32",
            "--seed",
            "1",
            "--density",
            "0.1",
            "--yaml",
        ],
        "random-32x32-d10-s1",
    ),
    (
        &[
            "worlds",
            "generate",
            "polygons",
            "--size",
            "128x128",
            "--seed",
            "1",
            "--yaml",
            "--resolution",
            "0.25",
        ],
        "polygons-128x128-d20-s1",
    ),
];

#[test]
fn the_example_maps_regenerate_bit_identically() {
    let dir = scratch("config-map");
    let maps = workspace().join("configs/maps");
    let readme = std::fs::read_to_string(maps.join("README.md")).unwrap();
    for (command, stem) in CONFIG_MAPS {
        let map = dir.join(format!("{stem}.map"));
        assert_ok(&smug(&[command, &["--out", text(&map)]].concat()));
        for ext in ["map", "yaml", "pgm"] {
            let file = format!("{stem}.{ext}");
            let fresh = std::fs::read(dir.join(&file)).unwrap();
            let tracked = std::fs::read(maps.join(&file)).unwrap();
            assert!(
                fresh == tracked,
                "{file} differs from a fresh `smug {}`",
                command.join(" ")
            );
        }
        assert!(
            readme.contains(&command.join(" ")),
            "the README names `{}`",
            command.join(" ")
        );
    }
}

#[test]
fn the_example_mission_lies_in_free_cells_reachable_from_its_start() {
    use smug_worlds::movingai::{octile_distances, read_map, world_to_scenario};
    let maps = workspace().join("configs/maps");
    let grid = read_map(&maps.join("random-32x32-d10-s1.map")).unwrap();
    let mission =
        smug_worlds::load_mission(&maps.join("random-32x32-d10-s1.mission.toml")).unwrap();
    let cell = |x: f64, y: f64| world_to_scenario([x, y], grid.width, grid.height, 1.0).unwrap();
    let start = cell(mission.start.x, mission.start.y);
    let distance = octile_distances(&grid, start);
    let reachable = |[x, y]: [usize; 2]| distance[y * grid.width + x].is_finite();
    assert!(reachable(start), "the start {start:?} is blocked");
    assert_eq!(mission.targets.len(), 6);
    for target in &mission.targets {
        let at = cell(target.position.x, target.position.y);
        assert!(reachable(at), "target `{}` at {at:?}", target.id);
        assert!(!target.pois.is_empty());
        for poi in &target.pois {
            assert!(
                reachable(cell(poi.x, poi.y)),
                "a PoI of `{}` at {poi:?}",
                target.id
            );
        }
    }
}

#[test]
fn convert_a_point_cloud_and_bad_terrain_files_exit_2() {
    let dir = scratch("convert-terrain");
    // A 6 × 4 m ramp, 5 points per 0.5 m cell side, as ASCII PLY.
    let mut ply = String::from(
        "ply\nformat ascii 1.0\nelement vertex 960\nproperty float x\nproperty float y\n\
         property float z\nend_header\n",
    );
    for j in 0..24 {
        for i in 0..40 {
            let (x, y) = (0.05 + 0.15 * i as f64, 0.05 + 0.15 * j as f64 + 0.2);
            ply += &format!("{x} {y} {}\n", 0.01 * x);
        }
    }
    let cloud = dir.join("ramp.ply");
    std::fs::write(&cloud, ply).unwrap();
    let out = smug(&[
        "worlds",
        "convert",
        text(&cloud),
        "--out",
        text(&dir.join("map")),
        "--cell-size",
        "0.5",
        "--reduce",
        "mean",
    ]);
    assert_ok(&out);
    assert!(
        stdout(&out).contains("12×8 cells at 0.5 m"),
        "{}",
        stdout(&out)
    );
    let yaml = std::fs::read_to_string(dir.join("map/ramp.yaml")).unwrap();
    assert!(yaml.contains("resolution: 0.5"), "{yaml}");
    assert!(dir.join("map/ramp.elevation.png").is_file());

    // Not terrain, a bad GeoTIFF, a bad PLY: exit 2 naming the file and the fault.
    let out = smug(&[
        "worlds",
        "convert",
        "configs/lunar.toml",
        "--out",
        text(&dir),
    ]);
    assert_bad_input(&out, &["configs/lunar.toml", "not a GeoTIFF DEM"]);
    let tif = dir.join("broken.tif");
    std::fs::write(&tif, b"II*\0garbage").unwrap();
    let out = smug(&[
        "worlds",
        "show",
        text(&tif),
        "--out",
        text(&dir.join("x.svg")),
    ]);
    assert_bad_input(&out, &["broken.tif", "not a readable TIFF"]);
    let ply = dir.join("broken.ply");
    std::fs::write(
        &ply,
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nend_header\n",
    )
    .unwrap();
    let out = smug(&["worlds", "convert", text(&ply), "--out", text(&dir)]);
    assert_bad_input(&out, &["broken.ply", "no vertex property `y` (found: x)"]);
}
