//! Closed-form exp and log: agreement with nalgebra's matrix exponential, round trips on
//! every hard family, angles near π, with their error bounds asserted.

use crate::support::*;
use rotorflow::prelude::*;
use std::f64::consts::PI;

/// Rotor of the rotation bivector Θ, checked against expm([Θ]ᵀ).
fn check_exp(theta: &Bivector) -> Rotor {
    let r = Rotor::from_rotation_bivector(theta);
    let q = r.to_matrix();
    let expm = theta.to_skew_matrix().transpose().exp();
    let scale = theta.max_abs().max(1.0);
    let err = max_abs_diff(&q, &expm);
    assert!(err < 1e-13 * scale, "|Q − expm| = {err:e} for {theta}");
    assert!(r.unit_error() <= 1e-14, "|RR̃ − 1| = {:e}", r.unit_error());
    assert!(
        orthogonality(&q) <= 1e-14,
        "orthogonality {:e}",
        orthogonality(&q)
    );
    r
}

/// log(exp(Θ)) = Θ for rotation angles below π, to `tol` relative.
fn check_round_trip(theta: &Bivector, tol: f64) {
    let r = check_exp(theta);
    let back = r.rotation_bivector();
    let rel = (&back - theta).max_abs() / theta.max_abs().max(f64::MIN_POSITIVE);
    assert!(rel <= tol, "log∘exp relative error {rel:e} for {theta}");
    // and exp(log R) = R always
    let again = Rotor::from_rotation_bivector(&back);
    assert!(rotor_distance(&again, &r) <= 1e-14);
}

#[test]
fn exp_matches_matrix_exponential_for_n_2_to_10() {
    let mut r = rng(21);
    for n in 2..=10 {
        for _ in 0..10 {
            check_exp(&random_bivector(&mut r, n, 2.0));
        }
    }
}

#[test]
fn round_trip_on_random_bivectors_with_angles_below_pi() {
    let mut r = rng(22);
    for n in 2..=10 {
        for _ in 0..10 {
            let mags: Vec<f64> = (0..n / 2)
                .map(|_| rand::Rng::gen_range(&mut r, 0.0..3.0))
                .collect();
            let b = bivector_with_planes(&mut r, n, &mags);
            check_round_trip(&b, 1e-13);
        }
    }
}

#[test]
fn round_trip_isoclinic_and_near_isoclinic() {
    let mut r = rng(23);
    for n in [4, 5, 6, 8, 10] {
        check_round_trip(&bivector_with_planes(&mut r, n, &[1.4, 1.4]), 1e-13);
        for gap in [1e-12, 1e-9, 1e-6, 1e-3] {
            check_round_trip(&bivector_with_planes(&mut r, n, &[1.4 + gap, 1.4]), 1e-13);
        }
    }
    // the isoclinic example 0.7(e12 + e34), in 4D exactly
    let b = Bivector::from_components(4, &[0.7, 0.0, 0.0, 0.0, 0.0, 0.7]).unwrap();
    check_round_trip(&b, 1e-15);
}

#[test]
fn round_trip_zero_tiny_and_rank_deficient() {
    let mut r = rng(24);
    for n in 2..=10 {
        let id = Rotor::from_rotation_bivector(&Bivector::zero(n));
        assert_eq!(id, Rotor::identity(n));
        assert_eq!(Rotor::identity(n).log(), Bivector::zero(n));
        let tiny = random_bivector(&mut r, n, 1e-300);
        let rt = Rotor::from_rotation_bivector(&tiny);
        assert_eq!(rt.scalar(), 1.0);
        let back = rt.rotation_bivector();
        assert!((&back - &tiny).max_abs() <= 1e-13 * tiny.max_abs(), "n={n}");
        check_round_trip(&bivector_with_planes(&mut r, n, &[2.0]), 1e-13);
    }
}

