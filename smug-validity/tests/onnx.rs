//! The `onnx` traversability plugin on SMUG's own test CNN
//! (configs/models/traversability-cnn.onnx) and on broken models (tests/models, both
//! written by tools/make-traversability-onnx.py).
#![cfg(feature = "onnx")]

use smug_core::{GridGeometry, GridLayer, TraversabilityEstimator, World};
use smug_validity::onnx::{OnnxEstimator, OnnxParams};
use std::path::PathBuf;

/// A model file of the repository.
fn model(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// The test CNN with `tile` and `overlap`.
fn cnn(tile: usize, overlap: usize) -> OnnxParams {
    OnnxParams {
        model: model("../configs/models/traversability-cnn.onnx"),
        tile,
        overlap,
        ..OnnxParams::default()
    }
}

/// 6 × 4 m at 0.1 m: flat on the left, a steep bump on the right, one cell unknown.
fn terrain() -> World {
    let g = GridGeometry::new([0.0, 0.0], 0.1, [60, 40]).unwrap();
    let mut z = GridLayer::from_fn(g, |i, j| {
        let (x, y) = (i as f32 * 0.1 - 4.5, j as f32 * 0.1 - 2.0);
        1.5 * (-(x * x + y * y) / 0.3).exp()
    });
    z.set(3, 3, f32::NAN);
    World::new("bump", z)
}

#[test]
fn the_cnn_scores_flat_ground_high_and_the_bump_low() {
    let layer = OnnxEstimator::new(cnn(256, 4))
        .unwrap()
        .estimate(&terrain())
        .unwrap();
    assert_eq!(layer.geometry, terrain().elevation.geometry);
    assert!(layer.get(3, 3).is_nan(), "unknown elevation stays unknown");
    assert!((layer.get(10, 30) - 1.0 / (1.0 + (-6.0f32).exp())).abs() < 1e-5);
    assert!(
        layer.get(40, 20) < 0.01,
        "the bump's flank: {}",
        layer.get(40, 20)
    );
    assert!(layer
        .data
        .iter()
        .all(|v| v.is_nan() || (0.0..=1.0).contains(v)));
}

#[test]
fn tiles_with_enough_overlap_equal_one_run_over_the_map() {
    let world = terrain();
    let whole = OnnxEstimator::new(cnn(256, 3))
        .unwrap()
        .estimate(&world)
        .unwrap();
    let tiled = OnnxEstimator::new(cnn(16, 3))
        .unwrap()
        .estimate(&world)
        .unwrap();
    for (a, b) in whole.data.iter().zip(&tiled.data) {
        assert!(
            a.is_nan() && b.is_nan() || (a - b).abs() < 1e-6,
            "{a} vs {b}"
        );
    }
}

#[test]
fn another_training_resolution_resamples_to_the_map() {
    let world = terrain();
    let params = OnnxParams {
        resolution: Some(0.2),
        ..cnn(64, 4)
    };
    let layer = OnnxEstimator::new(params)
        .unwrap()
        .estimate(&world)
        .unwrap();
    assert_eq!(layer.geometry, world.elevation.geometry);
    assert!(layer.get(3, 3).is_nan());
    assert!(layer.get(10, 30) > 0.99 && layer.get(45, 20) < 0.5);
}

/// The error text of a model that must be refused, at build or estimate time.
fn refusal(path: PathBuf) -> String {
    let params = OnnxParams {
        model: path,
        ..OnnxParams::default()
    };
    match OnnxEstimator::new(params) {
        Err(e) => e.to_string(),
        Ok(estimator) => estimator.estimate(&terrain()).err().unwrap().to_string(),
    }
}

#[test]
fn bad_models_are_errors_naming_the_file_and_the_reason() {
    let err = refusal(model("tests/models/missing.onnx"));
    assert!(
        err.contains("missing.onnx") && err.contains("no such file"),
        "{err}"
    );
    let err = refusal(model("tests/models/rank3.onnx"));
    assert!(
        err.contains("rank3.onnx") && err.contains("wrong input rank"),
        "{err}"
    );
    let err = refusal(model("tests/models/nan.onnx"));
    assert!(
        err.contains("nan.onnx") && err.contains("NaN output"),
        "{err}"
    );
    let err = refusal(model("Cargo.toml"));
    assert!(
        err.contains("Cargo.toml") && err.contains("not a readable ONNX model"),
        "{err}"
    );
}
