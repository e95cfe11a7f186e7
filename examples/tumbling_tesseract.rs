//! A 4D tesseract of unit point masses (the paper's section 4.1, half-edges 1, 1.2, 1.5, 2)
//! tumbling freely: `cargo run --release --example tumbling_tesseract`.
//!
//! Prints the body-frame angular velocity along the way and the drift of every invariant
//! for the Strang and Yoshida splittings and RK4.

use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::trajectory::even_times;
use rotorflow::dynamics::{Integrator, RigidBody, Rkmk4, Splitting, simulate};
use rotorflow::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let body = Body::cuboid_vertices(&[1.0, 1.2, 1.5, 2.0], 1.0)?;
    let inertia = InertiaMap::from_body(&body)?;
    println!(
        "tesseract: mass {}, principal moments {:?}",
        body.mass(),
        inertia.principal_second_moments().unwrap()
    );
    println!(
        "plane moments (12,13,14,23,24,34): {:?}",
        inertia.plane_moments()
    );
    // A double rotation, mostly in e12 and e34, slightly off the principal planes.
    let omega = Bivector::from_components(4, &[1.0, 0.05, 0.02, 0.03, 0.04, 0.7])?;
    let start = RigidBody::from_body_velocity(inertia, Rotor::identity(4), &omega)?;
    let times = even_times(100.0, 6);
    let mut integrators: Vec<Box<dyn Integrator>> = vec![
        Box::new(Splitting::strang()),
        Box::new(Splitting::yoshida4()),
        Box::new(Rkmk4),
    ];
    for integ in integrators.iter_mut() {
        let traj = simulate(&start, integ.as_mut(), &Free, 0.01, &times)?;
        println!("\n{} (h = 0.01, {} steps):", integ.name(), traj.steps());
        for s in traj.samples() {
            println!("  t = {:6.1}  ω = {:.4}", s.time, s.omega);
        }
        let d = traj.drift();
        println!(
            "  max drift: energy {:.2e}, Casimirs {:.2e}, space L {:.2e}, |RR̃ − 1| {:.2e}",
            d.energy, d.casimirs, d.space_momentum, d.attitude
        );
    }
    Ok(())
}
