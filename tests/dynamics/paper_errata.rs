//! The paper's kinematics and Euler equations (eqs. 14–68) checked against the crate.
//!
//! Each test pins one entry of the book's errata page `book/src/errata/dynamics.md` and one
//! row of the mapping chapter. Conventions: the book's Conventions chapter (v = x⌋ω = [ω]ᵀx,
//! dL/dt = ω×L + τ, Iⁱʲⁱʲ = ½(Jᵢ + Jⱼ) from eq. 22 read literally). Indices in comments are 1-based as in
//! the paper; code is 0-based.

use crate::{random_bivector, rng};
use nalgebra::{DMatrix, DVector};
use rand::Rng;
use rotorflow::algebra::Vector;
use rotorflow::dynamics::kinematics::{centrifugal_acceleration, point_velocity};
use rotorflow::inertia::tensor::RankFourTensor;
use rotorflow::prelude::*;

/// The sign of the permutation `idx` of distinct indices (0 if two are equal).
fn levi(idx: &[usize]) -> f64 {
    let mut sign = 1.0;
    for a in 0..idx.len() {
        for b in a + 1..idx.len() {
            if idx[a] == idx[b] {
                return 0.0;
            }
            if idx[a] > idx[b] {
                sign = -sign;
            }
        }
    }
    sign
}

/// The crate's body-frame rate dω/dt = I⁻¹(ω × I(ω)) (+ I⁻¹ τ) in the principal frame.
fn crate_rate(j: &[f64], w: &Bivector, tau: Option<&Bivector>) -> Bivector {
    let inertia = InertiaMap::from_principal_second_moments(j).unwrap();
    let mut dl = w.commutator(&inertia.apply(w));
    if let Some(t) = tau {
        dl += t;
    }
    inertia.apply_inverse(&dl)
}

/// Iᵃᵇᵃᵇ = ½(J_a + J_b), 1-based.
fn i4(j: &[f64], a: usize, b: usize) -> f64 {
    0.5 * (j[a - 1] + j[b - 1])
}

/// The bivector with components s_ij · w_ij.
fn signed(w: &Bivector, s: &[f64]) -> Bivector {
    let c: Vec<f64> = w.as_slice().iter().zip(s).map(|(x, s)| x * s).collect();
    Bivector::from_components(w.dim(), &c).unwrap()
}

/// All index tuples (all-different) of length k from 0..n.
fn tuples(n: usize, k: usize) -> Vec<Vec<usize>> {
    let mut out = vec![vec![]];
    for _ in 0..k {
        out = out
            .into_iter()
            .flat_map(|t| {
                (0..n)
                    .filter(|x| !t.contains(x))
                    .map(|x| {
                        let mut u = t.clone();
                        u.push(x);
                        u
                    })
                    .collect::<Vec<_>>()
            })
            .collect();
    }
    out
}

#[test]
fn paper_eqs_43_52_68_bracket_is_minus_the_commutator_times_factorial() {
    // ½ ε^{ijs r…} ε^{p r… kl} L_kl ω_sp (eqs. 43, 52, 68: N − 3 extra indices r…) equals
    // (N − 3)! [ω × L]_ij, so the paper's dL/dt = m − (N − 3)! ω × L: the opposite sign of the
    // quadratic term (the paper's orientation convention, see eqs. 44–46) and, for N = 5
    // (eq. 68), an extra factor 2.
    let mut r = rng(4301);
    for (n, factorial) in [(3usize, 1.0), (4, 1.0), (5, 2.0)] {
        let j: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
        let w = random_bivector(&mut r, n, 1.0);
        let l = InertiaMap::from_principal_second_moments(&j)
            .unwrap()
            .apply(&w);
        let extra = n - 3;
        let mut term = DMatrix::<f64>::zeros(n, n);
        for i in 0..n {
            for jj in 0..n {
                let mut sum = 0.0;
                for first in tuples(n, 1 + extra) {
                    // first = (s, r…)
                    let s = first[0];
                    let rest = &first[1..];
                    let mut e1 = vec![i, jj, s];
                    e1.extend_from_slice(rest);
                    let a = levi(&e1);
                    if a == 0.0 {
                        continue;
                    }
                    for p in 0..n {
                        for k in 0..n {
                            for ll in 0..n {
                                let mut e2 = vec![p];
                                e2.extend_from_slice(rest);
                                e2.extend_from_slice(&[k, ll]);
                                let b = levi(&e2);
                                if b != 0.0 {
                                    sum += 0.5 * a * b * l.get(k, ll) * w.get(s, p);
                                }
                            }
                        }
                    }
                }
                term[(i, jj)] = sum;
            }
        }
        let comm = w.commutator(&l).to_skew_matrix();
        let err = (&term - &comm * factorial).abs().max();
        assert!(err < 1e-12 * comm.abs().max(), "N = {n}: {err:e}");
    }
}

