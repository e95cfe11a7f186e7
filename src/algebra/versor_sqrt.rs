//! Square root and renormalisation of even versors in any signature Cl(p, q, r).
//!
//! # The central "Study number"
//! For an even element M of an algebra with N ≤ 4 the product M M̃ is its own reverse and
//! even, so it has grades 0 and 4 only: M M̃ = s + Q with Q a multiple of the pseudoscalar
//! e₁…N, which commutes with every even element. In 3D projective GA Cl(3, 0, 1) this is the
//! Study number s + p e₁₂₃₄ of a motor (written s + p e₀₁₂₃ with the projective e₀ in front);
//! the numbers a + b J with J = e₁…N, J² ∈ {−1, 0, +1}, are complex, dual or split-complex.
//! Where s + Q has a principal inverse square root,
//!
//! - **normalisation**: M′ = M (M M̃)^(−1/2) satisfies M′ M̃′ = M (M M̃)⁻¹ M̃ = 1 exactly, and
//!   for 3D PGA reads M′ = M / √s · (1 − p/(2s) e₁₂₃₄), the formula of De Keninck & Dorst,
//!   "Normalization, square roots, and the exponential and logarithmic maps in geometric
//!   algebras of less than 6D" (2022);
//! - **square root**: for V = R² with R = exp(½ log V), 1 + V = R (R + R̃) and R + R̃ is
//!   central, so R = (1 + V) (2 + V + Ṽ)^(−1/2), the same paper's closed form
//!   √V = (1 + V)/|1 + V|.
//!
//! Above N = 4 (and where 1 + V is nearly singular) the square root is exp(½ log V) and the
//! normalisation a Newton iteration M ← (3 − M M̃)/2 · M after scaling by
//! 1/√⟨M M̃⟩₀, which converges quadratically near the group: with M M̃ = 1 + E,
//! (1 − E/2)(1 + E)(1 − E/2) = 1 + O(E²).

use super::error::{check_finite, within};
use super::{AlgebraError, Multivector, VERSOR_TOLERANCE};
use nalgebra::Complex;

/// Default tolerance of [`Multivector::try_normalize_versor`] on max |M M̃ − 1|: far above
/// the drift that f64 round-off accumulates, far below any deviation that is not round-off
/// (the same value as the rotor's [`super::NORMALIZE_TOLERANCE`]).
pub const VERSOR_NORMALIZE_TOLERANCE: f64 = 1e-6;

/// Largest N where M M̃ of an even element is central (grades 0 and N only).
const CENTRAL_MAX_DIM: usize = 4;

/// (a + b J)^(−1/2) for J² = `eps`, on the principal branch, as (real part, J part); `None`
/// when that branch is not well inside its domain (an eigenvalue below `floor`).
fn inv_sqrt_central(a: f64, b: f64, eps: f64, floor: f64) -> Option<(f64, f64)> {
    if b == 0.0 || eps == 0.0 {
        if !a.is_finite() || a < floor {
            return None;
        }
        let r = 1.0 / a.sqrt();
        // (a + b J)^(−1/2) = a^(−1/2) (1 − b/(2a) J) exactly when J² = 0.
        return Some((r, -0.5 * b / a * r));
    }
    if eps > 0.0 {
        // Idempotents (1 ± J)/2: eigenvalues a ± b.
        let (u, w) = (a + b, a - b);
        if u < floor || w < floor {
            return None;
        }
        let (iu, iw) = (1.0 / u.sqrt(), 1.0 / w.sqrt());
        Some((0.5 * (iu + iw), 0.5 * (iu - iw)))
    } else {
        // J² = −1 plays i; the principal square root needs Re > 0 to stay off the cut.
        if a < floor {
            return None;
        }
        let z = Complex::new(a, b).sqrt().inv();
        Some((z.re, z.im))
    }
}

/// The pseudoscalar's mask and square (+1, −1 or 0) in `m`'s algebra.
fn pseudoscalar(m: &Multivector) -> (u64, f64) {
    let sig = m.signature();
    let mask = (1u64 << sig.dim()) - 1;
    let e = Multivector::basis_blade(sig, mask);
    (mask, e.geometric(&e).scalar_part())
}

/// m (a + b J) with J the pseudoscalar.
fn times_central(m: &Multivector, a: f64, b: f64, mask: u64) -> Multivector {
    let mut j = Multivector::scalar(m.signature(), a);
    j.as_mut_slice()[mask as usize] = b;
    m.geometric(&j)
}

/// Non-finite and odd-grade checks shared by the public functions.
fn check_even(m: &Multivector, what: &'static str) -> Result<(), AlgebraError> {
    check_finite(m.as_slice(), what)?;
    let odd = m.odd().max_abs();
    if odd != 0.0 {
        return Err(AlgebraError::NotAVersor {
            reason: "it has odd grades",
            deviation: odd,
        });
    }
    Ok(())
}

