//! Legendre's complete and incomplete elliptic integrals of the first, second
//! and third kind, in terms of Carlson's symmetric integrals (DLMF §19.25(i)).
//!
//! Conventions (DLMF 19.2.4–19.2.7 with k² = m, A&S 17.2):
//! * parameter m = k², complementary parameter m₁ = 1 − m;
//! * characteristic n as in Π(n;φ | m), the sign convention of DLMF
//!   (α² = n) and of mpmath — *not* A&S 17.2.14, which uses −n.
//!
//! Every function has a `_complement` twin taking m₁ = 1−m instead of m.
//! Use it when m is close to 1: m₁ = 10⁻²⁰ cannot be represented as
//! m = 1 − 10⁻²⁰ in `f64`, and the integrals depend on ln m₁ there.
//!
//! Incomplete integrals accept any real amplitude φ with
//! |φ| < 2⁵⁰: φ = jπ + r, |r| ≤ π/2, is reduced with a
//! double-double π (the low part of r enters through a first-order
//! correction), and quasi-periodicity (DLMF §19.2(ii); the integrands have
//! period π) gives F(φ|m) = 2jK(m) + F(r|m), and likewise for E and Π.

use crate::special::carlson::{rc, rd, rf, rj};
use crate::special::dd;
use crate::special::error::{EllipticError, check_domain, check_finite, finish};

/// Largest accepted |φ| / π for incomplete integrals.
const PHI_LIMIT_PERIODS: f64 = 1_125_899_906_842_624.0; // 2^50

/// A validated parameter pair (m, m₁ = 1 − m), each known to full precision.
#[derive(Debug, Clone, Copy)]
struct Param {
    m: f64,
    m1: f64,
}

impl Param {
    /// From m ≤ 1; 1 − m is exact for m ≥ 1/2 (Sterbenz) and
    /// correctly rounded otherwise.
    fn from_m(m: f64) -> Result<Self, EllipticError> {
        check_domain("m", m, "(-inf, 1]", |m| m <= 1.0)?;
        Ok(Param { m, m1: 1.0 - m })
    }

    /// From m₁ ≥ 0.
    fn from_m1(m1: f64) -> Result<Self, EllipticError> {
        check_domain("m1", m1, "[0, +inf)", |m1| m1 >= 0.0)?;
        Ok(Param { m: 1.0 - m1, m1 })
    }
}

// ---------------------------------------------------------------------------
// complete integrals

fn k_impl(p: Param) -> f64 {
    if p.m1 == 0.0 {
        return f64::INFINITY;
    }
    // DLMF 19.25.1: K(k) = R_F(0, k'^2, 1)
    rf(0.0, p.m1, 1.0)
}

fn e_impl(p: Param) -> f64 {
    if p.m1 == 0.0 {
        return 1.0;
    }
    if p.m1 < 1e-20 {
        // DLMF 19.12.2: E = 1 + (m1/4)(ln(16/m1) - 1) + O(m1^2 ln m1); the
        // correction is below 1e-18 here, and R_D(0, 1, m1) ~ 1/m1 could
        // overflow for subnormal m1.
        return 1.0 + 0.25 * p.m1 * (16f64.ln() - p.m1.ln() - 1.0);
    }
    // DLMF 19.25.1: E(k) = (k'^2/3) [R_D(0, k'^2, 1) + R_D(0, 1, k'^2)],
    // a sum of two positive terms (no cancellation, unlike K - (m/3) R_D).
    p.m1 / 3.0 * (rd(0.0, p.m1, 1.0) + rd(0.0, 1.0, p.m1))
}

