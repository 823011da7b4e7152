//! Python bindings of SMUG: the native module `smug._smug` behind the `smug` package.
//!
//! A thin layer over the library: configs are loaded, pipelines assembled and missions
//! planned by `smug-core` exactly as `smug plan` does, so a plan from Python equals the
//! CLI's for the same config and seed. What lives here is conversion (numpy arrays to
//! grid layers, Python data to missions, errors to exceptions) and the adapter that
//! lets a Python callable act as the pipeline's traversability estimator.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

mod mcap;
mod replan;
mod sweep;
mod team;
use smug_app::p2p::{P2pRequest, P2pWorld};
use smug_core::{
    Error, GridGeometry, GridLayer, LoadedConfig, Mission, Pipeline, Pose2,
    TraversabilityEstimator, World,
};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

// The built-in plugins are linked in through the application layer.
use smug_app::{one_line, AppError};

create_exception!(
    smug,
    SmugError,
    PyException,
    "Base class of every error SMUG raises."
);
create_exception!(
    smug,
    ConfigError,
    SmugError,
    "A bad config: file, key, plugin name or parameter (the CLI's exit 2)."
);
create_exception!(
    smug,
    InputError,
    SmugError,
    "Unusable input data: a map, mission, array or traversability layer (the CLI's exit 2)."
);
create_exception!(
    smug,
    NoSolution,
    SmugError,
    "The pipeline ran but no safe plan exists (the CLI's exit 1)."
);

/// The Python exception for a library error: `NoSolution` for unreachable targets and
/// a passed deadline, `ConfigError` for config and plugin errors, `InputError` for the rest.
fn to_py(err: Error) -> PyErr {
    if let Some(why) = smug_app::NoSolution::of(&err) {
        return no_solution(&why);
    }
    match &err {
        Error::Config(_)
        | Error::Registry(_)
        | Error::InvalidParam { .. }
        | Error::MissingStage { .. } => ConfigError::new_err(one_line(&err)),
        Error::Mission(_)
        | Error::InvalidInput(_)
        | Error::Io { .. }
        | Error::Stage { .. }
        | Error::DeadlinePassed { .. } => InputError::new_err(one_line(&err)),
    }
}

/// The Python `NoSolution` for an outcome without a solution.
fn no_solution(why: &smug_app::NoSolution) -> PyErr {
    NoSolution::new_err(format!("no solution: {why}"))
}

/// The Python exception for an application error: library errors as [`to_py`], a
/// map file's as the world stage's input error, config lookups as `ConfigError`, and
/// roadmap files, mission states, outputs as `InputError`.
fn app_to_py(err: AppError) -> PyErr {
    match err {
        AppError::Smug(err) => to_py(err),
        AppError::Config(err) => to_py(err.into()),
        AppError::Registry(err) => to_py(err.into()),
        AppError::Map(err) => to_py(Error::stage("world", err)),
        AppError::State(err) => InputError::new_err(err.to_string()),
        err @ (AppError::NoPlanner | AppError::NoWorld | AppError::NotATeam) => {
            ConfigError::new_err(err.to_string())
        }
        AppError::Robot { robot, source } => {
            let class = to_py(*source);
            Python::attach(|py| {
                let message = format!("robot `{robot}`: {}", class.value(py));
                PyErr::from_type(class.get_type(py), message)
            })
        }
        err => InputError::new_err(one_line(&err)),
    }
}

/// The solution of an outcome, or the Python `NoSolution`.
fn solved<T>(outcome: smug_app::Outcome<T>) -> PyResult<T> {
    match outcome {
        smug_app::Outcome::Solved(value) => Ok(value),
        smug_app::Outcome::NoSolution { why } => Err(no_solution(&why)),
    }
}

fn input_error(message: impl Into<String>) -> PyErr {
    InputError::new_err(message.into())
}

