//! End-to-end tests of `smug worlds`: convert, show, export, and bad maps.

mod common;

use common::*;
use std::path::{Path, PathBuf};
use std::process::Output;

fn movingai(file: &str) -> String {
    let path = workspace().join("../shared/data/movingai").join(file);
    path.to_string_lossy().into_owned()
}

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

const MISSION: &str = r#"start = { x = 1.5, y = 1.5, yaw = 0.0 }
[[targets]]
id = "rock-a"
position = { x = 10.0, y = 10.0 }
pois = [{ x = 9.5, y = 10.5, yaw = 1.0 }, { x = 10.5, y = 9.5, yaw = -2.0 }]
"#;

#[test]
fn convert_a_movingai_map_then_show_and_export_it() {
    let dir = scratch("convert");
    let yaml = dir.join("random.yaml");
    let out = smug(&[
        "worlds",
        "convert-movingai",
        &movingai("mapf/random-32-32-10.map"),
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
    for needle in [
        "<image",
        "data:image/png;base64,",
        "class=\"start\"",
        "class=\"legend\"",
    ] {
        assert!(picture.contains(needle), "`{needle}` missing");
    }

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
    for resolution in ["-1", "nan", "0"] {
        assert_bad_input(
            &smug(&[
                "worlds",
                "convert-movingai",
                &movingai("mapf/random-32-32-10.map"),
                text(&out_yaml),
                "--resolution",
                resolution,
            ]),
            &["random-32-32-10.map", "resolution"],
        );
    }
    assert!(!out_yaml.exists());
}
