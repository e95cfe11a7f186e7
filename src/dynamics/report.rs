//! The report of a sampled rotation, in the body's own axes: what `rotorflow simulate --json`
//! and `rotorflow exact --json` print, built from the states of a run.
//!
//! The integrators and the closed forms work in the principal frame of the inertia. A report
//! turns each state back to the body's own axes (ω, L and the attitude) and adds the
//! invariants and their largest drifts from t = 0, so that a numerical run and a closed form
//! give reports with the same keys. [`sample_states`] runs an integrator over a list of
//! sample times in blocks, as the command does.
//!
//! ```
//! use rotorflow::dynamics::report::{Report, Stepper, sample_states};
//! use rotorflow::dynamics::{Attitude, RigidBody, Rkmk4, torques::Free};
//! use rotorflow::inertia::InertiaMap;
//! use rotorflow::algebra::Bivector;
//!
//! let inertia = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0])?;
//! let w = Bivector::from_components(3, &[0.1, 1.0, 0.2])?;
//! let start = RigidBody::from_body_velocity(inertia, Attitude::identity(3), &w)?;
//! let times = [0.0, 0.5, 1.0];
//! let mut stepper = Stepper::Fixed { integrator: Box::new(Rkmk4), dt: 0.01 };
//! let mut states = Vec::new();
//! sample_states(&start, &Free, &mut stepper, &times, &mut |block| {
//!     states.extend(block);
//!     Ok::<(), ()>(())
//! })
//! .unwrap();
//! let report = Report::from_states(&start, &times, states.into_iter().map(Ok::<_, ()>)).unwrap();
//! assert_eq!(report.energy.len(), 3);
//! assert!(report.drift.energy < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::{
    Attitude, Dop853, Dopri5, Drift, DynamicsError, Integrator, Invariants, RigidBody, Torque,
    simulate,
};
use crate::algebra::Bivector;
use crate::inertia::InertiaError;
use nalgebra::DMatrix;
use std::fmt;

/// One state: attitude (principal frame → space) and body-frame momentum (principal frame).
pub type State = (Attitude, Bivector);

/// A sampled rotation as reported: everything in the body's own axes.
#[derive(Clone, Debug)]
pub struct Report {
    /// The dimension N.
    pub dim: usize,
    /// Sample times.
    pub times: Vec<f64>,
    /// Body-frame angular velocity in the body's own axes.
    pub omega: Vec<Bivector>,
    /// Body-frame angular momentum in the body's own axes.
    pub momentum: Vec<Bivector>,
    /// Kinetic energy.
    pub energy: Vec<f64>,
    /// Casimirs c₁ … c_⌊N/2⌋ (coefficients of det(λ − \[L\])).
    pub casimirs: Vec<Vec<f64>>,
    /// Rotation matrix of the body's own axes → space.
    pub attitude: Vec<DMatrix<f64>>,
    /// Relative drift of the energy from t = 0, per sample.
    pub energy_drift: Vec<f64>,
    /// Relative drift of the Casimirs from t = 0 (largest), per sample.
    pub casimir_drift: Vec<f64>,
    /// Largest drifts over all samples.
    pub drift: Drift,
    /// Largest relative drift of each Manakov integral over all samples (empty for a general
    /// inertia map or N above [`MANAKOV_MAX_DIM`](super::MANAKOV_MAX_DIM)).
    pub manakov_drift: Vec<f64>,
}

/// Why a report could not be built from the states of a run.
#[derive(Clone, Debug, PartialEq)]
pub enum ReportError<E> {
    /// A state could not be produced (the error of the caller's states).
    State(E),
    /// A state could not be set on the body (not finite, or not a rotation).
    Evaluate(InertiaError),
    /// The states ended before the sample times.
    TooFewStates,
}

impl<E: fmt::Display> fmt::Display for ReportError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReportError::State(e) => write!(f, "{e}"),
            ReportError::Evaluate(e) => write!(f, "the motion cannot be evaluated: {e}"),
            ReportError::TooFewStates => write!(f, "fewer states than sample times"),
        }
    }
}

