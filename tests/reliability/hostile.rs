//! Numerically hostile cases, each with an asserted bound.

use nalgebra::DMatrix;
use rotorflow::inertia::Body;
use rotorflow::prelude::*;
use std::f64::consts::PI;

/// The bivector θ₁ e12 + θ₂ e34 (+ θ₃ e56 …).
fn planes(n: usize, angles: &[f64]) -> Bivector {
    let mut b = Bivector::zero(n);
    for (k, &a) in angles.iter().enumerate() {
        b.set(2 * k, 2 * k + 1, a);
    }
    b
}

/// The same bivector turned by a fixed generic rotation (so no component is special).
fn turned(b: &Bivector) -> Bivector {
    let n = b.dim();
    let c: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|k| 0.3 * (1.0 + k as f64).sin())
        .collect();
    let r = Bivector::from_components(n, &c).unwrap().exp();
    r.rotate_bivector(b)
}

/// log(exp(B)) = B for isoclinic and near-isoclinic B (equal angles make the planes
/// ambiguous; the rotation, not the planes, is what must come back), N = 4, 6, 8.
#[test]
fn exp_log_round_trip_at_isoclinic_and_near_isoclinic_input() {
    for n in [4usize, 6, 8] {
        let k = n / 2;
        for gap in [0.0, 1e-15, 1e-12, 1e-8] {
            let angles: Vec<f64> = (0..k).map(|i| 1.1 * (1.0 + gap * i as f64)).collect();
            // the rotation bivector Θ = 2B of the rotor e^{-B}…: use rotation_bivector
            let theta = turned(&planes(n, &angles));
            let r = Rotor::from_rotation_bivector(&theta);
            let back = r.rotation_bivector();
            let err = (&back - &theta).max_abs();
            assert!(err < 1e-13, "N = {n}, gap {gap:e}: |Θ − log| = {err:e}");
            assert!(
                r.unit_error() < 1e-14,
                "N = {n}: unit error {:e}",
                r.unit_error()
            );
        }
    }
}

/// Rotation angles π ± 1e-12 in one and in two planes: the rotor's matrix is right to
/// round-off, and the logarithm returns a rotation bivector of the same rotation with
/// every angle in [0, π] (the least-norm branch).
#[test]
fn exp_log_at_angles_pi_plus_minus_1e_12() {
    for n in [3usize, 4, 5, 8] {
        for delta in [-1e-12, 0.0, 1e-12] {
            let mut angles = vec![PI + delta];
            if n >= 4 {
                angles.push(PI - 3.0 * delta + 1e-3 * (n as f64));
            }
            let theta = turned(&planes(n, &angles));
            let r = Rotor::from_rotation_bivector(&theta);
            let expected = theta.exp_skew_matrix().transpose();
            let err = (r.to_matrix() - &expected).amax();
            assert!(err < 1e-13, "N = {n}, δ = {delta:e}: matrix error {err:e}");
            let back = r.rotation_bivector();
            let again = Rotor::from_rotation_bivector(&back).to_matrix();
            let err = (again - &expected).amax();
            assert!(
                err < 1e-11,
                "N = {n}, δ = {delta:e}: log lost the rotation ({err:e})"
            );
            for m in back.decompose().magnitudes() {
                assert!(m <= PI + 1e-9, "N = {n}, δ = {delta:e}: angle {m} beyond π");
            }
        }
    }
}

/// 10⁶ compositions of small rotors (no renormalisation): the drift from Spin(N) grows about
/// linearly, because the rounding of each product is a deterministic function of the rotor
/// and does not average out along the orbit — measured 2.6e-11 (3D) and 1.8e-10 (4D), i.e.
/// below 3e-16 per product — and `normalize` brings it back to 1e-15. (The integrators
/// update by one exponential per step, so 1e5 steps stay near 1e-13; see the dynamics
/// tests.)
#[test]
fn a_rotor_composed_a_million_times_stays_a_rotor() {
    for n in [3usize, 4] {
        let c: Vec<f64> = (0..n * (n - 1) / 2)
            .map(|k| 1e-3 * (1.0 + k as f64).cos())
            .collect();
        let step = Bivector::from_components(n, &c).unwrap().exp();
        let mut r = Rotor::identity(n);
        for _ in 0..1_000_000 {
            r = r.compose(&step);
        }
        let drift = r.unit_error();
        assert!(
            drift < 3e-16 * 1e6,
            "N = {n}: |RR̃ − 1| = {drift:e} after 1e6 products"
        );
        let fixed = r.normalize();
        assert!(fixed.unit_error() < 1e-15, "N = {n}");
        // the product is the rotor of the summed generator (all steps commute)
        let expected = (Bivector::from_components(n, &c).unwrap() * 1e6).exp();
        let err = (fixed.to_matrix() - expected.to_matrix()).amax();
        assert!(err < 1e-9, "N = {n}: product off by {err:e}");
    }
}

