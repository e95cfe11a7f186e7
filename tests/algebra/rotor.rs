//! Rotors: composition, sandwiches, in-place plane rotations, matrices both ways, and the
//! projection onto Spin(N).

use crate::assert_close;
use crate::support::*;
use nalgebra::DMatrix;
use rotorflow::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

#[test]
fn plane_angle_turns_first_vector_toward_second() {
    // Conventions chapter: R = exp(−θ B̂/2) turns e_i toward e_j by θ.
    for n in 2..=8 {
        let r = Rotor::from_plane_angle(n, 0, 1, FRAC_PI_2).unwrap();
        let x = r.rotate_vector(&Vector::basis(n, 0));
        assert_close!(x[1], 1.0, 1e-15);
        assert_close!(x[0], 0.0, 1e-15);
        // the matrix agrees
        let q = r.to_matrix();
        assert_close!(q[(1, 0)], 1.0, 1e-15);
        // reversed index order turns the other way
        let r2 = Rotor::from_plane_angle(n, 1, 0, FRAC_PI_2).unwrap();
        assert_close!(r2.rotate_vector(&Vector::basis(n, 0))[1], -1.0, 1e-15);
    }
}

#[test]
fn composition_applies_right_factor_first() {
    let n = 3;
    let a = Rotor::from_plane_angle(n, 0, 1, FRAC_PI_2).unwrap(); // e1 → e2
    let b = Rotor::from_plane_angle(n, 1, 2, FRAC_PI_2).unwrap(); // e2 → e3
    // b·a: first e1 → e2, then e2 → e3
    let x = (&b * &a).rotate_vector(&Vector::basis(n, 0));
    assert_close!(x[2], 1.0, 1e-15);
    // matrices compose the same way
    let qa = a.to_matrix();
    let qb = b.to_matrix();
    assert!(max_abs_diff(&(&b * &a).to_matrix(), &(&qb * &qa)) < 1e-15);
}

#[test]
fn sandwich_matches_matrix_and_multivector_product() {
    let mut r = rng(31);
    for n in 2..=10 {
        let rot = random_rotor(&mut r, n);
        let q = rot.to_matrix();
        let x = random_vector(&mut r, n);
        let y = rot.rotate_vector(&x);
        let qy = &q * x.to_dvector();
        let mv = rot.rotate_multivector(&Multivector::from(&x)).unwrap();
        for i in 0..n {
            assert_close!(y[i], qy[i], 1e-14);
            assert_close!(y[i], mv.coefficient(1 << i), 1e-14);
        }
        assert!(mv.grade(1).max_abs() > 0.0 && (mv.clone() - mv.grade(1)).max_abs() < 1e-14);
        // bivectors: R B R̃ via the matrix equals the multivector sandwich
        let b = random_bivector(&mut r, n, 1.0);
        let rb = rot.rotate_bivector(&b);
        let mvb = rot.rotate_multivector(&Multivector::from(&b)).unwrap();
        let mvb = Bivector::try_from(&mvb.grade(2)).unwrap();
        assert!((&rb - &mvb).max_abs() < 1e-13, "n={n}");
    }
}

#[test]
fn sandwich_preserves_norms_inner_products_and_commutators() {
    let mut r = rng(32);
    for n in 3..=8 {
        let rot = random_rotor(&mut r, n);
        let (x, y) = (random_vector(&mut r, n), random_vector(&mut r, n));
        let (rx, ry) = (rot.rotate_vector(&x), rot.rotate_vector(&y));
        assert_close!(rx.dot(&ry), x.dot(&y), 1e-14);
        let (a, b) = (
            random_bivector(&mut r, n, 1.0),
            random_bivector(&mut r, n, 1.0),
        );
        let (ra, rb) = (rot.rotate_bivector(&a), rot.rotate_bivector(&b));
        assert_close!(ra.inner(&rb), a.inner(&b), 1e-13);
        // the commutator is equivariant: R(A×B)R̃ = (RAR̃)×(RBR̃)
        assert!((&ra.commutator(&rb) - &rot.rotate_bivector(&a.commutator(&b))).max_abs() < 1e-13);
        // and the wedge: R(x∧y)R̃ = Rx ∧ Ry
        assert!((&rot.rotate_bivector(&x.wedge(&y)) - &rx.wedge(&ry)).max_abs() < 1e-14);
    }
}

