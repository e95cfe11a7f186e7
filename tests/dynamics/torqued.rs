//! Torqued motion: the heavy top conserves total energy and the vertical momentum; damping
//! removes energy at the predicted rate.

use crate::{rng, run};
use rotorflow::algebra::Vector;
use rotorflow::dynamics::torques::{Gravity, LinearDamping};
use rotorflow::dynamics::{RigidBody, Rkmk4, Splitting};
use rotorflow::prelude::*;

fn heavy_top(n: usize) -> (RigidBody, Gravity) {
    let j: Vec<f64> = (0..n).map(|k| 0.6 + 0.35 * k as f64).collect();
    let inertia = InertiaMap::from_principal_second_moments(&j).unwrap();
    let mut r = rng(501);
    let w = crate::random_bivector(&mut r, n, 2.0);
    let tilt = Rotor::from_plane_angle(n, 0, n - 1, 0.4).unwrap();
    let body = RigidBody::from_body_velocity(inertia, tilt, &w).unwrap();
    let mut weight = Vector::zero(n);
    weight[n - 1] = -9.81;
    let mut offset = Vector::zero(n);
    offset[n - 1] = 0.3;
    (body, Gravity { weight, offset })
}

#[test]
fn heavy_top_conserves_energy_and_vertical_momentum() {
    for n in [3, 4] {
        let (start, gravity) = heavy_top(n);
        let e0 = start.energy() + gravity.potential_energy(start.principal_frame_attitude());
        // components of L_s in planes orthogonal to gravity (not containing e_N)
        let vertical = |b: &RigidBody| -> Vec<f64> {
            let ls = b.space_momentum();
            rotorflow::algebra::pairs(n)
                .zip(ls.as_slice())
                .filter(|((_, j), _)| *j != n - 1)
                .map(|(_, &c)| c)
                .collect()
        };
        let v0 = vertical(&start);
        for (name, integ) in [
            (
                "strang",
                &mut Splitting::strang() as &mut dyn rotorflow::dynamics::Integrator,
            ),
            ("rk4", &mut Rkmk4),
        ] {
            let mut body = start.clone();
            run(&mut body, integ, &gravity, 1e-3, 5000);
            let e = body.energy() + gravity.potential_energy(body.principal_frame_attitude());
            // Strang: O(h²), measured ≤ 7.4e-8 = 0.074·h² (n = 4), bound 3× that; RK4: O(h⁴)
            // truncation (~1e-14 measured) is below round-off, bound one ε per step.
            let bound = if name == "strang" {
                2.2e-7
            } else {
                5000.0 * f64::EPSILON
            };
            assert!(
                (e - e0).abs() < bound * e0.abs(),
                "{name} n={n}: {e} vs {e0}"
            );
            for (a, b) in vertical(&body).iter().zip(&v0) {
                assert!((a - b).abs() < 1e-9, "{name} n={n}: {a} vs {b}");
            }
            // the torque is not trivial: the tilted plane's momentum did change
            assert!((&body.space_momentum() - &start.space_momentum()).max_abs() > 1e-3);
        }
    }
}

#[test]
fn damped_body_loses_energy_at_the_predicted_rate() {
    // dT/dt = ⟨ω, τ⟩ = −c⟨ω, ω⟩: for a steady rotation in a principal plane with moment I,
    // ω(t) = ω₀ e^{−ct/I}, T(t) = T₀ e^{−2ct/I}.
    let c = 0.3;
    let n = 4;
    let inertia = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0, 4.0]).unwrap();
    let w = Bivector::from_plane(n, 1, 3, 1.5).unwrap();
    let moment = 2.0 + 4.0;
    let start = RigidBody::from_body_velocity(inertia, Rotor::identity(n), &w).unwrap();
    let t = 5.0;
    for integ in [
        &mut Rkmk4 as &mut dyn rotorflow::dynamics::Integrator,
        &mut Splitting::strang(),
    ] {
        let mut body = start.clone();
        run(&mut body, integ, &LinearDamping(c), 1e-3, 5000);
        let expected = start.energy() * (-2.0 * c * t / moment).exp();
        assert!(
            (body.energy() - expected).abs() < 1e-6 * expected,
            "{} vs {expected}",
            body.energy()
        );
    }
}
