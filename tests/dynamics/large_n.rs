//! Large N: the attitude kept as an SO(N) matrix above N = 4 (fixed-size storage up to
//! N = 8, dense above).

use super::{attitude_distance, random_bivector, rng, run};
use rand::Rng;
use rotorflow::dynamics::torques::{Free, Gravity};
use rotorflow::dynamics::{
    Attitude, Dopri5, Integrator, Invariants, Midpoint, RigidBody, Rkmk4, Splitting, TorqueInput,
};
use rotorflow::prelude::*;

/// `exp_skew_matrix` is the matrix of the rotor exponential, exp(B/2) ↔ expm([B]), including
/// isoclinic (degenerate) and rank-deficient bivectors.
#[test]
fn exp_skew_matrix_matches_rotor_exponential() {
    let mut r = rng(91);
    for n in 2..=9 {
        for case in 0..6 {
            let b = match case {
                // isoclinic: equal angles in e12 and e34 (and e56 …)
                0 if n >= 4 => {
                    let mut c = Bivector::zero(n);
                    for k in 0..n / 2 {
                        c.set(2 * k, 2 * k + 1, 1.3);
                    }
                    c
                }
                1 => Bivector::from_plane(n, 0, n - 1, 3.1).unwrap(),
                _ => random_bivector(&mut r, n, 2.0),
            };
            let q = b.exp_skew_matrix();
            let expected = (&b * 0.5).exp().to_matrix();
            let err = (&q - &expected).amax();
            assert!(err < 1e-13, "N = {n}, case {case}: {err:e}");
        }
    }
}

/// At N = 32 the exponential is orthogonal with det +1 and inverts under B → −B.
#[test]
fn exp_skew_matrix_is_a_rotation_at_n32() {
    let mut r = rng(92);
    let b = random_bivector(&mut r, 32, 1.0);
    let q = b.exp_skew_matrix();
    let qt = (&b * -1.0).exp_skew_matrix();
    let id = nalgebra::DMatrix::<f64>::identity(32, 32);
    assert!((q.transpose() * &q - &id).amax() < 1e-13);
    assert!((&q * &qt - &id).amax() < 1e-13);
    assert!((q.determinant() - 1.0).abs() < 1e-12);
}

/// A motion in the first 4 axes of a 10-D body (ω, L in those planes only) is the 4-D motion:
/// the matrix attitude (N = 10) restricted to the 4×4 block equals the rotor attitude's matrix
/// of the 4-D body, for every integrator.
#[test]
fn matrix_attitude_reproduces_rotor_attitude_of_embedded_motion() {
    let mut r = rng(93);
    let moments: Vec<f64> = (0..10).map(|_| r.gen_range(0.3..2.0)).collect();
    let l4 = random_bivector(&mut r, 4, 1.0);
    let mut l10 = Bivector::zero(10);
    for i in 0..4 {
        for j in i + 1..4 {
            l10.set(i, j, l4.get(i, j));
        }
    }
    let make = |n: usize, l: &Bivector| {
        RigidBody::from_body_momentum(
            InertiaMap::from_principal_second_moments(&moments[..n]).unwrap(),
            Attitude::identity(n),
            l,
        )
        .unwrap()
    };
    let integrators: Vec<Box<dyn Fn() -> Box<dyn Integrator>>> = vec![
        Box::new(|| Box::new(Rkmk4)),
        Box::new(|| Box::new(Splitting::strang())),
        Box::new(|| Box::new(Splitting::yoshida4())),
        Box::new(|| Box::new(Midpoint::default())),
        Box::new(|| Box::new(Dopri5::new(1e-10, 1e-10))),
    ];
    for make_integ in &integrators {
        let (mut small, mut big) = (make(4, &l4), make(10, &l10));
        assert!(
            small.principal_frame_attitude().as_rotor().is_some()
                && big.principal_frame_attitude().as_rotor().is_none()
        );
        run(&mut small, make_integ().as_mut(), &Free, 0.01, 200);
        run(&mut big, make_integ().as_mut(), &Free, 0.01, 200);
        let qs = small.principal_frame_attitude().to_matrix();
        let qb = big.principal_frame_attitude().to_matrix();
        let name = make_integ().name();
        let err = (qb.view((0, 0), (4, 4)) - &qs).amax();
        assert!(err < 1e-12, "{name}: attitude block differs by {err:e}");
        for k in 4..10 {
            assert!((qb[(k, k)] - 1.0).abs() < 1e-14, "{name}: axis {k} moved");
        }
        let dl = (big.momentum().get(0, 1) - small.momentum().get(0, 1)).abs();
        assert!(dl < 1e-12, "{name}: momentum differs by {dl:e}");
    }
}

