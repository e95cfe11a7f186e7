//! Exponential of a bivector in every signature with N ≤ 4, on fixed-size arrays.
//!
//! For N ≤ 4 a bivector commutes with its own square, which has grades 0 and 4 only:
//! B² = α + βI with I the pseudoscalar of N = 4 (β = 0 below N = 4). Splitting the series
//! into even and odd powers,
//!
//!   exp(B) = C(B²) + S(B²) B,   C(z) = Σ zᵏ/(2k)! = cosh √z,   S(z) = Σ zᵏ/(2k+1)! = sinh √z / √z,
//!
//! with C and S entire functions, so they are defined at every z without choosing a root.
//! z = α + βI lives in the two-dimensional commutative algebra spanned by 1 and I, which is
//! the complex numbers where I² = −1 (Cl(3, 1), Cl(1, 3)), the split-complex numbers where
//! I² = +1 (Cl(2, 2), Cl(0, 4)) and the dual numbers where I² = 0 (every degenerate metric),
//! and an entire f is evaluated there exactly:
//!
//! - complex: f(α + βI) = Re f(α + iβ) + Im f(α + iβ) I;
//! - split-complex: f(α + βI) = ½(f(α + β) + f(α − β)) + ½(f(α + β) − f(α − β)) I, since
//!   ½(1 ± I) are orthogonal idempotents;
//! - dual: f(α + βI) = f(α) + β f′(α) I.
//!
//! This is the invariant decomposition (Roelfs & De Keninck, "Graded symmetry groups: plane
//! and simple") without forming its parts: the roots √(α ± β) are the two simple parts'
//! generators, but C and S take their squares, so isoclinic rotations and repeated boosts
//! (equal roots), null parts (a zero root) and huge, nearly isoclinic bivectors (where the
//! quadratic for the roots cancels) need no special case. The general closed form of
//! `versor.rs` agrees to round-off (tests below); this route only saves its products.

use super::{Multivector, Signature, blade};
use nalgebra::Complex;

type C64 = Complex<f64>;