#[test]
fn paper_eq_36_47_65_matrix_is_a_checkerboard_automorphism() {
    // The printed matrices have entry (i, j) = (−1)^{i+j} ω_ij for i < j (1-based): they are
    // D[ω]D with D = diag(−1, 1, −1, …). Conjugation by D commutes with the Euler flow of a
    // principal-frame body, so the sign pattern changes no equation of motion.
    let mut r = rng(3647);
    for n in 3..=5 {
        let j: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
        let w = random_bivector(&mut r, n, 1.0);
        let d = DMatrix::from_diagonal(&DVector::from_fn(
            n,
            |i, _| {
                if i % 2 == 0 { -1.0 } else { 1.0 }
            },
        ));
        let printed = DMatrix::from_fn(n, n, |a, b| {
            let (i, k) = (a + 1, b + 1);
            let sign = if (i + k) % 2 == 0 { 1.0 } else { -1.0 };
            match a.cmp(&b) {
                std::cmp::Ordering::Less => sign * w.get(a, b),
                std::cmp::Ordering::Greater => -sign * w.get(b, a),
                std::cmp::Ordering::Equal => 0.0,
            }
        });
        let conj = &d * w.to_skew_matrix() * &d;
        assert!((&printed - &conj).abs().max() < 1e-15, "N = {n}");
        let wd = Bivector::from_skew_matrix(&conj).unwrap();
        let lhs = crate_rate(&j, &wd, None).to_skew_matrix();
        let rhs = &d * crate_rate(&j, &w, None).to_skew_matrix() * &d;
        assert!((lhs - rhs).abs().max() < 1e-13, "N = {n}");
    }
}

#[test]
fn paper_eqs_36_to_38_give_three_different_angular_velocity_vectors() {
    // Eq. (36) is the cross-product matrix of Ω_36 = (ω23, ω13, ω12); eq. (37) read with
    // ω_jk, Ω^i = −½ Σ ε^{ijk} ω_jk, gives (−ω23, ω13, −ω12) = −Ω_crate; eq. (38) gives half
    // of eq. (37). The crate (Conventions chapter): Ω = (ω23, −ω13, ω12), with v = x⌋ω = Ω × x.
    let w = Bivector::from_components(3, &[0.7, -1.1, 0.4]).unwrap(); // 12, 13, 23
    let (w12, w13, w23) = (w.get(0, 1), w.get(0, 2), w.get(1, 2));
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let x = [0.3, -0.8, 1.2];
    // The crate's velocity is Ω_crate × x.
    let v = point_velocity(&w, &Vector::from_components(&x).unwrap());
    let design = [w23, -w13, w12];
    let c = cross(design, x);
    for k in 0..3 {
        assert!((v[k] - c[k]).abs() < 1e-15);
    }
    // Eq. (36) as printed, applied to x, is Ω_36 × x.
    let m36 = [[0.0, -w12, w13], [w12, 0.0, -w23], [-w13, w23, 0.0]];
    let omega36 = [w23, w13, w12];
    let c36 = cross(omega36, x);
    for (row, expected) in m36.iter().zip(c36) {
        let mx: f64 = row.iter().zip(&x).map(|(a, b)| a * b).sum();
        assert!((mx - expected).abs() < 1e-15);
    }
    // Eq. (37) with the full double sum.
    let mut eq37 = [0.0; 3];
    for (i, value) in eq37.iter_mut().enumerate() {
        for j in 0..3 {
            for k in 0..3 {
                *value += -0.5 * levi(&[i, j, k]) * w.get(j, k);
            }
        }
    }
    let eq38 = [-0.5 * w23, 0.5 * w13, -0.5 * w12];
    for k in 0..3 {
        assert!((eq37[k] + design[k]).abs() < 1e-15, "eq. 37 = −Ω");
        assert!((eq38[k] - 0.5 * eq37[k]).abs() < 1e-15, "eq. 38 = ½ eq. 37");
    }
    assert!(
        (omega36[1] - design[1]).abs() > 1.0,
        "Ω_36 differs from Ω in the 13 sign"
    );
}

