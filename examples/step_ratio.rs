//! Paired timing of one RK4 step, rotorflow against the nalgebra DMatrix baseline of the
//! dynamics benches, and of the 4D Strang step against rotorflow's RK4:
//! `cargo run --release --example step_ratio`.
//!
//! Why beside criterion: on a shared machine a criterion group can land in a slow window
//! that its baseline, measured seconds later, misses, which moves a ratio by ±40 %. Here
//! both sides run in alternating rounds of a few milliseconds and each keeps its fastest
//! round, so interference that lasts longer than a round hits both sides alike.

use nalgebra::DMatrix;
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Attitude, Integrator, RigidBody, Rkmk4, Splitting};
use rotorflow::prelude::*;
use std::time::Instant;

#[path = "../benches/common/dmatrix_rk4.rs"]
mod dmatrix_baseline;
use dmatrix_baseline::{dmatrix_rk4, inverse_plane_moments};

/// The bench's body: J = 0.5 + 0.25 k, L = sin(0.7 k + 0.3), identity attitude.
fn body(n: usize) -> Result<RigidBody, Box<dyn std::error::Error>> {
    let j: Vec<f64> = (0..n).map(|k| 0.5 + 0.25 * k as f64).collect();
    let l: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|k| (0.7 * k as f64 + 0.3).sin())
        .collect();
    Ok(RigidBody::from_body_momentum(
        InertiaMap::from_principal_second_moments(&j)?,
        Attitude::identity(n),
        &Bivector::from_components(n, &l)?,
    )?)
}

/// Nanoseconds per call of `f`, over `calls` calls.
fn per_call(calls: usize, mut f: impl FnMut()) -> f64 {
    let start = Instant::now();
    for _ in 0..calls {
        f();
    }
    start.elapsed().as_secs_f64() * 1e9 / calls as f64
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let h = 0.01;
    let rounds = 25;
    println!("fastest of {rounds} alternating rounds, ns per step (h = {h}):");
    println!("   N | rotorflow RK4 | DMatrix RK4 | ratio | rotorflow Strang | Strang / RK4");
    for n in [3usize, 4, 5, 8, 12, 16, 24, 32] {
        let calls = (2_000_000 / (n * n * n)).clamp(200, 100_000);
        let (mut rk4, mut strang) = (body(n)?, body(n)?);
        let j: Vec<f64> = (0..n).map(|k| 0.5 + 0.25 * k as f64).collect();
        let inv = inverse_plane_moments(&j);
        let mut m = rk4.momentum().to_skew_matrix();
        let mut q = DMatrix::<f64>::identity(n, n);
        let (mut t_rk4, mut t_dm, mut t_strang) = (f64::MAX, f64::MAX, f64::MAX);
        for _ in 0..rounds {
            t_rk4 = t_rk4.min(per_call(calls, || {
                Rkmk4.step(&mut rk4, 0.0, h, &Free).expect("finite step");
            }));
            t_dm = t_dm.min(per_call(calls, || dmatrix_rk4(&mut m, &mut q, &inv, h)));
            t_strang = t_strang.min(per_call(calls, || {
                Splitting::strang()
                    .step(&mut strang, 0.0, h, &Free)
                    .expect("finite step");
            }));
        }
        println!(
            "{n:>4} | {t_rk4:>13.0} | {t_dm:>11.0} | {:>5.2} | {t_strang:>16.0} | {:>12.2}",
            t_rk4 / t_dm,
            t_strang / t_rk4
        );
    }
    Ok(())
}