fn pi_impl(n: f64, p: Param) -> f64 {
    if p.m1 == 0.0 {
        // the integrand behaves like 1/((1 - n) cos θ) at θ = π/2
        return if n > 1.0 {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        };
    }
    if n == 0.0 {
        return k_impl(p);
    }
    if n == 1.0 {
        return f64::INFINITY;
    }
    if n < 0.0 {
        // Avoid K + (n/3) R_J(0, m1, 1, 1 - n), which cancels badly for
        // n << -1. DLMF 19.21.12 (the R_J(p) <-> R_J(q) relation with
        // (p - x)(q - x) = (y - x)(z - x), x = 0) turns it into a sum of
        // positive terms:  with N = -n/(1 - n) and q = m1/(1 - n),
        //   Π(n|m) = (1 - N) K(m) + (N/3) q R_J(0, m1, 1, q).
        let one_minus_n = 1.0 - n;
        let big_n = -n / one_minus_n;
        let q = p.m1 / one_minus_n;
        if q == 0.0 {
            // q underflowed (subnormal m1, n << 0): fall back to the direct
            // form, whose cancellation is mild unless n is also huge.
            return k_impl(p) + n / 3.0 * rj(0.0, p.m1, 1.0, one_minus_n).unwrap_or(0.0);
        }
        let rj_q = rj(0.0, p.m1, 1.0, q).unwrap_or(f64::INFINITY);
        return k_impl(p) / one_minus_n + big_n / 3.0 * q * rj_q;
    }
    if n > 1.0 {
        // Principal value. K + (n/3) R_J(0, m1, 1, 1 - n) cancels (the value
        // tends to 0 as m -> 0); DLMF 19.6.5, Π(n|m) = K - Π(m/n|m), written
        // out gives one term:  -(m/(3n)) R_J(0, m1, 1, 1 - m/n).
        return -(p.m / (3.0 * n)) * rj(0.0, p.m1, 1.0, one_minus_m_over_n(n, p)).unwrap_or(0.0);
    }
    // 0 < n < 1: both terms positive.
    let coef = n / 3.0;
    if coef == 0.0 {
        return k_impl(p);
    }
    k_impl(p) + coef * rj(0.0, p.m1, 1.0, 1.0 - n).unwrap_or(f64::INFINITY)
}

/// 1 − m/n = ((n − 1) + m₁)/n for n > 1, without cancellation when
/// m/n → 1 (n − 1 is exact for 1 < n ≤ 2).
#[inline]
fn one_minus_m_over_n(n: f64, p: Param) -> f64 {
    ((n - 1.0) + p.m1) / n
}

/// Returns the complete elliptic integral of the first kind
/// K(m) = ∫₀^(π/2) dθ/√(1−m sin²θ) = R_F(0, 1−m, 1).
///
/// Domain: finite m ≤ 1 (negative m allowed). K(1) = +∞.
///
/// Accuracy: relative error ≤ 5.3e-16 (2.4 ulp) against mpmath for m from
/// −1000 to 1 − 2⁻⁵².
///
/// Source: DLMF 19.2.8 (definition), 19.25.1 (Carlson form).
///
/// # Errors
/// [`EllipticError::NonFinite`]; [`EllipticError::OutOfDomain`] for m > 1.
///
/// # Example
/// ```
/// # use rotorflow::special::elliptic_k;
/// assert_eq!(elliptic_k(0.0)?, std::f64::consts::FRAC_PI_2);
/// assert_eq!(elliptic_k(1.0)?, f64::INFINITY);
/// # Ok::<(), rotorflow::special::EllipticError>(())
/// ```
pub fn elliptic_k(m: f64) -> Result<f64, EllipticError> {
    finish("elliptic_k", k_impl(Param::from_m(m)?))
}

/// Returns K(1 − m₁) for a complementary parameter m₁ ≥ 0 given
/// exactly; see [`elliptic_k`]. Near the separatrix (m₁ → 0),
/// K ≈ ln(4/√m₁) (DLMF 19.12.1).
///
/// Accuracy: relative error ≤ 3.1e-16 (1.4 ulp) against mpmath for m₁
/// from 10⁻³⁰⁰ to 10³.
///
/// # Errors
/// [`EllipticError::NonFinite`]; [`EllipticError::OutOfDomain`] for m₁ < 0.
pub fn elliptic_k_complement(m1: f64) -> Result<f64, EllipticError> {
    finish("elliptic_k_complement", k_impl(Param::from_m1(m1)?))
}

