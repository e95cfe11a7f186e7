//! Bivector kernels: the commutator, contraction, invariants and the Pfaffian, each checked
//! against an independent route (the general multivector product or nalgebra).

use crate::assert_close;
use crate::support::*;
use nalgebra::DMatrix;
use rotorflow::prelude::*;

#[test]
fn commutator_matches_multivector_product_for_n_2_to_10() {
    let mut r = rng(1);
    for n in 2..=10 {
        for _ in 0..5 {
            let a = random_bivector(&mut r, n, 1.0);
            let b = random_bivector(&mut r, n, 1.0);
            let fast = a.commutator(&b);
            let slow = Multivector::from(&a).commutator(&Multivector::from(&b));
            let slow = Bivector::try_from(&slow.grade(2)).unwrap();
            assert!((&fast - &slow).max_abs() < 1e-14, "n={n}: {fast} vs {slow}");
            // and the skew-matrix bracket [A][B] − [B][A]
            let (ma, mb) = (a.to_skew_matrix(), b.to_skew_matrix());
            let m = &ma * &mb - &mb * &ma;
            assert!(max_abs_diff(&fast.to_skew_matrix(), &m) < 1e-14);
        }
    }
}

#[test]
fn commutator_in_3d_is_the_cross_product_of_dual_vectors() {
    // e12 ↔ e3, e13 ↔ −e2, e23 ↔ e1 (Conventions chapter: Ω = (ω23, −ω13, ω12)).
    let to_omega = |b: &Bivector| [b.get(1, 2), -b.get(0, 2), b.get(0, 1)];
    let a = Bivector::from_components(3, &[0.3, -1.2, 0.7]).unwrap();
    let b = Bivector::from_components(3, &[2.0, 0.5, -0.1]).unwrap();
    let (x, y) = (to_omega(&a), to_omega(&b));
    let cross = [
        x[1] * y[2] - x[2] * y[1],
        x[2] * y[0] - x[0] * y[2],
        x[0] * y[1] - x[1] * y[0],
    ];
    let c = to_omega(&a.commutator(&b));
    // A × B for bivectors is −(Ω_A × Ω_B) under this duality (the so(3) bracket).
    for k in 0..3 {
        assert_close!(c[k], -cross[k], 1e-15);
    }
}

#[test]
fn contraction_gives_point_velocity() {
    // Conventions chapter: v = x ⌋ ω = [ω]ᵀ x; ω = e12 turns e1 toward e2.
    let w = Bivector::from_plane(3, 0, 1, 1.0).unwrap();
    let v = Vector::basis(3, 0).left_contract(&w);
    assert_eq!(v.as_slice(), &[0.0, 1.0, 0.0]);
    let mut r = rng(2);
    for n in 2..=9 {
        let b = random_bivector(&mut r, n, 1.0);
        let x = random_vector(&mut r, n);
        let fast = x.left_contract(&b);
        let mat = b.to_skew_matrix().transpose() * x.to_dvector();
        let mv = Multivector::from(&x).left_contract(&Multivector::from(&b));
        for i in 0..n {
            assert_close!(fast[i], mat[i], 1e-15);
            assert_close!(fast[i], mv.coefficient(1 << i), 1e-15);
        }
    }
}

#[test]
fn pfaffian_squares_to_determinant() {
    let mut r = rng(3);
    for n in [2, 4, 6, 8, 10] {
        for _ in 0..5 {
            let b = random_bivector(&mut r, n, 1.0);
            let pf = b.pfaffian();
            let det = b.to_skew_matrix().determinant();
            assert_close!(pf * pf, det, 1e-12 * det.abs().max(1.0));
        }
    }
    let b = Bivector::from_components(4, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]).unwrap();
    assert_close!(b.pfaffian(), 1.0 * 6.0 - 2.0 * 5.0 + 3.0 * 4.0, 1e-14);
    assert_eq!(Bivector::from_plane(2, 0, 1, 2.5).unwrap().pfaffian(), 2.5);
    assert_eq!(random_bivector(&mut r, 5, 1.0).pfaffian(), 0.0);
}