/// N = 16 and 32: the splitting keeps the Casimirs and space momentum, the matrix stays
/// orthogonal, and the rotor is available on demand up to N = 16.
#[test]
fn large_n_free_body_keeps_invariants() {
    let mut r = rng(94);
    for n in [16usize, 32] {
        let moments: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
        let attitude =
            Attitude::from_matrix(&random_bivector(&mut r, n, 0.3).exp_skew_matrix()).unwrap();
        let mut body = RigidBody::from_body_momentum(
            InertiaMap::from_principal_second_moments(&moments).unwrap(),
            attitude,
            &random_bivector(&mut r, n, 1.0),
        )
        .unwrap();
        let start = Invariants::of(&body);
        run(&mut body, &mut Splitting::strang(), &Free, 0.01, 500);
        let now = Invariants::of(&body);
        let drift = now.drift_from(&start);
        assert!(
            drift.casimirs < 1e-12,
            "N = {n}: Casimirs {:e}",
            drift.casimirs
        );
        assert!(
            drift.space_momentum < 1e-12,
            "N = {n}: L_s {:e}",
            drift.space_momentum
        );
        // Strang keeps a modified energy: |ΔT|/T = O(h²), measured ≤ 5.4e-6 = 0.054·h²
        // (N = 32); bound 3× that.
        assert!(drift.energy < 1.7e-5, "N = {n}: energy {:e}", drift.energy);
        assert!(
            now.attitude_error < 1e-13,
            "N = {n}: |QᵀQ − 1| = {:e}",
            now.attitude_error
        );
        let rotor = body.principal_frame_attitude().to_rotor();
        assert_eq!(rotor.is_ok(), n <= 16, "N = {n}");
        if let Ok(rotor) = rotor {
            let err = (rotor.to_matrix() - body.principal_frame_attitude().to_matrix()).amax();
            assert!(err < 1e-12, "N = {n}: rotor on demand differs by {err:e}");
        }
    }
}

/// Torques see the matrix attitude: a 10-D heavy top conserves T + V and the space momentum
/// in the planes orthogonal to gravity.
#[test]
fn heavy_top_at_n10_conserves_energy_and_horizontal_momentum() {
    let n = 10;
    let moments: Vec<f64> = (0..n).map(|k| 0.6 + 0.1 * k as f64).collect();
    let mut r = rng(95);
    let mut body = RigidBody::from_body_momentum(
        InertiaMap::from_principal_second_moments(&moments).unwrap(),
        Attitude::identity(n),
        &random_bivector(&mut r, n, 1.0),
    )
    .unwrap();
    let gravity = Gravity {
        weight: Vector::basis(n, n - 1) * -1.0,
        offset: Vector::basis(n, 0) * 0.5,
    };
    let total = |b: &RigidBody| b.energy() + gravity.potential_energy(b.principal_frame_attitude());
    let e0 = total(&body);
    let ls0 = body.space_momentum();
    run(&mut body, &mut Rkmk4, &gravity, 1e-3, 2000);
    let ls = body.space_momentum();
    assert!((total(&body) - e0).abs() < 1e-9 * e0.abs().max(1.0));
    for i in 0..n - 1 {
        for j in i + 1..n - 1 {
            assert!(
                (ls.get(i, j) - ls0.get(i, j)).abs() < 1e-9,
                "plane ({i}, {j})"
            );
        }
    }
}

/// A state that overflows is reported as an error by every integrator and every attitude
/// form (rotor, fixed-size matrix, dynamic matrix), never returned as NaN or a hang; the
/// splitting, which only rotates, keeps huge states finite.
#[test]
fn overflowing_state_is_reported_not_propagated() {
    use rotorflow::dynamics::DynamicsError;
    for n in [3usize, 6, 10] {
        let moments: Vec<f64> = (0..n).map(|k| 1e-3 + k as f64).collect();
        let l: Vec<f64> = (0..n * (n - 1) / 2)
            .map(|k| 1e300 * (k as f64 + 1.0))
            .collect();
        let body = RigidBody::from_body_momentum(
            InertiaMap::from_principal_second_moments(&moments).unwrap(),
            Attitude::identity(n),
            &Bivector::from_components(n, &l).unwrap(),
        )
        .unwrap();
        let mut integrators: Vec<Box<dyn Integrator>> = vec![
            Box::new(Rkmk4),
            Box::new(Splitting::strang()),
            Box::new(Midpoint::default()),
            Box::new(Dopri5::new(1e-8, 1e-8).with_max_steps(50)),
        ];
        for integ in integrators.iter_mut() {
            let mut b = body.clone();
            let result = integ.step(&mut b, 0.0, 1.0, &Free);
            match &result {
                // The splitting only rotates: huge but finite states stay finite.
                Ok(()) => assert!(
                    b.momentum().as_slice().iter().all(|x| x.is_finite())
                        && b.principal_frame_attitude().is_finite(),
                    "N = {n}, {}: Ok with a non-finite state",
                    integ.name()
                ),
                Err(e) => assert!(
                    matches!(
                        e,
                        DynamicsError::NonFinite { .. }
                            | DynamicsError::SolverDidNotConverge { .. }
                            | DynamicsError::StepTooSmall { .. }
                            | DynamicsError::TooManySteps { .. }
                    ),
                    "N = {n}, {}: {e:?}",
                    integ.name()
                ),
            }
            if integ.name() == "rk4" {
                assert!(result.is_err(), "N = {n}: RK4 must overflow here");
            }
        }
    }
}

