//! `Multivector::exp` and `Multivector::log` in every signature: against an independent
//! reference (the Taylor series with scaling and squaring, built from the geometric product
//! alone), closed forms for the hard families, property tests and bad input.

use crate::support::*;
use proptest::prelude::*;
use rand::Rng;
use rotorflow::prelude::*;
use std::f64::consts::PI;

fn sig(p: usize, q: usize, r: usize) -> Signature {
    Signature::new(p, q, r).unwrap()
}

/// The signatures of the accuracy table (N ≤ 5 in every signature, projective GA to
/// Cl(6,0,1), Euclidean to 6).
fn table_signatures() -> Vec<Signature> {
    vec![
        sig(2, 0, 1),
        sig(3, 0, 1),
        sig(4, 0, 1),
        sig(5, 0, 1),
        sig(6, 0, 1),
        sig(4, 1, 0),
        sig(1, 3, 0),
        sig(3, 1, 0),
        sig(2, 2, 0),
        sig(1, 1, 0),
        sig(2, 1, 0),
        sig(3, 2, 0),
        sig(2, 0, 0),
        sig(3, 0, 0),
        sig(4, 0, 0),
        sig(5, 0, 0),
        sig(6, 0, 0),
    ]
}

fn bivector_masks(n: usize) -> Vec<u64> {
    let mut out = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            out.push((1u64 << i) | (1u64 << j));
        }
    }
    out
}

fn random_mv_bivector(r: &mut impl Rng, s: Signature, scale: f64) -> Multivector {
    let mut m = Multivector::zero(s);
    for b in bivector_masks(s.dim()) {
        m.as_mut_slice()[b as usize] = scale * r.gen_range(-1.0..1.0);
    }
    m
}

fn blade(s: Signature, name: &str, c: f64) -> Multivector {
    Multivector::blade_by_name(s, name, c).unwrap()
}

/// The reference: exp(B) = (Σ_{k ≤ 30} (B/2ʲ)ᵏ/k!)^(2ʲ), with 2ʲ ≥ 2 Σ|Bᵢ| so that the
/// series converges to round-off. Uses only the geometric product.
fn exp_series(b: &Multivector) -> Multivector {
    let l1: f64 = b.as_slice().iter().map(|c| c.abs()).sum();
    let mut j = 0;
    while l1 / 2f64.powi(j) > 0.5 {
        j += 1;
    }
    let small = b * (1.0 / 2f64.powi(j));
    let mut term = Multivector::scalar(b.signature(), 1.0);
    let mut sum = term.clone();
    for k in 1..=30 {
        term = &(&term * &small) * (1.0 / k as f64);
        sum = &sum + &term;
    }
    for _ in 0..j {
        sum = &sum * &sum;
    }
    sum
}

fn rel_diff(a: &Multivector, b: &Multivector) -> f64 {
    (a - b).max_abs() / b.max_abs()
}

/// max |V Ṽ − 1| / max(1, |V|²).
fn unit_error(v: &Multivector) -> f64 {
    let mut vv = v * &v.reverse();
    vv.as_mut_slice()[0] -= 1.0;
    vv.max_abs() / v.max_abs().powi(2).max(1.0)
}

#[test]
fn exp_matches_the_taylor_series_in_every_signature() {
    let mut r = rng(1401);
    for s in table_signatures() {
        let mut worst: f64 = 0.0;
        for &scale in &[0.05, 0.4, 1.0, 2.5] {
            for _ in 0..40 {
                let b = random_mv_bivector(&mut r, s, scale);
                let e = b.exp().unwrap();
                let err = rel_diff(&e, &exp_series(&b));
                worst = worst.max(err);
                assert!(err <= 1e-13, "{s}: exp error {err:e} for {b}");
                assert!(unit_error(&e) <= 1e-13, "{s}: V Ṽ ≠ 1 for {b}");
            }
        }
        eprintln!("exp vs series {s}: max relative error {worst:.2e}");
    }
}

