//! Products, involutions, duals and inverses of general multivectors in several signatures.

use crate::assert_close;
use rotorflow::prelude::*;

fn e(sig: Signature, mask: u64) -> Multivector {
    Multivector::basis_blade(sig, mask)
}

#[test]
fn basis_products_in_3d() {
    let s = Signature::euclidean(3);
    let (e1, e2, e3) = (e(s, 1), e(s, 2), e(s, 4));
    assert_eq!(&e1 * &e2, e(s, 0b011));
    assert_eq!(&e2 * &e1, -e(s, 0b011));
    assert_eq!((&e1 * &e1).scalar_part(), 1.0);
    // e12 e23 = e13
    assert_eq!(&e(s, 0b011) * &e(s, 0b110), e(s, 0b101));
    // pseudoscalar squares to −1 in 3D
    let i = &(&e1 * &e2) * &e3;
    assert_eq!((&i * &i).scalar_part(), -1.0);
}

#[test]
fn signature_squares_follow_p_q_r() {
    let sta = Signature::new(1, 3, 0).unwrap();
    assert_eq!((&e(sta, 1) * &e(sta, 1)).scalar_part(), 1.0);
    assert_eq!((&e(sta, 2) * &e(sta, 2)).scalar_part(), -1.0);
    let pga = Signature::new(3, 0, 1).unwrap();
    assert_eq!((&e(pga, 8) * &e(pga, 8)).scalar_part(), 0.0);
    assert_eq!(pga.to_string(), "Cl(3,0,1)");
    assert!(Signature::new(60, 4, 1).is_err());
}

#[test]
fn graded_products_match_their_filters() {
    let s = Signature::euclidean(4);
    let a = e(s, 0b0001); // e1
    let b = e(s, 0b0011); // e12
    assert_eq!(a.left_contract(&b), e(s, 0b0010)); // e1 ⌋ e12 = e2
    assert_eq!(b.right_contract(&a), -e(s, 0b0010)); // e12 ⌊ e1 = −e2
    assert_eq!(a.wedge(&b), Multivector::zero(s));
    assert_eq!(e(s, 0b0100).wedge(&b), e(s, 0b0111)); // e3 ∧ e12 = e123
    assert_eq!(b.scalar_product(&b), -1.0);
    // commutator of e12 and e23 is e13, anticommutator vanishes
    assert_eq!(b.commutator(&e(s, 0b0110)), e(s, 0b0101));
    assert_eq!(b.anticommutator(&e(s, 0b0110)), Multivector::zero(s));
}

#[test]
fn regressive_product_meets_planes_in_a_line() {
    let s = Signature::euclidean(3);
    assert_eq!(e(s, 0b011).regressive(&e(s, 0b110)), e(s, 0b010));
    // in PGA (degenerate metric) the meet is metric-free and still works
    let pga = Signature::new(3, 0, 1).unwrap();
    let m = e(pga, 0b0111).regressive(&e(pga, 0b1110));
    assert_eq!(m.grades(), vec![2]);
}

#[test]
fn involutions_have_the_right_signs() {
    let s = Signature::euclidean(4);
    let mut x = Multivector::zero(s);
    for (b, c) in x.as_mut_slice().iter_mut().enumerate() {
        *c = 1.0 + b as f64;
    }
    for (b, c) in x.reverse().terms() {
        let k = b.count_ones() as usize;
        let expected = if k % 4 == 2 || k % 4 == 3 { -1.0 } else { 1.0 };
        assert_eq!(c, expected * (1.0 + b as f64));
    }
    assert_eq!(x.grade_involution().grade_involution(), x);
    assert_eq!(x.clifford_conjugate(), x.reverse().grade_involution());
    assert_eq!(x.even() + x.odd(), x);
}

