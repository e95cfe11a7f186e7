//! Free rigid bodies of 3D and 4D space on the fixed-size types: [`FreeBody3`] and
//! [`FreeBody4`] hold the principal plane moments, the momentum as a [`Bivector3`] or
//! [`Bivector4`] and the attitude as a [`Rotor3`] (a quaternion) or [`Rotor4`] (a quaternion
//! pair), all `Copy` and on the stack, and step with the same formulas as [`Rkmk4`] and
//! [`Splitting::strang`] on a [`RigidBody`]: for a game loop or a swarm of bodies.
//!
//! Which step to use: [`FreeBody4::step_strang`] (and its 3D twin) keeps |L|, every Casimir
//! and the space-frame momentum to round-off at any step and the energy bounded (it is
//! symplectic), at the cost of one exact rotation per plane; it is the step for real-time use.
//! [`FreeBody4::step_rk4`] is order 4 with the attitude on the group; its energy drifts as
//! O(h⁴ t). Both agree with the run-time integrators to a few ulp per step
//! (`tests/dynamics/fixed.rs`).
//!
//! [`Rkmk4`]: super::Rkmk4
//! [`Splitting::strang`]: super::Splitting::strang

use super::integrate::{strang_drift_3, strang_drift_4};
use super::{DynamicsError, RigidBody};
use crate::algebra::{Bivector3, Bivector4, Rotor3, Rotor4, commutator_packed};

