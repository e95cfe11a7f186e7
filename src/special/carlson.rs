//! Carlson's symmetric elliptic integrals R_F, R_D, R_J and R_C.
//!
//! All four use Carlson's duplication theorem (B. C. Carlson, "Numerical
//! computation of real or complex elliptic integrals", Numer. Algorithms 10
//! (1995) 13–26, arXiv:math/9409227; DLMF §19.36(i)): the arguments are
//! replaced by (v + λ)/4 until they agree to about 1 %, and the
//! remaining integral is summed from its Taylor series in the elementary
//! symmetric functions E₂ … E₅ (DLMF 19.36.1 and 19.36.2, which carry
//! the series two orders further than the 1995 paper). The series is
//! truncated after degree 7, so stopping at relative spread t ≤ 10⁻²
//! leaves a truncation error of about 10⁻² t⁸ ≤ 10⁻¹⁸; the rest of
//! the error is rounding.
//!
//! Arguments are first rescaled by an even power of two (exact, and exact in
//! the square root) when the largest one is outside [2⁻³⁰⁰, 2³⁰⁰]
//! (R_J, R_D) or [2⁻⁹⁰⁰, 2⁹⁰⁰] (R_F, R_C), so that the cubes
//! formed inside R_J neither overflow nor underflow. Arguments whose ratio
//! exceeds about 2¹⁰⁰⁰ cannot all be represented after scaling; the
//! result is then finite but not accurate (this is the only loss of
//! accuracy inside the domain).

use crate::special::error::{EllipticError, check_domain, check_finite, finish};

/// Stop the duplication when 4⁻ⁿ max_i|A₀ − v_i| ≤ `TOL` · A_n.
/// The neglected series terms are then below ≈ 0.03 `TOL`⁸
/// (measured with mpmath for both series) — about 5 × 10⁻¹⁹.
const TOL: f64 = 8e-3;

/// Iteration cap; the spread shrinks at least by 4 per step once the
/// arguments are within a factor of a few, and the initial coalescence of
/// widely spread arguments takes log₂ log(max/min) steps, so 100 is
/// never reached for finite inputs.
const MAX_ITER: usize = 100;

/// Returns `s = 2^k` such that `s * s * largest` lies in `[2^-2, 2^2]` when
/// `largest` is outside `[1/limit, limit]`, else 1. Arguments are then scaled
/// by `s * s` (two exact multiplications, so that `s * s` itself may exceed
/// the `f64` range for subnormal input).
fn rescale(largest: f64, limit: f64) -> f64 {
    if largest > limit || (largest < 1.0 / limit && largest > 0.0) {
        let e = largest.log2().round() as i32;
        2f64.powi(-(e / 2))
    } else {
        1.0
    }
}

/// Scaling limit for R_J and R_D, whose duplication forms cubes of the
/// arguments: 2³⁰⁰.
const LIMIT_CUBIC: f64 = 2.037_035_976_334_486e90;
/// Scaling limit for R_F and R_C (no products beyond square roots):
/// 2⁹⁰⁰, which also keeps subnormal inputs away from the core loop.
const LIMIT_LINEAR: f64 = 8.452_712_498_170_644e270;

/// `v * s * s` without forming `s * s`. A non-zero argument that would
/// underflow to zero (only when the arguments span more than ~2^1000) is
/// kept at the smallest normal number, so that the integral stays finite;
/// the result then depends only logarithmically on the lost argument.
#[inline]
fn scaled(v: f64, s: f64) -> f64 {
    let r = v * s * s;
    if r == 0.0 && v != 0.0 {
        f64::MIN_POSITIVE.copysign(v)
    } else {
        r
    }
}

/// Degree-7 truncation of the R_F series, DLMF 19.36.1.
#[inline]
fn rf_series(e2: f64, e3: f64) -> f64 {
    // 1 - E2/10 + E3/14 + E2^2/24 - 3 E2 E3/44 - 5 E2^3/208 + 3 E3^2/104 + E2^2 E3/16
    1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0 - 5.0 * e2 * e2 * e2 / 208.0
        + 3.0 * e3 * e3 / 104.0
        + e2 * e2 * e3 / 16.0
}

