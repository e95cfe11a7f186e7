//! The paper's tensor views: the rank-4 tensor of eq. (22) reproduces L = J[ω] + [ω]J, has
//! the symmetries of eq. (22); the literal Levi-Civita contraction of eqs. (23)/(24)/(31)
//! equals 2 (N − 2)! (tr J · 1 − J); gyration radii (eq. 27) and trace (eq. 29).
use crate::common::{EPS, max_abs, random_rotation, random_skew, random_spd, rng};
use nalgebra::{DMatrix, DVector};
use rotorflow::inertia::Body;
use rotorflow::inertia::InertiaError;
use rotorflow::inertia::tensor::{ContractedInertia, ContractionNormalization, RankFourTensor};

#[test]
fn rank4_reproduces_angular_momentum_n2_to_n6() {
    // L_ij = Σ_{k,l} I^{ijkl} ω_kl = (J[ω] + [ω]J)_ij for random J and skew ω. Each entry is
    // a sum of N² products; 8 N² ulp of |J||ω| N covers it (observed ~1 ulp).
    for n in 2..=6 {
        let mut r = rng(1000 + n as u64);
        for _ in 0..20 {
            let j = random_spd(n, &mut r);
            let omega = random_skew(n, &mut r);
            let tensor = RankFourTensor::from_mass_tensor(&j).unwrap();
            let l = tensor.apply(&omega).unwrap();
            let expected = &j * &omega + &omega * &j;
            let tol = 8.0 * (n * n) as f64 * EPS * max_abs(&j) * max_abs(&omega) * n as f64;
            assert_matrix_close!(l, expected, tol, "N={n}");
            // L is skew.
            assert_matrix_close!(l.transpose(), -&l, tol, "N={n} skew");
        }
    }
}

#[test]
fn rank4_has_the_symmetries_stated_under_eq22() {
    // I^{ijkl} = −I^{jikl} = −I^{ijlk} = I^{klij}, I^{ijkl} + I^{iklj} + I^{iljk} = 0.
    for n in 2..=5 {
        let mut r = rng(2000 + n as u64);
        let j = random_spd(n, &mut r);
        let t = RankFourTensor::from_mass_tensor(&j).unwrap();
        let tol = 4.0 * EPS * max_abs(&j);
        for i in 0..n {
            for jj in 0..n {
                for k in 0..n {
                    for l in 0..n {
                        let v = t.get(i, jj, k, l);
                        assert_close!(v, -t.get(jj, i, k, l), tol);
                        assert_close!(v, -t.get(i, jj, l, k), tol);
                        assert_close!(v, t.get(k, l, i, jj), tol);
                        let bianchi = v + t.get(i, k, l, jj) + t.get(i, l, jj, k);
                        assert_close!(bianchi, 0.0, tol);
                    }
                }
            }
        }
    }
}

#[test]
fn rank4_principal_components_are_half_plane_moments() {
    // In the principal frame I^{ijij} = ½ (J_i + J_j) (paper eqs. 40–42).
    let j = DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, 2.5, 4.0, 7.0]));
    let t = RankFourTensor::from_mass_tensor(&j).unwrap();
    for a in 0..4 {
        for b in 0..4 {
            if a != b {
                assert_eq!(t.get(a, b, a, b), 0.5 * (j[(a, a)] + j[(b, b)]));
                assert_eq!(t.get(a, b, b, a), -0.5 * (j[(a, a)] + j[(b, b)]));
            }
        }
    }
    assert_eq!(t.components().len(), 256);
    assert_eq!(t.try_get(4, 0, 0, 0), None);
}

#[test]
#[should_panic(expected = "out of range")]
fn rank4_get_panics_out_of_range() {
    let t = RankFourTensor::from_mass_tensor(&DMatrix::identity(3, 3)).unwrap();
    let _ = t.get(0, 0, 3, 0);
}