/// exp(B) of a bivector B of N ≤ 4 (a non-Euclidean signature; any signature is exact) into
/// `out` (same algebra): true if it was written. False, with `out` unspecified, unless B is a
/// finite bivector whose square and exponential are finite: the general route then reports
/// what is wrong or scales the input.
#[inline]
pub(super) fn exp_to(b: &Multivector, out: &mut Multivector) -> bool {
    let sig = b.signature();
    let n = sig.dim();
    let x = b.as_slice();
    if n > 4 || x.len() != 1 << n || out.as_slice().len() != x.len() {
        return false;
    }
    let planes = planes(n);
    // Grades other than 2 must be exactly zero (one test on the bits of their coefficients).
    let mut others = 0u64;
    for (k, c) in x.iter().enumerate() {
        if k.count_ones() != 2 {
            others |= c.to_bits();
        }
    }
    if others << 1 != 0 {
        return false;
    }
    let (negative, null) = (sig.negative_mask(), sig.null_mask());
    let sq: [f64; 4] = core::array::from_fn(|i| {
        if null >> i & 1 == 1 {
            0.0
        } else if negative >> i & 1 == 1 {
            -1.0
        } else {
            1.0
        }
    });
    let plane_square = |m: usize| -> f64 {
        let (i, j) = (
            m.trailing_zeros() as usize,
            (63 - (m as u64).leading_zeros()) as usize,
        );
        -sq[i] * sq[j]
    };
    let i_square = if n == 4 {
        sq[0] * sq[1] * sq[2] * sq[3]
    } else {
        0.0
    };
    // (C, S) = (c₀ + c₁ I, s₀ + s₁ I). B² = α + βI with α = Σ b_m² e_m² and
    // β = 2 Σ ±b_m b_m′ over the complementary pairs (m, m′) of N = 4 (e_m e_m′ = ±I). Where
    // I² = ±1 each pair's share is a perfect square (e_m² e_m′² = I²), summed as such: a
    // huge, nearly isoclinic B then keeps its small root (|B| ≈ 10⁹ beside 1) exactly as
    // well as B's coefficients fix it, which α ± β formed from α and β would not.
    let (c0, c1, s0, s1) = if n < 4 {
        let alpha: f64 = planes
            .iter()
            .map(|&(_, _, m)| plane_square(m) * x[m] * x[m])
            .sum();
        if !alpha.is_finite() {
            return false;
        }
        let (c, s) = cosh_sinhc(alpha);
        (c, 0.0, s, 0.0)
    } else if i_square > 0.0 {
        // z± = α ± β = Σ e_m² (b_m ± σ e_m² b_m′)².
        let (mut zp, mut zm) = (0.0, 0.0);
        for (m, mc) in PAIRS {
            let (e, sigma) = (plane_square(m), blade::reorder_sign(m as u64, mc as u64));
            let (d, t) = (x[m] + sigma * e * x[mc], x[m] - sigma * e * x[mc]);
            zp += e * d * d;
            zm += e * t * t;
        }
        if !(zp.is_finite() && zm.is_finite()) {
            return false;
        }
        let (cp, sp) = cosh_sinhc(zp);
        let (cm, sm) = cosh_sinhc(zm);
        (
            0.5 * (cp + cm),
            0.5 * (cp - cm),
            0.5 * (sp + sm),
            0.5 * (sp - sm),
        )
    } else if i_square < 0.0 {
        // z = α + iβ = Σ e_m² (b_m + iσ e_m² b_m′)².
        let mut z = C64::new(0.0, 0.0);
        for (m, mc) in PAIRS {
            let (e, sigma) = (plane_square(m), blade::reorder_sign(m as u64, mc as u64));
            let w = C64::new(x[m], sigma * e * x[mc]);
            z += w * w * e;
        }
        if !(z.re.is_finite() && z.im.is_finite()) {
            return false;
        }
        let (c, s) = cosh_sinhc_complex(z);
        (c.re, c.im, s.re, s.im)
    } else {
        // Dual numbers: f(α + βI) = f(α) + β f′(α) I, with C′ = S/2.
        let mut alpha = 0.0;
        let mut beta = 0.0;
        for (m, mc) in PAIRS {
            alpha += plane_square(m) * x[m] * x[m] + plane_square(mc) * x[mc] * x[mc];
            beta += 2.0 * blade::reorder_sign(m as u64, mc as u64) * x[m] * x[mc];
        }
        if !(alpha.is_finite() && beta.is_finite()) {
            return false;
        }
        let (c, s) = cosh_sinhc(alpha);
        (c, beta * 0.5 * s, s, beta * sinhc_derivative(alpha, c, s))
    };
    let o = out.as_mut_slice();
    o.fill(0.0);
    o[0] = c0;
    for &(_, _, m) in planes {
        o[m] = s0 * x[m];
    }
    if n == 4 {
        let full = 0b1111u64;
        o[0b1111] = c1;
        if s1 != 0.0 {
            // s₁ I B: I e_m = [sign and metric of e_I e_m] e_(I^m).
            for &(_, _, m) in planes {
                let k = blade::reorder_sign(full, m as u64) * sig.metric_factor(full, m as u64);
                o[m ^ 0b1111] += s1 * k * x[m];
            }
        }
    }
    let mut sum = 0.0;
    for c in o.iter() {
        sum += c.abs();
    }
    sum.is_finite()
}

/// The complementary plane pairs of N = 4 (e_m e_m′ = ±I).
const PAIRS: [(usize, usize); 3] = [(0b0011, 0b1100), (0b0101, 0b1010), (0b0110, 0b1001)];

/// The bivector planes of N ≤ 4 as (i, j, mask) with i < j.
fn planes(n: usize) -> &'static [(usize, usize, usize)] {
    const ALL: [(usize, usize, usize); 6] = [
        (0, 1, 0b0011),
        (0, 2, 0b0101),
        (1, 2, 0b0110),
        (0, 3, 0b1001),
        (1, 3, 0b1010),
        (2, 3, 0b1100),
    ];
    match n {
        0 | 1 => &[],
        2 => &ALL[..1],
        3 => &ALL[..3],
        _ => &ALL,
    }
}

/// (C(x), S(x)) = (cosh √x, sinh √x / √x) for real x: cos and sin θ/θ of θ = √−x for x < 0.
#[inline(always)]
fn cosh_sinhc(x: f64) -> (f64, f64) {
    if x.abs() < 1e-6 {
        // The series to x², below 2⁻⁵³ relative here.
        return (
            1.0 + x * (0.5 + x / 24.0),
            1.0 + x * (1.0 / 6.0 + x / 120.0),
        );
    }
    if x < 0.0 {
        let w = (-x).sqrt();
        let (s, c) = w.sin_cos();
        (c, s / w)
    } else {
        let w = x.sqrt();
        let (sinh, cosh) = sinh_cosh(w);
        (cosh, sinh / w)
    }
}

