//! Tests of the dynamics layer: Euler's equations as rotor/bivector flows.

mod body_contact;
mod box_distance;
mod broad_phase;
mod compositions;
mod conservation;
mod contact_and_joints;
mod convex_bodies;
mod dop853;
mod equations;
mod fixed;
mod gyrostat;
mod lagrange_top;
mod large_n;
mod lie_poisson;
mod manakov;
mod manifolds;
mod moser_veselov;
mod motion;
mod motion_checks;
mod moving_bodies;
mod names;
mod narrow_phase;
mod orders;
mod paper_errata;
#[cfg(feature = "scene")]
mod piles;
mod soft_step;
mod stacks;
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

/// Least-squares slope of log e against log h: the measured order of a convergence run.
pub fn slope(hs: &[f64], es: &[f64]) -> f64 {
    let xs: Vec<f64> = hs.iter().map(|h| h.ln()).collect();
    let ys: Vec<f64> = es.iter().map(|e| e.ln()).collect();
    let k = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / k, ys.iter().sum::<f64>() / k);
    let num: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let den: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    num / den
}

/// The largest difference between two bodies' momenta and attitudes.
pub fn state_distance(a: &RigidBody, b: &RigidBody) -> f64 {
    let dl = (a.momentum() - b.momentum()).max_abs();
    dl.max(attitude_distance(
        a.principal_frame_attitude(),
        b.principal_frame_attitude(),
    ))
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
