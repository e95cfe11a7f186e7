//! The spacetime algebra Cl(1, 3): Lorentz boosts as even versors (Hestenes, *Space-Time
//! Algebra*, 1966; Doran & Lasenby, *Geometric Algebra for Physicists*, 2003, ch. 5).
//!
//! rotorflow's basis order puts the positive vector first: e₁ is time (e₁² = +1) and
//! e₂, e₃, e₄ are space (square −1); Hestenes's γ₀, γ₁, γ₂, γ₃ are e₁, e₂, e₃, e₄. A versor
//! V acts on a spacetime vector x by the sandwich x ↦ V x Ṽ, and the boost of rapidity φ
//! along the unit spatial direction n̂ is V = exp(½ φ n̂ e₁) = cosh(φ/2) − sinh(φ/2) e₁ n̂,
//! which maps e₁ ↦ cosh φ e₁ + sinh φ n̂: the rest frame's time axis becomes the 4-velocity
//! of a frame moving with velocity tanh φ along n̂.
//!
//! ```
//! use rotorflow::algebra::{Multivector, sta};
//! let v = sta::boost(0.7, &[1.0, 0.0, 0.0])?;
//! let t = Multivector::blade_by_name(v.signature(), "e1", 1.0)?;
//! let moved = &(&v * &t) * &v.reverse();
//! assert!((moved.coefficient(0b01) - 0.7f64.cosh()).abs() < 1e-15);
//! assert!((moved.coefficient(0b10) - 0.7f64.sinh()).abs() < 1e-15);
//! # Ok::<(), rotorflow::algebra::AlgebraError>(())
//! ```

use super::error::check_finite;
use super::versor_sqrt::check_unit_even_versor;
use super::{AlgebraError, Multivector, Signature};
use nalgebra::DMatrix;

/// The spacetime algebra Cl(1, 3) (e₁ time, e₂ e₃ e₄ space).
pub fn spacetime() -> Signature {
    Signature::new(1, 3, 0).expect("Cl(1, 3) is a valid signature")
}

/// The boost of rapidity `rapidity` along the spatial `direction` (three components along
/// e₂, e₃, e₄; normalised here): V = cosh(φ/2) − sinh(φ/2) e₁ n̂, so that
/// V e₁ Ṽ = cosh φ e₁ + sinh φ n̂ (velocity tanh φ along n̂).
///
/// # Errors
/// [`AlgebraError::NonFinite`]; [`AlgebraError::WrongComponentCount`] unless `direction` has
/// three components; [`AlgebraError::ZeroLength`] for a zero direction;
/// [`AlgebraError::Overflow`] when cosh(φ/2) overflows (|φ| ≳ 1420).
pub fn boost(rapidity: f64, direction: &[f64]) -> Result<Multivector, AlgebraError> {
    check_finite(&[rapidity], "rapidity")?;
    check_finite(direction, "boost direction")?;
    if direction.len() != 3 {
        return Err(AlgebraError::WrongComponentCount {
            what: "boost direction",
            expected: 3,
            found: direction.len(),
        });
    }
    let scale = direction.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if scale == 0.0 {
        return Err(AlgebraError::ZeroLength {
            what: "boost direction",
        });
    }
    let scaled: Vec<f64> = direction.iter().map(|c| c / scale).collect();
    let len = scaled.iter().map(|c| c * c).sum::<f64>().sqrt();
    let (c, s) = ((0.5 * rapidity).cosh(), (0.5 * rapidity).sinh());
    if !c.is_finite() {
        return Err(AlgebraError::Overflow { what: "the boost" });
    }
    let mut v = Multivector::scalar(spacetime(), c);
    for (k, &nk) in scaled.iter().enumerate() {
        v.as_mut_slice()[1 | (1 << (k + 1))] = -s * nk / len;
    }
    Ok(v)
}

/// The 4×4 Lorentz matrix Λ of an even versor V of Cl(1, 3): column k holds the components
/// of V e_(k+1) Ṽ, so Λ x is V x Ṽ on the components (t, x, y, z) along e₁, e₂, e₃, e₄.
///
/// ```
/// use rotorflow::algebra::sta;
/// let l = sta::lorentz_matrix(&sta::boost(0.5, &[0.0, 0.0, 1.0])?)?;
/// assert!((l[(0, 0)] - 0.5f64.cosh()).abs() < 1e-15);
/// assert!((l[(3, 0)] - 0.5f64.sinh()).abs() < 1e-15);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// [`AlgebraError::WrongSignature`] outside Cl(1, 3); [`AlgebraError::NonFinite`];
/// [`AlgebraError::NotAVersor`] for odd grades or max |V Ṽ − 1| above
/// [`VERSOR_TOLERANCE`](super::VERSOR_TOLERANCE) · max(1, max |Vᵢ|²).
pub fn lorentz_matrix(v: &Multivector) -> Result<DMatrix<f64>, AlgebraError> {
    if v.signature() != spacetime() {
        return Err(AlgebraError::WrongSignature {
            operation: "a Lorentz matrix",
            expected: "the spacetime algebra Cl(1, 3)",
            signature: v.signature(),
        });
    }
    check_unit_even_versor(v, "versor", "V Ṽ is not 1")?;
    let rev = v.reverse();
    let mut l = DMatrix::zeros(4, 4);
    for k in 0..4 {
        let e = Multivector::basis_blade(spacetime(), 1 << k);
        let moved = v.geometric(&e).geometric(&rev);
        for i in 0..4 {
            l[(i, k)] = moved.coefficient(1 << i);
        }
    }
    Ok(l)
}
