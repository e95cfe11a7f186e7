//! `RigidBody::exact_solution` picks the right closed form, and says why there is none.

use crate::{REFERENCE_TOLERANCE, no_closed_form_reasons, rotor_distance};
use rotorflow::dynamics::exact::ExactSolution;
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Attitude, Dopri5, Integrator, NoClosedFormReason, RigidBody};
use rotorflow::prelude::*;

fn body(j: &[f64], l: &[f64]) -> RigidBody {
    let n = j.len();
    RigidBody::from_body_momentum(
        InertiaMap::from_principal_second_moments(j).unwrap(),
        Attitude::identity(n),
        &Bivector::from_components(n, l).unwrap(),
    )
    .unwrap()
}

/// Each form agrees with Dopri5 (tight tolerance) at t = 7.
fn check(b: &RigidBody, name: &str) {
    let exact = b.exact_solution().unwrap();
    assert_eq!(exact.name(), name);
    let mut numeric = b.clone();
    Dopri5::new(REFERENCE_TOLERANCE, REFERENCE_TOLERANCE)
        .step(&mut numeric, 0.0, 7.0, &Free)
        .unwrap();
    let l = exact.momentum_at(7.0).unwrap();
    let dl = (&l - numeric.momentum()).max_abs() / b.momentum().max_abs();
    let dr = rotor_distance(
        &exact.attitude_at(7.0).unwrap(),
        numeric.principal_frame_attitude(),
    );
    assert!(dl < 1e-11 && dr < 1e-10, "{name}: ΔL {dl:e}, ΔR {dr:e}");
    let w = exact.omega_at(7.0).unwrap();
    assert!((&w - &b.inertia().apply_inverse(&l)).max_abs() < 1e-13);
}

#[test]
fn each_body_gets_its_closed_form() {
    check(&body(&[0.5, 1.0, 2.0], &[0.3, -0.8, 0.5]), "asymmetric top");
    check(
        &body(&[1.0, 1.0, 1.0, 4.0], &[0.3, -0.5, 0.8, 0.4, 0.2, -0.6]),
        "two moments",
    );
    // 5D, all principal values distinct, L in the span of axes 1, 3, 4: the 3D top inside.
    let mut l = vec![0.0; 10];
    l[1] = 0.7; // e13
    l[2] = -0.4; // e14
    l[7] = 0.9; // e34
    check(&body(&[0.4, 0.9, 1.3, 1.7, 2.2], &l), "embedded 3D top");
    // 6D, all distinct, a double rotation in disjoint principal planes: steady.
    let mut l = vec![0.0; 15];
    l[0] = 1.0; // e12
    l[14] = 0.5; // e56
    check(&body(&[0.4, 0.9, 1.3, 1.7, 2.2, 2.9], &l), "two moments");
}

#[test]
fn a_general_body_has_no_closed_form_and_says_why() {
    let b = body(&[0.4, 0.9, 1.3, 1.7], &[0.3, -0.5, 0.8, 0.4, 0.2, -0.6]);
    let err = ExactSolution::new(&b).unwrap_err();
    let why = err.to_string();
    assert!(why.contains("distinct"), "{why}");
    assert!(why.contains("three principal axes"), "{why}");
    assert!(!why.contains('\n'), "{why}");
    let reasons = no_closed_form_reasons::<ExactSolution>(Err(err));
    assert!(
        matches!(
            &reasons[..],
            [
                NoClosedFormReason::TooManyDistinctValues { .. },
                NoClosedFormReason::NotSteady { .. },
                NoClosedFormReason::MomentumSpansMoreThanThreeAxes,
            ]
        ),
        "{reasons:?}"
    );
}
