//! The 3D intermediate-axis flip (Dzhanibekov effect) and its predicted growth rate:
//! `cargo run --release --example intermediate_axis_flip`.

use rotorflow::dynamics::stability::growth_rate;
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::trajectory::even_times;
use rotorflow::dynamics::{RigidBody, Splitting, simulate};
use rotorflow::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // J = (1, 2, 3): classical moments I₁ = 5, I₂ = 4, I₃ = 3; the plane e13 (axis e2,
    // the intermediate one) is unstable.
    let j = [1.0, 2.0, 3.0];
    let inertia = InertiaMap::from_principal_second_moments(&j)?;
    let omega = Bivector::from_components(3, &[1e-3, 2.0, 1e-3])?; // mostly e13
    let body = RigidBody::from_body_velocity(inertia, Rotor::identity(3), &omega)?;
    let lambda = growth_rate(&j, 0, 2, 2.0);
    println!(
        "predicted e-folding rate of the flip: λ = {lambda:.6} (period of growth 1/λ = {:.3})",
        1.0 / lambda
    );
    let traj = simulate(
        &body,
        &mut Splitting::yoshida4(),
        &Free,
        0.005,
        &even_times(20.0, 41),
    )?;
    for s in traj.samples() {
        let w13 = s.omega.get(0, 2);
        let bar = "#".repeat(((w13 + 2.0) * 10.0).round().clamp(0.0, 40.0) as usize);
        println!("t = {:5.2}  ω13 = {:+.4}  {bar}", s.time, w13);
    }
    let d = traj.drift();
    println!(
        "max drift: energy {:.2e}, Casimirs {:.2e}, space L {:.2e}",
        d.energy, d.casimirs, d.space_momentum
    );
    Ok(())
}
