//! sin x and cos x − 1 of a plane angle, without cancellation and without a libm call for
//! the small angles of integrator steps.
//!
//! Why: a plane rotation [[1 + m, −s], [s, 1 + m]] with m = cos x − 1 is orthogonal exactly
//! when m(2 + m) = −s². If m is formed as the rounded cos x minus 1, the identity holds only to
//! ε (the rounding of cos x near 1), and millions of such rotations random-walk the norm. With
//! s and m each accurate to a few ε *relative to themselves*, it holds to O(ε x²).

// sin x = x Σ (−y)^k / (2k+1)!, cos x − 1 = y Σ (−1)^(k+1) y^k / (2k+2)!, k = 0 … 8.
const S: [f64; 9] = [
    1.0,
    -1.0 / 6.0,
    1.0 / 120.0,
    -1.0 / 5040.0,
    1.0 / 362_880.0,
    -1.0 / 39_916_800.0,
    1.0 / 6_227_020_800.0,
    -1.0 / 1_307_674_368_000.0,
    1.0 / 355_687_428_096_000.0,
];
const C: [f64; 9] = [
    -1.0 / 2.0,
    1.0 / 24.0,
    -1.0 / 720.0,
    1.0 / 40_320.0,
    -1.0 / 3_628_800.0,
    1.0 / 479_001_600.0,
    -1.0 / 87_178_291_200.0,
    1.0 / 20_922_789_888_000.0,
    -1.0 / 6_402_373_705_728_000.0,
];

/// Returns (sin x, cos x − 1), each to a few ulps relative to itself.
///
/// For |x| ≤ π/4 the Taylor series in y = x², truncated after y⁸ (the first omitted terms are
/// below 1e-19 relative; after y⁴ for |x| ≤ 1/16 and after y² for |x| ≤ 1/128, see
/// [`small_angle_factors`]), evaluated by Estrin's scheme (a short dependency chain: this
/// sits on the critical path of the splitting integrators). Beyond, libm's sin_cos, where
/// cos x − 1 ≤ −0.29 has no cancellation.
///
/// Inlined, with the libm call out of line: a call in a step kernel makes the caller save
/// every vector register around it (all are caller-saved), which cost a 3D Strang step more
/// than the series themselves.
#[inline(always)]
pub(crate) fn sin_cos_minus_one(x: f64) -> (f64, f64) {
    if let Some((y, ps, pc)) = small_angle_factors(x) {
        return (x * ps, y * pc);
    }
    if x.abs() > std::f64::consts::FRAC_PI_4 || x.is_nan() {
        return sin_cos_minus_one_libm(x);
    }
    let y = x * x;
    (x * estrin8(&S, y), y * estrin8(&C, y))
}

/// [`sin_cos_minus_one`] beyond π/4 (and NaN), from libm.
#[cold]
#[inline(never)]
fn sin_cos_minus_one_libm(x: f64) -> (f64, f64) {
    let (s, c) = x.sin_cos();
    (s, c - 1.0)
}

/// For |x| ≤ 1/16: (x², P_s, P_c) with sin x = x P_s and cos x − 1 = x² P_c, so that a caller
/// can multiply x and x² into its operands while the polynomials are evaluated (a shorter
/// dependency chain). `None` for larger |x| (and NaN).
#[inline(always)]
pub(crate) fn small_angle_factors(x: f64) -> Option<(f64, f64, f64)> {
    let y = x * x;
    let a = x.abs();
    if a <= 1.0 / 128.0 {
        // y ≤ 2⁻¹⁴: the first omitted terms, y³/5040 and y³/40320 against 1 and 1/2, are
        // below 0.41 and 0.1 units of the last place.
        let y2 = y * y;
        return Some((
            y,
            (S[0] + S[1] * y) + S[2] * y2,
            (C[0] + C[1] * y) + C[2] * y2,
        ));
    }
    if a <= 0.0625 {
        // Through y⁴ the first omitted terms are below 3e-20 relative.
        return Some((y, estrin4(&S, y), estrin4(&C, y)));
    }
    None
}

