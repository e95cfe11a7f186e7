//! The inertia map against independent routes: the direct sum Σ m x∧(x⌋ω) over point masses,
//! the point-velocity kinetic energy, the rank-4 view, and rotations of the body.

use crate::common::{random_bivector, random_rotation, random_spd, rng};
use nalgebra::{DMatrix, DVector};
use rand::Rng;
use rotorflow::algebra::Vector;
use rotorflow::inertia::tensor::RankFourTensor;
use rotorflow::prelude::*;

fn random_cloud(r: &mut impl Rng, n: usize, count: usize) -> (Vec<f64>, Vec<DVector<f64>>) {
    let masses = (0..count).map(|_| r.gen_range(0.5..2.0)).collect();
    let points = (0..count)
        .map(|_| DVector::from_fn(n, |_, _| r.gen_range(-1.0..1.0)))
        .collect();
    (masses, points)
}

#[test]
fn map_equals_direct_sum_over_point_masses() {
    // I(ω) = Σ m (x − c)∧((x − c)⌋ω): computed with the algebra alone, point by point.
    let mut r = rng(101);
    for n in 2..=7 {
        let (masses, points) = random_cloud(&mut r, n, 3 * n);
        let body = Body::point_masses(&masses, &points).unwrap();
        let map = InertiaMap::from_body(&body).unwrap();
        let c = body.center_of_mass();
        for _ in 0..5 {
            let w = random_bivector(&mut r, n, 1.0);
            let mut direct = Bivector::zero(n);
            let mut energy = 0.0;
            for (m, p) in masses.iter().zip(&points) {
                let x = Vector::from(&(p - c));
                let v = x.left_contract(&w);
                direct += &(x.wedge(&v) * *m);
                energy += 0.5 * m * v.norm_squared();
            }
            let l = map.apply(&w);
            assert!((&l - &direct).max_abs() < 1e-13, "n={n}");
            // T = ½⟨ω, I(ω)⟩ = ½ Σ m |x⌋ω|²
            assert!((map.kinetic_energy(&w) - energy).abs() < 1e-13 * energy.max(1.0));
        }
    }
}

#[test]
fn inverse_undoes_apply_in_any_frame() {
    let mut r = rng(102);
    for n in 2..=8 {
        let j = random_spd(n, &mut r);
        let map = InertiaMap::from_mass_tensor(&j).unwrap();
        assert!(!map.is_principal() || n == 1);
        for _ in 0..5 {
            let w = random_bivector(&mut r, n, 1.0);
            let back = map.apply_inverse(&map.apply(&w));
            assert!((&back - &w).max_abs() < 1e-12, "n={n}");
            // and the inverse solves the Lyapunov equation J[ω] + [ω]J = [L]
            let l = random_bivector(&mut r, n, 1.0);
            let w2 = map.apply_inverse(&l);
            let lhs = &j * w2.to_skew_matrix() + w2.to_skew_matrix() * &j;
            assert!((lhs - l.to_skew_matrix()).abs().max() < 1e-12);
        }
    }
}

#[test]
fn matrix_is_symmetric_positive_definite_with_plane_moment_eigenvalues() {
    let mut r = rng(103);
    for n in 2..=7 {
        let j = random_spd(n, &mut r);
        let map = InertiaMap::from_mass_tensor(&j).unwrap();
        let m = map.to_matrix();
        assert!((&m - m.transpose()).abs().max() < 1e-14);
        let mut eig: Vec<f64> = nalgebra::SymmetricEigen::new(m)
            .eigenvalues
            .iter()
            .copied()
            .collect();
        eig.sort_by(f64::total_cmp);
        let mut pm = map.plane_moments();
        pm.sort_by(f64::total_cmp);
        for (a, b) in eig.iter().zip(&pm) {
            assert!((a - b).abs() < 1e-12, "{eig:?} vs {pm:?}");
        }
        assert!(eig[0] > 0.0);
    }
}