/// Degree-7 truncation of the R_J (and R_D) series, DLMF 19.36.2.
#[inline]
fn rj_series(e2: f64, e3: f64, e4: f64, e5: f64) -> f64 {
    1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 - 9.0 * e2 * e3 / 52.0
        + 3.0 * e5 / 26.0
        - e2 * e2 * e2 / 16.0
        + 3.0 * e3 * e3 / 40.0
        + 3.0 * e2 * e4 / 20.0
        + 45.0 * e2 * e2 * e3 / 272.0
        - 9.0 * (e3 * e4 + e2 * e5) / 68.0
}

/// λ = √x√y + √x√z + √y√z of Carlson's duplication theorem, which moves every argument v
/// of R_F, R_D and R_J to (v + λ)/4, with (√x, √y, √z).
#[inline]
fn duplication(x: f64, y: f64, z: f64) -> (f64, [f64; 3]) {
    let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
    (sx * (sy + sz) + sy * sz, [sx, sy, sz])
}

/// R_F for finite `x, y, z >= 0` with at most one zero. No checks.
pub(crate) fn rf(x: f64, y: f64, z: f64) -> f64 {
    let zeros = (x == 0.0) as u8 + (y == 0.0) as u8 + (z == 0.0) as u8;
    if zeros >= 2 {
        return f64::INFINITY;
    }
    let sc = rescale(x.max(y).max(z), LIMIT_LINEAR);
    if sc != 1.0 {
        return sc * rf_core(scaled(x, sc), scaled(y, sc), scaled(z, sc));
    }
    rf_core(x, y, z)
}

fn rf_core(x0: f64, y0: f64, z0: f64) -> f64 {
    let a0 = (x0 + y0 + z0) / 3.0;
    let q = (a0 - x0).abs().max((a0 - y0).abs()).max((a0 - z0).abs()) / TOL;
    let (mut x, mut y, mut z, mut a) = (x0, y0, z0, a0);
    let mut f = 1.0; // 4^-n
    for _ in 0..MAX_ITER {
        if q * f <= a {
            break;
        }
        let (lam, _) = duplication(x, y, z);
        [x, y, z, a] = [x, y, z, a].map(|v| 0.25 * (v + lam));
        f *= 0.25;
    }
    let t = f / a;
    let xx = (a0 - x0) * t;
    let yy = (a0 - y0) * t;
    let zz = -(xx + yy);
    let e2 = xx * yy - zz * zz;
    let e3 = xx * yy * zz;
    rf_series(e2, e3) / a.sqrt()
}

/// R_D for finite `x, y >= 0` (not both zero) and `z > 0`. No checks.
pub(crate) fn rd(x: f64, y: f64, z: f64) -> f64 {
    if z == 0.0 || (x == 0.0 && y == 0.0) {
        return f64::INFINITY;
    }
    let sc = rescale(x.max(y).max(z), LIMIT_CUBIC);
    if sc != 1.0 {
        return rd_core(scaled(x, sc), scaled(y, sc), scaled(z, sc)) * sc * sc * sc;
    }
    rd_core(x, y, z)
}

fn rd_core(x0: f64, y0: f64, z0: f64) -> f64 {
    let a0 = (x0 + y0 + 3.0 * z0) / 5.0;
    let q = (a0 - x0).abs().max((a0 - y0).abs()).max((a0 - z0).abs()) / TOL;
    let (mut x, mut y, mut z, mut a) = (x0, y0, z0, a0);
    let mut f = 1.0;
    let mut sum = 0.0;
    for _ in 0..MAX_ITER {
        if q * f <= a {
            break;
        }
        let (lam, [_, _, sz]) = duplication(x, y, z);
        sum += f / (sz * (z + lam));
        [x, y, z, a] = [x, y, z, a].map(|v| 0.25 * (v + lam));
        f *= 0.25;
    }
    let t = f / a;
    let xx = (a0 - x0) * t;
    let yy = (a0 - y0) * t;
    let zz = -(xx + yy) / 3.0;
    let xy = xx * yy;
    let z2 = zz * zz;
    let e2 = xy - 6.0 * z2;
    let e3 = (3.0 * xy - 8.0 * z2) * zz;
    let e4 = 3.0 * (xy - z2) * z2;
    let e5 = xy * z2 * zz;
    f * rj_series(e2, e3, e4, e5) / (a * a.sqrt()) + 3.0 * sum
}