#[test]
fn log_inverts_exp_in_every_signature() {
    let mut r = rng(1402);
    for s in table_signatures() {
        let (mut worst_v, mut worst_b): (f64, f64) = (0.0, 0.0);
        for _ in 0..2000 {
            // Coefficients ≤ 0.4: every rotation angle sum stays below π.
            let b = random_mv_bivector(&mut r, s, 0.4);
            let v = b.exp().unwrap();
            let l = v.log().unwrap();
            let eb = rel_diff(&l, &b);
            let ev = rel_diff(&l.exp().unwrap(), &v);
            worst_b = worst_b.max(eb);
            worst_v = worst_v.max(ev);
            assert!(eb <= 1e-13, "{s}: log(exp B) − B = {eb:e} for {b}");
            assert!(ev <= 1e-13, "{s}: exp(log V) − V = {ev:e} for {b}");
        }
        eprintln!("log {s}: log∘exp {worst_b:.2e}, exp∘log {worst_v:.2e}");
    }
}

#[test]
fn isoclinic_and_near_isoclinic_families() {
    let mut r = rng(1403);
    // Rotation planes e12, e34 in Cl(4,1) and Cl(2,2) (e3, e4 negative: e34² = −1),
    // boost planes e13, e24 in Cl(2,2), rotated to a generic position by a random versor.
    let cases: [(Signature, &str, &str); 6] = [
        (sig(4, 1, 0), "e12", "e34"),
        (sig(2, 2, 0), "e12", "e34"),
        (sig(2, 2, 0), "e13", "e24"),
        (sig(4, 0, 1), "e12", "e34"),
        (sig(5, 0, 1), "e12", "e34"),
        (sig(6, 0, 1), "e12", "e34"),
    ];
    for (s, p1, p2) in cases {
        let (mut worst, mut worst_log): (f64, f64) = (0.0, 0.0);
        for gap in [0.0, 1e-15, 1e-12, 1e-9, 1e-6] {
            for theta in [0.3, 1.1, 2.0] {
                let b0 = &blade(s, p1, theta) + &blade(s, p2, theta + gap);
                let g = random_mv_bivector(&mut r, s, 0.5).exp().unwrap();
                let b = (&(&g * &b0) * &g.reverse()).grade(2);
                let e = b.exp().unwrap();
                let err = rel_diff(&e, &exp_series(&b));
                worst = worst.max(err);
                assert!(err <= 1e-13, "{s} gap {gap:e}: {err:e}");
                // Closed form of the commuting simple parts, transported by g.
                let parts =
                    &blade(s, p1, theta).exp().unwrap() * &blade(s, p2, theta + gap).exp().unwrap();
                let want = &(&g * &parts) * &g.reverse();
                assert!(rel_diff(&e, &want) <= 1e-13);
                let l = e.log().unwrap();
                assert!(rel_diff(&l.exp().unwrap(), &e) <= 1e-13);
                if 2.0 * theta < PI {
                    // Inside the principal branch (angle sum below π): log(exp B) = B.
                    let el = rel_diff(&l, &b);
                    worst_log = worst_log.max(el);
                    assert!(el <= 1e-13, "{s} gap {gap:e} θ {theta}: log error {el:e}");
                }
            }
        }
        eprintln!("isoclinic {s} {p1}+{p2}: exp vs series {worst:.2e}, log∘exp {worst_log:.2e}");
    }
}

#[test]
fn pure_translations_and_screws_in_projective_ga() {
    let pga = sig(3, 0, 1);
    // Translation: exp(t) = 1 + t exactly.
    for d in [1e-200, 1e-8, 0.3, 7.0, 1e150] {
        let t = &blade(pga, "e14", 0.3 * d) + &blade(pga, "e24", -d) + &blade(pga, "e34", 0.7 * d);
        let e = t.exp().unwrap();
        let want = &Multivector::scalar(pga, 1.0) + &t;
        assert_eq!(e, want, "translation by {d:e}");
        let l = e.log().unwrap();
        assert!(rel_diff(&l, &t) <= 1e-15, "log of a translation {d:e}");
    }
    // Screw: rotation in e12 commuting with a translation along e3 (e34); B² has a grade-4
    // part. exp is the product of the two exponentials.
    for (theta, d) in [
        (0.5, 2.0),
        (3.0, 1e-9),
        (1e-12, 5.0),
        (1.0, 1e150),
        (PI - 1e-12, 1.0),
    ] {
        let rot = blade(pga, "e12", theta);
        let tr = blade(pga, "e34", d);
        let b = &rot + &tr;
        assert!((&b * &b).grade(4).max_abs() > 0.0);
        let e = b.exp().unwrap();
        let want = &Multivector::from_coefficients(pga, &{
            let mut c = vec![0.0; 16];
            c[0] = theta.cos();
            c[0b11] = theta.sin();
            c
        })
        .unwrap()
            * &(&Multivector::scalar(pga, 1.0) + &tr);
        assert!(
            rel_diff(&e, &want) <= 1e-15,
            "screw {theta} {d:e}: {:e}",
            rel_diff(&e, &want)
        );
        let l = e.log().unwrap();
        assert!(rel_diff(&l.exp().unwrap(), &e) <= 1e-14);
        if theta < 3.0 {
            assert!(
                rel_diff(&l, &b) <= 1e-10,
                "screw log {theta} {d:e}: {:e}",
                rel_diff(&l, &b)
            );
        }
    }
}

