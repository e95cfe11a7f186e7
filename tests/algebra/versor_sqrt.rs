//! `Multivector::sqrt` and `Multivector::normalize_versor`: square roots checked by squaring
//! and against exp(½ B) for a known B, normalisation checked by M M̃ = 1, closeness to the
//! input and the 3D PGA Study-number formula written out by hand.

use crate::support::*;
use proptest::prelude::*;
use rand::Rng;
use rotorflow::algebra::VERSOR_NORMALIZE_TOLERANCE;
use rotorflow::prelude::*;

fn sig(p: usize, q: usize, r: usize) -> Signature {
    Signature::new(p, q, r).unwrap()
}

/// A random bivector with coefficients uniform in (−scale, scale).
fn random_bivector_mv(rng: &mut impl Rng, s: Signature, scale: f64) -> Multivector {
    let n = s.dim();
    let mut m = Multivector::zero(s);
    for i in 0..n {
        for j in i + 1..n {
            m.as_mut_slice()[(1 << i) | (1 << j)] = rng.gen_range(-scale..scale);
        }
    }
    m
}

/// A random even element with coefficients uniform in (−scale, scale).
fn random_even(rng: &mut impl Rng, s: Signature, scale: f64) -> Multivector {
    let mut m = Multivector::zero(s);
    for b in 0..(1usize << s.dim()) {
        if b.count_ones() % 2 == 0 {
            m.as_mut_slice()[b] = rng.gen_range(-scale..scale);
        }
    }
    m
}

fn unit_distance(m: &Multivector) -> f64 {
    let mut mm = m * &m.reverse();
    mm.as_mut_slice()[0] -= 1.0;
    mm.max_abs()
}

const SQRT_SIGNATURES: [(usize, usize, usize); 7] = [
    (3, 0, 1),
    (4, 0, 1),
    (2, 0, 1),
    (1, 3, 0),
    (3, 0, 0),
    (4, 0, 0),
    (2, 2, 0),
];

#[test]
fn sqrt_squares_back_to_the_versor() {
    let mut rng = rng(41);
    for &(p, q, r) in &SQRT_SIGNATURES {
        let s = sig(p, q, r);
        let mut worst = 0.0f64;
        for _ in 0..300 {
            // Half-angles below π/2 per plane keep V = exp(B) inside the principal domain.
            let v = random_bivector_mv(&mut rng, s, 0.6).exp().unwrap();
            let h = v.sqrt().unwrap();
            let err = (&(&h * &h) - &v).max_abs() / v.max_abs().max(1.0);
            worst = worst.max(err);
            assert!(unit_distance(&h) < 1e-13 * h.max_abs().powi(2).max(1.0));
        }
        // N = 5 goes through exp(½ log V), whose own error is a few 1e-15.
        let bound = if s.dim() == 5 { 5e-14 } else { 1e-14 };
        eprintln!("Cl({p},{q},{r}): max |√V² − V| = {worst:e}");
        assert!(worst < bound, "Cl({p},{q},{r}): max |√V² − V| = {worst:e}");
    }
}

#[test]
fn sqrt_is_half_the_generator() {
    // Independent of log: exp(B)'s principal square root is exp(B/2) when B is small enough.
    let mut rng = rng(42);
    for &(p, q, r) in &SQRT_SIGNATURES {
        let s = sig(p, q, r);
        let mut worst = 0.0f64;
        for _ in 0..300 {
            let b = random_bivector_mv(&mut rng, s, 0.6);
            let v = b.exp().unwrap();
            let want = (&b * 0.5).exp().unwrap();
            let got = v.sqrt().unwrap();
            worst = worst.max((&got - &want).max_abs() / want.max_abs());
        }
        let bound = if s.dim() == 5 { 5e-14 } else { 1e-14 };
        eprintln!("Cl({p},{q},{r}): max |√V − exp(B/2)| = {worst:e}");
        assert!(
            worst < bound,
            "Cl({p},{q},{r}): max |√V − exp(B/2)| = {worst:e}"
        );
    }
}

#[test]
fn closed_form_and_general_route_agree() {
    // Up to N = 4 sqrt takes (1 + V)(2 + V + Ṽ)^(−1/2); the general route is exp(½ log V).
    let mut rng = rng(43);
    for &(p, q, r) in &[
        (3, 0, 1),
        (2, 0, 1),
        (1, 3, 0),
        (3, 1, 0),
        (2, 2, 0),
        (4, 0, 0),
    ] {
        let s = sig(p, q, r);
        for _ in 0..200 {
            let v = random_bivector_mv(&mut rng, s, 1.0).exp().unwrap();
            let general = (&v.log().unwrap() * 0.5).exp().unwrap();
            let closed = v.sqrt().unwrap();
            let err = (&closed - &general).max_abs() / general.max_abs();
            assert!(err < 1e-13, "Cl({p},{q},{r}): {err:e}");
        }
    }
}