/// (cos x − 1, sin x / x) of x = √y from y = x² ≥ 0, each to a few ulps relative to itself
/// (the first without cancellation): the series in y up to x = π/4 (through y², y⁴ or y⁸ as
/// [`sin_cos_minus_one`] truncates them), libm beyond. A rotor exponential
/// cos|B| + B sin|B|/|B| needs only |B|², so for the small angles of a step it costs neither
/// a square root nor a libm call (whose call would spill a step kernel's registers).
#[inline(always)]
pub(crate) fn cos_minus_one_sinc_of_square(y: f64) -> (f64, f64) {
    if y <= 1.0 / 16384.0 {
        let y2 = y * y;
        return (
            y * ((C[0] + C[1] * y) + C[2] * y2),
            (S[0] + S[1] * y) + S[2] * y2,
        );
    }
    if y <= 1.0 / 256.0 {
        return (y * estrin4(&C, y), estrin4(&S, y));
    }
    if y <= std::f64::consts::FRAC_PI_4 * std::f64::consts::FRAC_PI_4 {
        return (y * estrin8(&C, y), estrin8(&S, y));
    }
    let x = y.sqrt();
    let (s, c) = x.sin_cos();
    (c - 1.0, s / x)
}

/// Σₖ aₖ yᵏ, k = 0 … 4, by Estrin's scheme.
#[inline(always)]
fn estrin4(a: &[f64; 9], y: f64) -> f64 {
    let y2 = y * y;
    (a[0] + a[1] * y) + (a[2] + a[3] * y) * y2 + a[4] * (y2 * y2)
}

/// Σₖ aₖ yᵏ, k = 0 … 8, by Estrin's scheme (depth 4 instead of Horner's 8).
#[inline(always)]
fn estrin8(a: &[f64; 9], y: f64) -> f64 {
    let y2 = y * y;
    let y4 = y2 * y2;
    let p01 = a[0] + a[1] * y;
    let p23 = a[2] + a[3] * y;
    let p45 = a[4] + a[5] * y;
    let p67 = a[6] + a[7] * y;
    let p03 = p01 + p23 * y2;
    let p47 = p45 + p67 * y2;
    p03 + (p47 + a[8] * y4) * y4
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against libm's sin and against cos x − 1 = −2 sin²(x/2) (no cancellation either).
    #[test]
    fn matches_libm_to_a_few_ulps() {
        let mut x = 1e-300f64;
        while x < 4.0 {
            for x in [x, -x] {
                let (s, m) = sin_cos_minus_one(x);
                let m_ref = -2.0 * (0.5 * x).sin().powi(2);
                // Absolute slack of one normal ulp where x² underflows.
                let tiny = f64::MIN_POSITIVE;
                assert!((s - x.sin()).abs() <= 4.0 * f64::EPSILON * x.sin().abs() + tiny);
                assert!(
                    (m - m_ref).abs() <= 6.0 * f64::EPSILON * m_ref.abs() + tiny,
                    "{x}"
                );
                // The rotation is orthogonal to O(ε x²): m(2 + m) + s² ≈ 0.
                let defect = m * (2.0 + m) + s * s;
                assert!(
                    defect.abs() <= 8.0 * f64::EPSILON * x * x + tiny,
                    "defect {x}: {defect:e}"
                );
            }
            x *= 1.07;
        }
        let (s, m) = sin_cos_minus_one(0.0);
        assert!(s == 0.0 && m == 0.0);
        assert!(sin_cos_minus_one(f64::NAN).0.is_nan());
    }

    /// Against cos x − 1 = −2 sin²(x/2) and sin x / x from libm, on every tier and across
    /// the switch to libm.
    #[test]
    fn cos_minus_one_and_sinc_of_the_square_match_libm() {
        let mut x = 1e-300f64;
        let mut checked = 0;
        while x < 4.0 {
            let (m, k) = cos_minus_one_sinc_of_square(x * x);
            let m_ref = -2.0 * (0.5 * x).sin().powi(2);
            let tiny = f64::MIN_POSITIVE;
            assert!(
                (m - m_ref).abs() <= 6.0 * f64::EPSILON * m_ref.abs() + tiny,
                "{x}"
            );
            // Relative to 1 (sin x / x ≤ 1): near π, sin x / x inherits the rounding of x.
            let k_ref = x.sin() / x;
            assert!((k - k_ref).abs() <= 2.0 * f64::EPSILON, "sinc {x}");
            checked += 1;
            x *= 1.07;
        }
        assert!(checked > 10_000);
        assert_eq!(cos_minus_one_sinc_of_square(0.0), (0.0, 1.0));
        assert!(cos_minus_one_sinc_of_square(f64::NAN).0.is_nan());
    }
}