#[test]
fn principal_frame_diagonalises_the_map() {
    let mut r = rng(104);
    for n in 2..=8 {
        let j = random_spd(n, &mut r);
        let map = InertiaMap::from_mass_tensor(&j).unwrap();
        let moments = map.principal_second_moments().unwrap().to_vec();
        let rp = map.principal_rotor().unwrap().unwrap();
        // the rotor takes eᵢ to the i-th principal axis
        let axes = map.principal_axes().unwrap();
        for i in 0..n {
            let pi = rp.rotate_vector(&Vector::basis(n, i));
            for k in 0..n {
                assert!((pi[k] - axes[(k, i)]).abs() < 1e-12);
            }
        }
        // the map of the principal-frame body is diagonal with Jᵢ + Jⱼ
        let principal = map.rotated(&rp.reverse()).unwrap();
        let m = principal.to_matrix();
        for ((i, jx), c) in rotorflow::algebra::pairs(n).zip(0..) {
            assert!((m[(c, c)] - (moments[i] + moments[jx])).abs() < 1e-12);
        }
        assert!(
            (m.clone() - DMatrix::from_diagonal(&m.diagonal()))
                .abs()
                .max()
                < 1e-12
        );
    }
}

#[test]
fn rotating_the_body_rotates_the_map() {
    let mut r = rng(105);
    for n in 2..=6 {
        let (masses, points) = random_cloud(&mut r, n, 2 * n + 2);
        let body = Body::point_masses(&masses, &points).unwrap();
        let q = random_rotation(n, &mut r);
        let turned = body.rotated(&q).unwrap();
        let rotor = Rotor::from_matrix(&q).unwrap();
        let a = InertiaMap::from_body(&turned).unwrap();
        let b = InertiaMap::from_body(&body)
            .unwrap()
            .rotated(&rotor)
            .unwrap();
        let w = random_bivector(&mut r, n, 1.0);
        assert!((&a.apply(&w) - &b.apply(&w)).max_abs() < 1e-12);
        // equivariance: I′(RωR̃) = R I(ω) R̃
        let map = InertiaMap::from_body(&body).unwrap();
        let lhs = a.apply(&rotor.rotate_bivector(&w));
        let rhs = rotor.rotate_bivector(&map.apply(&w));
        assert!((&lhs - &rhs).max_abs() < 1e-12);
        // the general (matrix) map rotates the same way
        let general = InertiaMap::from_matrix(n, &map.to_matrix()).unwrap();
        let g = general.rotated(&rotor).unwrap();
        assert!((&g.apply(&w) - &a.apply(&w)).max_abs() < 1e-12);
    }
}

#[test]
fn rank_four_view_reproduces_the_map() {
    let mut r = rng(106);
    for n in 2..=6 {
        let j = random_spd(n, &mut r);
        let map = InertiaMap::from_mass_tensor(&j).unwrap();
        let t = RankFourTensor::from_mass_tensor(&j).unwrap();
        let w = random_bivector(&mut r, n, 1.0);
        let l = t.apply(&w.to_skew_matrix()).unwrap();
        let expected = map.apply(&w).to_skew_matrix();
        assert!((l - expected).abs().max() < 1e-13, "n={n}");
    }
}

#[test]
fn plane_moments_in_4d_obey_the_weyl_relation() {
    // I12 + I34 = I13 + I24 = I14 + I23 = tr J for every physical 4D body.
    let mut r = rng(107);
    for _ in 0..20 {
        let j = random_spd(4, &mut r);
        let map = InertiaMap::from_mass_tensor(&j).unwrap();
        let p = map.plane_moments();
        let tr = j.trace();
        for s in [p[0] + p[5], p[1] + p[4], p[2] + p[3]] {
            assert!((s - tr).abs() < 1e-12 * tr);
        }
    }
}

#[test]
fn classical_3d_moments_and_the_non_physical_test_body() {
    // A physical body (1, 2, 2.5): classical I₁ = J₂ + J₃ about e1 is the plane moment of e23.
    let map = InertiaMap::from_classical_3d([1.0, 2.0, 2.5]).unwrap();
    assert!(map.is_physical());
    let m = map.to_matrix();
    assert!((m[(2, 2)] - 1.0).abs() < 1e-15 && (m[(1, 1)] - 2.0).abs() < 1e-15);
    assert!((m[(0, 0)] - 2.5).abs() < 1e-15);
    // Hairer–Lubich–Wanner (2, 1, 2/3) violates the triangle inequality: no J exists
    let hlw = InertiaMap::from_classical_3d([2.0, 1.0, 2.0 / 3.0]).unwrap();
    assert!(!hlw.is_physical());
    let w = Bivector::from_components(3, &[0.3, -0.2, 0.5]).unwrap();
    let l = hlw.apply(&w);
    assert_eq!(l.as_slice(), &[0.3 * 2.0 / 3.0, -0.2 * 1.0, 0.5 * 2.0]);
    assert!(matches!(
        InertiaMap::from_principal_second_moments(&[-1.0 / 6.0, 0.5, 1.5]),
        Err(InertiaError::NegativeMoment { .. })
    ));
}

