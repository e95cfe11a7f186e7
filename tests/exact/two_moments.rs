//! The closed form for bodies with at most two distinct principal values (any N) and for
//! steady rotations, against the adaptive Dopri5 at rtol = atol = 1e-13 over ≥ 100 periods,
//! and its invariants.
//!
//! Tolerances: agreement with Dopri5 ≤ 1e-10 (|ΔL|/|L| and max |ΔR| over the rotor
//! coefficients); invariants of the closed form ≤ 1e-13 relative (round-off of a few
//! rotor exponentials and rotations, independent of t).

use crate::{
    body_with_omega, dopri_reference, no_closed_form_reasons, random_bivector, random_rotor, rng,
    rotor_distance,
};
use rotorflow::dynamics::exact::two_moments::{TwoMomentKind, TwoMomentSolution};
use rotorflow::dynamics::{DynamicsError, Invariants, NoClosedFormReason, RigidBody};
use rotorflow::prelude::*;
use std::f64::consts::PI;

/// The fastest rate of the motion, max(|Ω|, α|L|) (|ω| for steady rotations): a "period"
/// below is 2π over it. (Over 100 periods of the *slowest* rate, up to ~900 fast periods,
/// Dopri5 at 1e-13 itself drifts by ~1e-10 in the rotor, scaling with its tolerance.)
fn fastest_rate(s: &TwoMomentSolution) -> f64 {
    let l = s.initial().momentum().norm();
    s.generator().norm().max(s.alpha() * l)
}

/// Compares the closed form with Dopri5 at `samples` times spread over `periods` periods
/// of the fastest rate; returns (max |ΔL|/|L|, max |ΔR|).
fn compare(body: &RigidBody, periods: f64, samples: usize) -> (f64, f64) {
    let exact = TwoMomentSolution::new(body).unwrap();
    let span = periods * 2.0 * PI / fastest_rate(&exact);
    let times: Vec<f64> = (1..=samples)
        .map(|k| span * k as f64 / samples as f64)
        .collect();
    let reference = dopri_reference(body, &times);
    let scale = body.momentum().norm();
    let mut el = 0.0f64;
    let mut er = 0.0f64;
    for (&t, (r, l)) in times.iter().zip(&reference) {
        el = el.max((&exact.momentum_at(t).unwrap() - l).norm() / scale);
        er = er.max(rotor_distance(&exact.attitude_at(t).unwrap(), r));
    }
    (el, er)
}

fn assert_agrees(label: &str, body: &RigidBody, periods: f64) {
    let (el, er) = compare(body, periods, 8);
    eprintln!("{label}: max |ΔL|/|L| = {el:.2e}, max |ΔR| = {er:.2e}");
    assert!(el <= 1e-10, "{label}: momentum differs by {el:e}");
    assert!(er <= 1e-10, "{label}: attitude differs by {er:e}");
}

#[test]
fn isotropic_body_matches_dopri5_n3_to_n8() {
    let mut r = rng(501);
    for n in [3, 4, 5, 6, 8] {
        let j = vec![0.7; n];
        let body = body_with_omega(
            &j,
            random_rotor(&mut r, n),
            &random_bivector(&mut r, n, 1.0),
        );
        let exact = TwoMomentSolution::new(&body).unwrap();
        assert_eq!(exact.kind(), TwoMomentKind::Isotropic);
        assert_eq!(exact.generator().max_abs(), 0.0);
        assert_agrees(&format!("isotropic N = {n}"), &body, 100.0);
    }
}