#[test]
fn literal_levi_civita_sum_matches_closed_form() {
    // The literal sum Σ ε_{pst r…n} ε_{m r…n kl} I^{stkl} over all indices equals
    // 2 (N − 2)! (tr J · 1 − J), for random non-diagonal J, N = 3…8.
    for n in 3..=8 {
        let mut r = rng(3000 + n as u64);
        let j = random_spd(n, &mut r);
        let literal = RankFourTensor::from_mass_tensor(&j)
            .unwrap()
            .levi_civita_contraction()
            .unwrap();
        let closed =
            ContractedInertia::from_mass_tensor(&j, ContractionNormalization::LeviCivita).unwrap();
        let factorial: f64 = (1..=n - 2).map(|k| k as f64).product();
        let by_hand = (DMatrix::identity(n, n) * j.trace() - &j) * (2.0 * factorial);
        let scale = max_abs(&by_hand);
        // The literal sum adds 6 N! terms of size ≤ max|J|; observed relative error ~1e-15.
        let tol = 1e-12 * scale;
        assert_matrix_close!(literal, by_hand, tol, "N={n} literal");
        assert_matrix_close!(*closed.matrix(), by_hand, 4.0 * EPS * scale, "N={n} closed");
    }
}

#[test]
fn eq23_is_twice_the_classical_inertia_tensor_in_3d() {
    // Classical inertia tensor of point masses: Σ m (|x|² 1 − x xᵀ).
    let mut r = rng(4000);
    let points: Vec<DVector<f64>> = (0..6)
        .map(|_| DVector::from_fn(3, |_, _| crate::common::gaussian(&mut r)))
        .collect();
    let masses = [1.0, 2.0, 0.5, 1.5, 3.0, 0.7];
    let body = Body::point_masses(&masses, &points).unwrap();
    let mut classical = DMatrix::zeros(3, 3);
    for (m, p) in masses.iter().zip(&points) {
        let d = p - body.center_of_mass();
        classical += (DMatrix::identity(3, 3) * d.norm_squared() - &d * d.transpose()) * *m;
    }
    let literal = RankFourTensor::from_mass_tensor(body.mass_tensor())
        .unwrap()
        .levi_civita_contraction()
        .unwrap();
    assert_matrix_close!(
        literal,
        &classical * 2.0,
        1e-13 * max_abs(&classical),
        "eq 23"
    );
    let axis = ContractedInertia::from_mass_tensor(
        body.mass_tensor(),
        ContractionNormalization::AxisMoment,
    )
    .unwrap();
    assert_matrix_close!(
        *axis.matrix(),
        classical,
        1e-13 * max_abs(&classical),
        "axis"
    );
}

#[test]
fn normalisations_are_related_by_their_factors() {
    for n in 3..=7 {
        let mut r = rng(5000 + n as u64);
        let j = random_spd(n, &mut r);
        let lc =
            ContractedInertia::from_mass_tensor(&j, ContractionNormalization::LeviCivita).unwrap();
        let ps =
            ContractedInertia::from_mass_tensor(&j, ContractionNormalization::PlaneSum).unwrap();
        let am =
            ContractedInertia::from_mass_tensor(&j, ContractionNormalization::AxisMoment).unwrap();
        let f = |k: usize| -> f64 { (1..=k).map(|x| x as f64).product() };
        let scale = max_abs(am.matrix());
        // LeviCivita = 2 (N−3)! · PlaneSum = 2 (N−2)! · AxisMoment.
        assert_matrix_close!(
            *lc.matrix(),
            ps.matrix() * (2.0 * f(n - 3)),
            1e-13 * scale * f(n - 2),
            "N={n} LC vs PS"
        );
        assert_matrix_close!(
            *lc.matrix(),
            am.matrix() * (2.0 * f(n - 2)),
            1e-13 * scale * f(n - 2),
            "N={n} LC vs AM"
        );
        // PlaneSum diagonal in the principal frame = Σ of plane moments of planes ∌ p.
        let body = Body::from_mass_properties(1.0, DVector::zeros(n), j.clone(), None).unwrap();
        let (moments, axes) = body.principal_frame();
        let principal = axes.transpose() * &j * &axes;
        let ps_principal =
            ContractedInertia::from_mass_tensor(&principal, ContractionNormalization::PlaneSum)
                .unwrap();
        for p in 0..n {
            let mut sum = 0.0;
            for s in 0..n {
                for t in s + 1..n {
                    if s != p && t != p {
                        sum += moments[s] + moments[t];
                    }
                }
            }
            assert_close!(
                ps_principal.axis_values()[p],
                sum,
                1e-12 * sum,
                "N={n} p={p}"
            );
        }
    }
}

