//! Kinematics of a rotating frame in any N (the paper's eqs. 18–21).
//!
//! With x_s = R y R̃ a point seen in space and y its coordinates in the rotating (body) frame,
//! dR/dt = −½ R ω gives
//!
//! ẋ_s = R (ẏ + y⌋ω) R̃,
//! ẍ_s = R (ÿ + 2 ẏ⌋ω + y⌋ω̇ + (y⌋ω)⌋ω) R̃,
//!
//! so a free particle seen from the rotating frame accelerates by the Coriolis term
//! −2 ẏ⌋ω, the centrifugal term −(y⌋ω)⌋ω and the Euler term −y⌋ω̇. In 3D, with
//! x⌋ω = Ω × x, these are the textbook −2Ω × ẏ, −Ω × (Ω × y) and −Ω̇ × y.

use crate::algebra::{Bivector, Vector};

/// Returns the velocity of the body point y (body coordinates) due to rotation, in the body
/// frame: y ⌋ ω.
///
/// # Panics
/// If the dimensions differ.
#[track_caller]
pub fn point_velocity(omega: &Bivector, y: &Vector) -> Vector {
    y.left_contract(omega)
}

/// Returns the Coriolis acceleration −2 ẏ⌋ω seen in a frame rotating with ω, for a point
/// moving with velocity ẏ in that frame.
///
/// # Panics
/// If the dimensions differ.
#[track_caller]
pub fn coriolis_acceleration(omega: &Bivector, velocity: &Vector) -> Vector {
    velocity.left_contract(omega) * -2.0
}

/// Returns the centrifugal acceleration −(y⌋ω)⌋ω seen in a frame rotating with ω at the
/// point y. It points away from every plane of rotation: ⟨y, −(y⌋ω)⌋ω⟩ = |y⌋ω|² ≥ 0.
///
/// # Panics
/// If the dimensions differ.
#[track_caller]
pub fn centrifugal_acceleration(omega: &Bivector, y: &Vector) -> Vector {
    y.left_contract(omega).left_contract(omega) * -1.0
}

/// Returns the Euler (angular-acceleration) term −y⌋ω̇ seen in a frame rotating with ω.
///
/// # Panics
/// If the dimensions differ.
#[track_caller]
pub fn euler_acceleration(omega_rate: &Bivector, y: &Vector) -> Vector {
    y.left_contract(omega_rate) * -1.0
}