#[test]
fn two_moment_bodies_match_dopri5_n3_to_n8() {
    let mut r = rng(502);
    // (N, axes in B, a, b): one axis apart, balanced splits, b < a and b > a.
    let cases: [(usize, &[usize], f64, f64); 8] = [
        (3, &[2], 1.0, 2.5),
        (3, &[0], 1.0, 0.4),
        (4, &[3], 1.0, 2.25),
        (4, &[2, 3], 1.0, 2.25),
        (5, &[1, 3], 0.8, 2.0),
        (5, &[0, 1, 2, 3], 1.5, 0.6),
        (6, &[0, 2, 4], 1.0, 3.0),
        (8, &[1, 4, 5, 7], 0.9, 2.0),
    ];
    for (n, b_axes, a, b) in cases {
        let j: Vec<f64> = (0..n)
            .map(|i| if b_axes.contains(&i) { b } else { a })
            .collect();
        let body = body_with_omega(
            &j,
            random_rotor(&mut r, n),
            &random_bivector(&mut r, n, 1.0),
        );
        let exact = TwoMomentSolution::new(&body).unwrap();
        assert_eq!(exact.kind(), TwoMomentKind::TwoMoments);
        let (va, vb) = exact.values();
        let in_b = exact.in_b();
        for (i, &x) in j.iter().enumerate() {
            assert!((x - if in_b[i] { vb } else { va }).abs() <= 4e-16 * x);
        }
        assert_agrees(&format!("J = {j:?}"), &body, 100.0);
    }
}

#[test]
fn steady_rotations_of_a_general_body_match_dopri5() {
    let mut r = rng(503);
    // All principal values distinct; ω in principal planes with disjoint index pairs.
    type Planes = &'static [(usize, usize, f64)];
    let cases: [(usize, Planes); 5] = [
        (3, &[(0, 1, 1.3)]),
        (4, &[(0, 1, 1.1), (2, 3, 0.4)]), // 4D double rotation
        (4, &[(0, 3, 0.8), (1, 2, 0.8)]), // isoclinic
        (5, &[(0, 4, 0.9), (1, 3, -0.5)]),
        (6, &[(0, 1, 0.6), (2, 5, 1.0), (3, 4, -0.3)]),
    ];
    for (n, planes) in cases {
        let j: Vec<f64> = (0..n).map(|i| 0.5 + 0.37 * i as f64).collect();
        let mut w = Bivector::zero(n);
        for &(i, k, x) in planes {
            w.set(i, k, x);
        }
        let body = body_with_omega(&j, random_rotor(&mut r, n), &w);
        let exact = TwoMomentSolution::new(&body).unwrap();
        assert_eq!(exact.kind(), TwoMomentKind::Steady);
        // Steady rotations about middle-moment planes can be unstable: compare over 100
        // periods of the fastest plane rate, where round-off has not yet grown.
        assert_agrees(&format!("steady N = {n}, {planes:?}"), &body, 100.0);
    }
}

#[test]
fn isoclinic_rotation_off_the_basis_planes_is_steady_for_any_body() {
    // ω = θ (cos φ (e12 + e34) + sin φ (e13 − e24)): [ω]² = −θ² 1 commutes with any J.
    let (theta, phi) = (0.9_f64, 0.6_f64);
    let w = Bivector::from_components(
        4,
        &[
            theta * phi.cos(),
            theta * phi.sin(),
            0.0,
            0.0,
            -theta * phi.sin(),
            theta * phi.cos(),
        ],
    )
    .unwrap();
    let body = body_with_omega(&[0.5, 0.9, 1.4, 2.0], Rotor::identity(4), &w);
    let exact = TwoMomentSolution::new(&body).unwrap();
    assert_eq!(exact.kind(), TwoMomentKind::Steady);
    assert_agrees("isoclinic off-basis", &body, 20.0);
}

