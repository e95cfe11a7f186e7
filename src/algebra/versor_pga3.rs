//! Exponential and logarithm of 3D projective GA Cl(3, 0, 1) on fixed-size arrays: the
//! motor algebra people use most, at the cost of a hand-written closed form.
//!
//! With e₄ the null vector (rotorflow's order; ganja.js and klein call it e₀ and put it
//! first), a bivector is B = A + T with A = a₁₂e₁₂ + a₁₃e₁₃ + a₂₃e₂₃ (rotation) and
//! T = t₁₄e₁₄ + t₂₄e₂₄ + t₃₄e₃₄ (translation). With θ = |A|, â = A/θ, the unit ideal line
//! u = âI (coefficients (−â₂₃, â₁₃, −â₁₂) on e₁₄, e₂₄, e₃₄) and π = â₁₂t₃₄ − â₁₃t₂₄ + â₂₃t₁₄
//! (so that T = T⊥ − πu with T⊥ ⟂ u), B² = −θ² + 2πθ e₁₂₃₄, and splitting B into its
//! commuting rotation and translation along the axis gives
//!
//!   exp(B) = cos θ + (sin θ/θ) A + (sin θ/θ) T⊥ − π cos θ u + π sin θ e₁₂₃₄,
//!
//! the formula of ganja.js's `Exp` and klein's `exp` (there written with α = −π/θ, which
//! divides by θ² and loses the axis at small angles). Here every factor is bounded: π by
//! |T|, sin θ/θ and cos θ by 1, so tiny (10⁻²⁰⁰) and huge (10¹⁵⁰) arguments neither
//! underflow nor overflow.
//!
//! The logarithm reads the same formula backwards: θ = atan2(|b|, c) from the scalar c and
//! the Euclidean bivector b = sin θ â, then from the translation part m = (sin θ/θ) T⊥ −
//! π cos θ u and the pseudoscalar q = π sin θ, π = q sin θ − ⟨m, u⟩ cos θ and
//! T⊥ = (θ/sin θ) m⊥. No step divides by a quantity that vanishes on the principal branch
//! except sin θ at θ = π, where the motor does not determine T⊥ (a rotation by 2π about an
//! axis the motor does not fix); there, and for motors without a rotation part, the general
//! closed form of `versor.rs` decides.
//!
//! The general closed form agrees with both to round-off (unit tests below); the fixed-size
//! route only saves the general products.

use super::{Multivector, Signature};
use crate::numeric::all_finite;

/// Blade masks of a Cl(3, 0, 1) bivector: e₁₂, e₁₃, e₂₃, e₁₄, e₂₄, e₃₄.
const PLANES: [usize; 6] = [0b0011, 0b0101, 0b0110, 0b1001, 0b1010, 0b1100];
/// The pseudoscalar e₁₂₃₄.
const PSEUDO: usize = 0b1111;

/// The even blades: 1, the six planes, e₁₂₃₄.
const MOTOR: [usize; 8] = [0, 0b0011, 0b0101, 0b0110, 0b1001, 0b1010, 0b1100, PSEUDO];
/// The blades outside grade 2.
const NOT_GRADE_2: [usize; 10] = [0, 1, 2, 4, 7, 8, 11, 13, 14, 15];
/// The odd blades.
const ODD: [usize; 8] = [1, 2, 4, 7, 8, 11, 13, 14];

/// True when the coefficients at `blades` are all ±0 (one test on their bits, no branch per
/// blade).
#[inline]
fn zero(c: &[f64; 16], blades: impl IntoIterator<Item = usize>) -> bool {
    blades.into_iter().fold(0u64, |a, k| a | c[k].to_bits()) << 1 == 0
}

/// True for 3D projective GA, Cl(3, 0, 1).
pub(super) fn is_pga3(sig: Signature) -> bool {
    sig.p() == 3 && sig.q() == 0 && sig.r() == 1
}

/// √(x² + y² + z²) without overflow or underflow: the plain sum where it is a normal
/// number well inside the range, else scaled by the largest magnitude.
#[inline(always)]
fn norm3(x: f64, y: f64, z: f64) -> f64 {
    let s = x * x + y * y + z * z;
    if (1e-290..1e300).contains(&s) {
        return s.sqrt();
    }
    if s.is_nan() {
        // f64::max below would drop a NaN.
        return s;
    }
    let m = x.abs().max(y.abs()).max(z.abs());
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    let (x, y, z) = (x / m, y / m, z / m);
    m * (x * x + y * y + z * z).sqrt()
}