#[test]
fn angles_at_pi_minus_1e_9() {
    let mut r = rng(25);
    let a = PI - 1e-9;
    for n in 2..=10 {
        // a single plane
        check_round_trip(&bivector_with_planes(&mut r, n, &[a]), 1e-13);
        // several planes at once, one of them near π
        if n >= 4 {
            check_round_trip(&bivector_with_planes(&mut r, n, &[a, 1.0]), 1e-13);
        }
        if n >= 6 {
            check_round_trip(&bivector_with_planes(&mut r, n, &[a, 2.0, 0.5]), 1e-13);
        }
    }
}

#[test]
fn isoclinic_rotation_by_nearly_pi_is_recovered_up_to_its_conditioning() {
    // Two planes both at π − δ: the logarithm's condition number is ~1/δ (DESIGN of log), so
    // only exp(log R) = R is asserted to round-off, and log(exp B) to eps/δ.
    let mut r = rng(26);
    for n in [4, 6, 8] {
        for delta in [1e-9, 1e-6, 1e-3] {
            let b = bivector_with_planes(&mut r, n, &[PI - delta, PI - delta]);
            let rot = Rotor::from_rotation_bivector(&b);
            let back = rot.rotation_bivector();
            let again = Rotor::from_rotation_bivector(&back);
            assert!(rotor_distance(&again, &rot) <= 1e-14, "n={n} δ={delta:e}");
            let rel = (&back - &b).max_abs() / b.max_abs();
            assert!(rel <= 1e-14 / delta, "n={n} δ={delta:e}: {rel:e}");
        }
    }
}

#[test]
fn exact_rotation_by_pi_has_a_valid_logarithm() {
    for n in 2..=8 {
        let r = Rotor::from_plane_angle(n, 0, 1, PI).unwrap();
        let l = r.log();
        let back = l.exp();
        assert!(rotor_distance(&back, &r) <= 1e-15, "n={n}");
        // −1 (rotation by 2π) also has a logarithm
        let minus_one = r.compose(&r);
        let back = minus_one.log().exp();
        assert!(rotor_distance(&back, &minus_one) <= 1e-15, "n={n}");
    }
}

#[test]
fn huge_angles_give_valid_rotors() {
    let mut r = rng(27);
    for n in [3, 4, 6] {
        let b = random_bivector(&mut r, n, 1e150);
        let rot = Rotor::from_rotation_bivector(&b);
        assert!(rot.unit_error() < 1e-14, "n={n}");
        assert!(rot.as_slice().iter().all(|c| c.is_finite()));
        assert!(orthogonality(&rot.to_matrix()) < 1e-14);
    }
}

#[test]
fn log_is_the_least_norm_branch() {
    // Rotation by 3π/2 in one plane: the principal log turns by π/2 the other way.
    let r = Rotor::from_plane_angle(4, 0, 1, 1.5 * PI).unwrap();
    let l = r.rotation_bivector();
    let d = l.decompose();
    // −2 log R has rotation angle in (π, 2π) only if needed; here R = −exp(+π/4 e12)…
    assert!(d.magnitudes()[0] <= 1.5 * PI + 1e-12);
    assert!(rotor_distance(&Rotor::from_rotation_bivector(&l), &r) < 1e-15);
    // half-angles of log: at most one beyond π/2
    let mut rr = rng(28);
    for n in 4..=9 {
        for _ in 0..5 {
            let rot = random_rotor(&mut rr, n);
            let l = rot.log();
            let mags = l.decompose().magnitudes();
            assert!(
                mags.iter().filter(|&&m| m > PI / 2.0 + 1e-12).count() <= 1,
                "{mags:?}"
            );
            assert!(mags.iter().all(|&m| m <= PI + 1e-12));
            assert!(rotor_distance(&l.exp(), &rot) <= 1e-14);
        }
    }
}

#[test]
fn slerp_spinor_interpolates_along_the_geodesic_of_spin_n() {
    let mut r = rng(29);
    for n in [3, 4, 6] {
        let a = random_rotor(&mut r, n);
        let b = random_rotor(&mut r, n);
        assert!(rotor_distance(&a.slerp_spinor(&b, 0.0), &a) < 1e-14);
        assert!(rotor_distance(&a.slerp_spinor(&b, 1.0), &b) < 1e-13);
        // the midpoint is equidistant: a⁻¹m = m⁻¹b
        let m = a.slerp_spinor(&b, 0.5);
        let d1 = a.reverse().compose(&m);
        let d2 = m.reverse().compose(&b);
        assert!(rotor_distance(&d1, &d2) < 1e-13);
    }
}