/// Returns the complete elliptic integral of the second kind
/// E(m) = ∫₀^(π/2) √(1−m sin²θ) dθ
/// = (1−m)/3 [R_D(0,1−m,1) + R_D(0,1,1−m)].
///
/// Domain: finite m ≤ 1. E(1) = 1.
///
/// Accuracy: relative error ≤ 3.3e-16 (1.5 ulp) against mpmath (m from −1000 to 1;
/// m₁ from 10⁻³⁰⁰ with the complement form).
///
/// Source: DLMF 19.2.8, 19.25.1 (second form: two positive terms).
///
/// # Errors
/// [`EllipticError::NonFinite`]; [`EllipticError::OutOfDomain`] for m > 1.
pub fn elliptic_e(m: f64) -> Result<f64, EllipticError> {
    finish("elliptic_e", e_impl(Param::from_m(m)?))
}

/// Returns E(1 − m₁) for a complementary parameter m₁ ≥ 0; see
/// [`elliptic_e`].
///
/// # Errors
/// [`EllipticError::NonFinite`]; [`EllipticError::OutOfDomain`] for m₁ < 0.
pub fn elliptic_e_complement(m1: f64) -> Result<f64, EllipticError> {
    finish("elliptic_e_complement", e_impl(Param::from_m1(m1)?))
}

/// Returns the complete elliptic integral of the third kind
/// Π(n|m) = ∫₀^(π/2) dθ/((1−n sin²θ)√(1−m sin²θ))
/// = K(m) + (n/3) R_J(0, 1−m, 1, 1−n),
/// as a Cauchy principal value when n > 1.
///
/// Domain: finite n, finite m ≤ 1.
/// * n < 0 uses the cancellation-free form Π = (1−N)K + N/3 q R_J(0,1−m,1,q)
///   with N = −n/(1−n), q = (1−m)/(1−n) (DLMF 19.21.12), accurate even for n → −∞.
/// * n = 1: +∞. n > 1: principal value, computed as
///   −(m/3n) R_J(0, 1−m, 1, 1−m/n), i.e. DLMF 19.6.5
///   K(m) − Π(m/n | m) without its cancellation.
/// * m = 1: +∞ for n ≤ 1, −∞ for n > 1.
///
/// Accuracy: relative error ≤ 4.0e-16 (1.8 ulp) against mpmath for n from
/// −10¹⁰ to 10⁴ (principal values included) and m from −10 to
/// 1 − 10⁻¹², m₁ down to 10⁻³⁰⁰.
///
/// Source: DLMF 19.2.7, 19.25.2, 19.21.12; Carlson (1995).
///
/// # Errors
/// [`EllipticError::NonFinite`]; [`EllipticError::OutOfDomain`] for m > 1.
pub fn elliptic_pi(n: f64, m: f64) -> Result<f64, EllipticError> {
    check_finite("n", n)?;
    finish("elliptic_pi", pi_impl(n, Param::from_m(m)?))
}

/// Returns Π(n | 1 − m₁) for a complementary parameter m₁ ≥ 0;
/// see [`elliptic_pi`].
///
/// # Errors
/// [`EllipticError::NonFinite`]; [`EllipticError::OutOfDomain`] for m₁ < 0.
pub fn elliptic_pi_complement(n: f64, m1: f64) -> Result<f64, EllipticError> {
    check_finite("n", n)?;
    finish("elliptic_pi_complement", pi_impl(n, Param::from_m1(m1)?))
}

// ---------------------------------------------------------------------------
// incomplete integrals

/// An amplitude reduced to φ = jπ + r.
#[derive(Debug, Clone, Copy)]
struct Reduced {
    /// number of half-turns, an integer
    j: f64,
    /// sin r
    s: f64,
    /// |cos r|
    c: f64,
    /// low part of the reduced amplitude (r + r_lo = phi - j π)
    r_lo: f64,
    /// cos r < 0, i.e. |r| slightly above π/2 after rounding
    beyond: bool,
    /// phi < 0
    negative: bool,
}

