//! Pipeline assembly across crates: invalid PoIs are dropped and reported, invalid
//! starts and targets without valid PoIs are errors that name them.

use smug_core::{LoadedConfig, Pipeline};
use std::path::Path;

use smug_app as _;

/// A flat 10 × 10 m world with a 2 m block at x ∈ [4, 6], y ∈ [4, 6] and one target
/// whose PoIs are given by `pois`. A pose facing the block from 1.3 m puts the front
/// of the 1.07 m base into it.
fn config(start: &str, pois: &str) -> String {
    format!(
        r#"
[world]
type = "flat"
[world.params]
obstacles = [{{ min = [4.0, 4.0], max = [6.0, 6.0], height = 2.0 }}]
[world.params.mission]
start = {start}
[[world.params.mission.targets]]
id = "block"
position = {{ x = 5.0, y = 5.0 }}
pois = {pois}

[validity]
type = "volumetric"
"#
    )
}

fn assemble(text: &str) -> Result<Pipeline, smug_core::Error> {
    let loaded = LoadedConfig::from_text(text, "test.toml", Path::new("."), &[]).unwrap();
    Pipeline::assemble(&loaded)
}

#[test]
fn invalid_pois_are_dropped_and_reported() {
    let pipeline = assemble(&config(
        "{ x = 1.5, y = 1.5 }",
        "[{ x = 5.0, y = 3.7, yaw = 1.5708 }, { x = 5.0, y = 2.5, yaw = 1.5708 }]",
    ))
    .unwrap();
    let mission = pipeline.mission.as_ref().unwrap();
    assert_eq!(mission.targets[0].pois.len(), 1);
    assert_eq!(pipeline.dropped_pois.len(), 1);
    assert_eq!(
        (
            pipeline.dropped_pois[0].target.as_str(),
            pipeline.dropped_pois[0].index
        ),
        ("block", 0)
    );
    assert_eq!(
        pipeline.given_mission.as_ref().unwrap().targets[0]
            .pois
            .len(),
        2,
        "the world keeps its mission"
    );
}

#[test]
fn a_target_without_valid_pois_is_named() {
    let err = assemble(&config(
        "{ x = 1.5, y = 1.5 }",
        "[{ x = 5.0, y = 3.7, yaw = 1.5708 }, { x = 3.7, y = 5.0 }]",
    ))
    .err()
    .unwrap()
    .to_string();
    assert!(
        err.contains("target `block` has no valid pose of interest"),
        "{err}"
    );
}

#[test]
fn a_start_in_collision_is_named() {
    let err = assemble(&config(
        "{ x = 5.0, y = 3.8, yaw = 1.5708 }",
        "[{ x = 5.0, y = 2.5 }]",
    ))
    .err()
    .unwrap()
    .to_string();
    assert!(err.contains("the start pose (5.000, 3.800"), "{err}");
}