/// A 2-D float32/float64 numpy array as `([nx, ny], row-major f32 data)`; errors name
/// `what`, the shape and the dtype.
fn float_grid(what: &str, obj: &Bound<'_, PyAny>) -> PyResult<([usize; 2], Vec<f32>)> {
    let array = obj.cast::<PyUntypedArray>().map_err(|_| {
        let kind = obj
            .get_type()
            .name()
            .map_or_else(|_| "?".to_string(), |n| n.to_string());
        input_error(format!("{what}: expected a numpy array, got {kind}"))
    })?;
    let shape = array.shape().to_vec();
    if shape.len() != 2 {
        return Err(input_error(format!(
            "{what}: expected a 2-D array (rows along y, columns along x), got shape {}",
            shape_text(&shape)
        )));
    }
    let size = [shape[1], shape[0]];
    let data: Vec<f32> = if let Ok(a) = obj.cast::<PyArray2<f32>>() {
        a.readonly().as_array().iter().copied().collect()
    } else if let Ok(a) = obj.cast::<PyArray2<f64>>() {
        a.readonly().as_array().iter().map(|&v| v as f32).collect()
    } else {
        return Err(input_error(format!(
            "{what}: dtype {} is not supported; use float32 or float64",
            array.dtype().str()?
        )));
    };
    Ok((size, data))
}

fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// Checks that every value of a traversability layer is NaN or in `[0, 1]`: else an
/// input error naming `what` and the first value outside.
fn check_unit_range(what: &str, size: [usize; 2], data: &[f32]) -> smug_core::Result<()> {
    match data
        .iter()
        .position(|v| !v.is_nan() && !(0.0..=1.0).contains(v))
    {
        None => Ok(()),
        Some(k) => Err(Error::InvalidInput(format!(
            "{what}: value {} at [{}, {}] (row, column) is outside [0, 1] (NaN = unknown)",
            data[k],
            k / size[0],
            k % size[0]
        ))),
    }
}

/// A layer's values as a `(ny, nx)` float32 array (row `j` = y index).
fn layer_array<'py>(py: Python<'py>, layer: &GridLayer) -> Bound<'py, PyArray2<f32>> {
    let [nx, ny] = layer.geometry.size;
    Array2::from_shape_vec((ny, nx), layer.data.clone())
        .expect("a layer's data matches its geometry")
        .into_pyarray(py)
}

/// A Python callable `(elevation, resolution) -> traversability` as the pipeline's
/// traversability estimator. A Python exception it raises is kept and re-raised.
struct PyEstimator {
    function: Py<PyAny>,
    raised: Arc<Mutex<Option<PyErr>>>,
}

impl TraversabilityEstimator for PyEstimator {
    fn estimate(&self, world: &World) -> smug_core::Result<GridLayer> {
        let geometry = world.elevation.geometry;
        let [nx, ny] = geometry.size;
        Python::attach(|py| {
            let elevation = Array2::from_shape_fn((ny, nx), |(j, i)| {
                f64::from(world.elevation.data[geometry.index(i, j)])
            })
            .into_pyarray(py);
            let returned = match self.function.call1(py, (elevation, geometry.resolution)) {
                Ok(returned) => returned,
                Err(err) => {
                    let message = format!("the traversability function raised {err}");
                    *self.raised.lock().unwrap_or_else(|e| e.into_inner()) = Some(err);
                    return Err(Error::InvalidInput(message));
                }
            };
            let what = "the traversability function's result";
            let (size, data) = float_grid(what, returned.bind(py))
                .map_err(|err| Error::InvalidInput(err.value(py).to_string()))?;
            if size != geometry.size {
                return Err(Error::InvalidInput(format!(
                    "{what}: shape {} differs from the elevation's {}",
                    shape_text(&[size[1], size[0]]),
                    shape_text(&[ny, nx])
                )));
            }
            check_unit_range(what, size, &data)?;
            Ok(GridLayer { geometry, data })
        })
    }
}

/// A world: elevation (and traversability) layers and a mission.
#[pyclass(name = "World", module = "smug", frozen)]
struct PyWorld {
    world: Arc<World>,
    mission: Arc<Mission>,
    /// `(target, PoI index)` of the PoIs the robot's validity checker rejected.
    invalid_pois: Arc<Vec<(String, usize)>>,
}

impl PyWorld {
    /// The world of `pipeline` with its mission as given (PoIs invalid for the robot
    /// included).
    fn of(pipeline: &Pipeline) -> PyResult<Self> {
        let no_world = || ConfigError::new_err("the config has no [world] section");
        Ok(Self {
            world: pipeline.world.clone().ok_or_else(no_world)?,
            mission: Arc::new(pipeline.given_mission.clone().ok_or_else(no_world)?),
            invalid_pois: Arc::new(
                pipeline
                    .dropped_pois
                    .iter()
                    .map(|d| (d.target.clone(), d.index))
                    .collect(),
            ),
        })
    }
}