fn negated(r: &Rotor) -> Rotor {
    Rotor::from_multivector_unchecked(&(r.to_multivector() * -1.0))
}

/// slerp interpolates rotations: b and −b give the same path, the path turns by at most π
/// in every plane, its endpoints are a and ±b, and it is the geodesic (equal steps).
#[test]
fn slerp_takes_the_shorter_arc_of_the_rotation() {
    let mut r = rng(31);
    for n in [2, 3, 4, 5, 6] {
        for _ in 0..20 {
            let a = random_rotor(&mut r, n);
            let b = random_rotor(&mut r, n);
            let minus_b = negated(&b);
            assert_eq!(rotor_distance(&a.slerp(&b, 0.0), &a), 0.0);
            assert!(rotor_distance_up_to_sign(&a.slerp(&b, 1.0), &b) < 1e-13);
            for t in [0.25, 0.5, 0.9] {
                let (p, q) = (a.slerp(&b, t), a.slerp(&minus_b, t));
                assert!(
                    (p.to_matrix() - q.to_matrix()).amax() < 1e-13,
                    "N = {n}, t = {t}"
                );
            }
            // The rotation from a to the end of the path turns by at most π in every plane.
            let step = a.reverse().compose(&a.slerp(&b, 1.0));
            let angles = step.rotation_bivector().decompose().magnitudes();
            assert!(
                angles.iter().all(|&x| x <= PI + 1e-12),
                "N = {n}: {angles:?}"
            );
            // Equal steps: a⁻¹m = m⁻¹(end).
            let (m, end) = (a.slerp(&b, 0.5), a.slerp(&b, 1.0));
            let d1 = a.reverse().compose(&m);
            let d2 = m.reverse().compose(&end);
            assert!(rotor_distance(&d1, &d2) < 1e-13, "N = {n}");
        }
    }
    // The case that reads wrong as spinors: b = −a is no rotation at all.
    let a = random_rotor(&mut r, 3);
    let path = a.slerp(&negated(&a), 0.5);
    assert!((path.to_matrix() - a.to_matrix()).amax() < 1e-14);
    assert!((a.slerp_spinor(&negated(&a), 0.5).to_matrix() - a.to_matrix()).amax() > 1.0);
}

/// try_exp agrees with exp where exp is defined and refuses what exp cannot do.
#[test]
fn try_exp_refuses_overflowing_angles_non_finite_input_and_large_n() {
    let mut r = rng(37);
    for n in [2, 3, 4, 5, 7] {
        let b = random_bivector(&mut r, n, 3.0);
        assert_eq!(b.try_exp().unwrap(), b.exp());
        // At |B| = f64::MAX/2 the exponential is still a unit rotor; beyond, an error.
        let mut edge = Bivector::zero(n);
        edge.set(0, 1, f64::MAX / 2.0);
        let e = edge.try_exp().unwrap();
        assert!(e.unit_error() < 1e-15, "N = {n}");
        let mut huge = Bivector::zero(n);
        huge.set(0, 1, f64::MAX);
        match huge.try_exp() {
            Err(AlgebraError::AngleTooLarge { norm }) => assert_eq!(norm, f64::MAX),
            other => panic!("N = {n}: {other:?}"),
        }
        let mut nan = Bivector::zero(n);
        nan.set(0, 1, f64::NAN);
        assert!(matches!(nan.try_exp(), Err(AlgebraError::NonFinite { .. })));
    }
    // Components that are each finite but whose norm overflows.
    let b = Bivector::from_components(3, &[f64::MAX, f64::MAX, 0.0]).unwrap();
    assert!(matches!(
        b.try_exp(),
        Err(AlgebraError::AngleTooLarge { .. })
    ));
    assert!(matches!(
        Bivector::zero(17).try_exp(),
        Err(AlgebraError::DimensionTooLarge { dim: 17, .. })
    ));
    let theta = random_bivector(&mut r, 5, 2.0);
    assert_eq!(
        Rotor::try_from_rotation_bivector(&theta).unwrap(),
        Rotor::from_rotation_bivector(&theta)
    );
    assert!(Rotor::try_from_rotation_bivector(&Bivector::zero(17)).is_err());
}