fn reduce_phi(phi: f64) -> Result<Reduced, EllipticError> {
    check_finite("phi", phi)?;
    let mut j = (phi / core::f64::consts::PI).round();
    if j.abs() >= PHI_LIMIT_PERIODS {
        return Err(EllipticError::ArgumentTooLarge {
            name: "phi",
            value: phi,
            limit: PHI_LIMIT_PERIODS * core::f64::consts::PI,
        });
    }
    // r + r_lo = phi - j π as a double-double, with π in double-double:
    // j π_hi is formed exactly and phi - p is exact (Sterbenz).
    let reduce = |j: f64| {
        let (p, e) = dd::two_prod(j, dd::PI.hi);
        dd::two_sum(phi - p, -e - j * dd::PI.lo)
    };
    let (mut r, mut r_lo) = reduce(j);
    let (mut s, mut c) = r.sin_cos();
    if c < 0.0 {
        // phi / π rounded to a half-integer (e.g. phi = fl(π/2)) and the
        // rounding picked the far side: move r back into [-π/2, π/2].
        j += r.signum();
        (r, r_lo) = reduce(j);
        (s, c) = r.sin_cos();
    }
    Ok(Reduced {
        j,
        s,
        c: c.abs(),
        r_lo,
        beyond: c < 0.0,
        negative: phi < 0.0,
    })
}

/// Adds the quasi-periodic part, `2 j complete + base`, and the first-order
/// correction `r_lo * integrand(r)` for the rounding of the reduced amplitude
/// (without it, F near r = ±π/2 and m → 1 would lose a relative ε/k').
/// `complete` and `integrand` are only evaluated when needed.
fn assemble(
    red: Reduced,
    base: f64,
    complete: impl Fn() -> f64,
    integrand: impl Fn() -> f64,
) -> f64 {
    let base = if red.r_lo != 0.0 {
        base + red.r_lo * integrand()
    } else {
        base
    };
    // For |r| just above π/2 (cos r < 0), base was computed at π - |r|:
    // I(±(π/2 + δ)) = ±(2 I_complete - I(π/2 - δ)).
    let needs_complete = red.j != 0.0 || red.beyond;
    if !needs_complete {
        return base;
    }
    let full = complete();
    if full.is_infinite() {
        // m = 1 (or n = 1): the range passes a non-integrable singularity;
        // the integral diverges in the direction of phi.
        return if red.negative { -full } else { full };
    }
    let local = if red.beyond {
        let sign = if red.s < 0.0 { -1.0 } else { 1.0 };
        sign * 2.0 * full - base
    } else {
        base
    };
    if red.j == 0.0 {
        local
    } else {
        2.0 * red.j * full + local
    }
}

/// Δ² = 1 − m sin² r, written as cos² r + m₁ sin² r so that it
/// keeps full relative accuracy when m → 1 and r → π/2.
#[inline]
fn delta2(p: Param, s: f64, c: f64) -> f64 {
    c * c + p.m1 * (s * s)
}

fn f_base(p: Param, s: f64, c: f64) -> f64 {
    // DLMF 19.25.5 in the form F = sin φ R_F(cos^2 φ, Δ^2, 1)
    s * rf(c * c, delta2(p, s, c), 1.0)
}

fn f_impl(phi: f64, p: Param) -> Result<f64, EllipticError> {
    let red = reduce_phi(phi)?;
    let base = f_base(p, red.s, red.c);
    let integrand = || 1.0 / delta2(p, red.s, red.c).sqrt();
    Ok(assemble(red, base, || k_impl(p), integrand))
}