#[test]
fn closed_form_conserves_energy_casimirs_and_space_momentum() {
    let mut r = rng(504);
    let mut worst = [0.0f64; 4];
    for (n, j) in [
        (3, vec![1.0, 1.0, 2.0]),
        (4, vec![1.0, 1.0, 1.0, 4.0]),
        (4, vec![1.0, 1.0, 2.25, 2.25]),
        (5, vec![2.0, 0.5, 2.0, 0.5, 0.5]),
        (6, vec![1.0; 6]),
        (8, vec![1.0, 3.0, 1.0, 3.0, 1.0, 3.0, 3.0, 1.0]),
    ] {
        let body = body_with_omega(
            &j,
            random_rotor(&mut r, n),
            &random_bivector(&mut r, n, 1.5),
        );
        let exact = TwoMomentSolution::new(&body).unwrap();
        let reference = Invariants::of(&body);
        for t in [0.1, 1.0, 17.3, 250.0, 1.0e4, -3.7e3] {
            let at = exact.body_at(t).unwrap();
            let d = Invariants::of(&at).drift_from(&reference);
            worst[0] = worst[0].max(d.energy);
            worst[1] = worst[1].max(d.casimirs);
            worst[2] = worst[2].max(d.space_momentum);
            worst[3] = worst[3].max(d.attitude);
            if let (Some(p), Some(p0)) = (Invariants::of(&at).pfaffian, reference.pfaffian) {
                let l2 = body.momentum().norm_squared();
                assert!((p - p0).abs() <= 1e-13 * l2.powi(n as i32 / 2), "Pfaffian");
            }
        }
    }
    eprintln!(
        "invariant drifts (energy, Casimirs, L_s, rotor): {:.2e} {:.2e} {:.2e} {:.2e}",
        worst[0], worst[1], worst[2], worst[3]
    );
    for (k, &w) in worst.iter().enumerate() {
        assert!(w <= 1e-13, "invariant {k} drifts by {w:e}");
    }
}

#[test]
fn closed_form_satisfies_the_flow_by_finite_differences() {
    // dL/dt = ω × L and dR/dt = −½ R ω, central differences (h = 1e-4: error ~h² ≈ 1e-8).
    let mut r = rng(505);
    for (n, j) in [
        (4, vec![1.0, 1.0, 1.0, 3.0]),
        (5, vec![1.0, 2.0, 1.0, 2.0, 2.0]),
    ] {
        let body = body_with_omega(
            &j,
            random_rotor(&mut r, n),
            &random_bivector(&mut r, n, 1.0),
        );
        let exact = TwoMomentSolution::new(&body).unwrap();
        let h = 1e-4;
        for t in [0.0, 2.3, 40.0] {
            let l = exact.momentum_at(t).unwrap();
            let w = exact.omega_at(t).unwrap();
            assert!((&w - &body.inertia().apply_inverse(&l)).norm() < 1e-14 * w.norm().max(1.0));
            let dl = (&exact.momentum_at(t + h).unwrap() - &exact.momentum_at(t - h).unwrap())
                * (0.5 / h);
            assert!((&dl - &w.commutator(&l)).norm() < 1e-7, "dL/dt at t = {t}");
            let rp = exact.attitude_at(t + h).unwrap();
            let rm = exact.attitude_at(t - h).unwrap();
            let rt = exact.attitude_at(t).unwrap();
            // R(t+h) ≈ R(t) exp(−½ h ω): compare through the rotor one step ahead.
            let predicted = rt.compose(&Rotor::from_rotation_bivector(&(&w * h)).into());
            assert!(rotor_distance(&rp, &predicted) < 1e-7, "R at t = {t}");
            let back = rt.compose(&Rotor::from_rotation_bivector(&(&w * -h)).into());
            assert!(rotor_distance(&rm, &back) < 1e-7, "R at t = {t}");
        }
    }
}