#[test]
fn paper_eqs_39_48_66_momentum_entries_are_half_of_eq_32() {
    // The printed L matrices carry I^{ijij} ω_ij; eq. (32) with the Einstein sum over all
    // k, l gives L_ij = 2 I^{ijij} ω_ij = (J_i + J_j) ω_ij in the principal frame.
    let mut r = rng(3948);
    for n in 3..=5 {
        let j: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
        let jm = DMatrix::from_diagonal(&DVector::from_vec(j.clone()));
        let rank4 = RankFourTensor::from_mass_tensor(&jm).unwrap();
        let w = random_bivector(&mut r, n, 1.0);
        let full = rank4.apply(&w.to_skew_matrix()).unwrap();
        let l = InertiaMap::from_principal_second_moments(&j)
            .unwrap()
            .apply(&w);
        for a in 0..n {
            for b in a + 1..n {
                let printed = rank4.get(a, b, a, b) * w.get(a, b);
                assert!((full[(a, b)] - l.get(a, b)).abs() < 1e-14);
                assert!((2.0 * printed - l.get(a, b)).abs() < 1e-14);
            }
        }
    }
}

/// The paper's 3D Euler equations (44)–(46) solved for dω/dt, torque m (paper components).
fn paper_3d_rate(j: &[f64], p: &[f64; 3], m: &[f64; 3]) -> [f64; 3] {
    let [p12, p13, p23] = *p;
    let (a, b, c) = (i4(j, 1, 2), i4(j, 1, 3), i4(j, 2, 3));
    [
        (m[0] - (b - c) * p13 * p23) / a,
        (m[1] - (c - a) * p12 * p23) / b,
        (m[2] - (a - b) * p12 * p13) / c,
    ]
}

#[test]
fn paper_eqs_44_to_46_are_eulers_equations_with_omega13_reversed_and_half_torque() {
    // With the paper's components p = (ω12, −ω13, ω23) (the Ω_36 of eq. 36) eqs. (44)–(46)
    // are the crate's equations, provided the torque in them is m = ½ τ (the paper's L is half
    // of eq. 32's). Reversing every component (p = −ω) works as well: the checkerboard sign
    // of eq. (36) is an automorphism.
    let mut r = rng(4446);
    for _ in 0..20 {
        let j: Vec<f64> = (0..3).map(|_| r.gen_range(0.3..2.0)).collect();
        let w = random_bivector(&mut r, 3, 1.0);
        let tau = random_bivector(&mut r, 3, 1.0);
        for s in [[1.0, -1.0, 1.0], [-1.0, -1.0, -1.0]] {
            let dw = signed(&crate_rate(&j, &w, Some(&tau)), &s);
            let p = signed(&w, &s);
            let m = signed(&tau, &s);
            let half = [
                0.5 * m.as_slice()[0],
                0.5 * m.as_slice()[1],
                0.5 * m.as_slice()[2],
            ];
            let pr = paper_3d_rate(
                &j,
                &[p.as_slice()[0], p.as_slice()[1], p.as_slice()[2]],
                &half,
            );
            for (k, (a, b)) in pr.iter().zip(dw.as_slice()).enumerate() {
                assert!((a - b).abs() < 1e-13, "{s:?} {k}");
            }
        }
    }
}