#[test]
fn pga_translation_moves_a_point_by_plus_d() {
    // The convention of the docs: e₄ is e₀; the point x is e₁₂₃ + x₁e₂₃₄ − x₂e₁₃₄ + x₃e₁₂₄,
    // and exp(−½(d₁e₁₄ + d₂e₂₄ + d₃e₃₄)) moves it by +d under X ↦ M X M̃.
    let pga = sig(3, 0, 1);
    let point = |x: [f64; 3]| {
        &(&(&blade(pga, "e123", 1.0) + &blade(pga, "e234", x[0])) + &blade(pga, "e134", -x[1]))
            + &blade(pga, "e124", x[2])
    };
    let d = [0.5, -2.0, 3.0];
    let generator = &(&blade(pga, "e14", -0.5 * d[0]) + &blade(pga, "e24", -0.5 * d[1]))
        + &blade(pga, "e34", -0.5 * d[2]);
    let m = generator.exp().unwrap();
    let x = [1.0, 2.0, -1.0];
    let moved = &(&m * &point(x)) * &m.reverse();
    let want = point([x[0] + d[0], x[1] + d[1], x[2] + d[2]]);
    assert!((&moved - &want).max_abs() < 1e-15, "{moved} vs {want}");
    // And exp(−½θ e₁₂) turns e₁ toward e₂: the point (1, 0, 0) goes to (cos θ, sin θ, 0).
    let theta = 0.8;
    let m = blade(pga, "e12", -0.5 * theta).exp().unwrap();
    let moved = &(&m * &point([1.0, 0.0, 0.0])) * &m.reverse();
    let want = point([theta.cos(), theta.sin(), 0.0]);
    assert!((&moved - &want).max_abs() < 1e-15, "{moved} vs {want}");
}

#[test]
fn light_like_bivectors_in_spacetime() {
    let sta = sig(1, 3, 0);
    // (e₁ + e₂)∧e₃ = e₁₃ + e₂₃ is null: exp = 1 + N exactly.
    for a in [1e-200, 1e-6, 1.0, 1e3, 1e150] {
        let n = &blade(sta, "e13", a) + &blade(sta, "e23", a);
        assert_eq!((&n * &n).max_abs(), 0.0);
        let e = n.exp().unwrap();
        assert_eq!(e, &Multivector::scalar(sta, 1.0) + &n);
        assert!(rel_diff(&e.log().unwrap(), &n) <= 1e-15);
    }
    // A null bivector plus a generic one, against the series.
    let mut r = rng(1404);
    for _ in 0..50 {
        let n = &blade(sta, "e13", 1.0) + &blade(sta, "e23", 1.0);
        let b = &n + &random_mv_bivector(&mut r, sta, 1e-3);
        assert!(rel_diff(&b.exp().unwrap(), &exp_series(&b)) <= 1e-13);
    }
}