#[test]
fn rotate_in_plane_mut_equals_right_multiplication() {
    let mut r = rng(33);
    for n in 2..=9 {
        let mut rot = random_rotor(&mut r, n);
        let reference = rot.clone();
        for (i, j, a) in [(0, 1, 0.3), (1, 0, -1.1), (0, n - 1, 2.5)] {
            if i == j {
                continue;
            }
            let step = Rotor::from_plane_angle(n, i, j, a).unwrap();
            let expected = rot.compose(&step);
            rot.rotate_in_plane_mut(i, j, a);
            assert!(rotor_distance(&rot, &expected) < 1e-15, "n={n} ({i},{j})");
        }
        // many steps keep it on Spin(N) without renormalisation
        let mut walk = reference.clone();
        for k in 0..10_000 {
            let (i, j) = (k % n, (k / n + 1 + k) % n);
            if i != j {
                walk.rotate_in_plane_mut(i, j, 0.1 + 1e-3 * k as f64);
            }
        }
        assert!(walk.unit_error() < 1e-12, "n={n}: {:e}", walk.unit_error());
    }
}

/// `matrix_to` writes what `to_matrix` returns, bit for bit, into a matrix reused across
/// rotors, and refuses a matrix of another shape.
#[test]
fn matrix_to_writes_the_matrix_of_to_matrix() {
    let mut r = rng(35);
    let mut checked = 0;
    for n in 1..=10 {
        let mut q = DMatrix::from_element(n, n, f64::NAN);
        for _ in 0..5 {
            let rot = random_rotor(&mut r, n);
            rot.matrix_to(&mut q).unwrap();
            assert_eq!(q, rot.to_matrix(), "n={n}");
            checked += 1;
        }
        for (rows, cols) in [(n + 1, n + 1), (n, n + 1), (n + 1, n)] {
            let mut wrong = DMatrix::zeros(rows, cols);
            assert!(matches!(
                Rotor::identity(n).matrix_to(&mut wrong),
                Err(AlgebraError::DimensionMismatch { left, .. }) if left == n
            ));
        }
    }
    assert_eq!(checked, 50);
}

#[test]
fn matrix_to_rotor_round_trip_up_to_sign() {
    let mut r = rng(34);
    for n in 2..=10 {
        for _ in 0..5 {
            let rot = random_rotor(&mut r, n);
            let q = rot.to_matrix();
            let back = Rotor::from_matrix(&q).unwrap();
            assert!(rotor_distance_up_to_sign(&back, &rot) < 1e-13, "n={n}");
            assert!(back.scalar() >= 0.0);
            let q2 = back.to_matrix();
            // ~100 ε: the rotor has 2^(N−1) = 512 coefficients at N = 10.
            assert!(
                max_abs_diff(&q, &q2) < 2e-14,
                "n={n}: {:e}",
                max_abs_diff(&q, &q2)
            );
        }
    }
}

#[test]
fn matrix_to_rotor_near_pi_and_isoclinic() {
    let mut r = rng(35);
    for n in [3, 4, 5, 6, 8] {
        for mags in [
            vec![PI],
            vec![PI - 1e-9],
            vec![PI, PI],
            vec![PI - 1e-9, PI - 1e-9],
            vec![PI - 1e-7, 1.0],
            vec![1.2, 1.2],
        ] {
            if 2 * mags.len() > n {
                continue;
            }
            let b = bivector_with_planes(&mut r, n, &mags);
            let rot = Rotor::from_rotation_bivector(&b);
            let back = Rotor::from_matrix(&rot.to_matrix()).unwrap();
            assert!(
                rotor_distance_up_to_sign(&back, &rot) < 1e-13,
                "n={n} mags={mags:?}: {:e}",
                rotor_distance_up_to_sign(&back, &rot)
            );
        }
    }
}

