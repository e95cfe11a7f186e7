//! A 4D spacecraft turned by reaction wheels (book chapter "Extending rotorflow"):
//! `cargo run --release --example reaction_wheels_4d`.
//!
//! The craft (a solid 4D cuboid) starts at rest. Two reaction wheels, spinning in the body
//! planes e₁₂ and e₃₄, are spun up and back down by a controller; the craft is a gyrostat
//! whose rotor momentum h(t) the controller sets between steps. The total momentum stays
//! zero, so the body turns the other way while the wheels run, and stops when they stop: a
//! double rotation (in two planes at once, which no 3D craft can make) with nothing thrown
//! overboard.

use rotorflow::dynamics::{Integrator, RigidBody, Rkmk4, torques::Free};
use rotorflow::inertia::Body;
use rotorflow::prelude::*;

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let craft = Body::solid_cuboid(&[1.0, 0.75, 0.6, 0.5], 1.0)?.with_mass(50.0)?;
    let inertia = InertiaMap::from_body(&craft)?;
    let mut body = RigidBody::from_body_velocity(inertia, Rotor::identity(4), &Bivector::zero(4))?
        .with_gyrostatic_momentum(&Bivector::zero(4))?;

    // The controller: each wheel's momentum ramps up for 5 s, holds, and ramps down, in a
    // profile with a continuous rate (so the craft turns smoothly and ends at rest).
    let profile = |t: f64, t_end: f64, peak: f64| {
        let s = (t / t_end).clamp(0.0, 1.0);
        peak * (std::f64::consts::PI * s).sin().powi(2)
    };
    let (h, steps) = (1e-3, 20_000);
    let t_end = h * steps as f64;
    let mut worst_space = 0.0f64;
    let mut integrator = Rkmk4;
    for k in 0..steps {
        let t = k as f64 * h;
        let mut wheels = Bivector::zero(4);
        wheels.set(0, 1, profile(t, t_end, 30.0));
        wheels.set(2, 3, profile(t, t_end, -12.0));
        body.set_gyrostatic_momentum(&wheels)?;
        integrator.step(&mut body, t, h, &Free)?;
        worst_space = worst_space.max(body.space_momentum().max_abs());
    }
    body.set_gyrostatic_momentum(&Bivector::zero(4))?;

    // The turn, read from the final attitude as a rotation bivector (one angle per plane).
    let turn = body.body_axes_attitude().to_rotor()?.rotation_bivector();
    println!(
        "after {t_end} s: rotation angles e12 {:.4}, e34 {:.4} rad",
        turn.get(0, 1),
        turn.get(2, 3)
    );
    println!("largest |L| in space during the slew: {worst_space:.1e} (the total stays zero)");
    println!("final |ω|: {:.1e}", body.omega().norm());
    assert!(worst_space < 1e-12, "the wheels only move momentum around");
    assert!(
        body.omega().norm() < 1e-12,
        "the craft stops when the wheels stop"
    );
    assert!(
        turn.get(0, 1).abs() > 0.1 && turn.get(2, 3).abs() > 0.1,
        "it turned in both planes"
    );
    Ok(())
}
