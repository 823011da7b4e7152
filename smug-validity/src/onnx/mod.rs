//! `onnx`: traversability from a learned model in an ONNX file, run with tract (pure
//! Rust; nothing downloaded at build or run time).
//!
//! The model takes `[1, C, H, W]` float32 (C = the `inputs` channels, row `h` = grid row
//! `j`, i.e. row 0 at the smallest y, as SMUG's layers and the Python arrays) and
//! returns `[1, 1, H', W']` (or `[1, H', W']`) with `H' = H` for 'same' padding or
//! smaller by an equal margin. The elevation is resampled to the model's training
//! `resolution` and the output back to the map's cells; the map is run in tiles of
//! `tile` cells with `overlap` cells of context (beyond the map: `padding`); NaN inputs
//! become `nan_fill` and their cells NaN in the layer; the output is clamped to [0, 1],
//! and a NaN output where the input was known is an error naming the model file.

mod input;
mod model;
mod tiles;

pub use input::{Channel, Normalisation};
pub use model::{Model, ModelError};
pub use tiles::{Padding, Tiling};

use serde::{Deserialize, Serialize};
use smug_core::{BuildContext, Error, GridLayer, TraversabilityEstimator, World};
use std::path::PathBuf;

/// Parameters of the ONNX estimator.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OnnxParams {
    /// The `.onnx` file, relative to the config file.
    pub model: PathBuf,
    /// The input channels, in the model's order.
    pub inputs: Vec<Channel>,
    /// How the channels are scaled.
    pub normalisation: Normalisation,
    /// The model's training cell size, metres (absent: the map's).
    pub resolution: Option<f64>,
    /// What the model sees beyond the map.
    pub padding: Padding,
    /// Side of a tile, cells of the model's grid.
    pub tile: usize,
    /// Context cells around each tile (at least the model's receptive radius).
    pub overlap: usize,
    /// The input value of cells without elevation (after normalisation).
    pub nan_fill: f64,
}

impl Default for OnnxParams {
    fn default() -> Self {
        Self {
            model: PathBuf::new(),
            inputs: vec![Channel::Elevation],
            normalisation: Normalisation::None,
            resolution: None,
            padding: Padding::Edge,
            tile: 256,
            overlap: 16,
            nan_fill: 0.0,
        }
    }
}

/// Traversability from an ONNX model.
pub struct OnnxEstimator {
    model: Model,
    params: OnnxParams,
}

impl OnnxEstimator {
    /// An estimator running the model at `params.model` (already resolved), checked
    /// now: a missing or unreadable file or a model that does not take
    /// `[1, C, H, W]` is an error naming the file.
    pub fn new(params: OnnxParams) -> Result<Self, Error> {
        let tiling = tiling(&params);
        let model = Model::load(&params.model, params.inputs.len(), tiling.window())
            .map_err(|e| Error::stage("traversability", e))?;
        Ok(Self { model, params })
    }
}

/// The tiling of `params`.
fn tiling(params: &OnnxParams) -> Tiling {
    Tiling {
        tile: params.tile,
        overlap: params.overlap,
        padding: params.padding,
    }
}

impl TraversabilityEstimator for OnnxEstimator {
    fn estimate(&self, world: &World) -> Result<GridLayer, Error> {
        let p = &self.params;
        let grid = input::model_grid(&world.elevation, p.resolution);
        let planes = input::input_planes(&grid, &p.inputs, &p.normalisation, p.nan_fill);
        let size = grid.geometry.size;
        let values = tiles::run_tiled(&planes, p.inputs.len(), size, tiling(p), |w| {
            self.model.run(w)
        })
        .map_err(|e| Error::stage("traversability", self.model.tile_error(e)))?;
        let mut out = GridLayer::from_data(grid.geometry, values)
            .map_err(|e| Error::stage("traversability", e))?;
        for (k, v) in out.data.iter_mut().enumerate() {
            if grid.data[k].is_nan() {
                *v = f32::NAN;
            } else if v.is_nan() {
                let [nx, _] = size;
                return Err(Error::stage(
                    "traversability",
                    self.model.nan_output([k % nx, k / nx]),
                ));
            } else {
                *v = v.clamp(0.0, 1.0);
            }
        }
        if out.geometry == world.elevation.geometry {
            return Ok(out);
        }
        let mut layer = input::resample(&out, world.elevation.geometry);
        // Keep NaN exactly where the map has no elevation.
        for (v, z) in layer.data.iter_mut().zip(&world.elevation.data) {
            if z.is_nan() {
                *v = f32::NAN;
            }
        }
        Ok(layer)
    }
}

/// Builds the estimator from its parameters, the model path resolved against the
/// config file's directory.
fn build_onnx(mut params: OnnxParams, ctx: &BuildContext) -> Result<OnnxEstimator, Error> {
    let invalid = |message: String| Err(Error::invalid_param("traversability", message));
    if params.model.as_os_str().is_empty() {
        return invalid("onnx needs a `model` (an .onnx file)".into());
    }
    if params.inputs.is_empty() {
        return invalid("`inputs` must name at least one channel".into());
    }
    if let Some(message) = params.normalisation.invalid(params.inputs.len()) {
        return invalid(message);
    }
    if params
        .resolution
        .is_some_and(|r| !(r.is_finite() && r > 0.0))
    {
        return invalid("`resolution` must be a finite cell size > 0".into());
    }
    if params.tile == 0 || params.tile > 4096 || params.overlap > 1024 {
        return invalid("`tile` must be 1..=4096 cells and `overlap` at most 1024".into());
    }
    if !params.nan_fill.is_finite() {
        return invalid("`nan_fill` must be finite".into());
    }
    params.model = ctx.resolve_path(&params.model);
    OnnxEstimator::new(params)
}

smug_core::register_plugin!(
    smug_core::registry::TraversabilityStage,
    name = "onnx",
    summary =
        "a learned model from an .onnx file (elevation, slope, roughness channels), run with tract",
    params = OnnxParams,
    build = |params, ctx| Ok(Box::new(build_onnx(params, ctx)?)),
);
