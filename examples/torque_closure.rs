//! A torque written as a closure (book chapter "Extending rotorflow"):
//! `cargo run --release --example torque_closure`.
//!
//! A 5D body driven by a time-dependent torque fixed in the body, integrated with RKMK4.
//! The work done by the torque, ∫⟨τ, ω⟩ dt, must equal the change of kinetic energy.

use rotorflow::dynamics::{Integrator, RigidBody, Rkmk4, TorqueInput};
use rotorflow::prelude::*;

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let inertia = InertiaMap::from_principal_second_moments(&[0.5, 0.8, 1.0, 1.3, 1.7])?;
    let omega = Bivector::from_plane(5, 0, 1, 1.0)?;
    let mut body = RigidBody::from_body_velocity(inertia, Rotor::identity(5), &omega)?;

    // Any `Fn(&TorqueInput) -> Bivector` is a torque: here a pulsed torque in the e1∧e3 plane
    // of the body plus a weak damping of the e4∧e5 component of ω.
    let torque = |input: &TorqueInput<'_>| {
        let mut tau = Bivector::from_plane(5, 0, 2, 0.3 * input.time.sin()).expect("plane");
        tau.set(3, 4, -0.1 * input.omega.get(3, 4));
        tau
    };

    let (h, steps) = (1e-3, 5_000);
    let mut integrator = Rkmk4;
    let energy0 = body.energy();
    let mut work = 0.0;
    let power = |b: &RigidBody, t: f64| {
        let omega = b.omega();
        let input = TorqueInput {
            time: t,
            attitude: b.principal_frame_attitude(),
            momentum: b.momentum(),
            omega: &omega,
        };
        torque(&input).inner(&omega) // ⟨τ, ω⟩ = dT/dt
    };
    for k in 0..steps {
        let t = k as f64 * h;
        let p0 = power(&body, t);
        integrator.step(&mut body, t, h, &torque)?;
        work += 0.5 * h * (p0 + power(&body, t + h)); // trapezoid rule
    }
    let change = body.energy() - energy0;
    println!("ΔT = {change:.9}, work ∫⟨τ, ω⟩dt = {work:.9}");
    assert!((change - work).abs() < 1e-6, "energy balance violated");
    Ok(())
}
