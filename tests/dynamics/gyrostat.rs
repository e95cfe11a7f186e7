//! Gyrostats: bodies carrying internal rotors of constant relative momentum h. The free
//! gyrostat (Zhukovsky–Volterra) keeps |L|², every Casimir of L and the energy ½⟨ω, I(ω)⟩;
//! it equals an ordinary body of momentum L − h under the torque ω × h; the integrators whose
//! formulas assume h = 0 refuse it.

use crate::{rng, run};
use rotorflow::dynamics::{
    Dop853, Dopri5, DynamicsError, FreeBody3, Integrator, Invariants, Midpoint, MoserVeselov,
    RigidBody, Rkmk4, Splitting, TorqueInput, torques::Free,
};
use rotorflow::prelude::*;

fn gyrostat(n: usize, seed: u64) -> (RigidBody, Bivector) {
    let mut r = rng(seed);
    let j: Vec<f64> = (0..n).map(|k| 0.5 + 0.4 * k as f64).collect();
    let inertia = InertiaMap::from_principal_second_moments(&j).unwrap();
    let w = crate::random_bivector(&mut r, n, 1.0);
    let h = crate::random_bivector(&mut r, n, 0.8);
    let attitude = Rotor::from_rotation_bivector(&crate::random_bivector(&mut r, n, 1.0));
    let rigid = RigidBody::from_body_velocity(inertia, attitude, &w).unwrap();
    // The total momentum I(ω) + h: the body keeps ω, the rotors add h.
    let total = rigid.momentum() + &h;
    let body = RigidBody::from_body_momentum(
        rigid.inertia().clone(),
        rigid.principal_frame_attitude().clone(),
        &total,
    )
    .unwrap()
    .with_gyrostatic_momentum(&h)
    .unwrap();
    (body, h)
}

/// ω = I⁻¹(L − h), the energy ½⟨ω, I(ω)⟩ and no Manakov integrals for a gyrostat.
#[test]
fn a_gyrostat_turns_with_the_momentum_its_rotors_do_not_carry() {
    let (body, h) = gyrostat(4, 1);
    let rigid_part = body.momentum() - &h;
    let omega = body.inertia().apply_inverse(&rigid_part);
    assert_eq!(body.omega(), omega);
    assert!((body.energy() - 0.5 * omega.inner(&rigid_part)).abs() <= 1e-15);
    assert_eq!(body.gyrostatic_momentum(), Some(&h));
    assert!(Invariants::of(&body).manakov.is_empty());
    // A zero h is an ordinary body again.
    let plain = body
        .clone()
        .with_gyrostatic_momentum(&Bivector::zero(4))
        .unwrap();
    assert_eq!(plain.gyrostatic_momentum(), None);
    assert!(!Invariants::of(&plain).manakov.is_empty());
    // Another dimension, or an h that makes ω overflow: refused, the body unchanged.
    let mut b = body.clone();
    assert!(b.set_gyrostatic_momentum(&Bivector::zero(3)).is_err());
    let huge = Bivector::from_components(4, &[f64::MAX, -f64::MAX, 0.0, 0.0, 0.0, 0.0]).unwrap();
    assert!(b.set_gyrostatic_momentum(&huge).is_err());
    assert_eq!(b, body);
}

/// Zhukovsky–Volterra: the free gyrostat keeps every Casimir of L, the energy and the
/// space-frame momentum. Dopri5 and Dop853 to their tolerance, RKMK4 to O(h⁴), the
/// implicit midpoint rule (both invariants are quadratic) to its solver tolerance (its
/// attitude update, as for a rigid body, keeps the space-frame momentum only to O(h²)).
#[test]
fn the_free_gyrostat_keeps_the_zhukovsky_volterra_integrals() {
    let mut cases = 0;
    for n in [3usize, 4, 5] {
        let (start, _) = gyrostat(n, 10 + n as u64);
        let i0 = Invariants::of(&start);
        let mut integrators: Vec<(&str, Box<dyn Integrator>, f64)> = vec![
            ("rk4", Box::new(Rkmk4), 1e-9),
            ("dopri5", Box::new(Dopri5::new(1e-12, 1e-14)), 1e-10),
            (
                "dop853",
                Box::new(Dop853::new(1e-12, 1e-14).unwrap()),
                1e-10,
            ),
            ("midpoint", Box::new(Midpoint::default()), 1e-12),
        ];
        for (name, integrator, bound) in integrators.iter_mut() {
            let mut body = start.clone();
            run(&mut body, integrator.as_mut(), &Free, 0.01, 1000);
            let d = Invariants::of(&body).drift_from(&i0);
            eprintln!(
                "N = {n} {name}: energy {:.1e}, Casimirs {:.1e}, space L {:.1e}",
                d.energy, d.casimirs, d.space_momentum
            );
            assert!(d.energy <= *bound, "{name}, N = {n}: energy {:e}", d.energy);
            if *name == "midpoint" && n > 4 {
                // Above 4D the midpoint rule keeps the quadratic |L|² but not the higher
                // Casimirs (as for a rigid body).
                let (a, b) = (
                    body.momentum().norm_squared(),
                    start.momentum().norm_squared(),
                );
                assert!((a - b).abs() <= *bound * b, "midpoint, N = {n}: |L|²");
            } else {
                assert!(
                    d.casimirs <= *bound,
                    "{name}, N = {n}: Casimirs {:e}",
                    d.casimirs
                );
            }
            if *name != "midpoint" {
                assert!(d.space_momentum <= 1e-9, "{name}, N = {n}: space L");
            }
            // The rotors matter: the same body without them ends elsewhere.
            let mut rigid = start.clone();
            rigid.set_gyrostatic_momentum(&Bivector::zero(n)).unwrap();
            run(&mut rigid, integrator.as_mut(), &Free, 0.01, 1000);
            assert!((rigid.momentum() - body.momentum()).max_abs() > 1e-2);
            cases += 1;
        }
    }
    assert_eq!(cases, 12);
}