#[test]
fn hodge_star_twice_is_plus_or_minus_one() {
    for (p, q) in [(2, 0), (3, 0), (4, 0), (5, 0), (1, 3), (2, 2), (3, 1)] {
        let s = Signature::new(p, q, 0).unwrap();
        let n = p + q;
        for b in 0..(1u64 << n) {
            let k = b.count_ones() as usize;
            let x = e(s, b);
            let twice = x.hodge().hodge();
            let sign = if (k * (n - k) + q).is_multiple_of(2) {
                1.0
            } else {
                -1.0
            };
            assert_eq!(twice, x.clone() * sign, "Cl({p},{q}) blade {b:b}");
        }
    }
    // The Levi-Civita contraction Ω_k = ½ ε_ijk ω_ij is the Hodge star in 3D: ⋆e12 = e3.
    let s3 = Signature::euclidean(3);
    assert_eq!(e(s3, 0b011).hodge(), e(s3, 0b100));
    assert_eq!(e(s3, 0b101).hodge(), -e(s3, 0b010));
    assert_eq!(e(s3, 0b110).hodge(), e(s3, 0b001));
}

#[test]
fn hodge_satisfies_its_definition() {
    // B ∧ ⋆A = ⟨B, A⟩ I for blades of equal grade in Euclidean 4D.
    let s = Signature::euclidean(4);
    let i = e(s, 0b1111);
    for a in 0..16u64 {
        for b in 0..16u64 {
            if (a.count_ones() as usize) != (b.count_ones() as usize) {
                continue;
            }
            let lhs = e(s, b).wedge(&e(s, a).hodge());
            let expected = if a == b {
                i.clone()
            } else {
                Multivector::zero(s)
            };
            assert_eq!(lhs, expected);
        }
    }
}

#[test]
fn dual_is_multiplication_by_inverse_pseudoscalar() {
    let s = Signature::euclidean(3);
    assert_eq!(e(s, 0b011).dual().unwrap(), e(s, 0b100));
    let pga = Signature::new(3, 0, 1).unwrap();
    assert!(matches!(
        e(pga, 1).dual(),
        Err(AlgebraError::NotInvertible { .. })
    ));
}

#[test]
fn inverse_of_versors_and_general_elements() {
    let s = Signature::euclidean(3);
    let v = Multivector::from_coefficients(s, &[0.0, 1.0, 2.0, 0.0, 3.0, 0.0, 0.0, 0.0]).unwrap();
    let vi = v.inverse().unwrap();
    let one = &v * &vi;
    assert_close!(one.scalar_part(), 1.0, 1e-15);
    assert!(one.grade(1).max_abs() < 1e-15);
    // a general (non-versor) invertible element: 2 + e1 + e23
    let g = Multivector::from_coefficients(s, &[2.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0]).unwrap();
    let gi = g.inverse().unwrap();
    let p = &g * &gi;
    assert_close!(p.scalar_part(), 1.0, 1e-14);
    assert!((p.clone() - Multivector::scalar(s, 1.0)).max_abs() < 1e-14);
    // The residual check of the linear-system path takes its tolerance from the caller.
    assert_eq!(
        g.inverse_eps(rotorflow::algebra::INVERSE_TOLERANCE)
            .unwrap(),
        gi
    );
    assert!(g.inverse_eps(f64::NAN).is_err());
    assert!(g.inverse_eps(-1.0).is_err());
    // zero divisor 1 + e1 (since (1+e1)(1−e1) = 0) has no inverse
    let z = Multivector::from_coefficients(s, &[1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]).unwrap();
    assert!(matches!(
        z.inverse(),
        Err(AlgebraError::NotInvertible { .. })
    ));
    assert!(Multivector::zero(s).inverse().is_err());
    // a null vector in PGA
    let pga = Signature::new(3, 0, 1).unwrap();
    assert!(e(pga, 8).inverse().is_err());
}

#[test]
fn norm_squared_is_sum_of_squares_in_euclidean_space() {
    let s = Signature::euclidean(4);
    let mut x = Multivector::zero(s);
    for (b, c) in x.as_mut_slice().iter_mut().enumerate() {
        *c = (b as f64).sin();
    }
    let expected: f64 = x.as_slice().iter().map(|c| c * c).sum();
    assert_close!(x.norm_squared(), expected, 1e-13);
    assert_close!((&x * &x.reverse()).scalar_part(), expected, 1e-13);
    // Minkowski: a timelike vector has positive, a spacelike one negative norm²
    let sta = Signature::new(1, 3, 0).unwrap();
    assert_eq!(e(sta, 1).norm_squared(), 1.0);
    assert_eq!(e(sta, 2).norm_squared(), -1.0);
}