/// The paper's 4D equations (53)–(58) as printed, torque-free, solved for dω/dt; components in
/// the order 12, 13, 14, 23, 24, 34.
fn paper_4d_rate(j: &[f64], w: &[f64]) -> [f64; 6] {
    let i = |a, b| i4(j, a, b);
    let [w12, w13, w14, w23, w24, w34] = [w[0], w[1], w[2], w[3], w[4], w[5]];
    let d12 = -((i(2, 4) - i(1, 2)) * w13 * w23 - (i(1, 3) - i(3, 4)) * w14 * w24) / i(1, 4);
    let d23 = -((i(1, 4) - i(2, 4)) * w13 * w12 - (i(2, 3) - i(1, 3)) * w24 * w34) / i(1, 2);
    let d13 = -((i(1, 2) - i(1, 4)) * w12 * w23 - (i(2, 3) - i(3, 4)) * w34 * w14) / i(2, 4);
    let d24 = -((i(1, 4) - i(3, 4)) * w12 * w14 - (i(1, 2) - i(2, 3)) * w23 * w34) / i(1, 3);
    let d14 = -((i(1, 3) - i(1, 4)) * w12 * w24 - (i(2, 4) - i(2, 3)) * w34 * w13) / i(3, 4);
    let d34 = -((i(2, 4) - i(3, 4)) * w13 * w14 - (i(1, 3) - i(1, 2)) * w23 * w24) / i(2, 3);
    [d12, d13, d14, d23, d24, d34]
}

fn permutations(n: usize) -> Vec<Vec<usize>> {
    tuples(n, n)
}

#[test]
fn paper_eqs_53_to_58_hold_only_for_cyclically_relabelled_moments() {
    // As printed, eqs. (53)–(58) disagree with dL/dt = ω × L. Searching all 24 relabellings
    // σ of the inertia axes and all 64 sign choices of the six components, they agree only
    // for J_crate = (J4, J1, J2, J3), i.e. the coefficient printed I^{abab} belongs to the
    // plane (σa σb) with σ = (1→4, 2→1, 3→2, 4→3); with p = −ω (the paper's convention).
    let mut r = rng(5358);
    let j: Vec<f64> = (0..4).map(|_| r.gen_range(0.3..2.0)).collect();
    let w = random_bivector(&mut r, 4, 1.0);
    let paper_identity = paper_4d_rate(&j, signed(&w, &[-1.0; 6]).as_slice());
    let crate_identity = signed(&crate_rate(&j, &w, None), &[-1.0; 6]);
    let mismatch = paper_identity
        .iter()
        .zip(crate_identity.as_slice())
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(mismatch > 1e-2, "as printed they should disagree");
    let mut found = Vec::new();
    for perm in permutations(4) {
        let jc: Vec<f64> = perm.iter().map(|&k| j[k]).collect();
        for bits in 0..64u32 {
            let s: Vec<f64> = (0..6)
                .map(|k| if bits >> k & 1 == 1 { -1.0 } else { 1.0 })
                .collect();
            let p = signed(&w, &s);
            let paper = paper_4d_rate(&j, p.as_slice());
            let expected = signed(&crate_rate(&jc, &w, None), &s);
            let ok = paper
                .iter()
                .zip(expected.as_slice())
                .all(|(a, b)| (a - b).abs() < 1e-12);
            if ok {
                found.push((perm.clone(), bits));
            }
        }
    }
    assert!(!found.is_empty());
    assert!(
        found.iter().all(|(perm, _)| perm == &vec![3, 0, 1, 2]),
        "{found:?}"
    );
    assert!(
        found.iter().any(|(_, bits)| *bits == 63),
        "p = −ω is among the solutions"
    );
}

