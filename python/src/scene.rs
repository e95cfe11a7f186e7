//! Scenes of bodies that move and turn: the crate's `rotorflow::scene` (the code path of
//! `rotorflow scene`), read from a file, from TOML text or from a dict built in code, run
//! without the GIL, and shown as the command's HTML animation inline in a notebook.

use crate::arrays::value_error;
use numpy::{IntoPyArray, PyArrayDyn, ndarray::ArrayD, ndarray::IxDyn};
use pyo3::exceptions::{PyFileNotFoundError, PyRuntimeError};
use pyo3::prelude::*;
use rotorflow::dynamics::motion::SystemTrajectory;
use rotorflow::scene::{Scene, SceneError};
use std::path::PathBuf;

fn scene_error(e: SceneError) -> PyErr {
    match e {
        SceneError::Invalid(m) => value_error(m),
        SceneError::Failed(m) => PyRuntimeError::new_err(m),
    }
}

/// A scene: bodies with their shapes, positions and velocities, gravity, springs, planes and
/// joints (the book's chapter "Scene files" lists the keys).
#[pyclass(name = "Scene", module = "rotorflow", frozen)]
pub struct PyScene {
    scene: Scene,
    title: String,
}

#[pymethods]
impl PyScene {
    /// The scene of a TOML file.
    #[new]
    fn new(path: PathBuf) -> PyResult<Self> {
        if !path.exists() {
            return Err(PyFileNotFoundError::new_err(format!(
                "scene file `{}` not found",
                path.display()
            )));
        }
        let scene = Scene::from_path(&path).map_err(scene_error)?;
        let title = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        Ok(PyScene { scene, title })
    }

    /// The scene of TOML text; `name` names it in messages and titles.
    #[staticmethod]
    #[pyo3(signature = (text, name = "scene.toml"))]
    fn from_toml(text: &str, name: &str) -> PyResult<Self> {
        Ok(PyScene {
            scene: Scene::from_toml_str(text, name).map_err(scene_error)?,
            title: name.to_string(),
        })
    }

    /// The scene of a dict with the keys of a scene file (`{"dim": 3, "t_end": 1.0, "dt":
    /// 0.01, "body": [{"name": "ball", "shape": "ball:3,0.5", ...}]}`), written as TOML and
    /// read as a file would be.
    #[staticmethod]
    #[pyo3(signature = (scene, name = "scene.toml"))]
    fn from_dict(py: Python<'_>, scene: &Bound<'_, PyAny>, name: &str) -> PyResult<Self> {
        let json: String = py
            .import("json")?
            .call_method1("dumps", (scene,))
            .map_err(|e| {
                value_error(format!(
                    "scene: not a dict of numbers, strings and lists ({e})"
                ))
            })?
            .extract()?;
        let table: toml::Table = serde_json::from_str(&json)
            .map_err(|e| value_error(format!("scene: expected a dict of scene keys ({e})")))?;
        let text = toml::to_string(&table)
            .map_err(|e| value_error(format!("scene: cannot be written as TOML ({e})")))?;
        Self::from_toml(&text, name)
    }

    /// The dimension N.
    #[getter]
    fn dim(&self) -> usize {
        self.scene.dim
    }

    /// The end time.
    #[getter]
    fn t_end(&self) -> f64 {
        self.scene.t_end
    }

    /// The sample times of a run without chosen times (those of `rotorflow scene`).
    fn default_times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        let t = self.scene.default_times();
        let n = t.len();
        ArrayD::from_shape_vec(IxDyn(&[n]), t)
            .expect("the data fills the shape")
            .into_pyarray(py)
    }

    /// Runs the scene and records it at `samples` evenly spaced times from 0 to t_end, or at
    /// `times`, or (neither) at the command's default times.
    #[pyo3(signature = (*, samples = None, times = None))]
    fn run(
        &self,
        py: Python<'_>,
        samples: Option<i64>,
        times: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PySceneRun> {
        let times = if samples.is_none() && times.is_none() {
            self.scene.default_times()
        } else {
            crate::bodies::sample_times(times, Some(self.scene.t_end), samples)?
        };
        let scene = &self.scene;
        let run = py.detach(|| scene.record(&times)).map_err(scene_error)?;
        Ok(PySceneRun {
            scene: self.scene.clone(),
            run,
            title: self.title.clone(),
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({:?}, dim={}, t_end={})",
            self.title, self.scene.dim, self.scene.t_end
        )
    }
}

/// A recorded run of a scene: its JSON (that of `rotorflow scene --output`), its HTML
/// animation, shown inline by notebooks.
#[pyclass(name = "SceneRun", module = "rotorflow", frozen)]
pub struct PySceneRun {
    scene: Scene,
    run: SystemTrajectory,
    title: String,
}

#[pymethods]
impl PySceneRun {
    /// The JSON text `rotorflow scene --output` writes.
    fn json(&self) -> PyResult<String> {
        self.scene.to_json(&self.run).map_err(scene_error)
    }

    /// The keys of `rotorflow scene --output`, numbers as numpy arrays.
    fn data<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let parsed = py.import("json")?.call_method1("loads", (self.json()?,))?;
        py.import("rotorflow._scene")?
            .call_method1("arrays", (parsed,))
    }

    /// The self-contained HTML page of the animation (play, time slider, drag to turn).
    #[pyo3(signature = (title = None))]
    fn html(&self, title: Option<&str>) -> String {
        self.scene
            .animation_html(&self.run, title.unwrap_or(&self.title))
    }

    /// The animation inline in a notebook (the page in an iframe of its own).
    fn _repr_html_(&self) -> String {
        let page = self.html(None);
        let escaped = page.replace('&', "&amp;").replace('"', "&quot;");
        format!(
            "<iframe srcdoc=\"{escaped}\" style=\"width: 100%; height: 520px; border: none\"></iframe>"
        )
    }

    /// The sample times.
    #[getter]
    fn times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        let t = self.run.times.clone();
        let n = t.len();
        ArrayD::from_shape_vec(IxDyn(&[n]), t)
            .expect("the data fills the shape")
            .into_pyarray(py)
    }

    fn __repr__(&self) -> String {
        format!(
            "SceneRun({:?}, {} bodies, {} samples)",
            self.title,
            self.run.bodies.len(),
            self.run.times.len()
        )
    }
}

/// Adds the scene classes to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScene>()?;
    m.add_class::<PySceneRun>()?;
    Ok(())
}