impl<E: fmt::Debug + fmt::Display> std::error::Error for ReportError<E> {}

impl Report {
    /// Builds the report from the states (principal frame) at `times` of the motion that
    /// starts as `start`; `states` may fail (a closed form that cannot be evaluated).
    ///
    /// # Errors
    /// [`ReportError::State`] with the first error of `states`; [`ReportError::Evaluate`]
    /// for a state the body refuses; [`ReportError::TooFewStates`].
    pub fn from_states<E>(
        start: &RigidBody,
        times: &[f64],
        states: impl IntoIterator<Item = Result<State, E>>,
    ) -> Result<Report, ReportError<E>> {
        let n = start.dim();
        let reference = Invariants::of(start);
        let rp = start.principal_frame().clone();
        let rp_rev = rp.inverse();
        let mut report = Report {
            dim: n,
            times: times.to_vec(),
            omega: Vec::with_capacity(times.len()),
            momentum: Vec::with_capacity(times.len()),
            energy: Vec::with_capacity(times.len()),
            casimirs: Vec::with_capacity(times.len()),
            attitude: Vec::with_capacity(times.len()),
            energy_drift: Vec::with_capacity(times.len()),
            casimir_drift: Vec::with_capacity(times.len()),
            drift: Drift::default(),
            manakov_drift: vec![0.0; reference.manakov.len()],
        };
        let mut b = start.clone();
        for state in states {
            let (r, l) = state.map_err(ReportError::State)?;
            b.set_state(r, l).map_err(ReportError::Evaluate)?;
            let inv = Invariants::of(&b);
            let d = inv.drift_from(&reference);
            report.drift = report.drift.max(d);
            for (worst, m) in report
                .manakov_drift
                .iter_mut()
                .zip(inv.manakov_drifts(&reference))
            {
                *worst = worst.max(m);
            }
            report.energy_drift.push(d.energy);
            report.casimir_drift.push(d.casimirs);
            report.omega.push(rp.rotate_bivector(&b.omega()));
            report.momentum.push(rp.rotate_bivector(b.momentum()));
            report.energy.push(inv.energy);
            report.casimirs.push(inv.casimirs);
            report
                .attitude
                .push(b.principal_frame_attitude().compose(&rp_rev).to_matrix());
        }
        if report.omega.len() != times.len() {
            return Err(ReportError::TooFewStates);
        }
        Ok(report)
    }

    /// The names 12, 13, …, 1N, 23, … of the bivector components, in their order.
    pub fn planes(&self) -> Vec<String> {
        crate::algebra::pairs(self.dim)
            .map(|(i, j)| crate::algebra::plane_name(self.dim, i, j))
            .collect()
    }

    /// The JSON object of `rotorflow simulate --json` and `rotorflow exact --json`: keys
    /// `dim`, `planes`, `times`, `omega`, `momentum`, `energy`, `casimirs`, `attitude` (one
    /// row-major N × N matrix per sample) and `drift` (`energy`, `casimirs`, `manakov`,
    /// `space_momentum`).
    #[cfg(feature = "serde")]
    pub fn to_json(&self) -> serde_json::Value {
        use serde_json::json;
        let bv =
            |v: &[Bivector]| -> Vec<Vec<f64>> { v.iter().map(|b| b.as_slice().to_vec()).collect() };
        let matrix = |m: &DMatrix<f64>| -> Vec<Vec<f64>> {
            (0..m.nrows())
                .map(|r| (0..m.ncols()).map(|c| m[(r, c)]).collect())
                .collect()
        };
        json!({
            "dim": self.dim,
            "planes": self.planes(),
            "times": self.times,
            "omega": bv(&self.omega),
            "momentum": bv(&self.momentum),
            "energy": self.energy,
            "casimirs": self.casimirs,
            "attitude": self.attitude.iter().map(matrix).collect::<Vec<_>>(),
            "drift": {
                "energy": self.drift.energy,
                "casimirs": self.drift.casimirs,
                "manakov": self.manakov_drift,
                "space_momentum": self.drift.space_momentum,
            },
        })
    }
}