/// Checks that `m` is a finite even versor with max |M M̃ − 1| within [`VERSOR_TOLERANCE`] ·
/// max(1, max |Mᵢ|²); `not_unit` is the error's reason when it is not.
pub(crate) fn check_unit_even_versor(
    m: &Multivector,
    what: &'static str,
    not_unit: &'static str,
) -> Result<(), AlgebraError> {
    check_even(m, what)?;
    let deviation = unit_distance(m);
    let scale = m.max_abs().powi(2).max(1.0);
    // A non-finite V Ṽ (coefficients beyond √f64::MAX) is never accepted.
    if !deviation.is_finite() || !within(deviation, VERSOR_TOLERANCE * scale) {
        return Err(AlgebraError::NotAVersor {
            reason: not_unit,
            deviation,
        });
    }
    Ok(())
}

/// max |M M̃ − 1|.
fn unit_distance(m: &Multivector) -> f64 {
    let mut mm = m.geometric(&m.reverse());
    mm.as_mut_slice()[0] -= 1.0;
    mm.max_abs()
}

impl Multivector {
    /// Returns the principal square root of an even versor V (V Ṽ = 1): the versor R with
    /// R² = V that performs half the rotation, boost or rigid motion, R = exp(½ log V).
    ///
    /// Up to N = 4, away from V ≈ −1, rotorflow uses the closed form
    /// R = (1 + V)(2 + V + Ṽ)^(−1/2), where 2 + V + Ṽ is a scalar plus a multiple of the
    /// pseudoscalar and its inverse square root is taken in closed form (De Keninck & Dorst,
    /// "Normalization, square roots, and the exponential and logarithmic maps in geometric
    /// algebras of less than 6D", 2022); it equals exp(½ [`Multivector::log`]) there. Elsewhere
    /// (N = 5, Euclidean N > 4, rotations near 2π) it is exp(½ log V), with the domain and
    /// branch of [`Multivector::log`].
    ///
    /// ```
    /// use rotorflow::algebra::{Multivector, Signature};
    /// let pga = Signature::new(3, 0, 1)?;
    /// // A screw motion: rotation in e12 with a translation along e3 (e34).
    /// let b = &Multivector::blade_by_name(pga, "e12", 0.8)?
    ///     + &Multivector::blade_by_name(pga, "e34", -1.2)?;
    /// let m = b.exp()?;
    /// let half = m.sqrt()?;
    /// assert!((&(&half * &half) - &m).max_abs() < 1e-15);
    /// assert!((&half - &(&b * 0.5).exp()?).max_abs() < 1e-15); // half the motion
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`]; [`AlgebraError::NotAVersor`] if V has odd grades or
    /// max |V Ṽ − 1| exceeds [`VERSOR_TOLERANCE`] · max(1, max |Vᵢ|²); and the errors of
    /// [`Multivector::log`] where that route is taken (no real logarithm, N > 8 in a
    /// signature neither Euclidean nor projective); [`AlgebraError::Overflow`] if a coefficient of the result
    /// overflows.
    pub fn sqrt(&self) -> Result<Multivector, AlgebraError> {
        check_unit_even_versor(self, "versor", "V Ṽ is not 1")?;
        if self.dim() <= CENTRAL_MAX_DIM {
            let (mask, eps) = pseudoscalar(self);
            let a = 2.0 + 2.0 * self.scalar_part();
            let b = if self.dim() == 4 {
                2.0 * self.coefficient(mask)
            } else {
                0.0
            };
            if let Some((x, y)) = inv_sqrt_central(a, b, eps, 0.5) {
                let one_plus = &Multivector::scalar(self.signature(), 1.0) + self;
                return finite(times_central(&one_plus, x, y, mask));
            }
        }
        let r = (&self.log()? * 0.5).exp()?;
        finite(polish_sqrt(self, r))
    }

    /// Returns the even versor nearest to a drifted one: M (M M̃)^(−1/2), so that the result
    /// satisfies M′ M̃′ = 1 to round-off. This is ganja.js's `Normalized` and klein's
    /// `motor::normalize` for motors, in any signature.
    ///
    /// Up to N = 4, M M̃ = s + Q is a scalar plus a multiple of the pseudoscalar (the Study
    /// number of a 3D PGA motor, s + p e₁₂₃₄ in rotorflow's order) and the inverse square root
    /// is closed-form: M′ = M / √s · (1 − p/(2s) e₁₂₃₄) in 3D PGA (De Keninck & Dorst, 2022).
    /// Above N = 4, M is scaled by 1/√⟨M M̃⟩₀ and refined by the Newton step
    /// M ← ½(3 − M M̃) M until M M̃ stops approaching 1. The result moves M by a first-order
    /// amount in its drift: for M = V(1 + E/2) with V a versor and E small,
    /// M′ = V + O(|E|).
    ///
    /// This function accepts any drift it can undo; [`Multivector::try_normalize_versor`]
    /// refuses elements far from the group.
    ///
    /// ```
    /// use rotorflow::algebra::{Multivector, Signature};
    /// let pga = Signature::new(3, 0, 1)?;
    /// let m = Multivector::blade_by_name(pga, "e12", 0.3)?.exp()?;
    /// // Drift: a small scale error and a small pseudoscalar part.
    /// let drifted = &(&m * 1.001) + &Multivector::blade_by_name(pga, "e1234", 1e-4)?;
    /// let fixed = drifted.normalize_versor()?;
    /// let mut unit = &fixed * &fixed.reverse();
    /// unit.as_mut_slice()[0] -= 1.0;
    /// assert!(unit.max_abs() < 1e-15);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`]; [`AlgebraError::NotAVersor`] for odd grades, or when
    /// M M̃ has no positive square root (a zero or null element, or one that is no multiple
    /// of a versor); [`AlgebraError::Overflow`] when M M̃ or the result overflows f64.
    pub fn normalize_versor(&self) -> Result<Multivector, AlgebraError> {
        check_even(self, "versor")?;
        let mm = self.geometric(&self.reverse());
        if mm.as_slice().iter().any(|c| !c.is_finite()) {
            return Err(AlgebraError::Overflow { what: "M M̃" });
        }
        let no_root = AlgebraError::NotAVersor {
            reason: "M M̃ has no positive square root",
            deviation: unit_distance(self),
        };
        if self.dim() <= CENTRAL_MAX_DIM {
            let (mask, eps) = pseudoscalar(self);
            let s = mm.scalar_part();
            let p = if self.dim() == 4 {
                mm.coefficient(mask)
            } else {
                0.0
            };
            return match inv_sqrt_central(s, p, eps, f64::MIN_POSITIVE) {
                Some((x, y)) => finite(times_central(self, x, y, mask)),
                None => Err(no_root),
            };
        }
        let s = mm.scalar_part();
        if !s.is_finite() || s <= 0.0 {
            return Err(no_root);
        }
        let mut m = self * (1.0 / s.sqrt());
        let mut d = unit_distance(&m);
        for _ in 0..60 {
            if d == 0.0 {
                break;
            }
            let mut step = m.geometric(&m.reverse()) * -0.5;
            step.as_mut_slice()[0] += 1.5;
            let next = step.geometric(&m);
            let dn = unit_distance(&next);
            if dn.is_nan() || dn >= d {
                break;
            }
            m = next;
            d = dn;
        }
        if within(d, 1e-12) {
            finite(m)
        } else {
            Err(no_root)
        }
    }