fn e_base(p: Param, s: f64, c: f64) -> f64 {
    let d2 = delta2(p, s, c);
    let s3 = s * s * s;
    if p.m < 0.0 {
        // DLMF 19.25.9: E = s R_F(c², Δ², 1) - (m/3) s³ R_D(c², Δ², 1); both terms ≥ 0 for m < 0
        s * rf(c * c, d2, 1.0) - p.m / 3.0 * s3 * rd(c * c, d2, 1.0)
    } else {
        // DLMF 19.25.10 rewritten with sin/cos (homogeneity): for 0 ≤ m ≤ 1 all
        // three terms are ≥ 0, so nothing cancels even at m → 1, φ → π/2:
        //   E = m1 F + (m m1 / 3) s³ R_D(c², 1, Δ²) + m s c / Δ
        let d = d2.sqrt();
        let last = if d > 0.0 { p.m * s * c / d } else { p.m * s };
        let first = if p.m1 > 0.0 {
            p.m1 * s * rf(c * c, d2, 1.0) + p.m * p.m1 / 3.0 * s3 * rd(c * c, 1.0, d2)
        } else {
            0.0
        };
        first + last
    }
}

fn e_inc_impl(phi: f64, p: Param) -> Result<f64, EllipticError> {
    let red = reduce_phi(phi)?;
    let base = e_base(p, red.s, red.c);
    let integrand = || delta2(p, red.s, red.c).sqrt();
    Ok(assemble(red, base, || e_impl(p), integrand))
}

fn pi_base(n: f64, p: Param, s: f64, c: f64) -> f64 {
    if s == 0.0 {
        return 0.0;
    }
    let x = c * c;
    let y = delta2(p, s, c);
    let s2 = s * s;
    if n == 0.0 {
        return s * rf(x, y, 1.0);
    }
    if n < 0.0 {
        // DLMF 19.21.12 with (p - x)(q - x) = (y - x)(z - x):
        //   Π = s [ (1 - N) R_F(x,y,1) + (N/3)(q - x) R_J(x,y,1,q) + N c R_C(y, p q) ]
        // with N = -n/(1 - n), p = c² + (1 - n) s², q = c² + m1 s²/(1 - n).
        // All terms are positive, so n → -∞ loses nothing.
        let one_minus_n = 1.0 - n;
        let big_n = -n / one_minus_n;
        let pp = x + one_minus_n * s2;
        // q - x = (y - x)(1 - x)/(p - x) = m1 s² / (1 - n)
        let q_minus_x = p.m1 * s2 / one_minus_n;
        let q = x + q_minus_x;
        let term_f = rf(x, y, 1.0) / one_minus_n;
        let term_j = if q_minus_x > 0.0 {
            big_n / 3.0 * q_minus_x * rj(x, y, 1.0, q).unwrap_or(f64::INFINITY)
        } else {
            0.0
        };
        let term_c = if c > 0.0 {
            big_n * c * rc(y, pp * q)
        } else {
            0.0
        };
        return s * (term_f + term_j + term_c);
    }
    if n > 1.0 {
        // Principal value by DLMF 19.7.8 (n -> m/n), which needs no principal
        // value of R_J and does not cancel for small m:
        //   Π(n;φ|m) = F(φ|m) - Π(m/n;φ|m) + (1/(2P)) ln|(Δ + P tan φ)/(Δ - P tan φ)|
        //            = -(m/(3n)) s³ R_J(c², Δ², 1, 1 - (m/n) s²) + (1/P) artanh(min(t, 1/t)),
        // P = sqrt((n - 1)(1 - m/n)), t = P |tan φ| / Δ.
        let a = one_minus_m_over_n(n, p);
        let big_p = ((n - 1.0) * a).sqrt();
        let rj_term = if p.m == 0.0 {
            0.0
        } else {
            let pp = x + a * s2;
            -(p.m / (3.0 * n)) * s * s2 * rj(x, y, 1.0, pp).unwrap_or(f64::INFINITY)
        };
        let num = big_p * s.abs();
        let den = c * y.sqrt();
        let ratio = if num <= den { num / den } else { den / num };
        let log_term = ratio.atanh() / big_p;
        return rj_term + if s < 0.0 { -log_term } else { log_term };
    }
    // 0 < n ≤ 1: DLMF 19.25.14 with sin/cos, both terms positive.
    let coef = n / 3.0 * s * s2;
    if coef == 0.0 {
        // the R_J term underflowed away (n or sin φ tiny); do not form 0 · ∞
        return s * rf(x, y, 1.0);
    }
    let pp = x + (1.0 - n) * s2;
    let rj_p = rj(x, y, 1.0, pp).unwrap_or(f64::INFINITY);
    s * rf(x, y, 1.0) + coef * rj_p
}