/// R_C(1, w²) for w ≥ 0 without forming w² (DLMF 19.2.18–19.2.19).
fn rc_one_sq(w: f64) -> f64 {
    if w < 1.0 {
        if w == 0.0 {
            return f64::INFINITY;
        }
        let d = ((1.0 - w) * (1.0 + w)).sqrt();
        if w * w >= 0.5 {
            d.atanh() / d
        } else {
            ((1.0 + d) / w).ln() / d
        }
    } else if w > 1.0 {
        let s = if w < 1e100 {
            ((w - 1.0) * (w + 1.0)).sqrt()
        } else {
            w * ((1.0 - 1.0 / w) * (1.0 + 1.0 / w)).sqrt()
        };
        s.atan() / s
    } else {
        1.0
    }
}

/// R_J for finite `x, y, z >= 0` with at most one zero and `p > 0`.
fn rj_positive(x: f64, y: f64, z: f64, p: f64) -> f64 {
    let sc = rescale(x.max(y).max(z).max(p), LIMIT_CUBIC);
    if sc != 1.0 {
        let core = rj_core(scaled(x, sc), scaled(y, sc), scaled(z, sc), scaled(p, sc));
        return core * sc * sc * sc;
    }
    rj_core(x, y, z, p)
}

fn rj_core(x0: f64, y0: f64, z0: f64, p0: f64) -> f64 {
    let a0 = (x0 + y0 + z0 + 2.0 * p0) / 5.0;
    let q = (a0 - x0)
        .abs()
        .max((a0 - y0).abs())
        .max((a0 - z0).abs())
        .max((a0 - p0).abs())
        / TOL;
    let (mut x, mut y, mut z, mut p, mut a) = (x0, y0, z0, p0, a0);
    let mut f = 1.0; // 4^-n
    let mut sum = 0.0;
    for _ in 0..MAX_ITER {
        if q * f <= a {
            break;
        }
        let (lam, [sx, sy, sz]) = duplication(x, y, z);
        // Carlson (1979/1988) form of the R_C terms: alpha and beta are
        // positive, so R_C(alpha, beta) has no cancellation even when p << x
        // (Carlson 1995's R_C(1, 1 + e_m) needs 1 + e_m, which cancels there).
        // R_C(alpha^2, beta) = R_C(1, w^2) / alpha with w^2 = beta / alpha^2;
        // forming alpha^2 and beta themselves would underflow when the
        // arguments span many orders of magnitude.
        let alpha = p * (sx + sy + sz) + sx * sy * sz;
        let w = p.sqrt() * (p + lam) / alpha;
        sum += f * rc_one_sq(w) / alpha;
        [x, y, z, p, a] = [x, y, z, p, a].map(|v| 0.25 * (v + lam));
        f *= 0.25;
    }
    let t = f / a;
    let xx = (a0 - x0) * t;
    let yy = (a0 - y0) * t;
    let zz = (a0 - z0) * t;
    let pp = -0.5 * (xx + yy + zz);
    let xyz = xx * yy * zz;
    let p2 = pp * pp;
    let e2 = xx * yy + xx * zz + yy * zz - 3.0 * p2;
    let e3 = xyz + 2.0 * e2 * pp + 4.0 * p2 * pp;
    let e4 = (2.0 * xyz + e2 * pp + 3.0 * p2 * pp) * pp;
    let e5 = xyz * p2;
    f * rj_series(e2, e3, e4, e5) / (a * a.sqrt()) + 3.0 * sum
}