#[test]
fn paper_corrected_component_form_matches_in_any_dimension() {
    // The corrected component form in the paper's convention (p = −ω, m = ½τ):
    // I^{ijij} dp_ij/dt + Σ_{k ∉ {i,j}} (I^{ikik} − I^{jkjk}) p_ik p_jk = m^{ij},
    // with p_ik = −p_ki. For N = 3 it is eqs. (44)–(46); for N = 4 it replaces (53)–(58).
    let mut r = rng(5999);
    for n in 3..=6 {
        let j: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
        let w = random_bivector(&mut r, n, 1.0);
        let tau = random_bivector(&mut r, n, 1.0);
        let p = &w * -1.0;
        let m = &tau * -0.5;
        let expected = &crate_rate(&j, &w, Some(&tau)) * -1.0;
        for a in 0..n {
            for b in a + 1..n {
                let ia = |x: usize, y: usize| i4(&j, x + 1, y + 1);
                let coupling: f64 = (0..n)
                    .filter(|&k| k != a && k != b)
                    .map(|k| (ia(a, k) - ia(b, k)) * p.get(a, k) * p.get(b, k))
                    .sum();
                let rate = (m.get(a, b) - coupling) / ia(a, b);
                assert!((rate - expected.get(a, b)).abs() < 1e-13, "N = {n}");
            }
        }
    }
}

#[test]
fn paper_eqs_59_to_64_reduced_systems_use_the_wrong_moments() {
    // S4 = {ω14 = ω24 = ω34 = 0} is invariant and its motion is the 3D body of axes 1, 2, 3:
    // the crate's rates do not depend on J4. The printed eqs. (59)–(61) divide by I^{1414} and
    // use I^{2424}, which do.
    let mut r = rng(5961);
    let j: Vec<f64> = (0..4).map(|_| r.gen_range(0.3..2.0)).collect();
    let w = Bivector::from_components(4, &[0.8, -0.4, 0.0, 0.6, 0.0, 0.0]).unwrap();
    let mut j2 = j.clone();
    j2[3] += 0.7;
    let a = crate_rate(&j, &w, None);
    let b = crate_rate(&j2, &w, None);
    assert!((&a - &b).max_abs() < 1e-15, "the 1-2-3 motion ignores J4");
    for k in [2, 4, 5] {
        assert_eq!(a.as_slice()[k], 0.0, "S4 is invariant");
    }
    let p = signed(&w, &[-1.0; 6]);
    let pa = paper_4d_rate(&j, p.as_slice());
    let pb = paper_4d_rate(&j2, p.as_slice());
    assert!(
        (pa[0] - pb[0]).abs() > 1e-3,
        "the printed eq. (59) depends on J4"
    );
}

#[test]
fn paper_eqs_49_to_51_polynomial_lacks_lambda4_and_its_coefficients_are_not_the_energy() {
    // det(L − λE) = λ⁴ + |L|² λ² + Pf(L)² for the printed (checkerboard) 4×4 matrix: eq. (49)
    // omits λ⁴; k0 (eq. 50) is Pf², k1 (eq. 51) is |L|² (with L_ij = I^{ijij}ω_ij as printed).
    // Neither is the energy: a rotated momentum has the same k0, k1 and another energy.
    let mut r = rng(4951);
    let j: Vec<f64> = vec![0.4, 0.9, 1.3, 2.0];
    let w = random_bivector(&mut r, 4, 1.0);
    let printed = Bivector::from_components(
        4,
        &rotorflow::algebra::pairs(4)
            .map(|(a, b)| i4(&j, a + 1, b + 1) * w.get(a, b))
            .collect::<Vec<_>>(),
    )
    .unwrap();
    let d = DMatrix::from_diagonal(&DVector::from_vec(vec![-1.0, 1.0, -1.0, 1.0]));
    let m = &d * printed.to_skew_matrix() * &d;
    let k0 = (i4(&j, 2, 3) * i4(&j, 1, 4) * w.get(0, 3) * w.get(1, 2)
        - i4(&j, 1, 3) * i4(&j, 2, 4) * w.get(0, 2) * w.get(1, 3)
        + i4(&j, 1, 2) * i4(&j, 3, 4) * w.get(0, 1) * w.get(2, 3))
    .powi(2);
    let k1 = printed.norm_squared();
    assert!((k0 - printed.pfaffian().powi(2)).abs() < 1e-14);
    for lambda in [0.3, 1.7, -2.2] {
        let det = (&m - DMatrix::identity(4, 4) * lambda).determinant();
        let full = lambda.powi(4) + k1 * lambda * lambda + k0;
        let eq49 = k0 + k1 * lambda * lambda;
        assert!((det - full).abs() < 1e-12 * full.abs().max(1.0));
        assert!((det - eq49).abs() > 1e-3);
    }
    // Same Casimirs, different energy.
    let inertia = InertiaMap::from_principal_second_moments(&j).unwrap();
    let l = inertia.apply(&w);
    let turned = Rotor::from_plane_angle(4, 0, 3, 0.9)
        .unwrap()
        .rotate_bivector(&l);
    let energy = |l: &Bivector| 0.5 * inertia.apply_inverse(l).inner(l);
    let (c1, c2) = (
        l.characteristic_coefficients(),
        turned.characteristic_coefficients(),
    );
    for k in 0..3 {
        assert!((c1[k] - c2[k]).abs() < 1e-12 * c1[k].abs().max(1.0));
    }
    assert!((energy(&l) - energy(&turned)).abs() > 0.05 * energy(&l));
}