#[test]
fn matrices_that_are_not_rotations_are_rejected() {
    let mut refl = DMatrix::<f64>::identity(4, 4);
    refl[(0, 0)] = -1.0;
    assert!(matches!(
        Rotor::from_matrix(&refl),
        Err(AlgebraError::NotARotation { .. })
    ));
    let scaled = DMatrix::<f64>::identity(3, 3) * 1.01;
    assert!(matches!(
        Rotor::from_matrix(&scaled),
        Err(AlgebraError::NotARotation { .. })
    ));
    assert!(matches!(
        Rotor::from_matrix(&DMatrix::zeros(3, 2)),
        Err(AlgebraError::NotSquare { .. })
    ));
    let mut nan = DMatrix::<f64>::identity(3, 3);
    nan[(1, 1)] = f64::NAN;
    assert!(matches!(
        Rotor::from_matrix(&nan),
        Err(AlgebraError::NonFinite { .. })
    ));
    // projection accepts a nearly orthogonal matrix, and still rejects reflections
    let mut rr = rng(36);
    let q = random_rotation_matrix(&mut rr, 5);
    let noisy = &q + DMatrix::from_fn(5, 5, |i, j| 1e-8 * ((i * 5 + j) as f64).sin());
    // orthogonal only to ~1e-8: the strict conversion says so, the projection fixes it
    assert!(matches!(
        Rotor::from_matrix(&noisy),
        Err(AlgebraError::NotARotation { .. })
    ));
    let projected = Rotor::from_matrix_projected(&noisy).unwrap();
    assert!(max_abs_diff(&projected.to_matrix(), &q) < 1e-7);
    assert!(projected.unit_error() < 1e-14);
    assert!(Rotor::from_matrix_projected(&refl).is_err());
    assert!(Rotor::from_matrix_eps(&noisy, 1e-12).is_err());
}

#[test]
fn normalize_projects_drifted_rotors_onto_spin_n() {
    let mut r = rng(37);
    for n in 2..=8 {
        let rot = random_rotor(&mut r, n);
        let mut coeffs = rot.to_multivector();
        // perturb every even coefficient by 1e-6
        for (k, c) in coeffs.as_mut_slice().iter_mut().enumerate() {
            if (k as u64).count_ones().is_multiple_of(2) {
                *c += 1e-6 * ((k as f64) * 1.7).sin();
            }
        }
        let drifted = Rotor::from_multivector_unchecked(&coeffs);
        assert!(drifted.unit_error() > 1e-8);
        let fixed = drifted.normalize();
        assert!(
            fixed.unit_error() < 1e-14,
            "n={n}: {:e}",
            fixed.unit_error()
        );
        assert!(orthogonality(&fixed.to_matrix()) < 1e-14);
        assert!(rotor_distance(&fixed, &rot) < 1e-5, "moved too far");
        // a true rotor is a fixed point
        assert!(rotor_distance(&rot.normalize(), &rot) < 1e-14);
    }
}

#[test]
fn dividing_by_the_norm_is_not_enough_in_4d() {
    // A drifted 4D rotor with a grade-4 error: norm division leaves R R̃ ≠ 1.
    let rot = Rotor::from_rotation_bivector(
        &Bivector::from_components(4, &[0.4, 0.0, 0.0, 0.0, 0.0, 1.3]).unwrap(),
    );
    let mut m = rot.to_multivector();
    m.as_mut_slice()[0b1111] += 1e-4;
    let drifted = Rotor::from_multivector_unchecked(&m);
    let norm = drifted.as_slice().iter().map(|c| c * c).sum::<f64>().sqrt();
    let naive = Rotor::from_multivector_unchecked(&(m.clone() * (1.0 / norm)));
    assert!(naive.unit_error() > 1e-6);
    assert!(drifted.normalize().unit_error() < 1e-15);
}

#[test]
fn rotors_from_10_6_compositions_stay_on_spin_n() {
    let mut r = rng(38);
    for n in [3, 4] {
        let step = random_rotor(&mut r, n);
        let mut acc = Rotor::identity(n);
        for _ in 0..1_000_000 {
            acc = acc.compose(&step);
        }
        // round-off accumulates at most linearly, ~steps · eps (measured: 1.4e-10 at N = 3);
        // renormalising restores the group to round-off
        assert!(
            acc.unit_error() < 1e6 * 4.0 * f64::EPSILON,
            "n={n}: {:e}",
            acc.unit_error()
        );
        let fixed = acc.normalize();
        assert!(fixed.unit_error() < 1e-15);
        let l = fixed.log();
        assert!(rotor_distance(&l.exp(), &fixed) < 1e-14);
    }
}