#[test]
fn rapidities_up_to_twenty() {
    let sta = sig(1, 3, 0);
    for half in [1e-8, 0.5, 3.0, 10.0] {
        for rot in [0.0, 0.7, 2.5] {
            // exp(½φ e₁₂) has rapidity φ = 2·half; e₃₄ commutes with e₁₂.
            let b = &blade(sta, "e12", half) + &blade(sta, "e34", rot);
            let e = b.exp().unwrap();
            let mut boost = Multivector::scalar(sta, half.cosh());
            boost.as_mut_slice()[0b11] = half.sinh();
            let mut turn = Multivector::scalar(sta, rot.cos());
            turn.as_mut_slice()[0b1100] = rot.sin();
            let want = &boost * &turn;
            assert!(
                rel_diff(&e, &want) <= 1e-15,
                "{half} {rot}: {:e}",
                rel_diff(&e, &want)
            );
            assert!(rel_diff(&e, &exp_series(&b)) <= 1e-13);
            let l = e.log().unwrap();
            assert!(
                rel_diff(&l, &b) <= 1e-14,
                "log {half} {rot}: {:e}",
                rel_diff(&l, &b)
            );
        }
    }
}

#[test]
fn angles_near_pi() {
    let mut r = rng(1405);
    for s in [
        sig(4, 1, 0),
        sig(3, 1, 0),
        sig(3, 0, 1),
        sig(2, 0, 1),
        sig(6, 0, 1),
    ] {
        for theta in [PI - 1e-12, PI, PI + 1e-12] {
            // A generic unit rotation plane: g e₁₂ g̃.
            let g = random_mv_bivector(&mut r, s, 0.3).exp().unwrap();
            let p = (&(&g * &blade(s, "e12", 1.0)) * &g.reverse()).grade(2);
            assert!(((&p * &p).scalar_part() + 1.0).abs() < 1e-14);
            let e = (&p * theta).exp().unwrap();
            let want = &Multivector::scalar(s, theta.cos()) + &(&p * theta.sin());
            assert!(rel_diff(&e, &want) <= 1e-14);
            if theta == PI {
                continue;
            }
            let l = e.log().unwrap();
            assert!(rel_diff(&l.exp().unwrap(), &e) <= 1e-14, "{s} {theta}");
        }
    }
}

#[test]
fn tiny_and_huge_magnitudes() {
    let mut r = rng(1406);
    for s in [
        sig(4, 1, 0),
        sig(1, 3, 0),
        sig(2, 2, 0),
        sig(4, 0, 1),
        sig(6, 0, 1),
    ] {
        // Tiny: exp(B) = 1 + B, with B itself to round-off relative to |B| (not just to 1).
        let b = random_mv_bivector(&mut r, s, 1e-200);
        let e = b.exp().unwrap();
        let one_plus_b = &Multivector::scalar(s, 1.0) + &b;
        let err = (&e - &one_plus_b).max_abs() / b.max_abs();
        assert!(err <= 1e-14, "{s}: {err:e}");
        let el = rel_diff(&e.log().unwrap(), &b);
        assert!(el <= 1e-14, "{s}: {el:e}");
        // Huge rotation: exp(θ P) = cos θ + sin θ P for a unit rotation plane.
        let theta = 1e150;
        let p = if s.p() >= 2 {
            blade(s, "e12", 1.0)
        } else {
            blade(s, "e23", 1.0)
        };
        let e = (&p * theta).exp().unwrap();
        let want = &Multivector::scalar(s, theta.cos()) + &(&p * theta.sin());
        assert!(rel_diff(&e, &want) <= 1e-15, "{s}");
    }
}