/// An independent formulation: the rigid part L' = L − h of a gyrostat moves as an ordinary
/// body under the torque ω × h (dL'/dt = dL/dt = ω × (L' + h)). Both, integrated by Dop853
/// at a tight tolerance, agree in L and attitude; in 3D this pins the sign of the coupling.
#[test]
fn a_gyrostat_is_a_rigid_body_under_the_torque_omega_cross_h() {
    for n in [3usize, 4, 6] {
        let (gyro, h) = gyrostat(n, 40 + n as u64);
        let rigid_part = gyro.momentum() - &h;
        let mut plain = RigidBody::from_body_momentum(
            gyro.inertia().clone(),
            gyro.principal_frame_attitude().clone(),
            &rigid_part,
        )
        .unwrap();
        let coupling = |input: &TorqueInput<'_>| input.omega.commutator(&h);
        let mut g = gyro.clone();
        run(
            &mut g,
            &mut Dop853::new(1e-13, 1e-15).unwrap(),
            &Free,
            0.05,
            40,
        );
        run(
            &mut plain,
            &mut Dop853::new(1e-13, 1e-15).unwrap(),
            &coupling,
            0.05,
            40,
        );
        let dl = (&(g.momentum() - &h) - plain.momentum()).max_abs();
        let dq = (g.principal_frame_attitude().to_matrix()
            - plain.principal_frame_attitude().to_matrix())
        .amax();
        assert!(dl <= 1e-10 && dq <= 1e-10, "N = {n}: ΔL {dl:e}, ΔQ {dq:e}");
        assert!(
            (g.momentum() - gyro.momentum()).max_abs() > 1e-2,
            "N = {n}: no motion"
        );
    }
}

/// A steady gyrostat in 3D: the rotors' momentum along the body's spin (L ∥ ω, both in the
/// plane e₁₂) gives ω × L = 0, so nothing moves but the attitude.
#[test]
fn a_3d_gyrostat_spinning_about_its_rotor_axis_is_steady() {
    let inertia = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0]).unwrap();
    let w = Bivector::from_plane(3, 0, 1, 0.7).unwrap();
    let h = Bivector::from_plane(3, 0, 1, 5.0).unwrap();
    let rigid = RigidBody::from_body_velocity(inertia, Rotor::identity(3), &w).unwrap();
    let total = rigid.momentum() + &h;
    let mut body =
        RigidBody::from_body_momentum(rigid.inertia().clone(), Rotor::identity(3), &total)
            .unwrap()
            .with_gyrostatic_momentum(&h)
            .unwrap();
    assert!((body.omega() - w.clone()).max_abs() <= 1e-15);
    run(&mut body, &mut Rkmk4, &Free, 0.01, 500);
    assert!((body.momentum() - &total).max_abs() <= 1e-14);
    assert!((body.omega() - w).max_abs() <= 1e-14);
}

/// The splittings, Moser–Veselov, the fixed-size bodies and the closed forms assume h = 0:
/// they refuse a gyrostat with `DynamicsError::Gyrostat`.
#[test]
fn integrators_that_assume_a_rigid_body_refuse_a_gyrostat() {
    let (body, _) = gyrostat(3, 5);
    let refuse = |r: Result<(), DynamicsError>| {
        assert!(matches!(r, Err(DynamicsError::Gyrostat { .. })), "{r:?}");
    };
    let mut b = body.clone();
    refuse(Splitting::strang().step(&mut b, 0.0, 0.01, &Free));
    refuse(Splitting::yoshida4().step(&mut b, 0.0, 0.01, &Free));
    refuse(MoserVeselov::new().step(&mut b, 0.0, 0.01, &Free));
    assert_eq!(b, body, "a refused step leaves the body");
    refuse(FreeBody3::from_rigid_body(&body).map(|_| ()));
    refuse(body.exact_solution().map(|_| ()));
    let message = Splitting::strang()
        .step(&mut b, 0.0, 0.01, &Free)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("rk4, dopri5, dop853 or midpoint"),
        "{message}"
    );
}
