//! What the plain matrix RK4 of the dynamics bench gives up for its speed: its attitude
//! matrix leaves SO(N), while rotorflow's RK4 advances the attitude by group exponentials.
//! `cargo run --release --example matrix_rk4_drift` prints |QᵀQ − 1| and the space-momentum
//! drift after 10⁴ steps (h = 0.01) for both, at N = 4, 8, 16, 32.

use nalgebra::DMatrix;
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Attitude, Integrator, Invariants, RigidBody, Rkmk4};
use rotorflow::prelude::*;

/// The bench's baseline: RK4 on (M, Q) with Ω = M ⊘ (Jᵢ + Jⱼ), dM = ΩM − MΩ, dQ = QΩᵀ.
fn dmatrix_rk4(m: &mut DMatrix<f64>, q: &mut DMatrix<f64>, inv: &DMatrix<f64>, h: f64) {
    let f = |m: &DMatrix<f64>, q: &DMatrix<f64>| {
        let w = m.component_mul(inv);
        (&w * m - m * &w, q * w.transpose())
    };
    let (k1m, k1q) = f(m, q);
    let (k2m, k2q) = f(&(&*m + &k1m * (0.5 * h)), &(&*q + &k1q * (0.5 * h)));
    let (k3m, k3q) = f(&(&*m + &k2m * (0.5 * h)), &(&*q + &k2q * (0.5 * h)));
    let (k4m, k4q) = f(&(&*m + &k3m * h), &(&*q + &k3q * h));
    *m += (k1m + k2m * 2.0 + k3m * 2.0 + k4m) * (h / 6.0);
    *q += (k1q + k2q * 2.0 + k3q * 2.0 + k4q) * (h / 6.0);
}

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
        let inv = DMatrix::from_fn(n, n, |a, b| if a == b { 0.0 } else { 1.0 / (j[a] + j[b]) });
        let (mut m, mut q) = (l.to_skew_matrix(), DMatrix::<f64>::identity(n, n));
        let ls0 = &q * &m * q.transpose();
        for _ in 0..steps {
            dmatrix_rk4(&mut m, &mut q, &inv, h);
        }
        let orth = (q.transpose() * &q - DMatrix::<f64>::identity(n, n)).amax();
        let ls = &q * &m * q.transpose();
        let matrix_drift = (&ls - &ls0).amax() / ls0.amax();

        let mut body = RigidBody::from_body_momentum(
            InertiaMap::from_principal_moments(&j)?,
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
            now.rotor_error,
            now.drift_from(&start).space_momentum
        );
    }
    Ok(())
}