#[test]
fn paper_eq_67_5d_polynomial_lacks_the_leading_term() {
    // det(L − λE) = −(λ⁵ + c1 λ³ + c2 λ) for a 5×5 skew L; eq. (67) keeps only k1 λ + k3 λ³.
    let mut r = rng(67);
    let l = random_bivector(&mut r, 5, 1.0);
    let c = l.characteristic_coefficients();
    for lambda in [0.4, -1.3, 2.1] {
        let det = (l.to_skew_matrix() - DMatrix::identity(5, 5) * lambda).determinant();
        let full = -(lambda.powi(5) + c[1] * lambda.powi(3) + c[2] * lambda);
        assert!((det - full).abs() < 1e-12 * full.abs().max(1.0));
        assert!((det + c[1] * lambda.powi(3) + c[2] * lambda).abs() > 1e-3);
    }
}

#[test]
fn paper_eqs_14_15_18_levi_civita_velocity_rotates_the_dual_plane() {
    // In 4D, (dT_rot)_l = Σ ε_{lijk} ω_ij T_k (eqs. 14, 15, 18) equals −2 T⌋(⋆ω), with
    // (⋆ω)_ab = ½ Σ ε_{abij} ω_ij: the velocity of a rotation in the orthogonal (dual)
    // planes. The point velocity is T⌋ω. For ω = e12: e1 moves to e2 (T⌋ω = e2), but the
    // printed form gives 0 for e1 and −2e4 for e3, which does not move at all.
    let mut r = rng(1415);
    let n = 4;
    let eps_velocity = |w: &Bivector, t: &Vector| {
        let mut v = Vector::zero(n);
        for l in 0..n {
            for i in 0..n {
                for jj in 0..n {
                    for k in 0..n {
                        v[l] += levi(&[l, i, jj, k]) * w.get(i, jj) * t[k];
                    }
                }
            }
        }
        v
    };
    let dual = |w: &Bivector| {
        let mut c = Vec::new();
        for (a, b) in rotorflow::algebra::pairs(n) {
            let mut s = 0.0;
            for i in 0..n {
                for jj in 0..n {
                    s += 0.5 * levi(&[a, b, i, jj]) * w.get(i, jj);
                }
            }
            c.push(s);
        }
        Bivector::from_components(n, &c).unwrap()
    };
    for _ in 0..10 {
        let w = random_bivector(&mut r, n, 1.0);
        let t = Vector::from_components(&[0.3, -0.7, 1.1, 0.5]).unwrap();
        let literal = eps_velocity(&w, &t);
        let expected = point_velocity(&dual(&w), &t) * -2.0;
        assert!((&literal - &expected).norm() < 1e-14);
    }
    let e12 = Bivector::from_plane(4, 0, 1, 1.0).unwrap();
    let (e1, e3) = (Vector::basis(4, 0), Vector::basis(4, 2));
    assert_eq!(point_velocity(&e12, &e1), Vector::basis(4, 1));
    assert!(eps_velocity(&e12, &e1).norm() == 0.0);
    assert!(point_velocity(&e12, &e3).norm() == 0.0);
    assert!((&eps_velocity(&e12, &e3) - &(Vector::basis(4, 3) * -2.0)).norm() == 0.0);
}