#[test]
fn sqrt_in_five_dimensions_and_near_half_turn() {
    let mut rng = rng(44);
    for &(p, q, r) in &[(4, 0, 1), (5, 0, 0), (4, 1, 0)] {
        let s = sig(p, q, r);
        for _ in 0..100 {
            let b = random_bivector_mv(&mut rng, s, 0.5);
            let v = b.exp().unwrap();
            let h = v.sqrt().unwrap();
            assert!((&h - &(&b * 0.5).exp().unwrap()).max_abs() < 1e-13);
        }
    }
    // Rotation by nearly 2π (V ≈ −1): the closed form is skipped, the general route is used.
    let pga = sig(3, 0, 1);
    let b = Multivector::blade_by_name(pga, "e12", 3.1).unwrap()
        + Multivector::blade_by_name(pga, "e14", 0.7).unwrap();
    let v = b.exp().unwrap();
    assert!(v.scalar_part() < -0.99);
    let h = v.sqrt().unwrap();
    assert!((&(&h * &h) - &v).max_abs() < 1e-14);
    assert!((&h - &(&b * 0.5).exp().unwrap()).max_abs() < 1e-13);
}

#[test]
fn sqrt_rejects_bad_input() {
    let pga = sig(3, 0, 1);
    let e1 = Multivector::basis_blade(pga, 0b1);
    assert!(matches!(e1.sqrt(), Err(AlgebraError::NotAVersor { .. })));
    let two = Multivector::scalar(pga, 2.0);
    assert!(matches!(two.sqrt(), Err(AlgebraError::NotAVersor { .. })));
    let mut nan = Multivector::scalar(pga, 1.0);
    nan.as_mut_slice()[3] = f64::NAN;
    assert!(matches!(nan.sqrt(), Err(AlgebraError::NonFinite { .. })));
    // −exp(boost) has no real square root in Cl(1, 1).
    let st = sig(1, 1, 0);
    let minus_boost = Multivector::blade_by_name(st, "e12", 0.4)
        .unwrap()
        .exp()
        .unwrap()
        * -1.0;
    assert!(minus_boost.sqrt().is_err());
}

#[test]
fn normalize_perturbed_versors() {
    let mut rng = rng(45);
    for &(p, q, r) in &[
        (3, 0, 1),
        (2, 0, 1),
        (4, 0, 1),
        (1, 3, 0),
        (3, 0, 0),
        (5, 0, 0),
        (2, 2, 0),
    ] {
        let s = sig(p, q, r);
        let mut worst_unit = 0.0f64;
        let mut worst_ratio = 0.0f64;
        for _ in 0..200 {
            let v = random_bivector_mv(&mut rng, s, 1.0).exp().unwrap();
            let delta = random_even(&mut rng, s, 1e-7);
            let drifted = &v + &delta;
            let fixed = drifted.try_normalize_versor().unwrap();
            worst_unit = worst_unit.max(unit_distance(&fixed) / fixed.max_abs().powi(2).max(1.0));
            // First order: the correction is of the size of the drift.
            let moved = (&fixed - &v).max_abs() / (delta.max_abs() * v.max_abs().powi(2).max(1.0));
            worst_ratio = worst_ratio.max(moved);
        }
        eprintln!("Cl({p},{q},{r}): max |M M̃ − 1| = {worst_unit:e}, moved ≤ {worst_ratio} × drift");
        assert!(
            worst_unit < 2e-15,
            "Cl({p},{q},{r}): max |M M̃ − 1| = {worst_unit:e}"
        );
        assert!(
            worst_ratio < 50.0,
            "Cl({p},{q},{r}): moved {worst_ratio} × the drift"
        );
    }
}

#[test]
fn normalize_keeps_versors_and_undoes_scale() {
    let mut rng = rng(46);
    for &(p, q, r) in &[(3, 0, 1), (4, 0, 1), (1, 3, 0), (5, 0, 0)] {
        let s = sig(p, q, r);
        for _ in 0..50 {
            let v = random_bivector_mv(&mut rng, s, 1.0).exp().unwrap();
            assert!((&v.normalize_versor().unwrap() - &v).max_abs() < 1e-14);
            let scaled = &v * 3.7;
            assert!((&scaled.normalize_versor().unwrap() - &v).max_abs() < 1e-14);
        }
    }
}

#[test]
fn normalize_matches_the_study_number_formula_in_3d_pga() {
    // M M̃ = s + p e₁₂₃₄ and M′ = M (1 − p/(2s) e₁₂₃₄)/√s, written out by hand here.
    let mut rng = rng(47);
    let pga = sig(3, 0, 1);
    let i = Multivector::basis_blade(pga, 0b1111);
    for _ in 0..100 {
        let m = random_even(&mut rng, pga, 1.0);
        let mm = &m * &m.reverse();
        let s = mm.scalar_part();
        let p = mm.coefficient(0b1111);
        // Only grades 0 and 4: the Study number.
        assert!((&mm - &(Multivector::scalar(pga, s) + &i * p)).max_abs() < 1e-14);
        let want = &m * &(Multivector::scalar(pga, 1.0) - &i * (p / (2.0 * s))) * (1.0 / s.sqrt());
        let got = m.normalize_versor().unwrap();
        assert!((&got - &want).max_abs() < 1e-14);
        assert!(unit_distance(&got) < 1e-14);
    }
}

