//! Integrators for systems of moving bodies.
//!
//! - [`splitting`]: [`MotionSplitting`], the symplectic splitting with contacts and joints;
//! - [`rk4`]: [`MotionRk4`], Runge–Kutta–Munthe-Kaas of order 4 without contacts;
//! - [`soft`]: [`SoftStep`], substeps with soft contacts and a fixed solver work per step.

mod rk4;
mod soft;
mod splitting;

pub use rk4::MotionRk4;
pub use soft::SoftStep;
pub use splitting::MotionSplitting;

use crate::dynamics::DynamicsError;
use crate::dynamics::integrate::axpy;
use crate::dynamics::motion::{MotionError, MovingBody, System, Wrench};

/// `count` if it is positive: an integrator's setting `what` (substeps, passes, sweeps).
fn positive_count(what: &'static str, count: usize) -> Result<usize, MotionError> {
    if count == 0 {
        return Err(MotionError::OutOfRange {
            what,
            value: 0.0,
            expected: "a positive integer",
        });
    }
    Ok(count)
}

/// An integrator of Newton–Euler for a [`System`]: advances every body by one step.
pub trait MotionIntegrator {
    /// Returns the order of accuracy.
    fn order(&self) -> u32;

    /// Returns a short name.
    fn name(&self) -> &'static str;

    /// Advances `system` from time `t` by a step `h`.
    ///
    /// # Errors
    /// [`DynamicsError::NonFinite`] if the state leaves f64; the errors of the rotation
    /// integrator.
    fn step(&mut self, system: &mut System, t: f64, h: f64) -> Result<(), DynamicsError>;

    /// Advances `system` from time `t` by `steps` steps of h (the k-th from t + k h): the
    /// same as that many calls of [`MotionIntegrator::step`], which is what this default
    /// does. An integrator may share work between consecutive steps here.
    ///
    /// # Errors
    /// Those of [`MotionIntegrator::step`], at the step that fails.
    fn advance(
        &mut self,
        system: &mut System,
        t: f64,
        h: f64,
        steps: usize,
    ) -> Result<(), DynamicsError> {
        one_by_one(self, system, (t, h), steps)
    }
}

/// `steps` calls of `integrator.step`, the k-th from t + k h.
fn one_by_one<I: MotionIntegrator + ?Sized>(
    integrator: &mut I,
    system: &mut System,
    (t, h): (f64, f64),
    steps: usize,
) -> Result<(), DynamicsError> {
    for k in 0..steps {
        integrator.step(system, t + k as f64 * h, h)?;
    }
    Ok(())
}

/// Adds h of each wrench to the momenta of the bodies that move.
fn kick(bodies: &mut [MovingBody], wrenches: &[Wrench], h: f64) {
    for (b, w) in bodies.iter_mut().zip(wrenches) {
        if b.is_fixed() {
            continue;
        }
        let (_, p, rotation) = b.state_mut();
        axpy(p.as_mut_slice(), h, w.force.as_slice());
        let (_, l) = rotation.state_mut();
        axpy(l.as_mut_slice(), h, w.torque.as_slice());
    }
}

/// How far the points of body b (bounding radius r) move in a flight of h that starts
/// after a kick of length `kick` by a force of norm `force`: h (|v| + kick |F|/m + |ω| r),
/// |ω| the norm of the bivector, at least the speed it gives a point at unit distance.
fn sweep(b: &MovingBody, r: f64, force: f64, (h, kick): (f64, f64)) -> f64 {
    h * ((b.linear_momentum().norm() + kick * force) / b.mass() + omega_norm(b) * r)
}

/// The norm of body b's angular velocity, without a bivector of room for eight dimensions
/// to copy out where it has at most that (a moving body is no gyrostat: ω = I⁻¹(L)).
fn omega_norm(b: &MovingBody) -> f64 {
    let rotation = b.rotation();
    let l = rotation.momentum().as_slice();
    let mut w = [0.0f64; 28];
    match w.get_mut(..l.len()) {
        Some(w) => {
            rotation.inertia().apply_inverse_into(l, w);
            w.iter().map(|x| x * x).sum::<f64>().sqrt()
        }
        None => rotation.omega().norm(),
    }
}

fn check_finite(system: &System, t: f64) -> Result<(), DynamicsError> {
    if system.bodies().iter().all(MovingBody::is_finite) {
        Ok(())
    } else {
        Err(DynamicsError::NonFinite { time: t })
    }
}
