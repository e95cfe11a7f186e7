//! Rigid bodies that move as well as turn, in any dimension.
//!
//! A [`MovingBody`] adds to the rotation of a [`crate::dynamics::RigidBody`] its mass, the
//! position of its centre of mass and its linear momentum. Newton–Euler in N dimensions is
//! then, for each body with total force F (space frame) and torque τ about its centre of
//! mass (principal body frame),
//!
//!   dx/dt = p/m,  dp/dt = F,  dL/dt = ω × L + τ,  dR/dt = −½ R ω:
//!
//! the rotation is exactly the rotation-only body's, and the two halves are coupled by the
//! forces and torques ([`Forque`]s) that read positions, velocities and attitudes. A force F
//! at a body point r contributes the torque r ∧ F (Dorst & De Keninck, "May the Forque Be
//! With You", 2022, write force and torque as one dual bivector of projective GA; here the
//! two halves stay apart so that the rotation keeps the principal-frame machinery and its
//! integrators). [`MovingBody::motor`] gives the placement as a motor of projective GA.
//!
//! - [`System`]: bodies and forques; energy, linear and angular momentum.
//! - [`forques`]: uniform gravity, Hooke springs with damping (to a point of space or
//!   between bodies), linear and angular drag, constant forces and torques; closures.
//! - [`MotionIntegrator`]: [`MotionSplitting`] (symplectic, order 2: the free flight exact
//!   and the rotation by the Lie–Poisson splitting) and [`MotionRk4`] (order 4, attitudes on
//!   their group).

mod body;
mod constraint;
mod contact;
mod forque;
mod integrate;
mod joint;
mod system;

pub use body::MovingBody;
pub use contact::{Contact, ContactShape, HalfSpace};
pub use forque::{Forque, ForqueInput, Wrench, forques};
pub use integrate::{MotionIntegrator, MotionRk4, MotionSplitting};
pub use joint::BallJoint;
pub use system::System;