#[test]
fn pfaffian_is_the_pseudoscalar_part_of_the_wedge_power() {
    // B^{∧m}/m! = Pf · e₁…ₙ for n = 2m.
    let mut r = rng(4);
    for n in [4, 6, 8] {
        let b = random_bivector(&mut r, n, 1.0);
        let mb = Multivector::from(&b);
        let mut w = mb.clone();
        let mut fact = 1.0;
        for k in 2..=n / 2 {
            w = w.wedge(&mb);
            fact *= k as f64;
        }
        let top = w.coefficient((1u64 << n) - 1) / fact;
        assert_close!(top, b.pfaffian(), 1e-13);
    }
}

#[test]
fn characteristic_coefficients_match_wedge_powers_and_eigenvalues() {
    let mut r = rng(5);
    for n in 3..=9 {
        let b = random_bivector(&mut r, n, 1.0);
        let c = b.characteristic_coefficients();
        assert_eq!(c.len(), n / 2 + 1);
        assert_eq!(c[0], 1.0);
        assert_close!(c[1], b.norm_squared(), 1e-13);
        // c_k = |B^{∧k}/k!|² from the multivector algebra
        let mb = Multivector::from(&b);
        let mut w = Multivector::scalar(mb.signature(), 1.0);
        let mut fact = 1.0;
        for (k, &ck) in c.iter().enumerate().skip(1) {
            w = w.wedge(&mb);
            fact *= k as f64;
            let expected = w.norm_squared() / (fact * fact);
            assert_close!(ck, expected, 1e-12 * expected.max(1.0));
        }
        // and the eigenvalues ±iθ of [B]: Σθ² over pairs = c₁
        let eig = b.to_skew_matrix().complex_eigenvalues();
        let sum_sq: f64 = eig.iter().map(|z| z.im * z.im).sum::<f64>() / 2.0;
        assert_close!(c[1], sum_sq, 1e-12);
    }
    // 4D: c₂ = Pf²
    let b = random_bivector(&mut r, 4, 1.0);
    assert_close!(
        b.characteristic_coefficients()[2],
        b.pfaffian().powi(2),
        1e-14
    );
}

#[test]
fn skew_matrix_round_trip_and_rejection() {
    let mut r = rng(6);
    let b = random_bivector(&mut r, 6, 1.0);
    let m = b.to_skew_matrix();
    assert_eq!(Bivector::from_skew_matrix(&m).unwrap(), b);
    let mut bad = m.clone();
    bad[(0, 1)] += 1e-3;
    assert!(matches!(
        Bivector::from_skew_matrix(&bad),
        Err(AlgebraError::NotSkewSymmetric { .. })
    ));
    assert!(matches!(
        Bivector::from_skew_matrix(&DMatrix::zeros(2, 3)),
        Err(AlgebraError::NotSquare { rows: 2, cols: 3 })
    ));
    let sm: nalgebra::SMatrix<f64, 4, 4> = b_to_s4(&random_bivector(&mut r, 4, 1.0));
    let back = Bivector::try_from(&sm).unwrap();
    assert_eq!(back.to_skew_smatrix::<4>(), sm);
}

fn b_to_s4(b: &Bivector) -> nalgebra::SMatrix<f64, 4, 4> {
    b.to_skew_smatrix::<4>()
}

#[test]
fn constructors_check_their_input() {
    assert!(matches!(
        Bivector::from_components(4, &[1.0; 5]),
        Err(AlgebraError::WrongComponentCount {
            expected: 6,
            found: 5,
            ..
        })
    ));
    assert!(matches!(
        Bivector::from_components(3, &[1.0, f64::INFINITY, 0.0]),
        Err(AlgebraError::NonFinite { .. })
    ));
    assert!(matches!(
        Bivector::from_plane(3, 1, 1, 1.0),
        Err(AlgebraError::RepeatedIndex { index: 1 })
    ));
    assert!(matches!(
        Bivector::from_plane(3, 0, 3, 1.0),
        Err(AlgebraError::IndexOutOfRange { index: 3, dim: 3 })
    ));
    assert!(Bivector::from_components(65, &[]).is_err());
    // from_plane with i > j flips the sign
    assert_eq!(
        Bivector::from_plane(3, 1, 0, 1.0).unwrap(),
        -Bivector::from_plane(3, 0, 1, 1.0).unwrap()
    );
}