#[test]
fn bad_input_gives_clear_errors() {
    // a rod (flat in two directions): the plane of its two zero moments is singular
    let err = InertiaMap::from_principal_second_moments(&[0.0, 0.0, 1.0]).unwrap_err();
    assert!(
        matches!(err, InertiaError::DegeneratePlane { plane: (0, 1), .. }),
        "{err}"
    );
    assert!(err.to_string().contains("p1∧p2"));
    // a flat plate in 3D is fine (one zero moment), a flat 4D body in two directions is not
    assert!(InertiaMap::from_principal_second_moments(&[0.0, 1.0, 1.0]).is_ok());
    assert!(InertiaMap::from_principal_second_moments(&[0.0, 0.0, 1.0, 1.0]).is_err());
    assert!(matches!(
        InertiaMap::from_mass_tensor(&DMatrix::from_row_slice(2, 2, &[1.0, 0.5, 0.0, 1.0])),
        Err(InertiaError::NotSymmetric { .. })
    ));
    assert!(matches!(
        InertiaMap::from_principal_second_moments(&[1.0, f64::NAN]),
        Err(InertiaError::NonFinite { .. })
    ));
    assert!(matches!(
        InertiaMap::from_plane_moments(&[1.0, 2.0]),
        Err(InertiaError::LengthMismatch { .. })
    ));
    assert!(matches!(
        InertiaMap::from_plane_moments(&[1.0, 0.0, 2.0]),
        Err(InertiaError::NotPositiveDefinite { .. })
    ));
    assert!(matches!(
        InertiaMap::from_matrix(3, &DMatrix::identity(2, 2)),
        Err(InertiaError::WrongShape { .. })
    ));
    let map = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0]).unwrap();
    assert!(matches!(
        map.try_apply(&Bivector::zero(4)),
        Err(InertiaError::DimensionMismatch {
            expected: 3,
            found: 4,
            ..
        })
    ));
    // a flat body from the catalogue: the error names the degenerate plane
    let rod = Body::point_masses(
        &[1.0, 1.0],
        &[
            DVector::from_vec(vec![1.0, 0.0, 0.0]),
            DVector::from_vec(vec![-1.0, 0.0, 0.0]),
        ],
    )
    .unwrap();
    assert!(matches!(
        InertiaMap::from_body(&rod),
        Err(InertiaError::DegeneratePlane { .. })
    ));
}

#[test]
fn nearly_flat_bodies_with_condition_1e12_still_invert() {
    // J = diag(1e-12, 1, 1, 1): plane moments 1 + 1e-12 … 2, condition ~2; a body flat in
    // one direction is fine, and the inverse stays accurate.
    let map = InertiaMap::from_principal_second_moments(&[1e-12, 1.0, 1.0, 1.0]).unwrap();
    let mut r = rng(108);
    let w = random_bivector(&mut r, 4, 1.0);
    assert!((&map.apply_inverse(&map.apply(&w)) - &w).max_abs() < 1e-15);
    // two small directions: plane moment 2e-12 against 2, condition 1e12
    let map = InertiaMap::from_principal_second_moments(&[1e-12, 1e-12, 1.0, 1.0]).unwrap();
    let back = map.apply_inverse(&map.apply(&w));
    assert!((&back - &w).max_abs() < 1e-15);
    let q = random_rotation(4, &mut r);
    let j = &q
        * DMatrix::from_diagonal(&DVector::from_vec(vec![1e-12, 1e-12, 1.0, 1.0]))
        * q.transpose();
    let map = InertiaMap::from_mass_tensor(&j).unwrap();
    let back = map.apply_inverse(&map.apply(&w));
    // in a general frame the 1e12 condition number costs digits: ε·κ ≈ 2e-4 worst case
    assert!(
        (&back - &w).max_abs() < 1e-3,
        "{:e}",
        (&back - &w).max_abs()
    );
}