#[test]
fn bad_input_is_refused() {
    let sta = sig(1, 3, 0);
    let mixed = &blade(sta, "e12", 1.0) + &blade(sta, "e1", 1.0);
    assert!(matches!(
        mixed.exp(),
        Err(AlgebraError::NotABivector { ref grades, .. }) if grades == &vec![1]
    ));
    assert!(matches!(
        Multivector::scalar(sta, 1.0).exp(),
        Err(AlgebraError::NotABivector { .. })
    ));
    let mut nan = blade(sta, "e12", 1.0);
    nan.as_mut_slice()[0b11] = f64::NAN;
    assert!(matches!(nan.exp(), Err(AlgebraError::NonFinite { .. })));
    let mut inf = blade(sta, "e12", 1.0);
    inf.as_mut_slice()[0b101] = f64::INFINITY;
    assert!(matches!(inf.exp(), Err(AlgebraError::NonFinite { .. })));
    assert!(matches!(inf.log(), Err(AlgebraError::NonFinite { .. })));
    // A boost too large for f64.
    assert!(matches!(
        blade(sta, "e12", 800.0).exp(),
        Err(AlgebraError::Overflow { .. })
    ));
    // Not a versor: 2 + e12, odd grades.
    let two = &Multivector::scalar(sta, 2.0) + &blade(sta, "e12", 1.0);
    assert!(matches!(two.log(), Err(AlgebraError::NotAVersor { .. })));
    assert!(matches!(
        blade(sta, "e1", 1.0).log(),
        Err(AlgebraError::NotAVersor { .. })
    ));
    // No real logarithm: −exp(boost) with one plane only, −(1 + null) in spacetime,
    // −exp(translation) in 2D PGA.
    for (s, b) in [
        (sig(1, 1, 0), "e12"),
        (sig(2, 1, 0), "e13"),
        (sig(1, 2, 0), "e12"),
    ] {
        let v = &blade(s, b, 0.8).exp().unwrap() * -1.0;
        assert!(
            matches!(v.log(), Err(AlgebraError::NoLogarithm { .. })),
            "{s}"
        );
    }
    let n = &blade(sta, "e13", 1.0) + &blade(sta, "e23", 1.0);
    let v = &n.exp().unwrap() * -1.0;
    assert!(matches!(v.log(), Err(AlgebraError::NoLogarithm { .. })));
    // −exp(boost) in Cl(1,3) is on the cut: it has the logarithms B ± π e₃₄ (e₃₄ = e₁₂ I
    // commutes with the boost e₁₂ and squares to −1), and log refuses it.
    let boost = blade(sta, "e12", 0.8);
    let v = &boost.exp().unwrap() * -1.0;
    let on_cut = &boost + &blade(sta, "e34", PI);
    assert!(rel_diff(&on_cut.exp().unwrap(), &v) <= 1e-15);
    assert!(matches!(v.log(), Err(AlgebraError::NoLogarithm { .. })));
    let pga2 = sig(2, 0, 1);
    let v = &blade(pga2, "e13", 0.7).exp().unwrap() * -1.0;
    assert!(matches!(v.log(), Err(AlgebraError::NoLogarithm { .. })));
    // Above N = 5: projective signatures of any N, others up to N = 8.
    let b = blade(sig(4, 0, 1), "e12", 1.0);
    assert!(b.exp().is_ok());
    assert!(blade(sig(6, 0, 1), "e12", 1.0).exp().is_ok());
    assert!(blade(sig(4, 1, 1), "e12", 1.0).exp().is_ok());
    let b9 = blade(sig(6, 2, 1), "e12", 1.0);
    assert!(matches!(
        b9.exp(),
        Err(AlgebraError::UnsupportedDimension { max: 8, .. })
    ));
}

fn signature_strategy() -> impl Strategy<Value = Signature> {
    prop::sample::select(table_signatures())
}

fn bivector_in(scale: f64) -> impl Strategy<Value = Multivector> {
    (signature_strategy(), any::<u64>())
        .prop_map(move |(s, seed)| random_mv_bivector(&mut rng(seed), s, scale))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(64)
    ))]

    #[test]
    fn exp_is_a_versor(b in bivector_in(1.5)) {
        let e = b.exp().unwrap();
        prop_assert!(unit_error(&e) <= 1e-13, "{}", unit_error(&e));
        prop_assert!(e.odd().max_abs() == 0.0);
    }

    /// Coefficients up to 2 reach past the principal branch. Where an angle of the log lands
    /// within δ of π the logarithm is ill-conditioned (its plane is fixed by a bivector part
    /// of size ~δ) and exp(log V) = V holds to ~ε/δ: random cases come within 1e-4 of π,
    /// hence the 1e-10.
    #[test]
    fn exp_of_log_is_the_identity(b in bivector_in(2.0)) {
        let v = b.exp().unwrap();
        let l = v.log();
        prop_assume!(!matches!(l, Err(AlgebraError::NoLogarithm { .. })));
        let back = l.unwrap().exp().unwrap();
        prop_assert!(rel_diff(&back, &v) <= 1e-10, "{}", rel_diff(&back, &v));
    }

    /// Inside the principal branch (coefficients up to 0.4) exp(log V) = V to round-off.
    #[test]
    fn exp_of_log_is_the_identity_to_round_off_inside_the_branch(b in bivector_in(0.4)) {
        let v = b.exp().unwrap();
        let back = v.log().unwrap().exp().unwrap();
        prop_assert!(rel_diff(&back, &v) <= 1e-13, "{}", rel_diff(&back, &v));
    }

    #[test]
    fn log_of_exp_is_the_identity_on_the_principal_branch(b in bivector_in(0.4)) {
        let l = b.exp().unwrap().log().unwrap();
        prop_assert!(rel_diff(&l, &b) <= 1e-13, "{}", rel_diff(&l, &b));
    }
}