/// sin θ/θ − cos θ, without cancellation at small θ (= θ²/3 − θ⁴/30 + …).
#[inline(always)]
fn sinc_minus_cos(theta: f64, sin: f64, cos: f64) -> f64 {
    if theta < 0.25 {
        // Σ_{k≥1} (−1)^(k+1) 2k θ^(2k) / (2k+1)!, to below 2⁻⁵³ relative for θ < ¼.
        let t = theta * theta;
        t * (1.0 / 3.0 - t * (1.0 / 30.0 - t * (1.0 / 840.0 - t * (1.0 / 45360.0 - t / 3991680.0))))
    } else {
        sin / theta - cos
    }
}

/// exp(B) for a multivector B of Cl(3, 0, 1), or None unless B is a finite bivector with a
/// finite exponential (the general route then reports what is wrong).
#[inline]
pub(super) fn exp(b: &Multivector) -> Option<Multivector> {
    let c: &[f64; 16] = b.as_slice().try_into().ok()?;
    let [s, a12, a13, a23, t14, t24, t34, q] = exp_motor(c)?;
    // One array expression, stored once into the result (a zeroed array written blade by
    // blade and then moved would be read back before its stores have landed).
    let o = [
        s, 0.0, 0.0, a12, 0.0, a13, a23, 0.0, 0.0, t14, t24, 0.0, t34, 0.0, 0.0, q,
    ];
    Some(Multivector::from_storage(b.signature(), o.into()))
}

/// [`exp`] into `out` (Cl(3, 0, 1) too): true if it was written.
#[inline]
pub(super) fn exp_to(b: &Multivector, out: &mut Multivector) -> bool {
    let (Ok(c), Ok(o)) = (
        <&[f64; 16]>::try_from(b.as_slice()),
        <&mut [f64; 16]>::try_from(out.as_mut_slice()),
    ) else {
        return false;
    };
    let Some(motor) = exp_motor(c) else {
        return false;
    };
    *o = [0.0; 16];
    for (k, x) in MOTOR.iter().zip(motor) {
        o[*k] = x;
    }
    true
}

/// The motor's even coefficients (1, e₁₂, e₁₃, e₂₃, e₁₄, e₂₄, e₃₄, e₁₂₃₄); None unless B is a
/// finite bivector with a finite exponential.
#[inline(always)]
fn exp_motor(c: &[f64; 16]) -> Option<[f64; 8]> {
    // A NaN or infinite plane coefficient makes the result non-finite (checked at the end).
    if !zero(c, NOT_GRADE_2) {
        return None;
    }
    let (a12, a13, a23, t14, t24, t34) = (c[3], c[5], c[6], c[9], c[10], c[12]);
    let theta = norm3(a12, a13, a23);
    let motor = if theta == 0.0 {
        [1.0, 0.0, 0.0, 0.0, t14, t24, t34, 0.0]
    } else {
        let inv = 1.0 / theta;
        let (n12, n13, n23) = (a12 * inv, a13 * inv, a23 * inv);
        let pi = n12 * t34 - n13 * t24 + n23 * t14;
        let (sin, cos) = theta.sin_cos();
        // sin θ/θ, and 1 − θ²/6 where θ underflows its own square (1/θ may overflow there).
        let sc = if theta < 1e-8 {
            1.0 - theta * theta * (1.0 / 6.0)
        } else {
            sin * inv
        };
        // The translation: sin θ/θ T + π (sin θ/θ − cos θ) u, u = (−â₂₃, â₁₃, −â₁₂).
        let k = pi * sinc_minus_cos(theta, sin, cos);
        [
            cos,
            sc * a12,
            sc * a13,
            sc * a23,
            sc * t14 - k * n23,
            sc * t24 + k * n13,
            sc * t34 - k * n12,
            pi * sin,
        ]
    };
    all_finite(&motor[..]).then_some(motor)
}

/// max |V Ṽ − 1| for an even V of Cl(3, 0, 1): V Ṽ = c² + |b|² + 2(cq − b∧m) e₁₂₃₄ (the
/// Study number), so no general product is needed.
#[inline(always)]
pub(super) fn versor_deviation(v: &Multivector) -> f64 {
    <&[f64; 16]>::try_from(v.as_slice()).map_or(f64::NAN, study_deviation)
}