/// R_J for finite `x, y, z >= 0` and any finite `p`, principal value for
/// `p < 0`. Returns `None` when `p < 0` and two of `x, y, z` vanish.
pub(crate) fn rj(x: f64, y: f64, z: f64, p: f64) -> Option<f64> {
    let zeros = (x == 0.0) as u8 + (y == 0.0) as u8 + (z == 0.0) as u8;
    if p > 0.0 {
        if zeros >= 2 {
            return Some(f64::INFINITY);
        }
        return Some(rj_positive(x, y, z, p));
    }
    if p == 0.0 {
        return Some(f64::INFINITY);
    }
    if zeros >= 2 {
        return None;
    }
    // Cauchy principal value, Carlson (1995) §2 / DLMF 19.20.14 in the
    // form with the middle argument y: sort x <= y <= z, so that the auxiliary
    // p' = y + (z - y)(y - x)/(y - p) is >= y > 0 and every term is regular.
    let sc = rescale(x.max(y).max(z).max(-p), LIMIT_CUBIC);
    if sc != 1.0 {
        let (x, y, z, p) = (scaled(x, sc), scaled(y, sc), scaled(z, sc), scaled(p, sc));
        return rj(x, y, z, p).map(|v| v * sc * sc * sc);
    }
    let mut v = [x, y, z];
    v.sort_by(f64::total_cmp);
    let [x, y, z] = v;
    let q = -p;
    let pmy = (z - y) * ((y - x) / (y + q)); // p' - y >= 0; the ratio is <= 1
    let pp = y + pmy;
    let pq = pp * q;
    let xz = x * z;
    let xz_pq = xz + pq;
    let mut value = -3.0 * rf(x, y, z);
    if pmy > 0.0 {
        value += pmy * rj_positive(x, y, z, pp);
    }
    if xz > 0.0 {
        // sqrt(xyz / (xz + p'q)) written so that xyz cannot underflow
        value += 3.0 * y.sqrt() * (xz / xz_pq).sqrt() * rc(xz_pq, pq);
    }
    Some(value / (y + q))
}

/// R_C for finite `x >= 0`, `y != 0` (principal value for `y < 0`);
/// `y == 0` gives `+inf`. No checks.
pub(crate) fn rc(x: f64, y: f64) -> f64 {
    if y < 0.0 {
        // DLMF 19.2.20: R_C(x, y) = sqrt(x/(x - y)) R_C(x - y, -y)
        if x == 0.0 {
            return 0.0;
        }
        return (x / (x - y)).sqrt() * rc(x - y, -y);
    }
    if y == 0.0 {
        return f64::INFINITY;
    }
    if x == y {
        return 1.0 / x.sqrt();
    }
    if x == 0.0 {
        // DLMF 19.2.17 limit; also keeps -0.0 away from the division below
        return core::f64::consts::FRAC_PI_2 / y.sqrt();
    }
    let sc = rescale(x.max(y), LIMIT_LINEAR);
    let (x, y) = (scaled(x, sc), scaled(y, sc));
    // DLMF 19.2.18 and 19.2.19 rewritten with atan / atanh / log so that no
    // subtraction loses digits: the differences y - x and x - y are exact
    // when x and y are close (Sterbenz) and harmless when they are not.
    let v = if x < y {
        let d = y - x;
        (d / x).sqrt().atan() / d.sqrt()
    } else {
        let d = x - y;
        if d <= 0.5 * x {
            (d / x).sqrt().atanh() / d.sqrt()
        } else {
            // acosh(sqrt(x/y)) = ln((sqrt(x) + sqrt(x - y)) / sqrt(y))
            ((x.sqrt() + d.sqrt()) / y.sqrt()).ln() / d.sqrt()
        }
    };
    sc * v
}

fn check_nonnegative(name: &'static str, value: f64) -> Result<(), EllipticError> {
    check_domain(name, value, "[0, +inf)", |v| v >= 0.0)
}

/// Returns Carlson's symmetric integral of the first kind,
/// R_F(x,y,z) = ½ ∫₀^∞ dt/√((t+x)(t+y)(t+z)).
///
/// Domain: finite x, y, z ≥ 0. If two (or three) arguments are zero the
/// integral diverges and `+inf` is returned. R_F is symmetric and
/// homogeneous of degree −1/2.
///
/// Accuracy: relative error ≤ 5.0e-16 (2.2 ulp) against 30-digit mpmath
/// values (352 argument triples from 0 to 1e15, `tests/special/mpmath_reference.rs`).
///
/// Source: Carlson (1995) §2 algorithm with the degree-7 series of DLMF 19.36.1.
///
/// # Errors
/// [`EllipticError::NonFinite`] for NaN/infinite input,
/// [`EllipticError::OutOfDomain`] for a negative argument.
///
/// # Example
/// ```
/// # use rotorflow::special::carlson_rf;
/// // Carlson (1995) test value
/// let v = carlson_rf(1.0, 2.0, 0.0)?;
/// assert!((v - 1.311_028_777_146_059_9).abs() < 1e-15);
/// # Ok::<(), rotorflow::special::EllipticError>(())
/// ```
pub fn carlson_rf(x: f64, y: f64, z: f64) -> Result<f64, EllipticError> {
    check_nonnegative("x", x)?;
    check_nonnegative("y", y)?;
    check_nonnegative("z", z)?;
    finish("carlson_rf", rf(x, y, z))
}

