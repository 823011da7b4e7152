//! The `from-file` traversability readers (.npy, .json, .csv) on a 3 × 2 world; the
//! first byte picks the format and the row order.
#![no_main]

mod common;

use libfuzzer_sys::fuzz_target;
use smug_core::stages::TraversabilityEstimator;
use smug_core::{GridGeometry, GridLayer, Mission, Pose2, World};
use smug_validity::from_file::{FromFileEstimator, RowOrder};

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else {
        return;
    };
    let name = ["t.npy", "t.json", "t.csv"][usize::from(pick % 3)];
    let order = if pick & 4 == 0 {
        RowOrder::TopDown
    } else {
        RowOrder::BottomUp
    };
    let path = common::scratch_file(name, bytes);
    let geometry = GridGeometry::new([0.0, 0.0], 1.0, [3, 2]).expect("geometry");
    let world = World::new(
        "fuzz",
        GridLayer::filled(geometry, 0.0),
        Mission {
            start: Pose2::new(0.5, 0.5, 0.0),
            end: None,
            targets: vec![],
        },
    );
    if let Ok(layer) = FromFileEstimator::new(path, order).estimate(&world) {
        let cells = (0..3).flat_map(|i| (0..2).map(move |j| (i, j)));
        let values: Vec<f32> = cells.map(|(i, j)| layer.get(i, j)).collect();
        assert!(values.iter().all(|v| v.is_nan() || (0.0..=1.0).contains(v)));
    }
});
