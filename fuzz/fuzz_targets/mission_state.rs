//! The mission state reader (`smug replan --state`), checked against a small mission.
#![no_main]

use libfuzzer_sys::fuzz_target;
use smug_core::mission::MissionState;
use smug_core::{Bounds2, Mission, Point3, Pose2, Target};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(state) = MissionState::from_toml(text, "state.toml") else {
        return;
    };
    let mission = Mission {
        start: Pose2::new(1.0, 1.0, 0.0),
        end: None,
        targets: vec![Target {
            id: "a".into(),
            position: Point3 {
                x: 5.0,
                y: 5.0,
                z: 0.0,
            },
            pois: vec![Pose2::new(4.0, 5.0, 0.0), Pose2::new(6.0, 5.0, 3.0)],
        }],
    };
    let bounds = Bounds2 {
        min: [0.0, 0.0],
        max: [10.0, 10.0],
    };
    let _ = state.check(&mission, &bounds, "state.toml");
    let _ = state.to_toml();
});