/// [`versor_deviation`] on the coefficients.
#[inline(always)]
fn study_deviation(x: &[f64; 16]) -> f64 {
    let (b12, b13, b23, m14, m24, m34) = (x[3], x[5], x[6], x[9], x[10], x[12]);
    let (c, q) = (x[0], x[PSEUDO]);
    let s = c * c + b12 * b12 + b13 * b13 + b23 * b23 - 1.0;
    let p = 2.0 * (c * q - (b12 * m34 - b13 * m24 + b23 * m14));
    s.abs().max(p.abs())
}

/// log V for a multivector V of Cl(3, 0, 1), or None where the general route decides:
/// V is not a finite even versor within `tolerance` (max |V Ṽ − 1| ≤ tolerance ·
/// max(1, max |Vᵢ|²), the general check, which then names the problem), has no rotation part
/// (|b| = 0), a rotation angle at or within 10⁻³⁰⁰ of π (sin θ/θ below 10⁻³⁰⁰), or a
/// coefficient of the result overflows.
#[inline]
pub(super) fn log(v: &Multivector, tolerance: f64) -> Option<Multivector> {
    let x: &[f64; 16] = v.as_slice().try_into().ok()?;
    let [a12, a13, a23, t14, t24, t34] = log_planes(x, tolerance)?;
    // One array expression, stored once into the result (a zeroed array written blade by
    // blade and then moved would be read back before its stores have landed).
    let o = [
        0.0, 0.0, 0.0, a12, 0.0, a13, a23, 0.0, 0.0, t14, t24, 0.0, t34, 0.0, 0.0, 0.0,
    ];
    Some(Multivector::from_storage(v.signature(), o.into()))
}

/// [`log`] into `out` (Cl(3, 0, 1) too): true if it was written.
#[inline]
pub(super) fn log_to(v: &Multivector, tolerance: f64, out: &mut Multivector) -> bool {
    let (Ok(x), Ok(o)) = (
        <&[f64; 16]>::try_from(v.as_slice()),
        <&mut [f64; 16]>::try_from(out.as_mut_slice()),
    ) else {
        return false;
    };
    let Some(planes) = log_planes(x, tolerance) else {
        return false;
    };
    *o = [0.0; 16];
    for (k, c) in PLANES.iter().zip(planes) {
        o[*k] = c;
    }
    true
}