fn raw_multivector() -> impl Strategy<Value = Multivector> {
    (
        signature_strategy(),
        prop::collection::vec(any::<u64>(), 128),
    )
        .prop_map(|(s, bits)| {
            let mut m = Multivector::zero(s);
            let n = m.as_slice().len();
            for (c, b) in m.as_mut_slice().iter_mut().zip(&bits[..n]) {
                *c = f64::from_bits(*b);
            }
            m
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(256)
    ))]

    /// Raw bit patterns (NaN, ∞, subnormals, 1e300): exp and log of the element, of its
    /// bivector part and of its even part never panic and never return a non-finite
    /// coefficient.
    #[test]
    fn raw_bit_patterns_give_an_error_or_a_finite_result(m in raw_multivector()) {
        let results = [m.exp(), m.grade(2).exp(), m.log(), m.even().log()];
        for r in results.iter().flatten() {
            prop_assert!(r.as_slice().iter().all(|c| c.is_finite()), "{r:?} from {m:?}");
        }
        if m.as_slice().iter().all(|c| c.is_finite()) {
            prop_assert!(m.grade(2).exp().is_ok() || m.grade(2).max_abs() > 1.0);
        }
    }
}

fn wide_range_bivector() -> impl Strategy<Value = Multivector> {
    (
        signature_strategy(),
        prop::collection::vec((-1.0f64..1.0, -300i32..300, any::<bool>()), 21),
    )
        .prop_map(|(s, terms)| {
            let mut m = Multivector::zero(s);
            for (b, (c, e, on)) in bivector_masks(s.dim()).into_iter().zip(terms) {
                if on {
                    m.as_mut_slice()[b as usize] = c * 10f64.powi(e);
                }
            }
            m
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(256)
    ))]

    /// Magnitudes from 1e-300 to 1e300 mixed in one bivector: exp returns a finite versor or
    /// a clear error (overflow, or an angle beyond f64::MAX/2), and log of the result a
    /// finite bivector or a clear error.
    #[test]
    fn wide_magnitudes_give_an_error_or_a_finite_result(b in wide_range_bivector()) {
        match b.exp() {
            Ok(e) => {
                prop_assert!(e.as_slice().iter().all(|c| c.is_finite()));
                if let Ok(l) = e.log() {
                    prop_assert!(l.as_slice().iter().all(|c| c.is_finite()));
                }
            }
            Err(err) => prop_assert!(
                matches!(err, AlgebraError::Overflow { .. } | AlgebraError::AngleTooLarge { .. }),
                "{err}"
            ),
        }
    }
}

/// Fuzz finding (versor_bits) F1: a huge rotation beside O(1) or tiny parts in the N = 5
/// mixed signatures. The closed form's B and B W terms cancel at a huge angle, so V is only
/// known to ~ε |B| (honest), but V Ṽ = 1 must hold to round-off: a versor stays a versor.
#[test]
fn fuzz_huge_rotation_beside_small_parts_stays_a_versor() {
    let s32 = sig(3, 2, 0);
    let (a, t) = (2.26e6, -1.8e-6);
    let mut cases = vec![
        &(&(&blade(s32, "e23", a) + &blade(s32, "e45", a))
            + &(&blade(s32, "e13", t) + &blade(s32, "e14", t)))
            + &(&blade(s32, "e15", t) + &blade(s32, "e35", t)),
    ];
    for s in [
        sig(4, 0, 1),
        sig(2, 2, 0),
        sig(2, 3, 0),
        sig(3, 2, 0),
        sig(4, 1, 0),
    ] {
        for a in [1e6, 1e8, 1e12] {
            let mut b = blade(s, "e12", a);
            for (i, n) in ["e13", "e14", "e23", "e25", "e34", "e35", "e45"]
                .iter()
                .enumerate()
            {
                if let Ok(x) = Multivector::blade_by_name(s, n, 0.3 + 0.1 * i as f64) {
                    b = &b + &x;
                }
            }
            cases.push(b);
        }
    }
    for b in cases {
        let v = b.exp().unwrap();
        let ue = unit_error(&v);
        assert!(ue <= 1e-14, "{b:?}: V Ṽ − 1 = {ue:e}");
        let back = v.log().unwrap().exp().unwrap();
        let d = rel_diff(&back, &v);
        assert!(d <= 1e-13, "{b:?}: exp(log V) − V = {d:e}");
    }
}