/// A nearly flat 4-D solid cuboid (half-edges 1, 1, 1e-6, 1e-6: mass-tensor condition number
/// 1e12): in the principal frame I⁻¹ is exact to round-off; after a generic rotation it is
/// as accurate as the condition number allows (relative error ≤ 10 κ ε against the exact
/// inverse R D⁻¹(R̃ L R) R̃ built from the known principal moments).
#[test]
fn inertia_of_a_nearly_flat_body() {
    let half = [1.0, 1.0, 1e-6, 1e-6];
    let body = Body::solid_cuboid(&half, 1.0).unwrap();
    let j = body.principal_second_moments();
    let kappa = j.max() / j.min();
    assert!(
        (kappa / 1e12 - 1.0).abs() < 1e-9,
        "condition number {kappa:e}"
    );
    let l = Bivector::from_components(4, &[1.0, -0.5, 0.25, 2.0, 0.1, -1.0]).unwrap();
    // Exact principal plane moments: J_i = m a_i²/3 for a solid cuboid.
    let mass = body.mass();
    let jj: Vec<f64> = half.iter().map(|a| mass * a * a / 3.0).collect();
    let inverse = |l: &Bivector| -> Bivector {
        let mut w = l.clone();
        for i in 0..4 {
            for k in i + 1..4 {
                w.set(i, k, l.get(i, k) / (jj[i] + jj[k]));
            }
        }
        w
    };
    let map = InertiaMap::from_body(&body).unwrap();
    let w = map.try_apply_inverse(&l).unwrap();
    let err = (&w - &inverse(&l)).max_abs() / inverse(&l).max_abs();
    assert!(err < 1e-15, "principal frame: {err:e}");

    let r = turned(&planes(4, &[0.7, 0.2])).exp();
    let rotated = body.rotated(&r.to_matrix()).unwrap();
    let map = InertiaMap::from_body(&rotated).unwrap();
    let w = map.try_apply_inverse(&l).unwrap();
    let exact = r.rotate_bivector(&inverse(&r.reverse().rotate_bivector(&l)));
    let err = (&w - &exact).max_abs() / exact.max_abs();
    let bound = 10.0 * kappa * f64::EPSILON;
    assert!(
        err < bound,
        "rotated: relative error {err:e} > 10κε = {bound:e}"
    );
}

/// A matrix orthogonal only to 1e-8: `from_matrix` (tolerance 1e-9) refuses it with the
/// measured error; `from_matrix_eps` and `from_matrix_projected` accept it and return the
/// nearest rotation, within 1e-8 of the input.
#[test]
fn matrix_to_rotor_for_matrices_orthogonal_only_to_1e_8() {
    for n in [3usize, 4, 6] {
        let q = turned(&planes(n, &[0.9, 0.4][..(n / 2).clamp(1, 2)])).exp_skew_matrix();
        let noise = DMatrix::from_fn(n, n, |i, j| 1e-8 * ((i * n + j) as f64).sin());
        let m = &q + noise;
        match Rotor::from_matrix(&m) {
            Err(AlgebraError::NotARotation {
                orthogonality_error,
                ..
            }) => assert!(
                orthogonality_error > 1e-9 && orthogonality_error < 1e-7,
                "N = {n}: reported {orthogonality_error:e}"
            ),
            other => panic!("N = {n}: expected NotARotation, got {other:?}"),
        }
        let projected = Rotor::from_matrix_projected(&m).unwrap();
        assert!(projected.unit_error() < 1e-14);
        let err = (projected.to_matrix() - &m).amax();
        assert!(err < 3e-8, "N = {n}: projection moved {err:e}");
        let loose = Rotor::from_matrix_eps(&m, 1e-6).unwrap();
        assert!((loose.to_matrix() - &m).amax() < 3e-8, "N = {n}");
    }
}

