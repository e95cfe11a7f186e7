//! Euler's equations as rotor/bivector flows in any dimension.
//!
//! The state of a rigid body is its attitude rotor R (body → space) and its body-frame angular
//! momentum L, a bivector. With ω = I⁻¹(L) the body-frame angular velocity and τ the torque
//! bivector in the body frame (signs as in the Conventions chapter of the rotorflow book):
//!
//! dL/dt = ω × L + τ,    dR/dt = −½ R ω,
//!
//! where × is the commutator product. For N = 3 this is exactly I₁Ω̇₁ = (I₂ − I₃)Ω₂Ω₃ and its
//! cyclic permutations; the paper derives the component forms for N = 3, 4, 5 (its eqs. 43–46,
//! 52–58, 68), which the book maps onto this one line.
//!
//! - [`RigidBody`]: the state, kept in the principal frame of the inertia
//!   ([`RigidBody::principal_frame_attitude`]; [`RigidBody::body_axes_attitude`] places the
//!   body's own axes, to render it).
//! - [`Attitude`]: the rotation body → space (a rotor for N ≤ 4, an SO(N) matrix above).
//! - [`Torque`]: external torques; closures implement it, and [`torques`] has the built-ins.
//! - [`integrate`]: the integrators behind the [`Integrator`] trait.
//! - [`invariants`]: energy, Casimirs, space-frame momentum, the attitude's drift from its
//!   group.
//! - [`trajectory`]: sampled runs ([`simulate`]) with a drift summary.
//! - [`report`]: a run's states reported in the body's own axes, as `rotorflow simulate`
//!   prints them.
//! - [`kinematics`]: point velocities, Coriolis and centrifugal accelerations (eqs. 18–21).
//! - [`stability`]: growth rates of perturbed steady rotations.
//! - [`motion`]: bodies that move as well as turn (centre of mass, forces and torques,
//!   systems of bodies with springs).
//! - [`exact`]: closed-form free motions, the references the integrators are measured against.
//! - [`DynamicsError`]: the one error type of the layer ([`NoClosedFormReason`] says why a
//!   body has no closed form).
//!
//! Book chapters: `book/src/dynamics.md` (the integrators compared) and `book/src/mapping.md`
//! (the paper's eqs. 14–68 in these terms).

mod attitude;
mod body;
mod error;
pub mod exact;
mod fixed;
pub mod integrate;
pub mod invariants;
pub mod kinematics;
mod lagrange_top;
pub mod motion;
pub mod report;
pub mod stability;
mod torque;
pub mod trajectory;

pub use attitude::Attitude;
pub use body::RigidBody;
pub use error::{DynamicsError, NoClosedFormReason};
pub use fixed::{Dop853Stats, FreeBody3, FreeBody4};
pub use integrate::{
    Dop853, Dopri5, Integrator, LiePoissonRk4, Midpoint, MoserVeselov, ProcessedOrder,
    ProcessedSplitting, Rkmk4, Splitting, SplittingOrder,
};
pub use invariants::{Drift, Invariants, MANAKOV_MAX_DIM, manakov_count, manakov_integrals};
pub use lagrange_top::LagrangeTop;
pub use torque::{Torque, TorqueInput, torques};
pub use trajectory::{Sample, Trajectory, equal_steps, simulate};