/// S′(x) = (C(x) − S(x)) / (2x) from C = C(x), S = S(x), by its power series where the
/// difference cancels.
#[inline(always)]
fn sinhc_derivative(x: f64, c: f64, s: f64) -> f64 {
    if x.abs() < 0.25 {
        // Σ_{k≥1} k x^(k−1)/(2k+1)!, the terms through k = 9 (the next is below 10⁻¹⁹).
        const K: [f64; 9] = [
            1.0 / 6.0,
            2.0 / 120.0,
            3.0 / 5040.0,
            4.0 / 362_880.0,
            5.0 / 39_916_800.0,
            6.0 / 6_227_020_800.0,
            7.0 / 1_307_674_368_000.0,
            8.0 / 355_687_428_096_000.0,
            9.0 / 121_645_100_408_832_000.0,
        ];
        K.iter().rev().fold(0.0, |acc, k| acc * x + k)
    } else {
        (c - s) / (2.0 * x)
    }
}

/// (C(z), S(z)) for complex z: w = √z = u + iv, cosh w and sinh w / w.
#[inline(always)]
fn cosh_sinhc_complex(z: C64) -> (C64, C64) {
    if z.norm_sqr() < 1e-12 {
        // |z| < 10⁻⁶: the series to z², below 2⁻⁵³ relative.
        let c = C64::new(1.0, 0.0) + z * (C64::new(0.5, 0.0) + z / 24.0);
        let s = C64::new(1.0, 0.0) + z * (C64::new(1.0 / 6.0, 0.0) + z / 120.0);
        return (c, s);
    }
    let w = principal_sqrt(z);
    let (sv, cv) = w.im.sin_cos();
    let (su, cu) = sinh_cosh(w.re);
    let cosh = C64::new(cu * cv, su * sv);
    let sinh = C64::new(su * cv, cu * sv);
    (cosh, sinh / w)
}

/// The principal square root, algebraically (no polar form): for z = a + ib and r = |z|,
/// √z = t + ib/(2t) with t = √((r + a)/2) where a ≥ 0, else |b|/(2t) ± it with
/// t = √((r − a)/2), so that neither branch cancels.
#[inline(always)]
fn principal_sqrt(z: C64) -> C64 {
    let (a, b) = (z.re, z.im);
    let r2 = a * a + b * b;
    let r = if (1e-300..1e300).contains(&r2) {
        r2.sqrt()
    } else {
        a.hypot(b)
    };
    let t = (0.5 * (r + a.abs())).sqrt();
    if t == 0.0 {
        return C64::new(0.0, 0.0);
    }
    if a >= 0.0 {
        C64::new(t, 0.5 * b / t)
    } else {
        C64::new(0.5 * b.abs() / t, t.copysign(b))
    }
}

/// (sinh u, cosh u) from one exponential, with `f64::sinh` where e^u − e^−u would cancel.
#[inline(always)]
fn sinh_cosh(u: f64) -> (f64, f64) {
    let e = u.exp();
    let cosh = 0.5 * (e + 1.0 / e);
    let sinh = if u.abs() < 0.5 {
        u.sinh()
    } else {
        0.5 * (e - 1.0 / e)
    };
    (sinh, cosh)
}