/// Returns Carlson's symmetric integral of the second kind,
/// R_D(x,y,z) = (3/2) ∫₀^∞ dt/((t+z)√((t+x)(t+y)(t+z))).
///
/// Domain: finite x, y ≥ 0, z ≥ 0. It is symmetric in x, y only.
/// If z = 0, or x = y = 0, the integral diverges and `+inf` is returned.
///
/// Accuracy: relative error ≤ 5.0e-16 (2.2 ulp) against mpmath (847 triples).
///
/// Source: Carlson (1995) §2 with the series of DLMF 19.36.2 (R_D = R_J(x,y,z,z)).
///
/// # Errors
/// [`EllipticError::NonFinite`], or [`EllipticError::OutOfDomain`] for a
/// negative argument.
///
/// # Example
/// ```
/// # use rotorflow::special::carlson_rd;
/// let v = carlson_rd(0.0, 2.0, 1.0)?; // Carlson (1995) test value
/// assert!((v - 1.797_210_352_103_388_3).abs() < 1e-15);
/// # Ok::<(), rotorflow::special::EllipticError>(())
/// ```
pub fn carlson_rd(x: f64, y: f64, z: f64) -> Result<f64, EllipticError> {
    check_nonnegative("x", x)?;
    check_nonnegative("y", y)?;
    check_nonnegative("z", z)?;
    finish("carlson_rd", rd(x, y, z))
}

/// Returns Carlson's symmetric integral of the third kind,
/// R_J(x,y,z,p) = (3/2) ∫₀^∞ dt/((t+p)√((t+x)(t+y)(t+z))),
/// taken as a Cauchy principal value when p < 0.
///
/// Domain: finite x, y, z ≥ 0 and finite p.
/// * p > 0: two zero arguments among x, y, z make it diverge → `+inf`.
/// * p = 0: diverges → `+inf`.
/// * p < 0: principal value from Carlson (1995) §2
///   (DLMF 19.20.14, form with x ≤ y ≤ z):
///   (y−p)R_J(x,y,z,p) = (p'−y)R_J(x,y,z,p') − 3R_F(x,y,z) +
///   3√(xyz/(xz+p'q)) R_C(xz+p'q, p'q), with q=−p and
///   p' = y + (z−y)(y−x)/(y+q). Undefined (error) if two of x,y,z vanish.
///
/// Accuracy: relative error ≤ 5.3e-16 (2.4 ulp) for p > 0 (385 cases) and
/// ≤ 9.5e-15 for the principal value (308 cases): the PV combines terms of
/// both signs, and its relative error is ~2 ulp times their cancellation ratio.
/// Arguments spanning more than ~10²⁵⁰ may give
/// [`EllipticError::Overflow`] or an inaccurate value.
///
/// Source: Carlson (1995) §2 duplication, with the R_C(α_m, β_m)
/// terms of Carlson (1988, Math. Comp. 51, 267) and the series DLMF 19.36.2.
///
/// # Errors
/// [`EllipticError::NonFinite`], [`EllipticError::OutOfDomain`] (negative
/// x, y, z), [`EllipticError::Divergent`] (p < 0 with two zero arguments).
///
/// # Example
/// ```
/// # use rotorflow::special::carlson_rj;
/// let v = carlson_rj(2.0, 3.0, 4.0, -0.5)?; // principal value, Carlson (1995)
/// assert!((v - 0.247_238_197_030_515_65).abs() < 1e-15);
/// # Ok::<(), rotorflow::special::EllipticError>(())
/// ```
pub fn carlson_rj(x: f64, y: f64, z: f64, p: f64) -> Result<f64, EllipticError> {
    check_nonnegative("x", x)?;
    check_nonnegative("y", y)?;
    check_nonnegative("z", z)?;
    check_finite("p", p)?;
    let v = rj(x, y, z, p).ok_or(EllipticError::Divergent {
        function: "carlson_rj",
    })?;
    finish("carlson_rj", v)
}