/// Fuzz finding F2: a boost of rapidity 128 with tiny parts whose B∧B is null (Q² = 0 in
/// V): the logarithm's dual-number branch divided by sinh³ζ ≈ 1e165 through |sinh ζ|⁶,
/// which overflows, and lost its Q v term (exp(log V) off by 2e-4 relative).
#[test]
fn fuzz_large_boost_with_tiny_parts_round_trips() {
    let s = sig(3, 2, 0);
    let t = -1.83e-6;
    let b = &(&blade(s, "e24", 128.00000018) + &blade(s, "e13", t))
        + &(&blade(s, "e14", t) + &blade(s, "e15", t));
    let v = b.exp().unwrap();
    assert!(unit_error(&v) <= 1e-14);
    let l = v.log().unwrap();
    let dl = (&l - &b).max_abs() / b.max_abs();
    assert!(dl <= 1e-13, "log: {dl:e}");
    let d = rel_diff(&l.exp().unwrap(), &v);
    assert!(d <= 1e-13, "exp(log V): {d:e}");
}

/// Fuzz finding F3: nearly null parts of 1e82 … 1e274 beside small terms (Cl(0,2,2),
/// Cl(2,0,2)): exp of the logarithm reported `Overflow` although it is finite. The closed
/// form divided complex numbers through |z|², which over- or underflows for |z| outside
/// 1e-154 … 1e154 (a division by zero: ∞).
#[test]
fn fuzz_no_overflow_for_nearly_null_parts() {
    let mk = |s: Signature, terms: &[(u64, f64)]| {
        let mut b = Multivector::zero(s);
        for &(m, c) in terms {
            b.as_mut_slice()[m as usize] = c;
        }
        b
    };
    let cases = [
        mk(
            sig(0, 2, 2),
            &[
                (3, 5.256633473081305e83),
                (5, 2.255858409778442e-305),
                (9, 5.256633473081304e83),
                (6, 1.5241268609589208e82),
                (10, 1.047042593e-314),
            ],
        ),
        mk(
            sig(2, 0, 2),
            &[
                (3, -5.1933465720748865e274),
                (5, -2.6699837501662295e97),
                (9, -5.403795835963677e274),
                (6, 6.36123895270227e-309),
                (10, -9.213530580391169e273),
                (12, 1.23e-321),
            ],
        ),
    ];
    for b in cases {
        let v = b.exp().unwrap();
        let l = v.log().unwrap();
        let back = l
            .exp()
            .unwrap_or_else(|e| panic!("exp(log V) for {b:?}: {e}"));
        let d = (&back - &v).max_abs() / v.max_abs();
        assert!(d <= 1e-13 * l.max_abs().max(1.0), "{b:?}: {d:e}");
    }
}

/// A subnormal rotation beside a huge translation in 2D PGA: the closed form scaled B by the
/// size of its non-null part (2^1074 here), which made the translation infinite, and
/// returned `Overflow` for a finite exp(B) = 1 + B. The scale now keeps the null parts
/// finite.
#[test]
fn subnormal_rotation_beside_a_huge_translation() {
    let s = sig(2, 0, 1);
    for t in [1e-170, 1e200, 1.8e300] {
        let b = &blade(s, "e12", -5e-324) + &blade(s, "e23", t);
        let v = b.exp().unwrap();
        let mut want = b.clone();
        want.as_mut_slice()[0] = 1.0;
        assert!((&v - &want).max_abs() <= 1e-15 * t, "{v:?}");
    }
}