#[test]
fn symmetric_top_3d_precesses_at_the_classical_rate() {
    // J = (a, a, b): classical I₃ = 2a (axis 3 ↔ e12), I₁ = I₂ = a + b. The body-frame
    // precession rate of Ω_⊥ is (I₁ − I₃)/I₁ · Ω₃ = ν ω₁₂.
    let (a, b) = (1.0, 2.5);
    let w = Bivector::from_components(3, &[0.8, 0.3, -0.2]).unwrap();
    let body = body_with_omega(&[a, a, b], Rotor::identity(3), &w);
    let exact = TwoMomentSolution::new(&body).unwrap();
    let (i1, i3) = (a + b, 2.0 * a);
    let rate = (i1 - i3) / i1 * w.get(0, 1);
    assert!((exact.generator().get(0, 1) - rate).abs() < 1e-15);
    assert!((exact.alpha() - 1.0 / i1).abs() < 1e-15);
    // After one body period the momentum is back.
    let period = 2.0 * PI / rate.abs();
    let l = exact.momentum_at(period).unwrap();
    assert!((&l - body.momentum()).norm() < 1e-14);
}

#[test]
fn mass_tensor_given_in_other_axes_is_diagonalised_first() {
    // J = Q diag(1, 1, 3, 3) Qᵀ with a random rotation: the body moves to its principal
    // frame and the eigenvalues, equal to ~1e-16, group into two values.
    let mut r = rng(506);
    let q = random_rotor(&mut r, 4).to_matrix();
    let d =
        nalgebra::DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![1.0, 1.0, 3.0, 3.0]));
    let j = &q * d * q.transpose();
    let inertia = InertiaMap::from_mass_tensor(&j).unwrap();
    let body = RigidBody::from_body_momentum(
        inertia,
        Rotor::identity(4),
        &random_bivector(&mut r, 4, 0.5),
    )
    .unwrap();
    let exact = TwoMomentSolution::new(&body).unwrap();
    assert_eq!(exact.kind(), TwoMomentKind::TwoMoments);
    assert_agrees("rotated mass tensor", &body, 100.0);
}

#[test]
fn plane_moment_maps_of_the_j_form_are_accepted() {
    // A diagonal map given by plane moments Jᵢ + Jⱼ with J = (1, 1, 1, 2) (4D): accepted.
    let p = [2.0, 2.0, 3.0, 2.0, 3.0, 3.0];
    let inertia = InertiaMap::from_plane_moments(&p).unwrap();
    let w = Bivector::from_components(4, &[0.3, -0.2, 0.9, 0.5, 0.1, -0.4]).unwrap();
    let body = RigidBody::from_body_velocity(inertia, Rotor::identity(4), &w).unwrap();
    let exact = TwoMomentSolution::new(&body).unwrap();
    assert_eq!(exact.kind(), TwoMomentKind::TwoMoments);
    assert_eq!(exact.values(), (1.0, 2.0));
    assert_agrees("plane-moment map", &body, 100.0);
}

#[test]
fn rejects_bodies_without_a_closed_form() {
    let w = Bivector::from_components(4, &[0.3, -0.2, 0.9, 0.5, 0.1, -0.4]).unwrap();
    // Three distinct principal values.
    let body = body_with_omega(&[1.0, 1.0, 2.0, 3.0], Rotor::identity(4), &w);
    let reasons = no_closed_form_reasons(TwoMomentSolution::new(&body));
    assert!(
        matches!(
            &reasons[..],
            [NoClosedFormReason::TooManyDistinctValues { values, .. }, NoClosedFormReason::NotSteady { .. }]
                if values.len() == 4
        ),
        "{reasons:?}"
    );
    assert!(reasons[0].to_string().contains("more than two distinct"));
    // Plane moments not of the form Jᵢ + Jⱼ.
    let inertia = InertiaMap::from_plane_moments(&[1.0, 2.0, 3.0, 4.0, 5.0, 7.0]).unwrap();
    let body = RigidBody::from_body_velocity(inertia, Rotor::identity(4), &w).unwrap();
    let reasons = no_closed_form_reasons(TwoMomentSolution::new(&body));
    assert!(
        matches!(
            &reasons[..],
            [
                NoClosedFormReason::NotPairSums { .. },
                NoClosedFormReason::NotSteady { .. }
            ]
        ),
        "{reasons:?}"
    );
    assert!(reasons[0].to_string().contains("not of the form"));
    // Moments that differ by more than the tolerance are distinct.
    let body = body_with_omega(&[1.0, 1.0 + 1e-9, 2.0, 3.0], Rotor::identity(4), &w);
    assert!(TwoMomentSolution::new(&body).is_err());
    // …and within it they are equal.
    let body = body_with_omega(&[1.0, 1.0 + 1e-14, 2.0, 2.0], Rotor::identity(4), &w);
    assert_eq!(
        TwoMomentSolution::new(&body).unwrap().kind(),
        TwoMomentKind::TwoMoments
    );
}

