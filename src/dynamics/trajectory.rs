//! Sampled trajectories and a driver that produces them.

use super::Attitude;
use super::integrate::{DynamicsError, Integrator};
use super::invariants::{Drift, Invariants};
use super::{RigidBody, Torque};
use crate::algebra::Bivector;

/// The state of the body at one sampled time.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Time t.
    pub time: f64,
    /// Body-frame angular velocity ω (principal frame).
    pub omega: Bivector,
    /// Body-frame angular momentum L (principal frame).
    pub momentum: Bivector,
    /// Attitude R (principal body frame → space).
    pub attitude: Attitude,
    /// Kinetic energy T.
    pub energy: f64,
    /// Casimirs c₁ … c_⌊N/2⌋ of L (coefficients of det(λ − \[L\])).
    pub casimirs: Vec<f64>,
}

/// A sampled trajectory and the largest drifts of its invariants.
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory {
    samples: Vec<Sample>,
    drift: Drift,
    steps: usize,
}

impl Trajectory {
    /// Returns the samples, in time order (the first is the initial state).
    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    /// Returns the largest relative drift of each invariant from its initial value over all
    /// samples (meaningful as conservation errors for free motion; monitors otherwise).
    pub fn drift(&self) -> Drift {
        self.drift
    }

    /// Returns the number of integrator steps taken.
    pub fn steps(&self) -> usize {
        self.steps
    }
}

/// The steps [`simulate`] takes over `span` with largest step `dt`: `count` equal steps of
/// size `h` = span / count, at most dt each, landing exactly on the end (no sliver step
/// from accumulated round-off; a span within 1e-12 relative of a multiple of dt takes that
/// multiple). For callers that step by other means and must take the same steps.
pub fn equal_steps(span: f64, dt: f64) -> (usize, f64) {
    let count = (span / dt * (1.0 - 1e-12)).ceil() as usize;
    (count, if count > 0 { span / count as f64 } else { 0.0 })
}

/// Integrates from t = 0 with steps of at most `dt`, sampling at `times` (ascending, from 0):
/// each interval between samples is split into equal steps that land on the sample time.
///
/// # Errors
/// [`DynamicsError::InvalidSampling`] for a non-positive or non-finite `dt` or `t_end`, or
/// times that are not ascending or outside [0, t_end]; any error of the integrator.
pub fn simulate(
    body: &RigidBody,
    integrator: &mut dyn Integrator,
    torque: &dyn Torque,
    dt: f64,
    times: &[f64],
) -> Result<Trajectory, DynamicsError> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(DynamicsError::InvalidSampling {
            reason: "the step must be positive and finite",
        });
    }
    if times.iter().any(|t| !t.is_finite() || *t < 0.0) || times.windows(2).any(|w| w[1] <= w[0]) {
        return Err(DynamicsError::InvalidSampling {
            reason: "sample times must be finite, non-negative and strictly increasing",
        });
    }
    let mut b = body.clone();
    let reference = Invariants::of(&b);
    let mut drift = Drift::default();
    let mut samples = Vec::with_capacity(times.len());
    let mut t = 0.0;
    let mut steps = 0;
    for &target in times {
        let (count, h) = equal_steps(target - t, dt);
        if count > 0 {
            for k in 0..count {
                integrator.step(&mut b, t + k as f64 * h, h, torque)?;
            }
            steps += count;
        }
        t = target;
        let inv = Invariants::of(&b);
        let d = inv.drift_from(&reference);
        drift = drift.max(d);
        samples.push(Sample {
            time: t,
            omega: b.omega(),
            momentum: b.momentum().clone(),
            attitude: b.principal_frame_attitude().clone(),
            energy: inv.energy,
            casimirs: inv.casimirs,
        });
    }
    Ok(Trajectory {
        samples,
        drift,
        steps,
    })
}

/// Returns `count` evenly spaced times from 0 to `t_end` inclusive (`count ≥ 2`; 1 gives
/// `[0]`).
pub fn even_times(t_end: f64, count: usize) -> Vec<f64> {
    match count {
        0 => Vec::new(),
        1 => vec![0.0],
        _ => (0..count)
            .map(|k| t_end * k as f64 / (count - 1) as f64)
            .collect(),
    }
}

mod observables;
pub use observables::{
    Oscillation, ProjectedObservables, crossings, oscillation, projected_observables,
    projection_planes,
};