    /// [`Multivector::normalize_versor`] with a check that the input is drift and not
    /// something else: the distance max |M M̃ − 1| must not exceed
    /// [`VERSOR_NORMALIZE_TOLERANCE`]. The versor analogue of
    /// [`super::Rotor::try_normalize`].
    ///
    /// # Errors
    /// [`AlgebraError::VersorFarFromGroup`] with the measured distance; the errors of
    /// [`Multivector::normalize_versor`].
    pub fn try_normalize_versor(&self) -> Result<Multivector, AlgebraError> {
        self.try_normalize_versor_eps(VERSOR_NORMALIZE_TOLERANCE)
    }

    /// [`Multivector::try_normalize_versor`] with an explicit tolerance on max |M M̃ − 1|.
    ///
    /// ```
    /// use rotorflow::algebra::{AlgebraError, Multivector, Signature};
    /// let pga = Signature::new(3, 0, 1)?;
    /// let far = Multivector::blade_by_name(pga, "e12", 0.3)?.exp()? * 1.5;
    /// assert!(matches!(
    ///     far.try_normalize_versor_eps(1e-6),
    ///     Err(AlgebraError::VersorFarFromGroup { .. })
    /// ));
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// As [`Multivector::try_normalize_versor`].
    pub fn try_normalize_versor_eps(&self, tolerance: f64) -> Result<Multivector, AlgebraError> {
        check_even(self, "versor")?;
        let distance = unit_distance(self);
        if !within(distance, tolerance) {
            return Err(AlgebraError::VersorFarFromGroup {
                distance,
                tolerance,
            });
        }
        self.normalize_versor()
    }
}

/// One Newton step for R² = V from R ≈ √V: with R̃ V R̃ = 1 + δ (δ small, R and V
/// commuting), R (1 + δ/2) squares to V up to O(δ²); the step is kept, renormalised, only if
/// it lowers max |R² − V|.
fn polish_sqrt(v: &Multivector, r: Multivector) -> Multivector {
    let residual = |x: &Multivector| (&x.geometric(x) - v).max_abs();
    let r0 = residual(&r);
    if r0 == 0.0 {
        return r;
    }
    let rr = r.reverse();
    let mut delta = rr.geometric(v).geometric(&rr);
    delta.as_mut_slice()[0] -= 1.0;
    let mut step = &delta * 0.5;
    step.as_mut_slice()[0] += 1.0;
    match r.geometric(&step).normalize_versor() {
        Ok(r1) if residual(&r1) < r0 => r1,
        _ => r,
    }
}

/// Ok(m) when every coefficient is finite, else Overflow.
fn finite(m: Multivector) -> Result<Multivector, AlgebraError> {
    if m.as_slice().iter().all(|c| c.is_finite()) {
        Ok(m)
    } else {
        Err(AlgebraError::Overflow {
            what: "the square root or normalisation of the versor",
        })
    }
}