#[test]
fn from_multivector_checks_membership() {
    let rot = Rotor::from_plane_angle(4, 0, 2, 0.7).unwrap();
    let m = rot.to_multivector();
    assert_eq!(Rotor::from_multivector(&m).unwrap(), rot);
    let mut odd = m.clone();
    odd.as_mut_slice()[1] = 0.1;
    assert!(matches!(
        Rotor::from_multivector(&odd),
        Err(AlgebraError::NotARotor { .. })
    ));
    let scaled = m.clone() * 2.0;
    assert!(Rotor::from_multivector(&scaled).is_err());
    // even, R R̃ = 1, but not a versor in 6D: (1 + e123456)/√2 ... (RR̃ = 1 needs I² = −1)
    let s6 = Signature::euclidean(6);
    let mut x = Multivector::scalar(s6, std::f64::consts::FRAC_1_SQRT_2);
    x.as_mut_slice()[0b111111] = std::f64::consts::FRAC_1_SQRT_2;
    assert_close!((&x * &x.reverse()).scalar_part(), 1.0, 1e-15);
    assert!(matches!(
        Rotor::from_multivector(&x),
        Err(AlgebraError::NotARotor { .. })
    ));
}

#[test]
fn display_of_rotors() {
    let r = Rotor::from_plane_angle(3, 0, 1, 2.0 * 0.6435011087932844).unwrap();
    assert_eq!(format!("{r:.1}"), "0.8 - 0.6·e12");
    assert_eq!(Rotor::identity(4).to_string(), "1");
}

/// try_normalize projects drift (the same result as normalize) and refuses what is far from
/// Spin(N), reporting the measured distance max |R R̃ − 1|.
#[test]
fn try_normalize_projects_drift_and_refuses_far_input() {
    let mut r = rng(41);
    for n in 2..=7 {
        let rot = random_rotor(&mut r, n);
        let mut m = rot.to_multivector();
        m.as_mut_slice()[0] += 1e-9;
        let drifted = Rotor::from_multivector_unchecked(&m);
        assert_eq!(drifted.try_normalize().unwrap(), drifted.normalize());
        // Twice a rotor: R R̃ = 4, distance 3.
        let far = Rotor::from_multivector_unchecked(&(rot.to_multivector() * 2.0));
        match far.try_normalize() {
            Err(AlgebraError::FarFromGroup {
                distance,
                tolerance,
            }) => {
                assert_close!(distance, 3.0, 1e-13);
                assert_eq!(tolerance, rotorflow::algebra::NORMALIZE_TOLERANCE);
            }
            other => panic!("N = {n}: {other:?}"),
        }
        // The tolerance is the caller's to choose, and the message names the distance.
        assert!(far.try_normalize_eps(3.5).is_ok());
        let text = far.try_normalize().unwrap_err().to_string();
        let distance = format!("{:e}", far.unit_error());
        assert!(text.contains(&distance) && text.contains("1e-6"), "{text}");
        let zero = Rotor::from_multivector_unchecked(&(rot.to_multivector() * 0.0));
        assert!(matches!(
            zero.try_normalize(),
            Err(AlgebraError::FarFromGroup { distance, .. }) if distance == 1.0
        ));
        let nan = Rotor::from_multivector_unchecked(&(rot.to_multivector() * f64::NAN));
        assert!(matches!(
            nan.try_normalize(),
            Err(AlgebraError::FarFromGroup { distance, .. }) if distance.is_nan()
        ));
    }
}

#[test]
fn try_identity_and_from_multivector_eps() {
    assert_eq!(Rotor::try_identity(4).unwrap(), Rotor::identity(4));
    assert!(matches!(
        Rotor::try_identity(17),
        Err(AlgebraError::DimensionTooLarge {
            dim: 17,
            max: 16,
            ..
        })
    ));
    // A rotor 1e-8 off the group: refused at the default tolerance, accepted at a looser one.
    let rot = Rotor::from_plane_angle(4, 0, 2, 0.7).unwrap();
    let mut m = rot.to_multivector();
    m.as_mut_slice()[0] += 1e-8;
    assert!(matches!(
        Rotor::from_multivector(&m),
        Err(AlgebraError::NotARotor { .. })
    ));
    let loose = Rotor::from_multivector_eps(&m, 1e-6).unwrap();
    assert_eq!(loose, Rotor::from_multivector_unchecked(&m));
    assert!(Rotor::from_multivector_eps(&m, 1e-9).is_err());
}