/// The logarithm's plane coefficients (e₁₂, e₁₃, e₂₃, e₁₄, e₂₄, e₃₄); None where the
/// general route decides.
#[inline(always)]
fn log_planes(x: &[f64; 16], tolerance: f64) -> Option<[f64; 6]> {
    if !zero(x, ODD) {
        return None;
    }
    // The general check max |V Ṽ − 1| ≤ tolerance · max(1, max |Vᵢ|²); the scale is needed
    // only when the deviation exceeds the tolerance itself. NaN fails every comparison, and
    // an infinite coefficient gives an infinite or NaN deviation.
    let deviation = study_deviation(x);
    if deviation.is_nan() || deviation > tolerance {
        let top = MOTOR.iter().fold(0.0f64, |a, &k| a.max(x[k].abs()));
        let scale = top * top;
        if !(scale.is_finite() && deviation <= tolerance * scale) {
            return None;
        }
    }
    let (b12, b13, b23, m14, m24, m34) = (x[3], x[5], x[6], x[9], x[10], x[12]);
    let (c, q) = (x[0], x[PSEUDO]);
    let s = norm3(b12, b13, b23);
    // Subnormal |b| (no reciprocal) and |b| = 0 go to the general route.
    if s < f64::MIN_POSITIVE {
        return None;
    }
    let theta = s.atan2(c);
    let inv_s = 1.0 / s;
    let (n12, n13, n23) = (b12 * inv_s, b13 * inv_s, b23 * inv_s);
    // sin θ = |b| and cos θ = c: V Ṽ = 1 within the tolerance (an accepted V off the group by
    // δ moves the result by O(δ), as it would any closed form).
    let (sin, cos) = (s, c);
    // θ / sin θ, with the series where θ is tiny (θ²/6 is below half an ulp of 1 there, so a
    // product by the rounded 1/6 gives the same result as the quotient, without a division
    // on the path from atan2 to the result).
    let inv_sc = if theta < 1e-8 {
        1.0 + theta * theta * (1.0 / 6.0)
    } else {
        theta * inv_s
    };
    if !(inv_sc.is_finite() && inv_sc < 1e300) {
        return None;
    }
    // u = (−â₂₃, â₁₃, −â₁₂) on (e₁₄, e₂₄, e₃₄); m = m⊥ + ⟨m, u⟩ u.
    let m_axis = -m14 * n23 + m24 * n13 - m34 * n12;
    let pi = q * sin - m_axis * cos;
    let (p14, p24, p34) = (m14 + m_axis * n23, m24 - m_axis * n13, m34 + m_axis * n12);
    // T = T⊥ − π u.
    let planes = [
        theta * n12,
        theta * n13,
        theta * n23,
        inv_sc * p14 + pi * n23,
        inv_sc * p24 - pi * n13,
        inv_sc * p34 + pi * n12,
    ];
    all_finite(&planes[..]).then_some(planes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pga() -> Signature {
        Signature::new(3, 0, 1).unwrap()
    }

    fn bivector(c: [f64; 6]) -> Multivector {
        let mut b = Multivector::zero(pga());
        for (k, x) in PLANES.iter().zip(c) {
            b.as_mut_slice()[*k] = x;
        }
        b
    }

    /// A deterministic stream in [−1, 1).
    fn stream(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || crate::numeric::tests::random(&mut s)
    }

    #[test]
    fn fixed_size_exp_and_log_agree_with_the_general_closed_form() {
        let mut r = stream(7);
        let mut checked = 0;
        for scale in [1e-200f64, 1e-9, 1e-3, 0.3, 1.0, 2.5, 40.0, 1e6] {
            for _ in 0..50 {
                let rot = scale.min(1.0);
                let b = bivector([
                    rot * r(),
                    rot * r(),
                    rot * r(),
                    scale * r(),
                    scale * r(),
                    scale * r(),
                ]);
                let fast = exp(&b).unwrap();
                let general = super::super::versor::exp_closed_form_for_tests(&b);
                let size = b.max_abs().max(1.0) * general.max_abs();
                let d = (&fast - &general).max_abs();
                assert!(d <= 1e-15 * size, "exp({b}): {d:e}");
                let l = log(&fast, 1e-8).unwrap();
                let lg = super::super::versor::log_closed_form_for_tests(&fast);
                let d = (&l - &lg).max_abs();
                assert!(d <= 1e-14 * lg.max_abs().max(1e-300), "log: {d:e} for {b}");
                checked += 1;
            }
        }
        assert_eq!(checked, 400);
    }

    #[test]
    fn study_number_deviation_matches_the_product() {
        let mut r = stream(11);
        for _ in 0..100 {
            let mut v = Multivector::zero(pga());
            for k in [0, 0b0011, 0b0101, 0b0110, 0b1001, 0b1010, 0b1100, PSEUDO] {
                v.as_mut_slice()[k] = r();
            }
            let mut vv = v.geometric(&v.reverse());
            vv.as_mut_slice()[0] -= 1.0;
            assert!((versor_deviation(&v) - vv.max_abs()).abs() <= 1e-15);
        }
    }

    #[test]
    fn non_finite_input_is_left_to_the_general_route() {
        for (k, x) in [
            (0, f64::NAN),
            (1, f64::NAN),
            (0, f64::INFINITY),
            (3, f64::NAN),
        ] {
            let mut c = [0.3, 0.2, 0.0, 1.0, 0.0, 0.0];
            c[k] = x;
            assert!(exp(&bivector(c)).is_none(), "{c:?}");
            c[1] = f64::NAN;
            c[0] = 0.0;
            assert!(exp(&bivector(c)).is_none(), "{c:?}");
        }
        let pure_nan_rotation = bivector([f64::NAN, f64::NAN, 0.0, 1e-309, 0.0, 0.0]);
        assert!(exp(&pure_nan_rotation).is_none());
    }

    #[test]
    fn edge_cases_go_to_the_general_closed_form() {
        // No rotation part: a pure translation, and −1 (a rotation by 2π, plane unknown).
        let t = bivector([0.0, 0.0, 0.0, 1.0, 2.0, 3.0]);
        assert!(log(&exp(&t).unwrap(), 1e-8).is_none());
        assert!(log(&Multivector::scalar(pga(), -1.0), 1e-8).is_none());
        // Not a versor, odd grades, NaN: the general route names the problem.
        let mut v = exp(&bivector([0.3, 0.1, 0.0, 1.0, 0.0, 0.0])).unwrap();
        assert!(log(&v, 1e-8).is_some());
        v.as_mut_slice()[0] *= 1.1;
        assert!(log(&v, 1e-8).is_none());
        v.as_mut_slice()[0] = f64::NAN;
        assert!(log(&v, 1e-8).is_none());
        let mut w = Multivector::scalar(pga(), 1.0);
        w.as_mut_slice()[1] = 1e-300;
        assert!(log(&w, 1e-8).is_none());
    }
}
