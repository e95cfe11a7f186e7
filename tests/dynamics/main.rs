//! Tests of the dynamics layer: Euler's equations as rotor/bivector flows.

mod compositions;
mod conservation;
mod contact_and_joints;
mod dop853;
mod equations;
mod fixed;
mod gyrostat;
mod lagrange_top;
mod large_n;
mod lie_poisson;
mod manakov;
mod moser_veselov;
mod motion;
mod moving_bodies;
mod names;
mod orders;
mod paper_errata;
mod torqued;

#[path = "../support/mod.rs"]
mod support;

use rand::Rng;
use rotorflow::dynamics::{Attitude, Integrator, RigidBody, Torque};
use rotorflow::prelude::*;
pub use support::{random_bivector, rng};

/// A random free body in its principal frame: moments in [0.3, 2], random L and attitude.
pub fn random_body(r: &mut impl Rng, n: usize) -> RigidBody {
    let moments: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
    let inertia = InertiaMap::from_principal_second_moments(&moments).unwrap();
    let attitude = Rotor::from_rotation_bivector(&random_bivector(r, n, 1.0));
    RigidBody::from_body_momentum(inertia, attitude, &random_bivector(r, n, 1.0)).unwrap()
}

/// Integrates `steps` steps of size `h` from t = 0.
pub fn run(
    body: &mut RigidBody,
    integrator: &mut dyn Integrator,
    torque: &dyn Torque,
    h: f64,
    steps: usize,
) {
    for k in 0..steps {
        integrator.step(body, k as f64 * h, h, torque).unwrap();
    }
}

/// Distance between two attitudes: the largest rotor-coefficient difference when both are
/// rotors (N ≤ 4, sign included), the largest rotation-matrix entry difference otherwise.
pub fn attitude_distance(a: &Attitude, b: &Attitude) -> f64 {
    match (a.as_rotor(), b.as_rotor()) {
        (Some(x), Some(y)) => x
            .as_slice()
            .iter()
            .zip(y.as_slice())
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs())),
        _ => (a.to_matrix() - b.to_matrix()).amax(),
    }
}