fn pi_inc_impl(n: f64, phi: f64, p: Param) -> Result<f64, EllipticError> {
    check_finite("n", n)?;
    let red = reduce_phi(phi)?;
    let base = pi_base(n, p, red.s, red.c);
    let integrand = || {
        let (s2, c2) = (red.s * red.s, red.c * red.c);
        1.0 / ((c2 + (1.0 - n) * s2) * delta2(p, red.s, red.c).sqrt())
    };
    Ok(assemble(red, base, || pi_impl(n, p), integrand))
}

/// Returns the incomplete elliptic integral of the first kind
/// F(φ|m) = ∫₀^φ dθ/√(1−m sin²θ)
/// = sin φ R_F(cos²φ, 1−m sin²φ, 1) (|φ|≤π/2),
/// extended to all real φ by F(φ + jπ|m) = F(φ|m) + 2jK(m).
///
/// Domain: finite |φ| < 2⁵⁰π, finite m ≤ 1.
/// F(φ|0) = φ; F(φ|1) = artanh(sin φ) for
/// |φ| < π/2 and ±∞ beyond.
///
/// Accuracy: relative error ≤ 6.1e-16 (2.7 ulp) against mpmath for φ from
/// 10⁻³⁰⁰ to 10¹⁰ (negative included) and m from −10 to 1.
///
/// Source: DLMF 19.2.4, 19.25.5, 19.2.10 (quasi-periodicity).
///
/// # Errors
/// [`EllipticError::NonFinite`]; [`EllipticError::OutOfDomain`] for m > 1;
/// [`EllipticError::ArgumentTooLarge`] for |φ| ≥ 2⁵⁰π.
///
/// # Example
/// ```
/// # use rotorflow::special::{elliptic_f, elliptic_k};
/// let (phi, m) = (0.3, 0.7);
/// let k = elliptic_k(m)?;
/// let lhs = elliptic_f(phi + 3.0 * std::f64::consts::PI, m)?;
/// assert!((lhs - (elliptic_f(phi, m)? + 6.0 * k)).abs() < 1e-14);
/// # Ok::<(), rotorflow::special::EllipticError>(())
/// ```
pub fn elliptic_f(phi: f64, m: f64) -> Result<f64, EllipticError> {
    finish("elliptic_f", f_impl(phi, Param::from_m(m)?)?)
}

/// Returns F(φ | 1 − m₁) for a complementary parameter m₁ ≥ 0;
/// see [`elliptic_f`].
///
/// # Errors
/// As [`elliptic_f`], with [`EllipticError::OutOfDomain`] for m₁ < 0.
pub fn elliptic_f_complement(phi: f64, m1: f64) -> Result<f64, EllipticError> {
    finish("elliptic_f_complement", f_impl(phi, Param::from_m1(m1)?)?)
}

/// Returns the incomplete elliptic integral of the second kind
/// E(φ|m) = ∫₀^φ √(1−m sin²θ) dθ,
/// extended by E(φ + jπ|m) = E(φ|m) + 2jE(m).
///
/// For 0 ≤ m ≤ 1 it is evaluated as
/// m₁F(φ|m) + (m m₁)/3 sin³φ R_D(cos²φ, 1, Δ²) + m sin φ cos φ/Δ,
/// Δ² = 1 − m sin²φ (DLMF 19.25.10, three non-negative terms, no
/// cancellation near m = 1); for m < 0 by DLMF 19.25.9.
///
/// Domain: finite |φ| < 2⁵⁰π, finite m ≤ 1. E(φ|1) = sin φ for
/// |φ| ≤ π/2.
///
/// Accuracy: relative error ≤ 6.8e-16 (3 ulp) against mpmath on the same
/// grid as [`elliptic_f`].
///
/// Source: DLMF 19.2.5, 19.25.9, 19.25.10, §19.2(ii).
///
/// # Errors
/// As [`elliptic_f`].
pub fn elliptic_e_inc(phi: f64, m: f64) -> Result<f64, EllipticError> {
    finish("elliptic_e_inc", e_inc_impl(phi, Param::from_m(m)?)?)
}

