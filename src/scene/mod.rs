//! Scene files (feature `scene`): bodies that move and turn together, read from TOML
//! (bodies by their SPEC, gravity, springs, planes, ball joints), built into a
//! [`System`], run with every sample time hit exactly, and
//! written as the JSON and CSV of `rotorflow scene` (and, with the feature `viz`, its HTML
//! animation and SVG plot). The command and any other program share this one code path.
//!
//! - [`format`](mod@format): the file, every key checked, one-line errors naming the file, the section
//!   and the key;
//! - [`run`]: the system and its run;
//! - [`output`]: JSON, CSV, the drawing and the summary.
//!
//! The book's chapter "Scene files" lists the keys.
//!
//! ```
//! use rotorflow::scene::Scene;
//! let scene = Scene::from_toml_str(
//!     r#"
//!     dim = 3
//!     gravity = [0, 0, -9.81]
//!     t_end = 1.0
//!     dt = 0.01
//!     [[body]]
//!     name = "ball"
//!     shape = "ball:3,0.5"
//!     position = [0, 0, 2]
//!     "#,
//!     "drop.toml",
//! )?;
//! let run = scene.record(&scene.default_times())?;
//! assert_eq!(run.times.len(), 101);
//! // Free fall: z = 2 − g t²/2 at t = 1.
//! let z = run.bodies[0].position.last().unwrap()[2];
//! assert!((z - (2.0 - 0.5 * 9.81)).abs() < 1e-12);
//! let json = scene.to_json(&run)?;
//! assert!(json.contains("\"contacts\""));
//! // Bad input is one line naming the file and the key.
//! let err = Scene::from_toml_str("dim = 3\nt_end = 1\ndt = -1\n", "bad.toml").unwrap_err();
//! assert_eq!(err.to_string(), "bad.toml: dt must be > 0, got -1");
//! # Ok::<(), rotorflow::scene::SceneError>(())
//! ```

pub mod format;
pub mod output;
pub mod run;

#[doc(inline)]
pub use format::{
    FileReader, IntegratorKind, MAX_STEP_PER_PERIOD, MAX_STEPS, Scene, SceneAnchor, SceneBody,
    SceneJoint, ScenePlane, SceneSpring,
};

use crate::dynamics::motion::{System, SystemTrajectory};
use crate::dynamics::trajectory::even_times;
use std::path::Path;

/// Why a scene could not be read or run. Every message is one line.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SceneError {
    /// The file is malformed or describes something that cannot be run: the message names
    /// the file, the section (`body "cube"`, `plane 2`, …) and the key.
    #[error("{0}")]
    Invalid(String),
    /// The scene was good but its run failed (the integrator gave up, a result is not
    /// finite).
    #[error("{0}")]
    Failed(String),
}

impl SceneError {
    /// Returns a [`SceneError::Invalid`] with `message`.
    pub fn invalid(message: impl Into<String>) -> Self {
        SceneError::Invalid(message.into())
    }

    /// Returns a [`SceneError::Failed`] with `message`.
    pub fn failed(message: impl Into<String>) -> Self {
        SceneError::Failed(message.into())
    }
}

/// The samples of a scene without chosen times: at most this many.
pub const DEFAULT_SAMPLES: usize = 201;

impl Scene {
    /// Reads the scene `text`; `file` names it in messages. `points:` and `mesh:` shapes are
    /// read from the file system.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the file, the section and the key.
    pub fn from_toml_str(text: &str, file: &str) -> Result<Scene, SceneError> {
        format::parse(text, file, None)
    }

    /// Reads the scene file `path`.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] if the file cannot be read or is not a good scene.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        format::load(path.as_ref())
    }

    /// Returns the sample times of a run without chosen times: one per step for runs of
    /// fewer than 200 steps, else [`DEFAULT_SAMPLES`] evenly spaced from 0 to t_end.
    pub fn default_times(&self) -> Vec<f64> {
        let steps = (self.t_end / self.dt - 1e-9).ceil().max(1.0);
        let k = if steps < (DEFAULT_SAMPLES - 1) as f64 {
            steps as usize + 1
        } else {
            DEFAULT_SAMPLES
        };
        even_times(self.t_end, k)
    }

    /// Returns the system of the scene at t = 0.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the body or the part the dynamics refuses (bodies that
    /// start inside a plane or overlapping among them).
    pub fn system(&self) -> Result<System, SceneError> {
        run::build_system(self)
    }

    /// Runs the scene from 0 to t_end and records it at `times` (strictly increasing, in
    /// [0, t_end]), the bodies under their names.
    ///
    /// # Errors
    /// As [`Scene::system`]; [`SceneError::Invalid`] for bad times, [`SceneError::Failed`]
    /// when the integrator fails.
    pub fn record(&self, times: &[f64]) -> Result<SystemTrajectory, SceneError> {
        run::run(self, &mut self.system()?, times, &mut |_| {})
    }

    /// Returns the JSON of a run of this scene, as `rotorflow scene --output` writes it
    /// ([`output::to_json`]).
    ///
    /// # Errors
    /// [`SceneError::Failed`] if a number is not finite.
    pub fn to_json(&self, run: &SystemTrajectory) -> Result<String, SceneError> {
        output::to_json(self, run)
    }

    /// Returns the HTML animation of a run of this scene under `title`, the axis of the
    /// gravity drawn upwards.
    #[cfg(feature = "viz")]
    pub fn animation_html(&self, run: &SystemTrajectory, title: &str) -> String {
        crate::viz::trajectory::animation_html(run, &output::drawing(self, title))
    }

    /// Returns the SVG plot of a run of this scene under `title`
    /// ([`crate::viz::trajectory::plot_svg`]).
    ///
    /// # Errors
    /// [`SceneError::Failed`] if the plot cannot be drawn.
    #[cfg(feature = "viz")]
    pub fn plot_svg(&self, run: &SystemTrajectory, title: &str) -> Result<String, SceneError> {
        crate::viz::trajectory::plot_svg(run, title)
            .map_err(|e| SceneError::failed(format!("cannot draw the plot: {e}")))
    }
}
