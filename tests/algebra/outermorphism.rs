//! `Multivector::exp` against the matrix exponential of the bivector's action on vectors: an
//! independent check in every signature.
//!
//! For any element B of an associative algebra, exp(B) X exp(−B) = exp(ad_B)(X) with
//! ad_B(X) = BX − XB. A bivector maps vectors to vectors under ad_B, so on the vectors of
//! Cl(p, q, r) the sandwich V X Ṽ by V = exp(B) (Ṽ = exp(−B)) is the (N×N) matrix
//! exponential of the matrix of ad_B. The matrix exponential here is nalgebra's
//! (`DMatrix::exp`, Padé with scaling and squaring), which shares nothing with rotorflow's
//! closed forms; the sandwich also checks Ṽ = V⁻¹.

use proptest::prelude::*;
use rotorflow::prelude::*;

/// The signatures checked: N ≤ 5 in every kind of signature, and projective GA above.
const SIGNATURES: &[(usize, usize, usize)] = &[
    (3, 0, 0),
    (4, 0, 0),
    (5, 0, 0),
    (2, 0, 1),
    (3, 0, 1),
    (4, 0, 1),
    (5, 0, 1),
    (1, 3, 0),
    (3, 1, 0),
    (4, 1, 0),
    (2, 2, 0),
    (3, 2, 0),
    (1, 1, 0),
    (2, 1, 0),
    (1, 2, 0),
    (2, 0, 2),
];

/// The bivector with the given components in lexicographic plane order.
fn bivector(sig: Signature, components: &[f64]) -> Multivector {
    let n = sig.dim();
    let mut b = Multivector::zero(sig);
    let mut k = 0;
    for i in 0..n {
        for j in i + 1..n {
            b.as_mut_slice()[(1 << i) | (1 << j)] = components[k];
            k += 1;
        }
    }
    b
}

/// The matrix of v ↦ f(v) on the vectors e₁ … e_N (column k is f(e_k)).
fn vector_matrix(
    sig: Signature,
    f: impl Fn(&Multivector) -> Multivector,
) -> nalgebra::DMatrix<f64> {
    let n = sig.dim();
    nalgebra::DMatrix::from_fn(n, n, |row, col| {
        let image = f(&Multivector::basis_blade(sig, 1 << col));
        image.coefficient(1 << row)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The sandwich by exp(B) on vectors equals expm(ad_B), to round-off relative to the
    /// size of the result.
    #[test]
    fn exp_acts_on_vectors_as_the_matrix_exponential(
        which in 0..SIGNATURES.len(),
        components in prop::collection::vec(-1.5f64..1.5, 15),
    ) {
        let (p, q, r) = SIGNATURES[which];
        let sig = Signature::new(p, q, r).unwrap();
        let n = sig.dim();
        let b = bivector(sig, &components[..n * (n - 1) / 2]);
        let v = b.exp().unwrap();
        let v_rev = v.reverse();
        let sandwich = vector_matrix(sig, |x| &(&v * x) * &v_rev);
        let ad = vector_matrix(sig, |x| &(&b * x) - &(x * &b));
        let expected = ad.exp();
        let scale = expected.amax().max(1.0);
        let err = (&sandwich - &expected).amax() / scale;
        prop_assert!(
            err < 1e-13,
            "Cl({p}, {q}, {r}): sandwich vs expm(ad_B) off by {err:e}\nB = {b}"
        );
        // The sandwich maps vectors to vectors: no other grade appears.
        for k in 0..n {
            let image = &(&v * &Multivector::basis_blade(sig, 1 << k)) * &v_rev;
            let other = image
                .terms()
                .filter(|(mask, _)| mask.count_ones() != 1)
                .map(|(_, c)| c.abs())
                .fold(0.0, f64::max);
            prop_assert!(other < 1e-13 * scale, "Cl({p}, {q}, {r}): grade leak {other:e}");
        }
    }
}

/// The check is not vacuous: a wrong exponential (the series cut after the linear term) fails
/// it in every signature with a bivector of size one.
#[test]
fn a_wrong_exponential_fails_the_check() {
    for &(p, q, r) in SIGNATURES {
        let sig = Signature::new(p, q, r).unwrap();
        let n = sig.dim();
        let b = bivector(sig, &vec![0.7; n * (n - 1) / 2]);
        let wrong = &Multivector::scalar(sig, 1.0) + &b;
        let wrong_rev = wrong.reverse();
        let sandwich = vector_matrix(sig, |x| &(&wrong * x) * &wrong_rev);
        let ad = vector_matrix(sig, |x| &(&b * x) - &(x * &b));
        let err = (&sandwich - &ad.exp()).amax();
        assert!(
            err > 1e-3,
            "Cl({p}, {q}, {r}): the check missed a wrong exponential"
        );
    }
}