#[test]
fn mismatched_signatures_are_errors_in_the_checked_api() {
    let a = Multivector::scalar(Signature::euclidean(3), 1.0);
    let b = Multivector::scalar(Signature::new(2, 1, 0).unwrap(), 1.0);
    assert!(matches!(
        a.try_product(&b, Product::Geometric),
        Err(AlgebraError::SignatureMismatch { .. })
    ));
    let c = Multivector::scalar(Signature::euclidean(4), 1.0);
    assert!(matches!(
        a.try_product(&c, Product::Wedge),
        Err(AlgebraError::DimensionMismatch { left: 3, right: 4 })
    ));
}

#[test]
#[should_panic(expected = "dimension mismatch")]
fn operators_panic_on_mismatched_dimensions() {
    let a = Multivector::scalar(Signature::euclidean(3), 1.0);
    let c = Multivector::scalar(Signature::euclidean(4), 1.0);
    let _ = &a * &c;
}

#[test]
fn multivectors_up_to_n_12_work() {
    let s = Signature::euclidean(12);
    let mut a = Multivector::zero(s);
    a.as_mut_slice()[0b11] = 1.0; // e12
    a.as_mut_slice()[0b1100_0000_0000] = 2.0; // e11,12
    let sq = &a * &a;
    // (e12 + 2 e_{11,12})² = −1 − 4 + 4 e12∧e_{11,12}
    assert_eq!(sq.scalar_part(), -5.0);
    assert_eq!(sq.coefficient(0b1100_0000_0011), 4.0);
    assert_eq!(a.to_string(), "1·e1_2 + 2·e11_12");
    assert!(Multivector::try_zero(Signature::euclidean(17)).is_err());
}

#[test]
fn display_is_readable() {
    let s = Signature::euclidean(3);
    let x = Multivector::from_coefficients(s, &[1.0, -2.0, 0.0, 0.5, 0.0, 0.0, 0.0, -1.0]).unwrap();
    assert_eq!(x.to_string(), "1 - 2·e1 + 0.5·e12 - 1·e123");
    assert_eq!(format!("{x:.2}"), "1.00 - 2.00·e1 + 0.50·e12 - 1.00·e123");
    assert_eq!(Multivector::zero(s).to_string(), "0");
}

#[test]
fn from_coefficients_rejects_bad_input() {
    let s = Signature::euclidean(2);
    assert!(matches!(
        Multivector::from_coefficients(s, &[1.0, 2.0]),
        Err(AlgebraError::WrongComponentCount {
            expected: 4,
            found: 2,
            ..
        })
    ));
    assert!(matches!(
        Multivector::from_coefficients(s, &[1.0, f64::NAN, 0.0, 0.0]),
        Err(AlgebraError::NonFinite { .. })
    ));
}

/// Splits `Display` output into signed terms ("1 - 2·e1" → [(1, "1"), (−1, "2·e1")]).
fn signed_terms(text: &str) -> Vec<(f64, &str)> {
    let (mut sign, mut rest) = match text.strip_prefix('-') {
        Some(r) => (-1.0, r),
        None => (1.0, text),
    };
    let mut out = Vec::new();
    loop {
        let next = [rest.find(" + "), rest.find(" - ")]
            .into_iter()
            .flatten()
            .min();
        match next {
            None => {
                out.push((sign, rest));
                return out;
            }
            Some(k) => {
                out.push((sign, &rest[..k]));
                sign = if rest[k..].starts_with(" - ") {
                    -1.0
                } else {
                    1.0
                };
                rest = &rest[k + 3..];
            }
        }
    }
}