#[test]
fn display_uses_one_based_lexicographic_names() {
    let b = Bivector::from_components(4, &[0.5, 0.0, 0.0, 0.0, 0.0, -1.25]).unwrap();
    assert_eq!(b.to_string(), "0.5·e12 - 1.25·e34");
    assert_eq!(Bivector::zero(3).to_string(), "0");
    let mut big = Bivector::zero(12);
    big.set(0, 11, 2.0);
    assert_eq!(big.to_string(), "2·e1_12");
    let v = Vector::from_components(&[1.0, 0.0, -3.0]).unwrap();
    assert_eq!(v.to_string(), "1·e1 - 3·e3");
}

#[test]
fn bivectors_work_up_to_n_64() {
    let mut r = rng(7);
    let n = 64;
    let a = random_bivector(&mut r, n, 1.0);
    let b = random_bivector(&mut r, n, 1.0);
    assert_eq!(a.as_slice().len(), 2016);
    let c = a.commutator(&b);
    let m = a.to_skew_matrix() * b.to_skew_matrix() - b.to_skew_matrix() * a.to_skew_matrix();
    assert!(max_abs_diff(&c.to_skew_matrix(), &m) < 1e-12);
    // Jacobi identity in so(64)
    let d = random_bivector(&mut r, n, 1.0);
    let jac = a.commutator(&b.commutator(&d))
        + b.commutator(&d.commutator(&a))
        + d.commutator(&a.commutator(&b));
    assert!(jac.max_abs() < 1e-11);
    let x = random_vector(&mut r, n);
    assert_eq!(x.left_contract(&a).dim(), 64);
    let dec = a.decompose();
    assert!((&dec.reconstruct() - &a).max_abs() < 1e-12);
    assert_eq!(dec.len(), 32);
}

/// The in-place plane rotation (three index ranges, packed storage) equals the rotor
/// sandwich R B R̃ with R = exp(−θ/2 eᵢⱼ), for every plane, both orders of the indices,
/// N = 2 … 12 (covering the sign pattern of each range).
#[test]
fn rotate_in_plane_mut_equals_the_rotor_sandwich() {
    for n in 2..=12usize {
        let c: Vec<f64> = (0..n * (n - 1) / 2)
            .map(|k| (1.3 * k as f64 + 0.2).sin())
            .collect();
        let b = Bivector::from_components(n, &c).unwrap();
        for i in 0..n {
            for j in 0..n {
                if i == j {
                    continue;
                }
                let angle = 0.7 + 0.1 * (i + 2 * j) as f64;
                let mut fast = b.clone();
                fast.rotate_in_plane_mut(i, j, angle);
                let r = Rotor::from_plane_angle(n.min(16), i, j, angle).unwrap();
                let expected = r.rotate_bivector(&b);
                let err = (&fast - &expected).max_abs();
                assert!(err < 1e-14, "N = {n}, plane ({i}, {j}): {err:e}");
            }
        }
    }
}

#[test]
fn zero_constructors_have_checked_siblings() {
    assert_eq!(Bivector::try_zero(5).unwrap(), Bivector::zero(5));
    assert_eq!(Vector::try_zero(5).unwrap(), Vector::zero(5));
    assert!(matches!(
        Bivector::try_zero(65),
        Err(AlgebraError::DimensionTooLarge { dim: 65, .. })
    ));
    assert!(matches!(
        Vector::try_zero(65),
        Err(AlgebraError::DimensionTooLarge { dim: 65, .. })
    ));
    assert_eq!(Vector::try_basis(3, 1).unwrap(), Vector::basis(3, 1));
    assert!(matches!(
        Vector::try_basis(3, 3),
        Err(AlgebraError::IndexOutOfRange { index: 3, dim: 3 })
    ));
}

#[test]
fn from_skew_matrix_eps_applies_its_tolerance() {
    let mut a = Bivector::from_components(3, &[0.3, -1.0, 2.0])
        .unwrap()
        .to_skew_matrix();
    a[(0, 1)] += 1e-10; // |A + Aᵀ| = 1e-10 against max |A| = 2: relative 5e-11
    assert!(matches!(
        Bivector::from_skew_matrix(&a),
        Err(AlgebraError::NotSkewSymmetric { .. })
    ));
    let b = Bivector::from_skew_matrix_eps(&a, 1e-10).unwrap();
    assert_close!(b.get(0, 1), 0.3 + 0.5e-10, 1e-16);
    assert!(Bivector::from_skew_matrix_eps(&a, 1e-11).is_err());
    assert!(Bivector::from_skew_matrix_eps(&a, f64::NAN).is_err());
}