/// Returns Carlson's degenerate integral
/// R_C(x,y) = R_F(x,y,y) = ½ ∫₀^∞ dt/((t+y)√(t+x)),
/// taken as a Cauchy principal value when y < 0.
///
/// Domain: finite x ≥ 0 and finite y. y = 0 diverges → `+inf`.
/// For y < 0: R_C(x,y) = √(x/(x−y)) R_C(x−y,−y) (DLMF 19.2.20), and
/// R_C(0, y<0) = 0.
///
/// Accuracy: relative error ≤ 2.8e-16 (1.2 ulp) against mpmath (70 pairs).
///
/// Source: closed forms DLMF 19.2.17–19.2.19 (arctan / artanh / log,
/// arranged to avoid cancellation), not duplication.
///
/// # Errors
/// [`EllipticError::NonFinite`], or [`EllipticError::OutOfDomain`] for x < 0.
///
/// # Example
/// ```
/// # use rotorflow::special::carlson_rc;
/// let v = carlson_rc(0.25, -2.0)?; // = ln(2)/3, Carlson (1995)
/// assert!((v - std::f64::consts::LN_2 / 3.0).abs() < 1e-16);
/// # Ok::<(), rotorflow::special::EllipticError>(())
/// ```
pub fn carlson_rc(x: f64, y: f64) -> Result<f64, EllipticError> {
    check_nonnegative("x", x)?;
    check_finite("y", y)?;
    finish("carlson_rc", rc(x, y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rc_one_sq_matches_rc() {
        for &w in &[
            1e-200, 1e-8, 0.3, 0.7, 0.99999999, 1.0, 1.00000001, 3.0, 1e8, 1e200,
        ] {
            let a = rc_one_sq(w);
            if (1e-150..1e150).contains(&w) {
                let b = rc(1.0, w * w);
                assert!((a - b).abs() <= 6e-16 * b, "{w}: {a} {b}");
            }
            assert!(a.is_finite() && a > 0.0);
        }
    }

    /// `rescale` brings the largest argument into [2⁻², 2²] by a power of four (its doc), so
    /// that scaling and unscaling are exact, also where s² itself is outside the f64 range.
    #[test]
    fn rescale_is_exact_power_of_four() {
        for (v, limit) in [
            (1e200, LIMIT_CUBIC),
            (3e95, LIMIT_CUBIC),
            (1e-200, LIMIT_CUBIC),
            (f64::MAX, LIMIT_LINEAR),
            (1e-300, LIMIT_LINEAR),
            (5e-324, LIMIT_LINEAR),
        ] {
            let s = rescale(v, limit);
            assert_eq!(s.log2().fract(), 0.0, "{v:e}: s = {s:e}");
            let r = scaled(v, s);
            assert!((0.25..=4.0).contains(&r), "{v:e} scaled to {r}");
            assert_eq!(r / s / s, v, "{v:e}: scaling is not exact");
        }
        assert_eq!(rescale(1.0, LIMIT_CUBIC), 1.0);
        assert_eq!(rescale(1e90, LIMIT_CUBIC), 1.0);
        assert_eq!(rescale(1e270, LIMIT_LINEAR), 1.0);
    }

    #[test]
    fn extreme_scales_are_homogeneous() {
        let base = rf(1.0, 2.0, 3.0);
        let big = rf(1e300, 2e300, 3e300);
        assert!((big * 1e150 - base).abs() < 1e-15 * base);
        let small = rj(1e-200, 2e-200, 3e-200, 4e-200).unwrap();
        let base_j = rj(1.0, 2.0, 3.0, 4.0).unwrap();
        assert!((small * 1e-300 - base_j).abs() < 1e-15 * base_j);
    }
}