#[test]
fn non_finite_times_are_errors_and_large_times_stay_finite() {
    let mut r = rng(507);
    let body = body_with_omega(
        &[1.0, 1.0, 1.0, 2.0, 2.0],
        random_rotor(&mut r, 5),
        &random_bivector(&mut r, 5, 1.0),
    );
    let exact = TwoMomentSolution::new(&body).unwrap();
    for t in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert!(matches!(
            exact.momentum_at(t),
            Err(DynamicsError::NonFiniteArgument { name: "t", .. })
        ));
        assert!(matches!(
            exact.omega_at(t),
            Err(DynamicsError::NonFiniteArgument { .. })
        ));
        assert!(matches!(
            exact.attitude_at(t),
            Err(DynamicsError::NonFiniteArgument { .. })
        ));
    }
    // t · rate overflows: an error, never NaN.
    assert!(matches!(
        exact.attitude_at(f64::MAX),
        Err(DynamicsError::NonFiniteArgument { .. })
    ));
    for t in [1e9, -1e12, 1e15] {
        let l = exact.momentum_at(t).unwrap();
        let rt = exact.attitude_at(t).unwrap();
        assert!(l.as_slice().iter().all(|x| x.is_finite()));
        assert!(rt.is_finite());
        assert!((l.norm() - body.momentum().norm()).abs() < 1e-12);
        assert!(rt.unit_error() < 1e-12);
    }
}

#[test]
fn zero_momentum_is_at_rest() {
    let body = body_with_omega(
        &[1.0, 2.0, 3.0, 4.0],
        Rotor::identity(4),
        &Bivector::zero(4),
    );
    let exact = TwoMomentSolution::new(&body).unwrap();
    assert_eq!(exact.attitude_at(5.0).unwrap(), Rotor::identity(4).into());
    assert_eq!(exact.momentum_at(5.0).unwrap(), Bivector::zero(4));
}

#[test]
fn dopri5_difference_scales_with_its_tolerance() {
    // The residual difference is the integrator's: it falls ~10× per decade of tolerance
    // (1e-10 → 1e-13), so the closed form is at least that much closer to the true flow.
    use rotorflow::dynamics::torques::Free;
    use rotorflow::dynamics::{Dopri5, Integrator};
    let mut r = rng(609);
    let body = body_with_omega(
        &[1.0, 1.0, 3.0, 3.0],
        random_rotor(&mut r, 4),
        &random_bivector(&mut r, 4, 1.0),
    );
    let exact = TwoMomentSolution::new(&body).unwrap();
    let span = 100.0 * 2.0 * PI / fastest_rate(&exact);
    let mut errors = Vec::new();
    for tol in [1e-10, 1e-13] {
        let mut d = Dopri5::new(tol, tol);
        let mut b = body.clone();
        d.step(&mut b, 0.0, span, &Free).unwrap();
        let er = rotor_distance(
            &exact.attitude_at(span).unwrap(),
            b.principal_frame_attitude(),
        );
        let el = (&exact.momentum_at(span).unwrap() - b.momentum()).norm() / body.momentum().norm();
        eprintln!("Dopri5 tol {tol:e}: |ΔL|/|L| = {el:.2e}, |ΔR| = {er:.2e}");
        errors.push(er);
    }
    assert!(errors[0] > 300.0 * errors[1], "{errors:?}");
}