/// Display reads back exactly through `blade_by_name`, and no blade term reads as a float
/// (`1e1` would be ten): only the scalar term parses as a number.
#[test]
fn display_reads_back_through_blade_names_and_no_term_reads_as_a_float() {
    use rand::Rng;
    let mut r = crate::support::rng(43);
    for n in [1, 2, 3, 4, 5, 11] {
        let s = Signature::euclidean(n);
        for _ in 0..20 {
            let coeffs: Vec<f64> = (0..1usize << n)
                .map(|_| {
                    if r.gen_bool(0.3) {
                        r.gen_range(-10.0..10.0)
                    } else {
                        0.0
                    }
                })
                .collect();
            let x = Multivector::from_coefficients(s, &coeffs).unwrap();
            let text = x.to_string();
            let mut back = Multivector::zero(s);
            for (sign, term) in signed_terms(&text) {
                match term.split_once('·') {
                    Some((c, name)) => {
                        assert!(term.parse::<f64>().is_err(), "{term} reads as a float");
                        let c: f64 = c.parse().unwrap();
                        back += &Multivector::blade_by_name(s, name, sign * c).unwrap();
                    }
                    None => back += &Multivector::scalar(s, sign * term.parse::<f64>().unwrap()),
                }
            }
            assert_eq!(back, x, "{text}");
        }
    }
}

#[test]
fn blades_by_name_match_blades_by_mask() {
    let s = Signature::euclidean(4);
    for (name, mask, sign) in [
        ("1", 0, 1.0),
        ("e1", 0b1, 1.0),
        ("e13", 0b101, 1.0),
        ("e1e3", 0b101, 1.0),
        ("e₁₃", 0b101, 1.0),
        ("e31", 0b101, -1.0),
        ("e1234", 0b1111, 1.0),
        ("e2143", 0b1111, 1.0),
    ] {
        let by_name = Multivector::blade_by_name(s, name, 2.5).unwrap();
        assert_eq!(
            by_name,
            Multivector::basis_blade(s, mask) * (sign * 2.5),
            "{name}"
        );
    }
    // e31 = e3 e1 as a geometric product.
    let e1 = Multivector::basis_blade(s, 0b1);
    let e3 = Multivector::basis_blade(s, 0b100);
    assert_eq!(
        Multivector::blade_by_name(s, "e31", 1.0).unwrap(),
        &e3 * &e1
    );
    for bad in ["e5", "e11", "x1", "e", "e1.5", "12"] {
        match Multivector::blade_by_name(s, bad, 1.0) {
            Err(AlgebraError::InvalidBladeName { name, .. }) => assert_eq!(name, bad),
            other => panic!("{bad}: {other:?}"),
        }
    }
    assert!(matches!(
        Multivector::blade_by_name(s, "e1", f64::NAN),
        Err(AlgebraError::NonFinite { .. })
    ));
    assert!(Multivector::try_basis_blade(s, 0b10000).is_err());
    assert_eq!(
        Multivector::try_scalar(s, 2.0).unwrap(),
        Multivector::scalar(s, 2.0)
    );
    assert!(Multivector::try_scalar(Signature::euclidean(17), 1.0).is_err());
}

/// Converting a multivector with other grades to a graded type names the problem.
#[test]
fn graded_conversions_report_mixed_grades() {
    let s = Signature::euclidean(3);
    let x = Multivector::from_coefficients(s, &[1.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0]).unwrap();
    match Bivector::try_from(&x) {
        Err(AlgebraError::MixedGrades {
            what,
            grade,
            others,
        }) => assert_eq!((what, grade, others), ("bivector", 2, 1)),
        other => panic!("{other:?}"),
    }
    let err = Vector::try_from(&x).unwrap_err();
    assert_eq!(
        err,
        AlgebraError::MixedGrades {
            what: "vector",
            grade: 1,
            others: 2
        }
    );
    assert!(!err.to_string().contains("expected 0"), "{err}");
    let pure = Multivector::blade_by_name(s, "e13", 0.5).unwrap();
    assert_eq!(Bivector::try_from(&pure).unwrap().get(0, 2), 0.5);
}
