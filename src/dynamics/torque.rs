//! External torques.

use super::Attitude;
use crate::algebra::{Bivector, Vector};

/// What a torque may depend on at one instant: time, attitude (principal body frame → space),
/// body-frame angular momentum and angular velocity.
#[derive(Clone, Copy, Debug)]
pub struct TorqueInput<'a> {
    /// Time t.
    pub time: f64,
    /// Attitude R: principal body frame → space, as
    /// [`RigidBody::principal_frame_attitude`](super::RigidBody::principal_frame_attitude).
    pub attitude: &'a Attitude,
    /// Body-frame angular momentum L.
    pub momentum: &'a Bivector,
    /// Body-frame angular velocity ω = I⁻¹(L).
    pub omega: &'a Bivector,
}

/// An external torque, returned as a bivector in the body (principal) frame.
///
/// Any closure `Fn(&TorqueInput) -> Bivector` is a torque; the built-ins are in [`torques`].
/// A torque of a force F applied at body point r is the bivector r ∧ F (space frame); the
/// body-frame torque is R̃ (r_s ∧ F) R.
pub trait Torque {
    /// Returns the body-frame torque bivector τ.
    fn torque(&self, input: &TorqueInput<'_>) -> Bivector;

    /// Returns true if the torque is identically zero (lets integrators skip work).
    fn is_zero(&self) -> bool {
        false
    }
}

impl<F> Torque for F
where
    F: Fn(&TorqueInput<'_>) -> Bivector,
{
    fn torque(&self, input: &TorqueInput<'_>) -> Bivector {
        self(input)
    }
}

/// The built-in torques.
pub mod torques {
    use super::*;

    /// No torque: free rotation.
    #[derive(Clone, Copy, Debug, Default)]
    pub struct Free;

    impl Torque for Free {
        fn torque(&self, input: &TorqueInput<'_>) -> Bivector {
            Bivector::zero(input.momentum.dim())
        }
        fn is_zero(&self) -> bool {
            true
        }
    }

    /// A constant torque fixed in the body frame.
    #[derive(Clone, Debug)]
    pub struct BodyFrame(pub Bivector);

    impl Torque for BodyFrame {
        fn torque(&self, _: &TorqueInput<'_>) -> Bivector {
            self.0.clone()
        }
    }

    /// A constant torque fixed in space: τ_body = R̃ τ_s R.
    #[derive(Clone, Debug)]
    pub struct SpaceFrame(pub Bivector);

    impl Torque for SpaceFrame {
        fn torque(&self, input: &TorqueInput<'_>) -> Bivector {
            input.attitude.inverse_rotate_bivector(&self.0)
        }
    }

    /// Uniform gravity on a body pivoted at a fixed point: the heavy top in any N.
    ///
    /// The force m g acts at the centre of mass, `offset` from the pivot in the body
    /// (principal) frame; the torque is r ∧ F, in the body frame
    /// τ = offset ∧ (R̃ m g R). The inertia of the body must be taken about the pivot.
    #[derive(Clone, Debug)]
    pub struct Gravity {
        /// m g, the weight as a space-frame vector (e.g. −m g e_N).
        pub weight: Vector,
        /// Centre of mass relative to the pivot, in the body frame.
        pub offset: Vector,
    }

    impl Torque for Gravity {
        fn torque(&self, input: &TorqueInput<'_>) -> Bivector {
            let f_body = input.attitude.inverse_rotate_vector(&self.weight);
            self.offset.wedge(&f_body)
        }
    }

    impl Gravity {
        /// Returns the potential energy V = −⟨m g, R r R̃⟩ (so that T + V is conserved).
        pub fn potential_energy(&self, attitude: &Attitude) -> f64 {
            -self.weight.dot(&attitude.rotate_vector(&self.offset))
        }
    }

    /// Linear damping τ = −c ω: the energy decays at the rate dT/dt = −2c T·(⟨ω,ω⟩/⟨ω,L⟩)…,
    /// exactly dT/dt = −c⟨ω, ω⟩.
    #[derive(Clone, Copy, Debug)]
    pub struct LinearDamping(pub f64);

    impl Torque for LinearDamping {
        fn torque(&self, input: &TorqueInput<'_>) -> Bivector {
            input.omega * -self.0
        }
    }
}
