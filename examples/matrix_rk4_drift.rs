//! What the plain matrix RK4 of the dynamics bench gives up for its speed: its attitude
//! matrix leaves SO(N), while rotorflow's RK4 advances the attitude by group exponentials.
//! `cargo run --release --example matrix_rk4_drift` prints |QᵀQ − 1| and the space-momentum
//! drift after 10⁴ steps (h = 0.01) for both, at N = 4, 8, 16, 32.

use nalgebra::DMatrix;
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Attitude, Integrator, Invariants, RigidBody, Rkmk4};
use rotorflow::prelude::*;

/// The bench's baseline (RK4 on the matrix equations).
#[path = "../benches/common/dmatrix_rk4.rs"]
mod dmatrix_baseline;
use dmatrix_baseline::{dmatrix_rk4, inverse_plane_moments};

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (h, steps) = (0.01, 10_000);
    println!("after {steps} RK4 steps of h = {h}:");
    println!("   N | matrix RK4 |QᵀQ − 1|  space-L drift | rotorflow RK4 |QᵀQ − 1|  space-L drift");
    for n in [4usize, 8, 16, 32] {
        let j: Vec<f64> = (0..n).map(|k| 0.5 + 0.25 * k as f64).collect();
        let l: Vec<f64> = (0..n * (n - 1) / 2)
            .map(|k| (0.7 * k as f64 + 0.3).sin())
            .collect();
        let l = Bivector::from_components(n, &l)?;
        let inv = inverse_plane_moments(&j);
        let (mut m, mut q) = (l.to_skew_matrix(), DMatrix::<f64>::identity(n, n));
        let ls0 = &q * &m * q.transpose();
        for _ in 0..steps {
            dmatrix_rk4(&mut m, &mut q, &inv, h);
        }
        let orth = (q.transpose() * &q - DMatrix::<f64>::identity(n, n)).amax();
        let ls = &q * &m * q.transpose();
        let matrix_drift = (&ls - &ls0).amax() / ls0.amax();

        let mut body = RigidBody::from_body_momentum(
            InertiaMap::from_principal_second_moments(&j)?,
            Attitude::identity(n),
            &l,
        )?;
        let start = Invariants::of(&body);
        for k in 0..steps {
            Rkmk4.step(&mut body, k as f64 * h, h, &Free)?;
        }
        let now = Invariants::of(&body);
        println!(
            "{n:4} | {orth:22.2e} {matrix_drift:14.2e} | {:25.2e} {:14.2e}",
            now.attitude_error,
            now.drift_from(&start).space_momentum
        );
    }
    Ok(())
}
