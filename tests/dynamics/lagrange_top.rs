//! The N-dimensional Lagrange top: the body-frame momentum in the planes orthogonal to the
//! symmetry axis is conserved (`LagrangeTop::spin`); Runge–Kutta methods keep it to
//! round-off, the splitting to its order; asymmetric tops are refused.

use crate::{rng, run};
use rotorflow::algebra::Vector;
use rotorflow::dynamics::torques::Gravity;
use rotorflow::dynamics::{
    Dop853, Dopri5, DynamicsError, Integrator, LagrangeTop, Midpoint, RigidBody, Rkmk4, Splitting,
};
use rotorflow::prelude::*;

/// A tilted, spinning Lagrange top in N dimensions: J = (a, …, a, b) with the axis e_N, the
/// centre of mass 0.3 up the axis, gravity along −e_(N−1) in space (so that the tilt matters).
fn lagrange_top(n: usize, seed: u64) -> (RigidBody, Gravity) {
    let mut j = vec![1.1; n];
    j[n - 1] = 0.35;
    let inertia = InertiaMap::from_principal_second_moments(&j).unwrap();
    let mut r = rng(seed);
    let w = crate::random_bivector(&mut r, n, 1.5);
    let tilt = Rotor::from_plane_angle(n, n - 2, n - 1, 0.5).unwrap();
    let body = RigidBody::from_body_velocity(inertia, tilt, &w).unwrap();
    let mut weight = Vector::zero(n);
    weight[n - 2] = -9.81;
    let mut offset = Vector::zero(n);
    offset[n - 1] = 0.3;
    (body, Gravity { weight, offset })
}

fn energy(body: &RigidBody, gravity: &Gravity) -> f64 {
    body.energy() + gravity.potential_energy(body.principal_frame_attitude())
}

/// 3D regression (Lagrange's case): with J = (a, a, b), axis e₃, the spin about the axis,
/// L₁₂ = 2a ω₁₂, stays constant while the top nutates; the other components do not.
#[test]
fn the_3d_lagrange_top_keeps_its_spin_about_the_axis() {
    let (start, gravity) = lagrange_top(3, 7);
    let top = LagrangeTop::new(&start, &gravity).unwrap();
    assert_eq!(top.axis(), 2);
    let spin0 = top.spin(&start);
    assert_eq!(spin0.as_slice()[1..], [0.0, 0.0]);
    assert!(spin0.as_slice()[0].abs() > 0.1);
    assert_eq!(spin0.as_slice()[0], start.momentum().as_slice()[0]);
    let mut body = start.clone();
    run(&mut body, &mut Rkmk4, &gravity, 1e-3, 5000);
    let spin = top.spin(&body);
    assert!((spin.as_slice()[0] - spin0.as_slice()[0]).abs() <= 1e-14);
    // ω₁₂ = L₁₂ / (J₁ + J₂) with J₁ = J₂ = 1.1.
    assert!((body.omega().as_slice()[0] - spin0.as_slice()[0] / 2.2).abs() <= 1e-14);
    // The torque turned the other components by O(1).
    let moved = (body.momentum() - start.momentum()).max_abs();
    assert!(moved > 0.1, "{moved}");
}