#[test]
fn contracted_matrix_shares_the_principal_axes_of_j() {
    for n in 3..=6 {
        let mut r = rng(6000 + n as u64);
        let diag = DVector::from_fn(n, |i, _| 1.0 + i as f64 * 0.7);
        let q = random_rotation(n, &mut r);
        let j = &q * DMatrix::from_diagonal(&diag) * q.transpose();
        let lc =
            ContractedInertia::from_mass_tensor(&j, ContractionNormalization::LeviCivita).unwrap();
        let rotated_back = q.transpose() * lc.matrix() * &q;
        let f: f64 = (1..=n - 2).map(|k| k as f64).product();
        for p in 0..n {
            let want = 2.0 * f * (diag.sum() - diag[p]);
            assert_close!(rotated_back[(p, p)], want, 1e-12 * want);
            for m in 0..n {
                if m != p {
                    assert_close!(rotated_back[(p, m)], 0.0, 1e-12 * want);
                }
            }
        }
        // Principal values: ascending, equal to the sorted diagonal above.
        let pv = lc.principal_values();
        for p in 0..n {
            let want = 2.0 * f * (diag.sum() - diag[n - 1 - p]);
            assert_close!(pv[p], want, 1e-12 * want);
        }
    }
}

#[test]
fn gyration_radii_and_trace_follow_eqs_27_and_29() {
    let body = Body::solid_ellipsoid(&[1.0, 1.5, 2.0, 2.5, 3.0], 1.0).unwrap();
    let mu = body.mass();
    for norm in [
        ContractionNormalization::LeviCivita,
        ContractionNormalization::PlaneSum,
        ContractionNormalization::AxisMoment,
    ] {
        let c = ContractedInertia::from_mass_tensor(body.mass_tensor(), norm).unwrap();
        let radii = c.gyration_radii(mu).unwrap();
        let values = c.axis_values();
        let mut sum_sq = 0.0;
        for a in 0..5 {
            // eq. (27)/(28): 𝕀_α = μ L_α².
            assert_close!(mu * radii[a] * radii[a], values[a], 1e-13 * values[a]);
            sum_sq += radii[a] * radii[a];
        }
        // eq. (29): tr 𝕀 = μ Σ L_α² = c_N (N − 1) tr J.
        assert_close!(c.trace(), mu * sum_sq, 1e-13 * c.trace());
        let want = norm.factor(5) * 4.0 * body.mass_tensor().trace();
        assert_close!(c.trace(), want, 1e-13 * want);
        let pr = c.principal_gyration_radii(mu).unwrap();
        let mut sorted: Vec<f64> = radii.iter().copied().collect();
        sorted.sort_by(f64::total_cmp);
        for a in 0..5 {
            assert_close!(pr[a], sorted[a], 1e-13 * sorted[a]);
        }
        assert_eq!(c.normalization(), norm);
        assert_eq!(c.dim(), 5);
    }
}