/// Regression (found by the adversarial property tests): components 1e150 beside 1e37 in 8-D made
/// nalgebra's symmetric eigen-solver return ∞/NaN inside the decomposition, which then lost
/// every plane. Fixed by the crate's robust symmetric eigensolver (`numeric::eigen`) (flush below ε²·max, check, Jacobi fallback).
#[test]
fn regression_decomposition_of_a_wide_range_bivector_in_8d() {
    let c = [
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1e38,
        2.892761935129748e148,
        2.412037944016982e150,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1e37,
        -6.369184931809316e150,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        9.78176666059664e50,
        0.0,
        0.0,
        0.0,
    ];
    let b = Bivector::from_components(8, &c).unwrap();
    let d = b.decompose();
    let err = (&d.reconstruct() - &b).max_abs() / b.max_abs();
    assert!(err < 1e-15, "relative reconstruction error {err:e}");
    assert!(d.len() >= 2);
}

/// Regression (adversarial proptest): the same eigen-solver failure made log(exp(B)) a
/// different rotation for this 7-D bivector.
#[test]
fn regression_exp_log_of_a_wide_range_bivector_in_7d() {
    let c = [
        7.5293313147332e-41,
        0.0,
        4.9321379179895105e110,
        4.421730107098586e-5,
        87622857.93778197,
        3.966751503126538e34,
        0.0,
        -235.21270177408334,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        6.315432673992644e-14,
        0.0,
        0.0,
        0.0,
    ];
    let r = Bivector::from_components(7, &c).unwrap().exp();
    let err = (r.log().exp().to_matrix() - r.to_matrix()).amax();
    assert!(err < 1e-12, "exp(log R) off by {err:e}");
}

/// Regression (adversarial proptest): a plane angle h L/I that overflows to ∞ in 2-D left L
/// finite, and the splitting returned Ok with a NaN attitude; it now reports `NonFinite`.
#[test]
fn regression_splitting_reports_an_overflowing_angle() {
    use rotorflow::dynamics::torques::Free;
    use rotorflow::dynamics::{Attitude, DynamicsError, Integrator, RigidBody, Splitting};
    let inertia = InertiaMap::from_principal_second_moments(&[1e-181, 1e-181]).unwrap();
    let l = Bivector::from_components(2, &[5.0814314796920635e126]).unwrap();
    let mut body = RigidBody::from_body_momentum(inertia, Attitude::identity(2), &l).unwrap();
    let result = Splitting::strang().step(&mut body, 0.0, 10.0, &Free);
    assert!(
        matches!(result, Err(DynamicsError::NonFinite { .. })),
        "{result:?}"
    );
}

/// Regression (adversarial proptest): the same overflow in the adaptive integrator, where the
/// increment A = ∞ scales its own error tolerance to ∞, so the error estimate read 0 and the
/// step was accepted with a NaN attitude; it now reports `NonFinite`.
#[test]
fn regression_dopri5_reports_an_overflowing_angle() {
    use rotorflow::dynamics::torques::Free;
    use rotorflow::dynamics::{Attitude, Dopri5, DynamicsError, Integrator, RigidBody};
    let inertia =
        InertiaMap::from_principal_second_moments(&[3.281159545697099e-222, 0.0]).unwrap();
    let l = Bivector::from_components(2, &[-4.9729193217462704e86]).unwrap();
    let mut body = RigidBody::from_body_momentum(inertia, Attitude::identity(2), &l).unwrap();
    let result = Dopri5::new(1e-8, 1e-8)
        .with_max_steps(2_000)
        .step(&mut body, 0.0, 10.0, &Free);
    assert!(
        matches!(result, Err(DynamicsError::NonFinite { .. })),
        "{result:?}"
    );
}