/// N = 3, 4, 5: RKMK4, Dopri5, Dop853 and the implicit midpoint rule keep every component of
/// L₀ to round-off over 2000 steps; Strang keeps it only to O(h²) (the error falls by 4 when
/// h halves) while it keeps the energy bounded.
#[test]
fn runge_kutta_methods_keep_the_lagrange_integral_and_the_splitting_to_its_order() {
    let mut cases = 0;
    for n in [3usize, 4, 5] {
        let (start, gravity) = lagrange_top(n, 11 + n as u64);
        let top = LagrangeTop::new(&start, &gravity).unwrap();
        let spin0 = top.spin(&start);
        let scale = start.momentum().max_abs();
        let drift = |body: &RigidBody| (&top.spin(body) - &spin0).max_abs() / scale;
        let mut integrators: Vec<(&str, Box<dyn Integrator>)> = vec![
            ("rk4", Box::new(Rkmk4)),
            ("dopri5", Box::new(Dopri5::new(1e-10, 1e-12))),
            ("dop853", Box::new(Dop853::new(1e-10, 1e-12).unwrap())),
            ("midpoint", Box::new(Midpoint::default())),
        ];
        for (name, integrator) in integrators.iter_mut() {
            let mut body = start.clone();
            run(&mut body, integrator.as_mut(), &gravity, 2e-3, 2000);
            let d = drift(&body);
            eprintln!("N = {n} {name}: L₀ drift {d:.1e}");
            assert!(d <= 1e-13, "{name}, N = {n}: L₀ drifted by {d:e}");
            let moved = (body.momentum() - start.momentum()).max_abs() / scale;
            assert!(moved > 1e-2, "{name}, N = {n}: the torque did nothing");
            cases += 1;
        }
        // Strang: the plane flows e_i ∧ e_N turn L₀ into L₁; the error is of second order.
        let strang_drift = |h: f64| {
            let mut body = start.clone();
            let steps = (1.0 / h).round() as usize;
            run(&mut body, &mut Splitting::strang(), &gravity, h, steps);
            let e = (energy(&body, &gravity) - energy(&start, &gravity)).abs();
            (drift(&body), e)
        };
        let (coarse, e_coarse) = strang_drift(4e-3);
        let (fine, _) = strang_drift(2e-3);
        let ratio = coarse / fine;
        eprintln!("N = {n} strang: L₀ drift {coarse:.1e} (h = 4e-3), {fine:.1e} (h = 2e-3)");
        assert!(
            coarse > 1e-9,
            "N = {n}: Strang keeps L₀ better than its order ({coarse:e})"
        );
        assert!(
            (3.0..5.5).contains(&ratio),
            "N = {n}: Strang L₀ ratio {ratio}"
        );
        assert!(e_coarse < 1e-3 * energy(&start, &gravity).abs().max(1.0));
        cases += 1;
    }
    assert_eq!(cases, 15);
}

/// An asymmetric body, an offset off the axis and a general inertia map are refused with
/// the reason.
#[test]
fn tops_without_the_symmetry_are_refused() {
    let (body, gravity) = lagrange_top(4, 3);
    let mut off_axis = gravity.clone();
    off_axis.offset[0] = 0.01;
    let err = LagrangeTop::new(&body, &off_axis).unwrap_err();
    assert!(
        matches!(err, DynamicsError::NotALagrangeTop { .. }),
        "{err}"
    );
    assert!(err.to_string().contains("off the axis e4"), "{err}");

    let asymmetric = RigidBody::from_body_velocity(
        InertiaMap::from_principal_second_moments(&[1.1, 1.2, 1.1, 0.35]).unwrap(),
        Rotor::identity(4),
        &Bivector::zero(4),
    )
    .unwrap();
    let err = LagrangeTop::new(&asymmetric, &gravity).unwrap_err();
    assert!(err.to_string().contains("differ off the axis"), "{err}");

    let mut nowhere = gravity.clone();
    nowhere.offset = Vector::zero(4);
    assert!(matches!(
        LagrangeTop::new(&body, &nowhere),
        Err(DynamicsError::NotALagrangeTop { .. })
    ));
    let mut wrong_dim = gravity;
    wrong_dim.offset = Vector::zero(3);
    assert!(LagrangeTop::new(&body, &wrong_dim).is_err());

    // A sphere (all moments equal) is symmetric about the axis of its offset.
    let sphere = RigidBody::from_body_velocity(
        InertiaMap::from_principal_second_moments(&[0.7; 4]).unwrap(),
        Rotor::identity(4),
        &Bivector::zero(4),
    )
    .unwrap();
    let mut sideways = nowhere;
    sideways.offset[1] = -0.2;
    assert_eq!(LagrangeTop::new(&sphere, &sideways).unwrap().axis(), 1);
}
