//! Error of the adaptive Dormand–Prince integrator against a fine Yoshida reference, and its
//! step counts, for a free 4D body: `cargo run --release --example adaptive_accuracy`.

use rand::{Rng, SeedableRng};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Dopri5, Integrator, Invariants, RigidBody, Splitting};
use rotorflow::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let n = 4;
    let moments: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
    let l: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|_| r.gen_range(-1.0..1.0))
        .collect();
    let start = RigidBody::from_body_momentum(
        InertiaMap::from_principal_second_moments(&moments)?,
        Rotor::identity(n),
        &Bivector::from_components(n, &l)?,
    )?;
    let t_end = 10.0;
    let mut reference = start.clone();
    let mut y = Splitting::yoshida4();
    for k in 0..50_000 {
        y.step(&mut reference, k as f64 * 2e-4, 2e-4, &Free)?;
    }
    println!("free 4D body, T = {t_end}, reference: Yoshida-4 with h = 2e-4");
    for tol in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
        let mut d = Dopri5::new(tol, tol);
        let mut b = start.clone();
        d.step(&mut b, 0.0, t_end, &Free)?;
        let err = (b.momentum() - reference.momentum()).max_abs();
        let drift = Invariants::of(&b).drift_from(&Invariants::of(&start));
        println!(
            "rtol = atol = {tol:.0e}: |ΔL| = {err:.2e}, accepted {:5}, rejected {:3}, energy drift {:.1e}, |RR̃−1| {:.1e}",
            d.accepted_steps(),
            d.rejected_steps(),
            drift.energy,
            drift.attitude
        );
    }
    Ok(())
}