macro_rules! free_body {
    ($name:ident, $n:literal, $k:literal, $biv:ident, $rotor:ident, $drift:ident, $doc:literal) => {
        #[doc = $doc]
        ///
        /// The body frame is the principal frame: the plane moments are the inertia map's
        /// eigenvalues on the basis planes, the momentum L and ω = I⁻¹(L) are in that frame,
        /// and the attitude turns it to space (x_space = R x R̃).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $name {
            moments: [f64; $k],
            inverse: [f64; $k],
            momentum: [f64; $k],
            attitude: $rotor,
        }

        impl $name {
            /// The body with principal plane moments `moments` (lexicographic planes),
            /// attitude `attitude` (principal frame → space) and principal-frame momentum
            /// `momentum`.
            ///
            /// # Errors
            /// [`DynamicsError::InvalidMotion`] for a moment that is not positive and finite
            /// or a momentum or attitude that is not finite.
            pub fn new(
                moments: [f64; $k],
                attitude: $rotor,
                momentum: $biv,
            ) -> Result<Self, DynamicsError> {
                if !moments.iter().all(|m| m.is_finite() && *m > 0.0) {
                    return Err(DynamicsError::InvalidMotion {
                        what: "plane moments",
                        reason: "must be positive and finite".into(),
                    });
                }
                let momentum = momentum.to_array();
                if !momentum.iter().all(|x| x.is_finite()) {
                    return Err(DynamicsError::InvalidMotion {
                        what: "momentum",
                        reason: "must be finite".into(),
                    });
                }
                if !attitude.unit_error().is_finite() {
                    return Err(DynamicsError::InvalidMotion {
                        what: "attitude",
                        reason: "must be finite".into(),
                    });
                }
                Ok(Self {
                    moments,
                    inverse: moments.map(|m| 1.0 / m),
                    momentum,
                    attitude,
                })
            }

            /// The fixed-size copy of a run-time body's state.
            ///
            /// # Errors
            /// [`DynamicsError::Algebra`] unless the body has this dimension;
            /// [`DynamicsError::UnsupportedInertia`] unless its inertia map is diagonal on the
            /// principal planes (every physical body).
            pub fn from_rigid_body(body: &RigidBody) -> Result<Self, DynamicsError> {
                body.refuse_gyrostat(stringify!($name))?;
                if body.dim() != $n {
                    return Err(crate::algebra::AlgebraError::DimensionMismatch {
                        left: $n,
                        right: body.dim(),
                    }
                    .into());
                }
                let unsupported = DynamicsError::UnsupportedInertia {
                    integrator: stringify!($name),
                };
                let moments: [f64; $k] = body
                    .inertia()
                    .diagonal_plane_moments()
                    .ok_or(unsupported)?
                    .try_into()
                    .expect("one moment per plane");
                let attitude = $rotor::from_rotor(&body.principal_frame_attitude().to_rotor()?)?;
                let momentum = $biv::from_bivector(body.momentum())?;
                Self::new(moments, attitude, momentum)
            }

            /// Writes this state into a run-time body of the same inertia.
            ///
            /// # Errors
            /// As [`RigidBody::set_state`].
            pub fn write_to(&self, body: &mut RigidBody) -> Result<(), DynamicsError> {
                body.set_state(self.attitude.to_rotor(), self.momentum().to_bivector())?;
                Ok(())
            }

            /// The principal plane moments.
            pub fn moments(&self) -> [f64; $k] {
                self.moments
            }

            /// The angular momentum L in the principal frame.
            pub fn momentum(&self) -> $biv {
                $biv::from_array(self.momentum)
            }

            /// The angular velocity ω = I⁻¹(L) in the principal frame.
            pub fn omega(&self) -> $biv {
                $biv::from_array(std::array::from_fn(|k| self.momentum[k] * self.inverse[k]))
            }

            /// The attitude (principal frame → space).
            pub fn attitude(&self) -> $rotor {
                self.attitude
            }

            /// The kinetic energy ½⟨ω, L⟩.
            pub fn energy(&self) -> f64 {
                let mut e = 0.0;
                for k in 0..$k {
                    e += self.momentum[k] * self.momentum[k] * self.inverse[k];
                }
                0.5 * e
            }

            /// One step of RKMK4 (order 4), the formulas of [`super::Rkmk4`]'s free step.
            #[inline]
            pub fn step_rk4(&mut self, h: f64) {
                let inverse = self.inverse;
                let rate = |l: &[f64; $k]| {
                    let w: [f64; $k] = std::array::from_fn(|k| l[k] * inverse[k]);
                    let mut dl = [0.0; $k];
                    commutator_packed($n, &w, l, &mut dl);
                    (dl, w)
                };
                let axpy =
                    |x: &[f64; $k], y: &[f64; $k], s: f64| std::array::from_fn(|k| x[k] + s * y[k]);
                let l0 = self.momentum;
                let (dl1, w1) = rate(&l0);
                let (dl2, w2) = rate(&axpy(&l0, &dl1, 0.5 * h));
                let (dl3, w3) = rate(&axpy(&l0, &dl2, 0.5 * h));
                let (dl4, w4) = rate(&axpy(&l0, &dl3, h));
                let mut correction = [0.0; $k];
                commutator_packed($n, &w1, &w4, &mut correction);
                let mut u = [0.0; $k];
                for k in 0..$k {
                    u[k] = -h / 12.0 * (w1[k] + 2.0 * w2[k] + 2.0 * w3[k] + w4[k])
                        + h * h / 24.0 * correction[k];
                    self.momentum[k] =
                        l0[k] + h / 6.0 * (dl1[k] + 2.0 * dl2[k] + 2.0 * dl3[k] + dl4[k]);
                }
                self.attitude = self.attitude * $biv::from_array(u).exp();
            }

            /// One Strang step of the Lie–Poisson splitting over the planes, the updates of
            /// [`super::Splitting::strang`]: every plane's flow is an exact rotation.
            #[inline]
            pub fn step_strang(&mut self, h: f64) {
                let d = $drift(&mut self.momentum, &self.moments, h);
                self.attitude = self.attitude.plus_product($rotor::from_even_layout(&d));
            }

            /// [`Self::step_rk4`] on every body.
            pub fn step_all_rk4(bodies: &mut [Self], h: f64) {
                bodies.iter_mut().for_each(|b| b.step_rk4(h));
            }

            /// [`Self::step_strang`] on every body.
            pub fn step_all_strang(bodies: &mut [Self], h: f64) {
                bodies.iter_mut().for_each(|b| b.step_strang(h));
            }

            /// [`Self::step_rk4`] on every body across rayon's threads (feature `parallel`).
            #[cfg(feature = "parallel")]
            pub fn par_step_all_rk4(bodies: &mut [Self], h: f64) {
                use rayon::prelude::*;
                bodies
                    .par_chunks_mut(PAR_CHUNK)
                    .for_each(|c| Self::step_all_rk4(c, h));
            }

            /// [`Self::step_strang`] on every body across rayon's threads (feature `parallel`).
            #[cfg(feature = "parallel")]
            pub fn par_step_all_strang(bodies: &mut [Self], h: f64) {
                use rayon::prelude::*;
                bodies
                    .par_chunks_mut(PAR_CHUNK)
                    .for_each(|c| Self::step_all_strang(c, h));
            }
        }
    };
}

/// Bodies per rayon task: enough work (tens of µs) to pay for the split.
#[cfg(feature = "parallel")]
const PAR_CHUNK: usize = 256;

free_body!(
    FreeBody3,
    3,
    3,
    Bivector3,
    Rotor3,
    strang_drift_3,
    "A free rigid body of 3D space on the fixed-size types (quaternion attitude)."
);
free_body!(
    FreeBody4,
    4,
    6,
    Bivector4,
    Rotor4,
    strang_drift_4,
    "A free rigid body of 4D space on the fixed-size types (quaternion-pair attitude)."
);
