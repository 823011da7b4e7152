//! The ONNX model, loaded and optimised with tract for one window shape, and run on
//! windows; every error names the model file.

use super::tiles::{TileError, WindowOutput};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use tract_onnx::prelude::{
    tvec, Datum, Framework, InferenceFact, InferenceModelExt, Tensor, TypedRunnableModel,
};
use tract_onnx::tract_core::model::IntoRunnable;
use tract_onnx::tract_hir::infer::Factoid;

/// Why a model cannot be used; the message names the file.
#[derive(Debug, thiserror::Error)]
#[error("{}: {reason}", path.display())]
pub struct ModelError {
    /// The model file.
    pub path: PathBuf,
    /// Why.
    pub reason: String,
}

/// A model ready to run on `[1, C, side, side]` windows.
pub struct Model {
    path: PathBuf,
    channels: usize,
    side: usize,
    plan: Arc<TypedRunnableModel>,
}

impl Model {
    /// Loads `path` and prepares it for `[1, channels, side, side]` input.
    pub fn load(path: &Path, channels: usize, side: usize) -> Result<Self, ModelError> {
        let error = |reason: String| ModelError {
            path: path.to_path_buf(),
            reason,
        };
        if !path.is_file() {
            return Err(error("cannot read: no such file".into()));
        }
        let model = tract_onnx::onnx()
            .model_for_path(path)
            .map_err(|e| error(format!("not a readable ONNX model: {e}")))?;
        let inputs = model.input_outlets().map_or(0, |o| o.len());
        if inputs != 1 {
            return Err(error(format!("has {inputs} inputs; SMUG feeds one")));
        }
        let fact = model
            .input_fact(0)
            .map_err(|e| error(format!("no input: {e}")))?;
        if let Some(rank) = fact.shape.rank().concretize() {
            if rank != 4 {
                return Err(error(format!(
                    "wrong input rank: the model takes rank {rank}, SMUG feeds [1, C, H, W] (rank 4)"
                )));
            }
        }
        let shape = [1, channels, side, side];
        let plan = model
            .with_input_fact(0, InferenceFact::dt_shape(f32::datum_type(), shape))
            .and_then(|m| m.into_optimized())
            .and_then(|m| m.into_runnable())
            .map_err(|e| error(format!("cannot run on input {shape:?}: {e:#}")))?;
        Ok(Self {
            path: path.to_path_buf(),
            channels,
            side,
            plan,
        })
    }

    /// An error about this model.
    fn error(&self, reason: String) -> ModelError {
        ModelError {
            path: self.path.clone(),
            reason,
        }
    }

    /// The model's output for one window (`channels` planes of `side²`, row-major).
    pub fn run(&self, window: &[f32]) -> Result<WindowOutput, ModelError> {
        let shape = [1, self.channels, self.side, self.side];
        let input = Tensor::from_shape(&shape, window)
            .map_err(|e| self.error(format!("input {shape:?}: {e}")))?;
        let outputs = self
            .plan
            .run(tvec!(input.into()))
            .map_err(|e| self.error(format!("failed to run: {e:#}")))?;
        let output = &outputs[0];
        let dims = output.shape();
        let side = match dims {
            [1, 1, h, w] | [1, h, w] if h == w => *h,
            _ => {
                return Err(self.error(format!(
                    "output shape {dims:?}: expected [1, 1, H, W] or [1, H, W] with H = W"
                )))
            }
        };
        let values = output
            .to_plain_array_view::<f32>()
            .map_err(|e| self.error(format!("output is not float32: {e}")))?
            .iter()
            .copied()
            .collect();
        Ok(WindowOutput { side, values })
    }

    /// A tiling error about this model.
    pub fn tile_error(&self, e: TileError<ModelError>) -> ModelError {
        match e {
            TileError::Model(e) => e,
            other => self.error(other.to_string()),
        }
    }

    /// The error for a NaN output at model-grid cell `cell` where the input was known.
    pub fn nan_output(&self, cell: [usize; 2]) -> ModelError {
        self.error(format!(
            "NaN output at cell ({}, {}) where the elevation is known",
            cell[0], cell[1]
        ))
    }
}