#[test]
fn paper_energy_eq34_is_twice_the_kinetic_energy() {
    // Also recorded in ERRATA_INERTIA.md; here for N = 2…6 with random J and ω.
    for n in 2..=6 {
        let mut r = rng(7000 + n as u64);
        let j = random_spd(n, &mut r);
        let omega = random_skew(n, &mut r);
        let t = RankFourTensor::from_mass_tensor(&j).unwrap();
        let l = &j * &omega + &omega * &j;
        let mut kinetic = 0.0;
        for a in 0..n {
            for b in a + 1..n {
                kinetic += 0.5 * omega[(a, b)] * l[(a, b)];
            }
        }
        let w = t.paper_energy(&omega).unwrap();
        assert_close!(w, 2.0 * kinetic, 1e-12 * kinetic.abs().max(1.0));
    }
}

#[test]
fn tensor_views_reject_bad_input() {
    let j3 = DMatrix::identity(3, 3);
    let t = RankFourTensor::from_mass_tensor(&j3).unwrap();
    assert!(matches!(
        RankFourTensor::from_mass_tensor(&DMatrix::zeros(2, 3)),
        Err(InertiaError::NotSquare {
            rows: 2,
            cols: 3,
            ..
        })
    ));
    let mut bad = j3.clone();
    bad[(0, 1)] = 0.5;
    assert!(matches!(
        RankFourTensor::from_mass_tensor(&bad),
        Err(InertiaError::NotSymmetric {
            quantity: "mass_tensor",
            ..
        })
    ));
    let mut nan = j3.clone();
    nan[(2, 2)] = f64::NAN;
    assert!(matches!(
        ContractedInertia::from_mass_tensor(&nan, ContractionNormalization::LeviCivita),
        Err(InertiaError::NonFinite { index: Some(8), .. })
    ));
    assert!(matches!(
        t.apply(&DMatrix::identity(3, 3)),
        Err(InertiaError::NotSkewSymmetric { .. })
    ));
    assert!(matches!(
        t.apply(&DMatrix::zeros(4, 4)),
        Err(InertiaError::DimensionMismatch {
            expected: 3,
            found: 4,
            ..
        })
    ));
    assert!(matches!(
        ContractedInertia::from_mass_tensor(
            &DMatrix::identity(2, 2),
            ContractionNormalization::AxisMoment
        ),
        Err(InertiaError::UnsupportedDimension { dim: 2, min: 3, .. })
    ));
    let t2 = RankFourTensor::from_mass_tensor(&DMatrix::identity(2, 2)).unwrap();
    assert!(matches!(
        t2.levi_civita_contraction(),
        Err(InertiaError::UnsupportedDimension { dim: 2, .. })
    ));
    let t9 = RankFourTensor::from_mass_tensor(&DMatrix::identity(9, 9)).unwrap();
    assert!(matches!(
        t9.levi_civita_contraction(),
        Err(InertiaError::UnsupportedDimension { dim: 9, max: 8, .. })
    ));
    let c = ContractedInertia::from_mass_tensor(&j3, ContractionNormalization::LeviCivita).unwrap();
    for m in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            c.gyration_radii(m),
            Err(InertiaError::NotPositive {
                quantity: "mass",
                ..
            } | InertiaError::NonFinite {
                quantity: "mass",
                ..
            })
        ));
    }
    // A non-physical "J" = diag(1, 1, −5): tr J · 1 − J = diag(−4, −4, 2) is negative first.
    let unphysical = DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, 1.0, -5.0]));
    let c = ContractedInertia::from_mass_tensor(&unphysical, ContractionNormalization::AxisMoment)
        .unwrap();
    assert!(matches!(
        c.gyration_radii(1.0),
        Err(InertiaError::NegativeValue { index: 0, .. })
    ));
    // Error messages are real sentences.
    let msg = InertiaError::NotSquare {
        quantity: "mass_tensor",
        rows: 2,
        cols: 3,
    }
    .to_string();
    assert_eq!(msg, "`mass_tensor` is 2×3, expected a square matrix");
}