/// The integrator of a run and its step: fixed-step with largest step `dt`, or one of the
/// adaptive Dormand–Prince pairs sampled from its dense output.
pub enum Stepper {
    /// A fixed-step integrator with largest step `dt`.
    Fixed {
        /// The integrator.
        integrator: Box<dyn Integrator>,
        /// The largest step.
        dt: f64,
    },
    /// Adaptive Dormand–Prince 5(4).
    Dopri5(Dopri5),
    /// Adaptive Dormand–Prince 8(5,3) (sixteen stages kept inline, hence the box).
    Dop853(Box<Dop853>),
}

impl Stepper {
    /// The adaptive integrators' internal steps so far, rejected ones included (0 for a
    /// fixed-step integrator, whose steps [`sample_states`] counts itself).
    fn adaptive_steps(&self) -> usize {
        match self {
            Stepper::Fixed { .. } => 0,
            Stepper::Dopri5(d) => d.accepted_steps() + d.rejected_steps(),
            Stepper::Dop853(d) => d.accepted_steps() + d.rejected_steps(),
        }
    }
}

/// Why [`sample_states`] stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum SampleError<E> {
    /// The integrator failed.
    Integration(DynamicsError),
    /// The state stopped being finite (a step too large for the motion).
    NotFinite,
    /// The caller's `sink` refused a block.
    Sink(E),
}

/// The most samples integrated as one block.
const BLOCK_MAX: usize = 128;

/// Samples per block of [`sample_states`] for a run of `samples`: about a hundredth of them
/// (so that a caller's progress display moves), at most 128.
pub fn sample_block_len(samples: usize) -> usize {
    samples.div_ceil(100).clamp(1, BLOCK_MAX)
}

/// Integrates `body` under `torque` and hands the states at `times` (from t = 0, increasing)
/// to `sink`, one block of [`sample_block_len`] samples at a time; returns the number of
/// steps taken. Each block restarts the integrator from the last state of the previous one,
/// with times relative to it (the torques of [`torques`](super::torques) do not depend on
/// time), so that only one block of states is held at a time.
///
/// # Errors
/// [`SampleError::Integration`], [`SampleError::NotFinite`], or the first error of `sink`.
pub fn sample_states<E>(
    body: &RigidBody,
    torque: &dyn Torque,
    stepper: &mut Stepper,
    times: &[f64],
    sink: &mut dyn FnMut(Vec<State>) -> Result<(), E>,
) -> Result<usize, SampleError<E>> {
    let mut steps = 0;
    let mut current = body.clone();
    let mut t0 = 0.0;
    for block in times.chunks(sample_block_len(times.len())) {
        let relative: Vec<f64> = block.iter().map(|t| t - t0).collect();
        let before = stepper.adaptive_steps();
        let states: Vec<State> = match stepper {
            Stepper::Fixed { integrator, dt } => {
                let traj = simulate(&current, integrator.as_mut(), torque, *dt, &relative)
                    .map_err(SampleError::Integration)?;
                steps += traj.steps();
                traj.samples()
                    .iter()
                    .map(|s| (s.attitude.clone(), s.momentum.clone()))
                    .collect()
            }
            Stepper::Dopri5(d) => d
                .dense_samples(&current, torque, &relative)
                .map_err(SampleError::Integration)?,
            Stepper::Dop853(d) => d
                .dense_samples(&current, torque, &relative)
                .map_err(SampleError::Integration)?,
        };
        steps += stepper.adaptive_steps() - before;
        if states
            .iter()
            .any(|(r, l)| l.as_slice().iter().any(|x| !x.is_finite()) || !r.is_finite())
        {
            return Err(SampleError::NotFinite);
        }
        if let Some((r, l)) = states.last() {
            current
                .set_state(r.clone(), l.clone())
                .map_err(|_| SampleError::NotFinite)?;
            t0 = *block.last().expect("chunks are not empty");
        }
        sink(states).map_err(SampleError::Sink)?;
    }
    Ok(steps)
}