#[pymethods]
impl PyWorld {
    /// A world from numpy arrays (see the package's `World.from_arrays`).
    #[staticmethod]
    #[pyo3(signature = (elevation, resolution, origin, mission_json, traversability=None, occupancy=None, obstacle_height=2.0, name="arrays".to_string()))]
    #[allow(clippy::too_many_arguments)]
    fn _from_arrays(
        elevation: &Bound<'_, PyAny>,
        resolution: f64,
        origin: (f64, f64),
        mission_json: &str,
        traversability: Option<&Bound<'_, PyAny>>,
        occupancy: Option<&Bound<'_, PyAny>>,
        obstacle_height: f64,
        name: String,
    ) -> PyResult<Self> {
        let (size, mut data) = float_grid("elevation", elevation)?;
        let geometry = GridGeometry::new([origin.0, origin.1], resolution, size)
            .map_err(|m| input_error(format!("elevation: {m}")))?;
        if geometry.is_empty() {
            return Err(input_error("elevation: the array has no cells"));
        }
        if !(obstacle_height.is_finite() && obstacle_height >= 0.0) {
            return Err(input_error(format!(
                "obstacle_height must be finite and ≥ 0, got {obstacle_height}"
            )));
        }
        let same_shape = |what: &str, got: [usize; 2]| {
            if got == size {
                Ok(())
            } else {
                Err(input_error(format!(
                    "{what}: shape {} differs from the elevation's {}",
                    shape_text(&[got[1], got[0]]),
                    shape_text(&[size[1], size[0]])
                )))
            }
        };
        if let Some(occupancy) = occupancy {
            let (got, occupied) = bool_grid("occupancy", occupancy)?;
            same_shape("occupancy", got)?;
            for (z, occupied) in data.iter_mut().zip(occupied) {
                if occupied {
                    *z += obstacle_height as f32;
                }
            }
        }
        let traversability = traversability
            .map(|t| {
                let (got, values) = float_grid("traversability", t)?;
                same_shape("traversability", got)?;
                check_unit_range("traversability", got, &values).map_err(to_py)?;
                Ok::<_, PyErr>(GridLayer {
                    geometry,
                    data: values,
                })
            })
            .transpose()?;
        let mission = parse_mission(mission_json)?;
        mission
            .validate()
            .map_err(|e| input_error(format!("mission: {e}")))?;
        if let Some(what) = mission.first_pose_outside(&geometry.bounds()) {
            let b = geometry.bounds();
            return Err(input_error(format!(
                "mission: {what} lies outside the map (bounds [{}, {}] to [{}, {}])",
                b.min[0], b.min[1], b.max[0], b.max[1]
            )));
        }
        let mut world = World::new(name, GridLayer { geometry, data });
        world.traversability = traversability;
        Ok(Self {
            world: Arc::new(world),
            mission: Arc::new(mission),
            invalid_pois: Arc::default(),
        })
    }

    /// Name in reports.
    #[getter]
    fn name(&self) -> String {
        self.world.name.clone()
    }

    /// Terrain height, float32 `(ny, nx)`; row `j` is `y = origin_y + (j + ½)·resolution`.
    #[getter]
    fn elevation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f32>> {
        layer_array(py, &self.world.elevation)
    }

    /// Traversability in `[0, 1]` (NaN = unknown), float32 `(ny, nx)`, or `None`.
    #[getter]
    fn traversability<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f32>>> {
        self.world
            .traversability
            .as_ref()
            .map(|layer| layer_array(py, layer))
    }

    /// Cell edge length, metres.
    #[getter]
    fn resolution(&self) -> f64 {
        self.world.elevation.geometry.resolution
    }

    /// Lower-left corner `(x, y)` of cell `(0, 0)`.
    #[getter]
    fn origin(&self) -> (f64, f64) {
        let [x, y] = self.world.elevation.geometry.origin;
        (x, y)
    }

    /// `(xmin, ymin, xmax, ymax)`.
    #[getter]
    fn bounds(&self) -> (f64, f64, f64, f64) {
        let b = self.world.bounds();
        (b.min[0], b.min[1], b.max[0], b.max[1])
    }