/// log(exp B) relative to |B| (times max(1, |B|) by the caller's tolerance).
fn log_exp_error(b: &Bivector) -> f64 {
    let back = b.exp().log();
    let scale = b.max_abs().max(f64::MIN_POSITIVE);
    (&back - b).max_abs() / scale
}

#[test]
fn log_is_relatively_accurate_for_tiny_angles_and_near_pi_in_n_5_6_8() {
    // The matrix route alone carried the planes with absolute precision: 1.4e-9 relative at
    // |B| = 1e-8 and 2.3e-5 at π ± 1e-12 in N = 5 (the 45-digit reference's rows); the
    // Newton refinement against the rotor restores relative precision.
    let mut r = rng(27);
    let mut worst: f64 = 0.0;
    for n in [5, 6, 8] {
        for scale in [1e-200, 1e-100, 1e-30, 1e-12, 1e-8, 1e-4] {
            for _ in 0..4 {
                let b = random_bivector(&mut r, n, scale);
                let e = log_exp_error(&b);
                worst = worst.max(e);
                assert!(e <= 1e-14, "n={n} |B|~{scale:e}: {e:e}");
            }
            let iso = bivector_with_planes(&mut r, n, &[scale, scale]);
            let e = log_exp_error(&iso);
            assert!(e <= 1e-14, "n={n} isoclinic {scale:e}: {e:e}");
            let near = bivector_with_planes(&mut r, n, &[scale, scale * (1.0 + 1e-6)]);
            let e = log_exp_error(&near);
            assert!(e <= 1e-14, "n={n} near-isoclinic {scale:e}: {e:e}");
        }
        // Rotation angles π ± 1e-12 (plane magnitudes (π ± 1e-12)/2 of B), in one plane and
        // alongside others.
        for d in [-1e-12, 1e-12, -1e-9] {
            let h = 0.5 * (PI + d);
            let mut sets: Vec<Vec<f64>> = vec![vec![h], vec![h, 0.3]];
            if n >= 6 {
                sets.push(vec![h, 1.0, 1e-9]);
            }
            for mags in &sets {
                for _ in 0..3 {
                    let b = bivector_with_planes(&mut r, n, mags);
                    let e = log_exp_error(&b);
                    worst = worst.max(e);
                    assert!(e <= 1e-14, "n={n} planes {mags:?}: {e:e}");
                }
            }
        }
    }
    println!("worst relative error of log(exp B): {worst:.1e}");
}

#[test]
fn log_keeps_planes_of_rotors_near_minus_one_in_n_5_6_8() {
    // Plane magnitude π ∓ 1e-12 (the rotor is near −1, its matrix near I): below π the
    // logarithm is B, above π the same plane on the other branch, B (1 − 2π/|B|).
    let mut r = rng(28);
    for n in [5, 6, 8] {
        for d in [-1e-12, 1e-12, -1e-9] {
            let m = PI + d;
            let b = bivector_with_planes(&mut r, n, &[m]);
            let expected = if d < 0.0 {
                b.clone()
            } else {
                &b * (1.0 - 2.0 * PI / m)
            };
            let back = b.exp().log();
            let e = (&back - &expected).max_abs() / expected.max_abs();
            assert!(e <= 1e-14, "n={n} |B| = π{d:+e}: {e:e}");
            if d < 0.0 {
                // B is the least-norm logarithm only while the other planes are below −d
                // (else moving one of them by π costs less), so: a plane at 1e-13.
                let b2 = bivector_with_planes(&mut r, n, &[m, 1e-13]);
                let e = log_exp_error(&b2);
                assert!(e <= 1e-14, "n={n} planes π{d:+e}, 1e-13: {e:e}");
            }
        }
    }
}