/// True where this route applies (non-Euclidean N ≤ 4: Euclidean signatures take the rotor
/// route, which keeps the bivector part relatively accurate near π).
#[inline]
pub(super) fn applies(sig: Signature) -> bool {
    sig.dim() <= 4 && !sig.is_euclidean()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic pseudo-random stream in [−1, 1).
    fn stream(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        }
    }

    #[test]
    fn agrees_with_the_general_closed_form_in_every_signature_up_to_n4() {
        let mut checked = 0;
        let mut next = stream(7);
        for n in 2..=4 {
            for p in 0..=n {
                for q in 0..=n - p {
                    let sig = Signature::new(p, q, n - p - q).unwrap();
                    for scale in [1e-7, 0.3, 1.0, 3.0, 12.0] {
                        let mut b = Multivector::zero(sig);
                        for &(_, _, m) in planes(n) {
                            b.as_mut_slice()[m] = scale * next();
                        }
                        let mut fast = Multivector::zero(sig);
                        assert!(exp_to(&b, &mut fast), "{sig}, scale {scale}");
                        let mut general = Multivector::zero(sig);
                        super::super::versor_general::exp_general_to(&b, &mut general).unwrap();
                        let size = general.max_abs().max(1.0);
                        let err = (&fast - &general).max_abs() / size;
                        assert!(
                            err < 1e-13 * scale.max(1.0),
                            "{sig}, scale {scale}: {err:e}"
                        );
                        checked += 1;
                    }
                }
            }
        }
        // Signatures with N = 2, 3, 4: 6 + 10 + 15, five scales each.
        assert_eq!(checked, 5 * (6 + 10 + 15));
    }

    #[test]
    fn principal_sqrt_matches_the_polar_form_in_every_quadrant() {
        let mut next = stream(11);
        let mut checked = 0;
        for scale in [1e-200, 1e-5, 1.0, 1e5, 1e200, 1e300] {
            for _ in 0..50 {
                let z = C64::new(scale * next(), scale * next());
                let (fast, polar) = (principal_sqrt(z), z.sqrt());
                assert!((fast - polar).norm() <= 4e-16 * polar.norm(), "{z}");
                assert!(fast.re >= 0.0);
                checked += 1;
            }
        }
        assert_eq!(checked, 300);
        assert_eq!(principal_sqrt(C64::new(-4.0, 0.0)), C64::new(0.0, 2.0));
        assert_eq!(principal_sqrt(C64::new(0.0, 0.0)), C64::new(0.0, 0.0));
    }

    #[test]
    fn isoclinic_null_and_light_like_bivectors_are_exact() {
        // Cl(2, 2): an isoclinic pair of rotations, e12 and e34 with e12 e34 = I, I² = +1.
        let sig = Signature::new(2, 2, 0).unwrap();
        let b = &Multivector::blade_by_name(sig, "e12", 0.7).unwrap()
            + &Multivector::blade_by_name(sig, "e34", 0.7).unwrap();
        let mut v = Multivector::zero(sig);
        assert!(exp_to(&b, &mut v));
        let e12 = Multivector::blade_by_name(sig, "e12", 0.7).unwrap();
        let e34 = Multivector::blade_by_name(sig, "e34", 0.7).unwrap();
        let product = {
            let mut a = Multivector::zero(sig);
            let mut c = Multivector::zero(sig);
            assert!(exp_to(&e12, &mut a));
            assert!(exp_to(&e34, &mut c));
            &a * &c
        };
        assert!((&v - &product).max_abs() < 1e-15);
        // |B| ≈ 10⁹ nearly isoclinic (angles 10⁹ and 10⁹ + 1): the small root 1 survives.
        let (a, c) = (1e9, 1e9 + 1.0);
        let b = &Multivector::blade_by_name(sig, "e12", a).unwrap()
            + &Multivector::blade_by_name(sig, "e34", c).unwrap();
        assert!(exp_to(&b, &mut v));
        let expected = &(&Multivector::scalar(sig, a.cos())
            + &Multivector::blade_by_name(sig, "e12", a.sin()).unwrap())
            * &(&Multivector::scalar(sig, c.cos())
                + &Multivector::blade_by_name(sig, "e34", c.sin()).unwrap());
        // The angles themselves are fixed by B only to ε · 10⁹ ≈ 10⁻⁷.
        assert!(
            (&v - &expected).max_abs() < 1e-6,
            "{}",
            (&v - &expected).max_abs()
        );
        // Cl(1, 3): a light-like bivector (boost e12 plus rotation e23 of equal size) squares
        // to zero, so exp(B) = 1 + B exactly.
        let sta = Signature::new(1, 3, 0).unwrap();
        let b = &Multivector::blade_by_name(sta, "e12", 0.9).unwrap()
            + &Multivector::blade_by_name(sta, "e23", 0.9).unwrap();
        assert_eq!((&b * &b).max_abs(), 0.0);
        let mut v = Multivector::zero(sta);
        assert!(exp_to(&b, &mut v));
        let expected = &Multivector::scalar(sta, 1.0) + &b;
        assert_eq!(v, expected);
    }
}
