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
//! at a body point r contributes the torque r ∧ F, a bivector in every dimension (Dorst & De
//! Keninck, "May the Forque Be With You", 2022, write force and torque as one dual bivector
//! of projective GA; here the two halves stay apart, as a [`Wrench`], so that the free
//! flight of the centre of mass is exact and the rotation keeps the principal-frame
//! machinery and its integrators). [`MovingBody::motor`] gives the placement as a motor of
//! projective GA, [`MovingBody::homogeneous_matrix`] as an (N+1) × (N+1) matrix.
//!
//! - [`System`]: bodies, forques, contact shapes, half-spaces and joints; energy, linear
//!   and angular momentum.
//! - [`forques`]: uniform gravity, Hooke springs with damping (to a point of space or
//!   between bodies), linear and angular drag, constant forces and torques; closures.
//! - [`BallJoint`]: a body point held on a point of space or of another body, kept by
//!   impulses as RATTLE keeps constraints (Andersen, "Rattle: a 'velocity' version of the
//!   Shake algorithm", 1983), so that no energy is stored in it.
//! - [`HalfSpace`] and [`ContactShape`]: contact of a body's vertices or ellipsoid with
//!   planes of solid world, with restitution and Coulomb friction of maximal dissipation
//!   (the impulse in the (N−1)-dimensional disc |J_t| ≤ μλ that removes the most energy);
//!   impacts with restitution are located in time within a step, the others held by
//!   speculative contacts, so nothing tunnels. [`Contact`] reports
//!   the impulses of the last step.
//! - Bodies touch each other too: [`shape`] (convex shapes with their support functions)
//!   and [`detect`] (GJK distance and EPA penetration in any N) find the pairs, and the
//!   solver takes them with the half-spaces and the joints (one point per pair).
//!   [`MovingBody::fixed`] is solid world of any shape.
//! - The integrators ([`MotionIntegrator`]): [`MotionSplitting`] (symplectic, order 2: the
//!   free flight exact and the rotation by the Lie–Poisson splitting; the only one with
//!   joints and contact) and [`MotionRk4`] (order 4, attitudes on their group, any forques).
//! - [`System::record`]: a sampled run ([`SystemTrajectory`]: bodies, energies, momenta and
//!   the contacts of each sample) with every sample time hit exactly, written as JSON
//!   (feature `serde`) or one CSV per body; the feature `viz` draws it.
//!
//! The book's chapter "Bodies that move" derives the equations, the contact model and the
//! final velocity of a ball that slides into rolling, v₀ (N+2)/(N+4), and tabulates the
//! measured accuracy of all of it.
//!
//! ```
//! use rotorflow::prelude::*;
//! use rotorflow::dynamics::motion::forques::Gravity;
//! use rotorflow::dynamics::motion::{MotionIntegrator, MotionSplitting, MovingBody, System};
//! // A 3D box thrown upward under gravity: its centre of mass follows the exact parabola.
//! let inertia = InertiaMap::from_principal_second_moments(&[0.2, 0.5, 0.9])?;
//! let thrown = MovingBody::new(
//!     1.0,
//!     inertia,
//!     Rotor::identity(3),
//!     &Vector::zero(3),
//!     &Vector::from_components(&[1.0, 0.0, 5.0])?,
//!     &Bivector::from_components(3, &[0.3, -1.0, 2.0])?,
//! )?;
//! let mut system = System::new(vec![thrown])?;
//! system.add_forque(Gravity(Vector::from_components(&[0.0, 0.0, -9.81])?))?;
//! let mut stepper = MotionSplitting::new();
//! for k in 0..100 {
//!     stepper.step(&mut system, k as f64 * 0.01, 0.01)?;
//! }
//! let x = system.bodies()[0].position();
//! assert!((x.as_slice()[2] - (5.0 - 0.5 * 9.81)).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod body;
mod contact;
pub mod detect;
mod error;
mod forque;
mod integrate;
mod joint;
mod placement;
mod record;
pub mod shape;
mod solve;
mod system;

pub use body::MovingBody;
pub use contact::{BodyContact, Contact, ContactShape, HalfSpace};
pub use error::MotionError;
pub use forque::{Forque, ForqueInput, Wrench, forques};
pub use integrate::{MotionIntegrator, MotionRk4, MotionSplitting, SoftStep};
pub use joint::BallJoint;
pub use record::{
    BodyTrack, RecordedPlane, SampleBodyContact, SampleContact, SystemTrajectory, csv_number,
};
pub use solve::SolverReport;
pub use system::System;
