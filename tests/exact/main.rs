//! Tests of the closed-form free motions: bodies with at most two distinct principal moments
//! in any N, steady rotations, the 3D asymmetric top and its embeddings, and the paper's §7
//! formulas.

mod dispatch;
mod paper_section7;
mod top3d;
mod two_moments;

#[path = "../support/mod.rs"]
mod support;

use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{
    Attitude, Dopri5, DynamicsError, Integrator, NoClosedFormReason, RigidBody,
};
use rotorflow::prelude::*;
pub use support::{random_bivector, random_rotor, rng};

/// The reasons of a [`DynamicsError::NoClosedForm`], or a panic naming what came instead.
pub fn no_closed_form_reasons<T: std::fmt::Debug>(
    result: Result<T, DynamicsError>,
) -> Vec<NoClosedFormReason> {
    match result {
        Err(DynamicsError::NoClosedForm { reasons }) => {
            assert!(!reasons.is_empty(), "NoClosedForm without a reason");
            reasons
        }
        other => panic!("expected NoClosedForm, got {other:?}"),
    }
}

/// The body with principal values `j`, attitude `attitude` and body angular velocity ω.
pub fn body_with_omega(j: &[f64], attitude: Rotor, omega: &Bivector) -> RigidBody {
    let inertia = InertiaMap::from_principal_second_moments(j).unwrap();
    RigidBody::from_body_velocity(inertia, attitude, omega).unwrap()
}

/// The tolerance of the Dopri5 reference. At 1e-13 its own rotor error over 100 periods is
/// 1e-11 … 1e-9 depending on the body (it scales 10× per decade of tolerance:
/// `two_moments::dopri5_difference_scales_with_its_tolerance`), so the references use 1e-14,
/// where it is 1e-12 … 1e-10 and round-off has not yet taken over.
pub const REFERENCE_TOLERANCE: f64 = 1e-14;

/// Anything that is an attitude: a rotor or an [`Attitude`].
pub trait AsAttitude {
    /// Returns it as an [`Attitude`].
    fn as_attitude(&self) -> Attitude;
}

impl AsAttitude for Rotor {
    fn as_attitude(&self) -> Attitude {
        self.into()
    }
}

impl AsAttitude for Attitude {
    fn as_attitude(&self) -> Attitude {
        self.clone()
    }
}

/// Max |Δ| over the rotor coefficients when both are rotors (N ≤ 4, sign included), over
/// the rotation-matrix entries otherwise.
pub fn rotor_distance(a: &impl AsAttitude, b: &impl AsAttitude) -> f64 {
    let (a, b) = (a.as_attitude(), b.as_attitude());
    match (a.as_rotor(), b.as_rotor()) {
        (Some(x), Some(y)) => x
            .as_slice()
            .iter()
            .zip(y.as_slice())
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs())),
        _ => (a.to_matrix() - b.to_matrix()).amax(),
    }
}

/// Integrates with Dopri5 (rtol = atol = [`REFERENCE_TOLERANCE`]), stepping exactly to each time, and returns
/// the states (attitude, momentum).
pub fn dopri_reference(body: &RigidBody, times: &[f64]) -> Vec<(Attitude, Bivector)> {
    let mut d = Dopri5::new(REFERENCE_TOLERANCE, REFERENCE_TOLERANCE);
    let mut b = body.clone();
    let mut t = 0.0;
    let mut out = Vec::with_capacity(times.len());
    for &target in times {
        if target > t {
            d.step(&mut b, t, target - t, &Free).unwrap();
            t = target;
        }
        out.push((b.principal_frame_attitude().clone(), b.momentum().clone()));
    }
    out
}