    /// The mission as JSON (the package's `World.mission` parses it).
    fn _mission_json(&self) -> String {
        serde_json::to_string(self.mission.as_ref()).unwrap_or_default()
    }

    fn __repr__(&self) -> String {
        let g = self.world.elevation.geometry;
        format!(
            "World({:?}, {}×{} cells at {} m, {} targets)",
            self.world.name,
            g.size[0],
            g.size[1],
            g.resolution,
            self.mission.targets.len()
        )
    }
}

/// A 2-D boolean numpy array as `([nx, ny], row-major data)`.
fn bool_grid(what: &str, obj: &Bound<'_, PyAny>) -> PyResult<([usize; 2], Vec<bool>)> {
    let array = obj
        .cast::<PyUntypedArray>()
        .map_err(|_| input_error(format!("{what}: expected a numpy array of bool")))?;
    let shape = array.shape().to_vec();
    if shape.len() != 2 {
        return Err(input_error(format!(
            "{what}: expected a 2-D array, got shape {}",
            shape_text(&shape)
        )));
    }
    let a = obj.cast::<PyArray2<bool>>().map_err(|_| {
        let dtype = array
            .dtype()
            .str()
            .map(|s| s.to_string())
            .unwrap_or_default();
        input_error(format!(
            "{what}: dtype {dtype} is not supported; use bool (True = occupied)"
        ))
    })?;
    let data = a.readonly().as_array().iter().copied().collect();
    Ok(([shape[1], shape[0]], data))
}

/// A mission from JSON whose poses are `{x, y, yaw}` objects or `[x, y, yaw]` lists
/// and whose target positions are `{x, y, z}` or `[x, y(, z)]`.
fn parse_mission(text: &str) -> PyResult<Mission> {
    use serde_json::{json, Value};
    let mut value: Value =
        serde_json::from_str(text).map_err(|e| input_error(format!("mission: {e}")))?;
    fn pose(value: &mut Value, what: &str) -> PyResult<()> {
        if let Value::Array(items) = value {
            if items.len() != 3 {
                return Err(input_error(format!(
                    "{what}: expected (x, y, yaw), got {} numbers",
                    items.len()
                )));
            }
            *value = json!({"x": items[0], "y": items[1], "yaw": items[2]});
        }
        Ok(())
    }
    if !value.is_object() {
        return Err(input_error(
            "mission: expected a dict with `start` and `targets`",
        ));
    }
    for key in ["start", "end"] {
        if let Some(v) = value.get_mut(key).filter(|v| !v.is_null()) {
            pose(v, &format!("mission.{key}"))?;
        } else if key == "end" {
            value.as_object_mut().map(|m| m.remove("end"));
        }
    }
    if let Some(Value::Array(targets)) = value.get_mut("targets") {
        for (t, target) in targets.iter_mut().enumerate() {
            if let Some(Value::Array(p)) = target.get_mut("position") {
                let z = p.get(2).cloned().unwrap_or(json!(0.0));
                if !(2..=3).contains(&p.len()) {
                    return Err(input_error(format!(
                        "mission.targets[{t}].position: expected (x, y) or (x, y, z), got {} numbers",
                        p.len()
                    )));
                }
                let v = json!({"x": p[0], "y": p[1], "z": z});
                target["position"] = v;
            }
            if let Some(Value::Array(pois)) = target.get_mut("pois") {
                for (k, p) in pois.iter_mut().enumerate() {
                    pose(p, &format!("mission.targets[{t}].pois[{k}]"))?;
                }
            }
        }
    }
    serde_json::from_value(value).map_err(|e| input_error(format!("mission: {e}")))
}

/// `err` caused by the Python exception the estimator kept, if it kept one.
fn raise(raised: &Mutex<Option<PyErr>>, err: PyErr) -> PyErr {
    let kept = raised.lock().unwrap_or_else(|e| e.into_inner()).take();
    if let Some(original) = kept {
        Python::attach(|py| err.set_cause(py, Some(original)));
    }
    err
}

/// Loads a config with overrides and a seed, as `smug plan --set … --seed N` does.
fn load(config: &Path, set: Vec<String>, seed: Option<u64>) -> PyResult<LoadedConfig> {
    smug_app::load_config(config, &set, seed).map_err(app_to_py)
}