#[test]
fn paper_eq_17_tensor_transport_is_quadratic_in_omega() {
    // A body-fixed tensor T seen in space, Q T Qᵀ with Q(t) = expm(t[ω]ᵀ), changes at the rate
    // [ω]ᵀT + T[ω] at t = 0: linear in ω. Eq. (17)'s rotation term, the product of the two
    // vector terms, is quadratic in ω (doubling ω quadruples it) and has the wrong value.
    let mut r = rng(17);
    let n = 4;
    let t_body = DMatrix::from_diagonal(&DVector::from_vec(vec![0.4, 0.9, 1.3, 2.0]));
    let w = random_bivector(&mut r, n, 1.0);
    let rate = |w: &Bivector| {
        let h = 1e-6;
        let q = |s: f64| Rotor::from_rotation_bivector(&(w * s)).to_matrix();
        let (qp, qm) = (q(h), q(-h));
        (&qp * &t_body * qp.transpose() - &qm * &t_body * qm.transpose()) / (2.0 * h)
    };
    let a = |w: &Bivector| {
        DMatrix::from_fn(n, n, |l, k| {
            let mut s = 0.0;
            for i in 0..n {
                for jj in 0..n {
                    s += levi(&[l, i, jj, k]) * w.get(i, jj);
                }
            }
            s
        })
    };
    let paper = |w: &Bivector| a(w) * &t_body * a(w).transpose();
    let wm = w.to_skew_matrix();
    let exact = wm.transpose() * &t_body + &t_body * &wm;
    assert!((rate(&w) - &exact).abs().max() < 1e-8);
    let w2 = &w * 2.0;
    assert!((rate(&w2) - &exact * 2.0).abs().max() < 1e-7);
    assert!((paper(&w2) - paper(&w) * 4.0).abs().max() < 1e-12);
    assert!((paper(&w) - &exact).abs().max() > 1e-2);
}

#[test]
fn paper_eqs_19_to_21_use_the_inertial_velocity_where_the_rotating_one_belongs() {
    // A particle at rest in space, seen from a frame rotating with constant ω, moves on a
    // circle: its acceleration in that frame points inward, −(centrifugal). The crate's
    // Coriolis term with the rotating-frame velocity V plus the centrifugal term give it.
    // Eq. (20) with v the inertial velocity (here 0) leaves only the centrifugal term,
    // which points outward.
    use rotorflow::dynamics::kinematics::coriolis_acceleration;
    let n = 4;
    let w = Bivector::from_components(n, &[0.9, 0.0, 0.3, 0.0, -0.2, 0.6]).unwrap();
    let x = Vector::from_components(&[1.0, 0.4, -0.3, 0.7]).unwrap();
    // y(t) = R̃(t) x R(t), R(t) = exp(−ωt/2): body coordinates of the fixed point.
    let y = |t: f64| {
        Rotor::from_rotation_bivector(&(&w * t))
            .reverse()
            .rotate_vector(&x)
    };
    let h = 1e-4;
    let vel = (&y(h) - &y(-h)) * (0.5 / h);
    let acc = (&(&y(h) + &y(-h)) - &(&y(0.0) * 2.0)) * (1.0 / (h * h));
    let crate_acc = &coriolis_acceleration(&w, &vel) + &centrifugal_acceleration(&w, &y(0.0));
    assert!((&acc - &crate_acc).norm() < 1e-6, "{acc} vs {crate_acc}");
    let paper20 = centrifugal_acceleration(&w, &y(0.0)); // a = 0, v = 0
    assert!(
        (&acc + &paper20).norm() < 1e-6,
        "the true acceleration is −(eq. 20)"
    );
    assert!(paper20.norm() > 0.1);
}