/// Returns E(φ | 1 − m₁) for a complementary parameter m₁ ≥ 0;
/// see [`elliptic_e_inc`].
///
/// # Errors
/// As [`elliptic_f_complement`].
pub fn elliptic_e_inc_complement(phi: f64, m1: f64) -> Result<f64, EllipticError> {
    finish(
        "elliptic_e_inc_complement",
        e_inc_impl(phi, Param::from_m1(m1)?)?,
    )
}

/// Returns the incomplete elliptic integral of the third kind
/// Π(n;φ|m) = ∫₀^φ dθ/((1−n sin²θ)√(1−m sin²θ))
/// = sin φ R_F(c²,Δ²,1) + n/3 sin³φ R_J(c²,Δ²,1,1−n sin²φ),
/// (c = cos φ, Δ² = 1−m sin²φ), extended by
/// Π(n;φ+jπ|m) = Π(n;φ|m) + 2j Π(n|m).
///
/// Domain: finite n, finite |φ| < 2⁵⁰π, finite m ≤ 1.
/// * n < 0 (the rigid-body case, where n can be very negative) uses the
///   positive-term form of DLMF 19.21.12 (see [`elliptic_pi`]).
/// * n > 1 with n sin²θ = 1 inside the range: Cauchy principal
///   value (also for the periods added by quasi-periodicity), computed with
///   DLMF 19.7.8 (n → m/n plus a logarithm), which needs no principal
///   value of R_J. If n sin²φ = 1 exactly the integral diverges
///   (the logarithm is infinite).
///
/// Accuracy: relative error ≤ 8.0e-16 (3.6 ulp) for n ≤ 1 against mpmath
/// (n from −10⁸ to 0.95, the grid of [`elliptic_f`]); for n > 1 the
/// two terms of DLMF 19.7.8 partly cancel and the relative error reached
/// 6.5e-15 (absolute error below 2e-17).
///
/// Source: DLMF 19.2.7, 19.25.14, 19.21.12, 19.7.8; Carlson (1995).
///
/// # Errors
/// As [`elliptic_f`], plus [`EllipticError::NonFinite`] for n.
pub fn elliptic_pi_inc(n: f64, phi: f64, m: f64) -> Result<f64, EllipticError> {
    finish("elliptic_pi_inc", pi_inc_impl(n, phi, Param::from_m(m)?)?)
}

/// Returns Π(n;φ | 1 − m₁) for a complementary parameter
/// m₁ ≥ 0; see [`elliptic_pi_inc`].
///
/// # Errors
/// As [`elliptic_pi_inc`], with [`EllipticError::OutOfDomain`] for m₁ < 0.
pub fn elliptic_pi_inc_complement(n: f64, phi: f64, m1: f64) -> Result<f64, EllipticError> {
    finish(
        "elliptic_pi_inc_complement",
        pi_inc_impl(n, phi, Param::from_m1(m1)?)?,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reduce_phi_keeps_small_angles() {
        let r = reduce_phi(0.25).unwrap();
        assert_eq!(r.j, 0.0);
        assert_eq!(r.s, 0.25f64.sin());
    }

    #[test]
    fn reduce_phi_rejects_huge() {
        assert!(matches!(
            reduce_phi(1e20),
            Err(EllipticError::ArgumentTooLarge { .. })
        ));
    }

    #[test]
    fn m_above_one_is_an_error() {
        assert!(matches!(
            elliptic_k(1.5),
            Err(EllipticError::OutOfDomain { name: "m", .. })
        ));
        assert!(matches!(
            elliptic_k_complement(-0.1),
            Err(EllipticError::OutOfDomain { name: "m1", .. })
        ));
    }
}