/// Builds a config's world (with its traversability layer) without planning.
#[pyfunction]
#[pyo3(signature = (config, set=Vec::new(), seed=None))]
fn load_world(
    py: Python<'_>,
    config: PathBuf,
    set: Vec<String>,
    seed: Option<u64>,
) -> PyResult<PyWorld> {
    let mut loaded = load(&config, set, seed)?;
    // Only the world and its traversability are needed.
    loaded.config.keep_sections(&smug_app::WORLD_STAGES);
    let pipeline = py.detach(|| Pipeline::assemble(&loaded)).map_err(to_py)?;
    PyWorld::of(&pipeline)
}

/// Every registered plugin by stage, as JSON (what `smug plugins --json` prints).
#[pyfunction]
fn plugins_json() -> PyResult<String> {
    let stages = smug_core::registry::catalogue().map_err(|e| to_py(e.into()))?;
    serde_json::to_string(&stages).map_err(|e| InputError::new_err(e.to_string()))
}

/// Point-to-point queries `(n, 6)` `sx, sy, syaw, gx, gy, gyaw`, in order, on one
/// shared roadmap; returns the JSON `smug p2p --out` writes.
#[pyfunction]
#[pyo3(signature = (queries, config=None, set=Vec::new(), world=None, map=None, obstacle_height=2.0))]
fn p2p(
    py: Python<'_>,
    queries: &Bound<'_, PyAny>,
    config: Option<PathBuf>,
    set: Vec<String>,
    world: Option<PyRef<'_, PyWorld>>,
    map: Option<PathBuf>,
    obstacle_height: f64,
) -> PyResult<String> {
    let array = queries
        .cast::<PyArray2<f64>>()
        .map_err(|_| input_error("queries: expected a float64 array of shape (n, 6)"))?;
    let shape = array.shape().to_vec();
    if shape[1] != 6 {
        return Err(input_error(format!(
            "queries: expected shape (n, 6) (sx, sy, syaw, gx, gy, gyaw), got {}",
            shape_text(&shape)
        )));
    }
    let values: Vec<f64> = array.readonly().as_array().iter().copied().collect();
    let queries: Vec<(Pose2, Pose2)> = values
        .chunks(6)
        .map(|v| (Pose2::new(v[0], v[1], v[2]), Pose2::new(v[3], v[4], v[5])))
        .collect();
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        return Err(input_error(format!(
            "queries: row {} holds a non-finite number",
            k / 6
        )));
    }
    let world = match (world, map) {
        (Some(_), Some(_)) => return Err(input_error("give either `world` or `map`, not both")),
        (Some(w), None) => P2pWorld::Given(Box::new((*w.world).clone())),
        (None, Some(path)) => P2pWorld::Map {
            path,
            obstacle_height,
        },
        (None, None) => P2pWorld::Config,
    };
    let request = P2pRequest {
        config,
        set,
        world,
        prefer_exact: false,
    };
    let results = py
        .detach(move || smug_app::p2p::p2p(&request, &queries))
        .map_err(app_to_py)?;
    let mut value = serde_json::to_value(&results)
        .map_err(|e| InputError::new_err(format!("cannot write the results as JSON: {e}")))?;
    // The Python rows have always held `no_path` and `why`, `None` when solved.
    if let Some(rows) = value["queries"].as_array_mut() {
        for row in rows.iter_mut().filter_map(|r| r.as_object_mut()) {
            for key in ["no_path", "why"] {
                row.entry(key).or_insert(serde_json::Value::Null);
            }
        }
    }
    Ok(value.to_string())
}

/// The native module `smug._smug`.
#[pymodule]
fn _smug(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SmugError", py.get_type::<SmugError>())?;
    m.add("ConfigError", py.get_type::<ConfigError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("NoSolution", py.get_type::<NoSolution>())?;
    m.add_class::<PyWorld>()?;
    m.add_class::<replan::PySession>()?;
    m.add_function(wrap_pyfunction!(replan::plan, m)?)?;
    m.add_function(wrap_pyfunction!(replan::replan, m)?)?;
    m.add_function(wrap_pyfunction!(load_world, m)?)?;
    m.add_function(wrap_pyfunction!(plugins_json, m)?)?;
    m.add_function(wrap_pyfunction!(p2p, m)?)?;
    m.add_function(wrap_pyfunction!(mcap::write_plan_mcap, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_runs, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_seeds, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_task, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_failed_row, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