/// Large rotations (angles up to 1e6): `exp_skew_matrix` goes plane by plane and stays
/// orthogonal to round-off, and agrees with the rotor exponential.
#[test]
fn exp_skew_matrix_of_large_rotations_stays_orthogonal() {
    let mut r = rng(96);
    for n in [4usize, 7, 12] {
        for scale in [10.0, 1e3, 1e6] {
            let b = random_bivector(&mut r, n, scale);
            let q = b.exp_skew_matrix();
            let id = nalgebra::DMatrix::<f64>::identity(n, n);
            let orth = (q.transpose() * &q - id).amax();
            assert!(
                orth < 1e-14,
                "N = {n}, scale {scale:e}: |QᵀQ − 1| = {orth:e}"
            );
            if n <= 8 {
                let expected = (&b * 0.5).exp().to_matrix();
                let err = (&q - &expected).amax();
                assert!(err < 1e-14 * scale, "N = {n}, scale {scale:e}: {err:e}");
            }
        }
    }
}

/// Above N = 8 a free RK4 step runs on dense matrices: ω × L as (ω²)ᵢⱼ(Jⱼ − Jᵢ) for a
/// physical body, C − Cᵀ (C = ωL) for a general diagonal map, the exponential by its Taylor
/// polynomial. It must agree with the bivector path of the same formulas, which a torque
/// that is zero without saying so (`is_zero() == false`) takes, and keep Q orthogonal.
#[test]
fn dense_free_rk4_matches_the_bivector_path() {
    let silent_zero = |input: &TorqueInput<'_>| Bivector::zero(input.momentum.dim());
    let mut r = rng(95);
    for n in [9usize, 12, 16, 24] {
        let moments: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
        let physical = InertiaMap::from_principal_second_moments(&moments).unwrap();
        // A diagonal map that is not of the form Jᵢ + Jⱼ.
        let k = n * (n - 1) / 2;
        let planes: Vec<f64> = (0..k).map(|_| r.gen_range(0.5..3.0)).collect();
        let general = InertiaMap::from_plane_moments(&planes).unwrap();
        for inertia in [physical, general] {
            let attitude =
                Attitude::from_matrix(&random_bivector(&mut r, n, 0.3).exp_skew_matrix()).unwrap();
            let l = random_bivector(&mut r, n, 2.0);
            let start = RigidBody::from_body_momentum(inertia, attitude, &l).unwrap();
            let (mut dense, mut general_path) = (start.clone(), start.clone());
            run(&mut dense, &mut Rkmk4, &Free, 0.02, 50);
            run(&mut general_path, &mut Rkmk4, &silent_zero, 0.02, 50);
            let dl = (dense.momentum() - general_path.momentum()).max_abs();
            let dq = attitude_distance(
                dense.principal_frame_attitude(),
                general_path.principal_frame_attitude(),
            );
            assert!(
                dl < 1e-13 && dq < 1e-13,
                "N = {n}: |ΔL| = {dl:e}, |ΔQ| = {dq:e}"
            );
            // And the step moved: the comparison is not between two unchanged states.
            assert!(
                (dense.momentum() - start.momentum()).max_abs() > 1e-3,
                "N = {n}"
            );
            assert!(
                dense.principal_frame_attitude().unit_error() < 1e-14,
                "N = {n}"
            );
        }
    }
}

/// Attitudes compose as their matrices at every N (rotors up to 4, nalgebra's fixed-size
/// product at 5 … 8, the column loop above).
#[test]
fn attitudes_compose_as_their_matrices() {
    let mut r = rng(97);
    for n in 2..=10 {
        let a = Attitude::from(&Rotor::from_rotation_bivector(&random_bivector(
            &mut r, n, 1.5,
        )));
        let b = Attitude::from(&Rotor::from_rotation_bivector(&random_bivector(
            &mut r, n, 1.5,
        )));
        let err = (a.compose(&b).to_matrix() - a.to_matrix() * b.to_matrix()).amax();
        assert!(err < 1e-14, "N = {n}: {err:e}");
    }
}