#[test]
fn normalize_refuses_far_and_invalid_input() {
    let pga = sig(3, 0, 1);
    let m = Multivector::blade_by_name(pga, "e12", 0.3)
        .unwrap()
        .exp()
        .unwrap();
    match (&m * 1.5).try_normalize_versor() {
        Err(AlgebraError::VersorFarFromGroup {
            distance,
            tolerance,
        }) => {
            assert!((distance - 1.25).abs() < 1e-14);
            assert_eq!(tolerance, VERSOR_NORMALIZE_TOLERANCE);
        }
        other => panic!("{other:?}"),
    }
    assert!((&m * 1.5).try_normalize_versor_eps(2.0).is_ok());
    // Odd grades, NaN, zero, and a null element have no normalisation.
    let e1 = Multivector::basis_blade(pga, 0b1);
    assert!(matches!(
        e1.normalize_versor(),
        Err(AlgebraError::NotAVersor { .. })
    ));
    let mut nan = m.clone();
    nan.as_mut_slice()[0] = f64::NAN;
    assert!(matches!(
        nan.try_normalize_versor(),
        Err(AlgebraError::NonFinite { .. })
    ));
    assert!(Multivector::zero(pga).normalize_versor().is_err());
    let null = Multivector::blade_by_name(pga, "e14", 1.0).unwrap();
    assert!(null.normalize_versor().is_err());
    assert!(Multivector::zero(sig(5, 0, 0)).normalize_versor().is_err());
}

/// The signatures of the property tests: every Cl(p, q, r) with N ≤ 5 and r ≤ 1 that has a
/// bivector.
fn property_signatures() -> Vec<Signature> {
    let mut out = Vec::new();
    for n in 2..=5 {
        for r in 0..=1usize {
            for q in 0..=(n - r) {
                out.push(sig(n - r - q, q, r));
            }
        }
    }
    out
}

fn bivector_in(scale: f64) -> impl Strategy<Value = Multivector> {
    let sigs = property_signatures();
    (0..sigs.len(), proptest::collection::vec(-scale..scale, 10)).prop_map(move |(k, c)| {
        let s = sigs[k];
        let n = s.dim();
        let mut m = Multivector::zero(s);
        let mut it = c.into_iter();
        for i in 0..n {
            for j in i + 1..n {
                m.as_mut_slice()[(1 << i) | (1 << j)] = it.next().unwrap();
            }
        }
        m
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(64)
    ))]

    #[test]
    fn sqrt_squared_is_v(b in bivector_in(0.7)) {
        let v = b.exp().unwrap();
        let h = v.sqrt().unwrap();
        let err = (&(&h * &h) - &v).max_abs() / v.max_abs().max(1.0);
        prop_assert!(err < 1e-13, "{}: {err:e}", b.signature());
        let want = (&b * 0.5).exp().unwrap();
        prop_assert!((&h - &want).max_abs() < 1e-13 * want.max_abs());
    }

    #[test]
    fn normalize_is_on_the_group_and_near(b in bivector_in(1.0), seed in 0u64..1000) {
        let v = b.exp().unwrap();
        let delta = random_even(&mut rng(seed), v.signature(), 1e-8);
        let fixed = (&v + &delta).try_normalize_versor().unwrap();
        let scale = fixed.max_abs().powi(2).max(1.0);
        prop_assert!(unit_distance(&fixed) < 4e-15 * scale, "{}", b.signature());
        prop_assert!((&fixed - &v).max_abs() < 1e-6 * scale);
    }
}

#[test]
fn raw_bit_patterns_never_give_nan() {
    // Even elements from random f64 bit patterns (finite ones, any exponent): every Ok
    // result is finite, everything else is an error.
    let mut rng = rng(48);
    for &(p, q, r) in &[
        (3, 0, 1),
        (4, 0, 1),
        (1, 3, 0),
        (2, 2, 0),
        (5, 0, 0),
        (2, 0, 1),
    ] {
        let s = sig(p, q, r);
        let mut accepted = 0;
        for k in 0..2000 {
            let mut m = Multivector::zero(s);
            for b in 0..(1usize << s.dim()) {
                if b.count_ones() % 2 == 0 {
                    let mut x = f64::from_bits(rng.r#gen::<u64>());
                    if !x.is_finite() {
                        x = 0.0;
                    }
                    // Half the cases near a versor, so that the closed forms run too.
                    m.as_mut_slice()[b] = if k % 2 == 0 {
                        x
                    } else {
                        x.clamp(-1.0, 1.0) * 1e-9
                    };
                }
            }
            if k % 2 == 1 {
                m.as_mut_slice()[0] += 1.0;
            }
            for v in [m.sqrt(), m.normalize_versor(), m.try_normalize_versor()]
                .into_iter()
                .flatten()
            {
                assert!(v.as_slice().iter().all(|c| c.is_finite()), "{m:?}");
                accepted += 1;
            }
        }
        // The near-versor half reaches the closed forms.
        assert!(accepted > 1000, "Cl({p},{q},{r}): only {accepted} accepted");
    }
}
