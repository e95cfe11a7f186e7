//! Conformal geometric algebra Cl(N + 1, 1, 0) of Euclidean ℝᴺ: points as null vectors,
//! spheres and planes as vectors, and the conformal maps (translations, rotations, dilations,
//! transversions) as even versors acting by the sandwich X ↦ V X Ṽ (Hestenes, Li &
//! Rockwood, *New algebraic tools for classical geometry*, 2001; Dorst, Fontijne & Mann,
//! *Geometric Algebra for Computer Science*, 2007, ch. 13–16).
//!
//! The functions here work on plain [`Multivector`]s (a versor is an ordinary even
//! multivector, so it goes straight into [`Multivector::exp`], `log` and `sqrt`); the types
//! [`Point`], [`Sphere`] and [`Circle`] hold what a geometric question needs to be asked
//! once: [`Sphere::through`] N + 1 points and [`Circle::through`] three, with their
//! [`centre`](Sphere::centre) and [`radius`](Sphere::radius). A versor V moves each of them
//! with `V.apply(&x)` ([`super::Versor`]).
//!
//! ```
//! use rotorflow::algebra::{Versor, cga};
//! let p = |x: &[f64]| cga::Point::new(x);
//! let c = cga::Circle::through(&p(&[1.0, 0.0])?, &p(&[0.0, 1.0])?, &p(&[-1.0, 0.0])?)?;
//! let moved = cga::translator(&[3.0, 4.0])?.apply(&c)?;
//! assert!((moved.centre()[0] - 3.0).abs() < 1e-15 && (moved.centre()[1] - 4.0).abs() < 1e-15);
//! assert!((moved.radius() - 1.0).abs() < 1e-15);
//! # Ok::<(), rotorflow::algebra::AlgebraError>(())
//! ```
//!
//! # Basis and the two null vectors
//! rotorflow orders basis vectors positive first, so in Cl(N + 1, 1, 0) e₁ … e_N span ℝᴺ,
//! e₊ = e_(N+1) squares to +1 and e₋ = e_(N+2) squares to −1. The origin and the point at
//! infinity are the null vectors
//!
//!   n₀ = ½(e₋ − e₊),  n∞ = e₋ + e₊,  n₀² = n∞² = 0,  n₀ · n∞ = −1,
//!
//! Dorst, Fontijne & Mann's o and ∞ (with o · ∞ = −1). A point of ℝᴺ is the null vector
//! up(x) = n₀ + x + ½ x² n∞, and the inner product of two points is −½ |x − y|².
//!
//! | element | rotorflow (Cl(N + 1, 1, 0)) |
//! |---|---|
//! | point x | [`up`]: X = n₀ + x + ½ x² n∞; [`down`] reads x back from any multiple of X |
//! | sphere, centre c, radius r | [`sphere`]: σ = up(c) − ½ r² n∞, X · σ = ½ (r² − \|x − c\|²) |
//! | plane n · x = d | [`plane`]: π = n̂ + d̂ n∞ (n̂ = n/\|n\|, d̂ = d/\|n\|), X · π = n̂ · x − d̂ |
//! | translation by t | [`translator`]: T = 1 + ½ n∞ t = exp(½ n∞ ∧ t) |
//! | rotation about the origin | [`rotor`]: a Euclidean [`Rotor`] R, unchanged |
//! | dilation by s about the origin | [`dilator`]: D = exp(½ ln s · n₀ ∧ n∞) |
//! | transversion by b | [`transversor`]: K = 1 + n₀ b = exp(n₀ ∧ b), x ↦ (x + x² b) / (1 + 2 b · x + b² x²) |
//!
//! The transversion is the translation by b seen through the inversion in the unit sphere:
//! K = e₊ T_b e₊, and e₊ up(x) e₊ = −x² up(x / x²).
//!
//! # Dimensions
//! Every N from 2 to [`MULTIVECTOR_MAX_DIM`] − 2 = 14 is supported. [`Multivector::exp`] and
//! [`Multivector::log`] of these versors are available up to N = 6 (Cl(7, 1, 0), total
//! dimension ≤ [`super::GENERAL_MAX_DIM`]): in closed form for N = 2 and 3, through the
//! general route above; from N = 7 on they return [`AlgebraError::UnsupportedDimension`],
//! and the constructors here (which need neither) still work.
//!
//! # Precision
//! Elements are stored in the e₊, e₋ basis, where the weight −X · n∞ of a point is the
//! difference a₋ − a₊ of two coefficients of size ½ |x|². [`down`] reads the weight without
//! that difference far from the origin (X² = 0 gives it as v² / (a₊ + a₋)), so
//! down(up(x)) = x to full relative precision at any distance. Products do use the
//! difference: a point at distance |x| moved by a versor V carries an absolute error of
//! about ε |x|² max |Vᵢ| (a translation by t: ε |x|² |t|), and a sphere of centre c keeps its
//! radius to about ε |c|² / r. Work near the origin (translate the scene there first) when
//! that matters.
//!
//! ```
//! use rotorflow::algebra::{Multivector, cga};
//! // A translation by (1, 2, 3) moves the origin to (1, 2, 3).
//! let t = cga::translator(&[1.0, 2.0, 3.0])?;
//! let origin = cga::up(&[0.0, 0.0, 0.0])?;
//! let moved = &(&t * &origin) * &t.reverse();
//! assert_eq!(cga::down(&moved)?, vec![1.0, 2.0, 3.0]);
//! // A dilation by 2 about the origin doubles every point (the result is a multiple of up(2x)).
//! let d = cga::dilator(3, 2.0)?;
//! let y = &(&d * &cga::up(&[1.0, 0.5, -1.0])?) * &d.reverse();
//! let x = cga::down(&y)?;
//! assert!((x[0] - 2.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14 && (x[2] + 2.0).abs() < 1e-14);
//! // The point (2, 0, 0) lies on the unit sphere about (1, 0, 0).
//! let s = cga::sphere(&[1.0, 0.0, 0.0], 1.0)?;
//! assert!(cga::up(&[2.0, 0.0, 0.0])?.scalar_product(&s).abs() < 1e-15);
//! assert!(cga::point_on(&s, &[2.0, 0.0, 0.0], 1e-12)?);
//! # Ok::<(), rotorflow::algebra::AlgebraError>(())
//! ```

use super::check_grade;
use super::error::{check_finite, check_same_dim, negligible, within};
use super::{AlgebraError, MULTIVECTOR_MAX_DIM, Multivector, Rotor, Signature};
use crate::numeric::scaled_norm;

/// Default tolerance of [`down`] on a point's relative deviation from the null cone,
/// |X²| / (w² (1 + 2 |x|²)) for X of weight w: far above the round-off of points moved by
/// versors, far below the X² = r² w² of any sphere worth telling from a point.
pub const POINT_TOLERANCE: f64 = 1e-8;

/// The conformal algebra Cl(n + 1, 1, 0) of ℝⁿ, for 2 ≤ n ≤ [`MULTIVECTOR_MAX_DIM`] − 2.
///
/// ```
/// let cga3 = rotorflow::algebra::cga::conformal(3)?;
/// assert_eq!((cga3.p(), cga3.q(), cga3.r()), (4, 1, 0));
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// [`AlgebraError::WrongSignature`] for n < 2; [`AlgebraError::DimensionTooLarge`] for
/// n > 14.
pub fn conformal(n: usize) -> Result<Signature, AlgebraError> {
    AlgebraError::check_dimension("conformal algebra", n + 2, MULTIVECTOR_MAX_DIM)?;
    if n < 2 {
        return Err(AlgebraError::WrongSignature {
            operation: "conformal geometry",
            expected: "Cl(N + 1, 1, 0) with N ≥ 2",
            signature: Signature::new(n + 1, 1, 0)?,
        });
    }
    Signature::new(n + 1, 1, 0)
}

/// N for a conformal signature Cl(N + 1, 1, 0), else an error.
fn euclidean_dim(sig: Signature, operation: &'static str) -> Result<usize, AlgebraError> {
    if sig.q() == 1 && sig.r() == 0 && sig.p() >= 3 {
        Ok(sig.p() - 1)
    } else {
        Err(AlgebraError::WrongSignature {
            operation,
            expected: "Cl(N + 1, 1, 0) with N ≥ 2",
            signature: sig,
        })
    }
}

/// The masks of e₊ and e₋ in Cl(n + 1, 1, 0).
fn plus_minus(n: usize) -> (u64, u64) {
    (1 << n, 1 << (n + 1))
}

/// The origin n₀ = ½(e₋ − e₊) of Cl(n + 1, 1, 0) (Dorst, Fontijne & Mann's o).
///
/// # Errors
/// As [`conformal`].
pub fn n0(n: usize) -> Result<Multivector, AlgebraError> {
    let mut m = Multivector::zero(conformal(n)?);
    let (p, q) = plus_minus(n);
    m.as_mut_slice()[p as usize] = -0.5;
    m.as_mut_slice()[q as usize] = 0.5;
    Ok(m)
}

/// The point at infinity n∞ = e₋ + e₊ of Cl(n + 1, 1, 0) (Dorst, Fontijne & Mann's ∞).
///
/// # Errors
/// As [`conformal`].
pub fn ninf(n: usize) -> Result<Multivector, AlgebraError> {
    let mut m = Multivector::zero(conformal(n)?);
    let (p, q) = plus_minus(n);
    m.as_mut_slice()[p as usize] = 1.0;
    m.as_mut_slice()[q as usize] = 1.0;
    Ok(m)
}

/// The Euclidean vector x of ℝᴺ as a vector of Cl(N + 1, 1, 0).
fn euclidean_vector(x: &[f64], what: &'static str) -> Result<Multivector, AlgebraError> {
    check_finite(x, what)?;
    let mut m = Multivector::zero(conformal(x.len())?);
    for (i, &xi) in x.iter().enumerate() {
        m.as_mut_slice()[1 << i] = xi;
    }
    Ok(m)
}

/// The conformal point up(x) = n₀ + x + ½ x² n∞ of x ∈ ℝᴺ (N = `x.len()`), a null vector
/// with up(x) · up(y) = −½ |x − y|².
///
/// ```
/// use rotorflow::algebra::cga;
/// let x = cga::up(&[1.0, 2.0, 3.0])?;
/// assert_eq!(x.scalar_product(&x), 0.0);
/// assert_eq!(x.scalar_product(&cga::up(&[1.0, 2.0, 5.0])?), -2.0);
/// assert_eq!(x.scalar_product(&cga::ninf(3)?), -1.0);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// [`AlgebraError::NonFinite`]; [`AlgebraError::Overflow`] when ½ x² overflows
/// (|x| ≳ 1e154); as [`conformal`] for N.
pub fn up(x: &[f64]) -> Result<Multivector, AlgebraError> {
    let n = x.len();
    let half_sq = 0.5 * scaled_norm(x).powi(2);
    let mut m = euclidean_vector(x, "point coordinates")?;
    if !half_sq.is_finite() {
        return Err(AlgebraError::Overflow {
            what: "the point's n∞ coefficient",
        });
    }
    let (p, q) = plus_minus(n);
    m.as_mut_slice()[p as usize] = half_sq - 0.5;
    m.as_mut_slice()[q as usize] = half_sq + 0.5;
    Ok(m)
}

/// The Euclidean point x of a conformal point X = w up(x) of any weight w ≠ 0 (the inverse
/// of [`up`], after dividing by the weight w = −X · n∞). A point moved by a versor is such a
/// multiple, so `down` reads the image of a conformal map.
///
/// ```
/// use rotorflow::algebra::cga;
/// let x = cga::down(&(&cga::up(&[0.5, -2.0])? * -3.0))?; // any weight
/// assert!((x[0] - 0.5).abs() < 1e-15 && (x[1] + 2.0).abs() < 1e-15);
/// assert!(cga::down(&cga::ninf(2)?).is_err()); // the point at infinity
/// assert!(cga::down(&cga::sphere(&[0.0, 0.0], 1.0)?).is_err()); // not null
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// [`AlgebraError::WrongSignature`] outside Cl(N + 1, 1, 0); [`AlgebraError::NonFinite`];
/// [`AlgebraError::MixedGrades`] for parts of other grades larger than [`POINT_TOLERANCE`]
/// times the vector part (smaller ones, the round-off of a sandwich, are ignored);
/// [`AlgebraError::PointAtInfinity`]
/// for a multiple of n∞ to within round-off (n∞ itself, a point mapped to infinity; a point
/// beyond |x| ≈ 1e14 is not told from it) or a weight so small that a coordinate overflows;
/// [`AlgebraError::NotAPoint`] when
/// X is not null: |X²| above [`POINT_TOLERANCE`] · w² (1 + 2 |x|²), the size of its terms,
/// beyond the round-off of its e₊ and e₋ coefficients (a sphere).
pub fn down(x: &Multivector) -> Result<Vec<f64>, AlgebraError> {
    let n = euclidean_dim(x.signature(), "a conformal point")?;
    check_finite(x.as_slice(), "conformal point")?;
    let x = &vector_part(x, "conformal point")?;
    let (p, q) = plus_minus(n);
    let (a_plus, a_minus) = (x.coefficient(p), x.coefficient(q));
    // X = v + w n₀ + β n∞ with w = a₋ − a₊ = −X · n∞ and 2β = a₊ + a₋ = w x².
    let (diff, sum) = (a_minus - a_plus, a_plus + a_minus);
    let v: Vec<f64> = (0..n).map(|i| x.coefficient(1 << i)).collect();
    let v_len = scaled_norm(&v);
    // A point far from the origin has a weight that cancels to round-off, but a Euclidean
    // part √(w · 2β) far above it; only a multiple of n∞ has neither.
    if negligible(diff, x.max_abs()) && negligible(v_len, x.max_abs()) {
        return Err(AlgebraError::PointAtInfinity { weight: diff });
    }
    let v2 = v_len * v_len;
    // X² = v² − w · 2β vanishes for a point. Its terms have size w² (1 + 2x²); the
    // round-off of a± (ε ½ w x² each) reaches it through (a₋ − a₊)(a₊ + a₋), and is
    // discounted, so that a point far out is not refused for its representation.
    let size = v2 + (diff * sum).abs() + diff * diff;
    let round_off = 16.0 * f64::EPSILON * (v2 + sum * sum + diff * diff);
    let deviation = ((v2 - diff * sum).abs() - round_off).max(0.0) / size;
    if !deviation.is_finite() || !within(deviation, POINT_TOLERANCE) {
        return Err(AlgebraError::NotAPoint {
            reason: "X² is not 0 (a sphere or a plane)",
            deviation,
        });
    }
    // Far from the origin a₋ − a₊ cancels; X² = 0 gives w = v² / (a₊ + a₋) there instead.
    let w = if sum.abs() > diff.abs() {
        v2 / sum
    } else {
        diff
    };
    let y: Vec<f64> = v.iter().map(|c| c / w).collect();
    if y.iter().any(|c| !c.is_finite()) {
        return Err(AlgebraError::PointAtInfinity { weight: w });
    }
    Ok(y)
}

/// The translation by t: T = 1 + ½ n∞ t = exp(½ n∞ ∧ t), with T up(x) T̃ = up(x + t).
///
/// ```
/// use rotorflow::algebra::cga;
/// let t = cga::translator(&[3.0, 4.0])?;
/// let y = &(&t * &cga::up(&[1.0, 1.0])?) * &t.reverse();
/// assert_eq!(cga::down(&y)?, vec![4.0, 5.0]);
/// // It is the exponential of ½ n∞ ∧ t.
/// let t_vec = &cga::up(&[3.0, 4.0])? - &cga::n0(2)? - &(&cga::ninf(2)? * 12.5);
/// let generator = &cga::ninf(2)?.wedge(&t_vec) * 0.5;
/// assert!((&generator.exp()? - &t).max_abs() < 1e-15);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// [`AlgebraError::NonFinite`]; as [`conformal`] for N = `t.len()`.
pub fn translator(t: &[f64]) -> Result<Multivector, AlgebraError> {
    let tv = euclidean_vector(t, "translation")?;
    let v = &ninf(t.len())?.geometric(&tv) * 0.5;
    Ok(&Multivector::scalar(tv.signature(), 1.0) + &v)
}

/// The rotation of a Euclidean [`Rotor`] of ℝᴺ about the origin, embedded in Cl(N + 1, 1, 0)
/// with the same coefficients (R commutes with n₀ and n∞): R up(x) R̃ = up(R x R̃).
///
/// ```
/// use rotorflow::algebra::{Rotor, cga};
/// // A quarter turn from e₁ toward e₂.
/// let r = cga::rotor(&Rotor::from_plane_angle(3, 0, 1, std::f64::consts::FRAC_PI_2)?)?;
/// let x = cga::down(&(&(&r * &cga::up(&[1.0, 0.0, 7.0])?) * &r.reverse()))?;
/// assert!(x[0].abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14 && (x[2] - 7.0).abs() < 1e-14);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// As [`conformal`] for N = `r.dim()`.
pub fn rotor(r: &Rotor) -> Result<Multivector, AlgebraError> {
    let mut m = Multivector::zero(conformal(r.dim())?);
    for (mask, c) in r.terms() {
        m.as_mut_slice()[mask as usize] = c;
    }
    Ok(m)
}

/// The dilation by `scale` about the origin in ℝⁿ:
/// D = exp(½ ln s · n₀ ∧ n∞) = cosh(½ ln s) + sinh(½ ln s) n₀ ∧ n∞, with
/// D up(x) D̃ = up(s x) / s.
///
/// ```
/// use rotorflow::algebra::cga;
/// let d = cga::dilator(2, 0.5)?;
/// let x = cga::down(&(&(&d * &cga::up(&[4.0, -2.0])?) * &d.reverse()))?;
/// assert!((x[0] - 2.0).abs() < 1e-15 && (x[1] + 1.0).abs() < 1e-15);
/// assert!(cga::dilator(2, -1.0).is_err());
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// [`AlgebraError::NonFinite`]; [`AlgebraError::NotPositive`] for `scale` ≤ 0 (a negative
/// factor is a dilation composed with the point reflection in the origin, an odd map);
/// as [`conformal`] for n.
pub fn dilator(n: usize, scale: f64) -> Result<Multivector, AlgebraError> {
    check_finite(&[scale], "dilation factor")?;
    if scale <= 0.0 {
        return Err(AlgebraError::NotPositive {
            what: "dilation factor",
            value: scale,
        });
    }
    let half_log = 0.5 * scale.ln();
    let e = n0(n)?.wedge(&ninf(n)?);
    let mut d = &e * half_log.sinh();
    d.as_mut_slice()[0] = half_log.cosh();
    Ok(d)
}

/// The transversion (special conformal transformation) by b:
/// K = 1 + n₀ b = exp(n₀ ∧ b), the map x ↦ (x + x² b) / (1 + 2 b · x + b² x²), which is the
/// translation by b conjugated by the inversion in the unit sphere (K = e₊ T_b e₊). The point
/// −b / b² goes to infinity.
///
/// ```
/// use rotorflow::algebra::cga;
/// // b = e₁ takes x = e₁ to (1 + 1) / (1 + 2 + 1) e₁ = ½ e₁, and fixes the origin.
/// let k = cga::transversor(&[1.0, 0.0])?;
/// let moved = |x: &[f64]| -> Result<Vec<f64>, rotorflow::algebra::AlgebraError> {
///     cga::down(&(&(&k * &cga::up(x)?) * &k.reverse()))
/// };
/// assert_eq!(moved(&[1.0, 0.0])?, vec![0.5, 0.0]);
/// assert_eq!(moved(&[0.0, 0.0])?, vec![0.0, 0.0]);
/// assert!(moved(&[-1.0, 0.0]).is_err()); // −b/b² goes to infinity
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// [`AlgebraError::NonFinite`]; as [`conformal`] for N = `b.len()`.
pub fn transversor(b: &[f64]) -> Result<Multivector, AlgebraError> {
    let bv = euclidean_vector(b, "transversion")?;
    let v = n0(b.len())?.geometric(&bv);
    Ok(&Multivector::scalar(bv.signature(), 1.0) + &v)
}

/// The sphere with `center` and `radius` as a vector of Cl(N + 1, 1, 0) (the dual sphere):
/// σ = up(c) − ½ r² n∞, normalised so that −σ · n∞ = 1 and σ² = r². A point X lies on it
/// exactly when X · σ = ½ (r² − |x − c|²) vanishes.
///
/// ```
/// use rotorflow::algebra::cga;
/// let s = cga::sphere(&[1.0, 2.0, 3.0], 2.0)?;
/// assert_eq!(s.scalar_product(&s), 4.0); // σ² = r²
/// assert_eq!(cga::up(&[1.0, 2.0, 5.0])?.scalar_product(&s), 0.0); // on it
/// assert_eq!(cga::up(&[1.0, 2.0, 3.0])?.scalar_product(&s), 2.0); // the centre: ½ r²
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// [`AlgebraError::NonFinite`]; [`AlgebraError::NotPositive`] for a radius ≤ 0;
/// [`AlgebraError::Overflow`]; as [`conformal`] for N = `center.len()`.
pub fn sphere(center: &[f64], radius: f64) -> Result<Multivector, AlgebraError> {
    check_finite(&[radius], "sphere radius")?;
    if radius <= 0.0 {
        return Err(AlgebraError::NotPositive {
            what: "sphere radius",
            value: radius,
        });
    }
    let c = up(center)?;
    let shift = &ninf(center.len())? * (0.5 * radius * radius);
    let s = &c - &shift;
    if s.as_slice().iter().all(|v| v.is_finite()) {
        Ok(s)
    } else {
        Err(AlgebraError::Overflow {
            what: "the sphere's n∞ coefficient",
        })
    }
}

/// The plane `normal` · x = `d` as a vector of Cl(N + 1, 1, 0) (the dual plane):
/// π = n̂ + d̂ n∞ with n̂ = n/|n| and d̂ = d/|n|, so that X · π = n̂ · x − d̂ is the signed
/// distance of the point x, positive on the side the normal points to.
///
/// ```
/// use rotorflow::algebra::cga;
/// let p = cga::plane(&[0.0, 3.0, 4.0], 10.0)?; // (0, 0.6, 0.8) · x = 2
/// assert!((cga::up(&[9.0, 0.0, 5.0])?.scalar_product(&p) - 2.0).abs() < 1e-15);
/// assert!(cga::point_on(&p, &[-3.0, 2.0, 1.0], 1e-15)?);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// [`AlgebraError::NonFinite`]; [`AlgebraError::ZeroLength`] for a zero normal; as
/// [`conformal`] for N = `normal.len()`.
pub fn plane(normal: &[f64], d: f64) -> Result<Multivector, AlgebraError> {
    check_finite(&[d], "plane offset")?;
    let mut m = euclidean_vector(normal, "plane normal")?;
    let len = scaled_norm(normal);
    if len == 0.0 {
        return Err(AlgebraError::ZeroLength {
            what: "plane normal",
        });
    }
    for c in m.as_mut_slice() {
        *c /= len;
    }
    let shift = &ninf(normal.len())? * (d / len);
    Ok(&m + &shift)
}

/// A sphere or plane read back from its vector.
enum Surface {
    Sphere { center: Vec<f64>, radius: f64 },
    Plane { normal: Vec<f64>, offset: f64 },
}

/// Reads the centre and radius, or the unit normal and offset, of a dual sphere or plane of
/// any weight and sign.
fn surface(s: &Multivector) -> Result<Surface, AlgebraError> {
    let n = euclidean_dim(s.signature(), "a sphere or plane")?;
    check_finite(s.as_slice(), "sphere or plane")?;
    let s = &vector_part(s, "sphere or plane")?;
    let (p, q) = plus_minus(n);
    let (a_plus, a_minus) = (s.coefficient(p), s.coefficient(q));
    // s = v + w n₀ + β n∞ with w = a₋ − a₊ = −s · n∞ and β = ½ (a₊ + a₋).
    let w = a_minus - a_plus;
    let beta = 0.5 * (a_plus + a_minus);
    let v: Vec<f64> = (0..n).map(|i| s.coefficient(1 << i)).collect();
    if negligible(w, s.max_abs()) {
        let len = scaled_norm(&v);
        if len == 0.0 {
            return Err(AlgebraError::NotASphere {
                reason: "it is zero or a multiple of n∞",
                deviation: 0.0,
            });
        }
        return Ok(Surface::Plane {
            normal: v.iter().map(|c| c / len).collect(),
            offset: beta / len,
        });
    }
    let center: Vec<f64> = v.iter().map(|c| c / w).collect();
    let c2 = scaled_norm(&center).powi(2);
    // (s/w)² = c² − 2β/w = r².
    let r2 = c2 - 2.0 * beta / w;
    if !r2.is_finite() || !center.iter().all(|c| c.is_finite()) {
        return Err(AlgebraError::Overflow {
            what: "the sphere's centre or radius",
        });
    }
    if negligible(r2, c2.max((beta / w).abs())) || r2 < 0.0 {
        return Err(AlgebraError::NotASphere {
            reason: "its square is not positive (a point or an imaginary sphere)",
            deviation: r2,
        });
    }
    Ok(Surface::Sphere {
        center,
        radius: r2.sqrt(),
    })
}

/// The signed Euclidean distance from the point `x` to a sphere or plane built by [`sphere`]
/// or [`plane`] (or moved by a versor): |x − c| − r for a sphere (negative inside), and
/// n̂ · x − d̂ for a plane (positive on the side its normal points to). A sphere's sign and
/// weight do not matter; a plane's sign is its orientation.
///
/// ```
/// use rotorflow::algebra::cga;
/// let s = cga::sphere(&[0.0, 0.0, 1.0], 2.0)?;
/// assert_eq!(cga::signed_distance(&s, &[0.0, 0.0, 4.0])?, 1.0);
/// let p = cga::plane(&[0.0, 0.0, 2.0], 2.0)?; // x₃ = 1
/// assert_eq!(cga::signed_distance(&p, &[5.0, 5.0, -1.0])?, -2.0);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// [`AlgebraError::WrongSignature`]; [`AlgebraError::NonFinite`];
/// [`AlgebraError::MixedGrades`] for grades other than 1 (beyond round-off, as in [`down`]);
/// [`AlgebraError::NotASphere`] for a
/// point, an imaginary sphere (σ² < 0), zero or n∞; [`AlgebraError::DimensionMismatch`]
/// when `x` has the wrong length; [`AlgebraError::Overflow`].
pub fn signed_distance(surface_vector: &Multivector, x: &[f64]) -> Result<f64, AlgebraError> {
    let parts = surface(surface_vector)?;
    check_finite(x, "point coordinates")?;
    check_same_dim(surface_vector.dim() - 2, x.len())?;
    Ok(match parts {
        Surface::Sphere { center, radius } => {
            let off: Vec<f64> = x.iter().zip(&center).map(|(a, b)| a - b).collect();
            scaled_norm(&off) - radius
        }
        Surface::Plane { normal, offset } => {
            x.iter().zip(&normal).map(|(a, b)| a * b).sum::<f64>() - offset
        }
    })
}

/// Whether the point `x` lies on the sphere or plane, to within the Euclidean distance
/// `tolerance`: |[`signed_distance`]| ≤ `tolerance`.
///
/// # Errors
/// As [`signed_distance`]; [`AlgebraError::NonFinite`] for a NaN or infinite tolerance.
pub fn point_on(
    surface_vector: &Multivector,
    x: &[f64],
    tolerance: f64,
) -> Result<bool, AlgebraError> {
    check_finite(&[tolerance], "tolerance")?;
    Ok(within(signed_distance(surface_vector, x)?.abs(), tolerance))
}

/// Whether the point `x` lies in the closed ball of a sphere, or in the closed half-space
/// behind a plane (the side its normal points away from, n̂ · x ≤ d̂, as for a sphere whose
/// outward normal it is): [`signed_distance`] ≤ 0.
///
/// ```
/// use rotorflow::algebra::cga;
/// let ball = cga::sphere(&[1.0, 1.0], 1.0)?;
/// assert!(cga::contains(&ball, &[1.5, 1.5])?);
/// assert!(!cga::contains(&ball, &[0.0, 0.0])?);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
///
/// # Errors
/// As [`signed_distance`].
pub fn contains(surface_vector: &Multivector, x: &[f64]) -> Result<bool, AlgebraError> {
    Ok(signed_distance(surface_vector, x)? <= 0.0)
}

/// The vector part of `x`, refusing other grades above [`POINT_TOLERANCE`] relative to it:
/// a sandwich V X Ṽ of a vector leaves round-off in grade 3, which is not a reason to fail.
fn vector_part(x: &Multivector, what: &'static str) -> Result<Multivector, AlgebraError> {
    let v = x.grade(1);
    let others = (x - &v).max_abs();
    if others != 0.0 && !within(others, POINT_TOLERANCE * v.max_abs()) {
        return Err(check_grade(x, 1, what).expect_err("other grades are present"));
    }
    Ok(v)
}

/// A point of ℝᴺ as a null vector of Cl(N + 1, 1, 0), [`up`]`(x)` (or any non-zero multiple
/// of it: a versor keeps it null and may scale it).
///
/// ```
/// use rotorflow::algebra::cga::Point;
/// let p = Point::new(&[1.0, 2.0, 3.0])?;
/// assert_eq!(p.coordinates()?, vec![1.0, 2.0, 3.0]);
/// assert_eq!(p.to_string(), "point(1, 2, 3)");
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Point(Multivector);

impl Point {
    /// The point at Euclidean coordinates `x` (N = `x.len()`).
    ///
    /// # Errors
    /// As [`up`].
    pub fn new(x: &[f64]) -> Result<Point, AlgebraError> {
        Ok(Point(up(x)?))
    }

    /// Wraps a null vector of Cl(N + 1, 1, 0) of any non-zero weight (round-off of other
    /// grades, as a sandwich leaves it, is dropped).
    ///
    /// # Errors
    /// As [`down`]: not a conformal vector, not null, or a multiple of n∞.
    pub fn from_multivector(m: Multivector) -> Result<Point, AlgebraError> {
        down(&m)?;
        Ok(Point(m.grade(1)))
    }

    /// The Euclidean dimension N.
    pub fn dim(&self) -> usize {
        self.0.dim() - 2
    }

    /// The Euclidean coordinates x (divided by the weight), [`down`].
    ///
    /// # Errors
    /// [`AlgebraError::PointAtInfinity`] for a weight so small that a coordinate overflows.
    pub fn coordinates(&self) -> Result<Vec<f64>, AlgebraError> {
        down(&self.0)
    }
}

multivector_newtype!(Point, "null vector");

/// The centre and radius of a round: the direct blade X of a circle (grade 3) or a
/// sphere (grade N + 1) spanned by points. X n∞ X is a multiple of the centre (n∞ reflected
/// in the round), and ρ² = X X̂ / (n∞ ⌋ X)² (Dorst, Fontijne & Mann, *Geometric Algebra for
/// Computer Science*, §14.2) with X̂ the grade involution.
fn round_centre_radius(
    x: &Multivector,
    grade: usize,
    what: &'static str,
) -> Result<(Vec<f64>, f64), AlgebraError> {
    let n = x.dim() - 2;
    let inf = ninf(n)?;
    let scale = x.max_abs();
    if scale == 0.0 {
        return Err(AlgebraError::Degenerate {
            operation: what,
            reason: "the points are not in general position (two coincide, or they lie on a \
                     smaller round)",
        });
    }
    let carrier = inf.left_contract(x);
    let flat = x.wedge(&inf);
    if negligible(flat.max_abs(), 4.0 * scale) {
        return Err(AlgebraError::Degenerate {
            operation: what,
            reason: "the points lie on a flat (a line or a hyperplane: a round of infinite \
                     radius)",
        });
    }
    let sign = if grade.is_multiple_of(2) { 1.0 } else { -1.0 };
    let r2 = sign * x.scalar_product(x) / carrier.scalar_product(&carrier);
    let centre = down(&x.geometric(&inf).geometric(x).grade(1))?;
    if !r2.is_finite() || r2 <= 0.0 {
        return Err(AlgebraError::NotASphere {
            reason: "its squared radius is not positive",
            deviation: r2,
        });
    }
    Ok((centre, r2.sqrt()))
}

/// The points moved so that their mean is the origin, and the mean: the blade of points
/// near the origin has no large ½ x² terms to cancel, so a round is read from it to the
/// precision of the points' spread rather than of their distance from the origin.
fn centred(points: &[&Point]) -> Result<(Vec<Multivector>, Vec<f64>), AlgebraError> {
    let coords = points
        .iter()
        .map(|p| p.coordinates())
        .collect::<Result<Vec<_>, _>>()?;
    let n = coords[0].len();
    let k = coords.len() as f64;
    let mean: Vec<f64> = (0..n)
        .map(|i| coords.iter().map(|x| x[i]).sum::<f64>() / k)
        .collect();
    let local = coords
        .iter()
        .map(|x| {
            up(&x
                .iter()
                .zip(&mean)
                .map(|(a, m)| a - m)
                .collect::<Vec<f64>>())
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok((local, mean))
}

/// x + m.
fn shifted(x: &[f64], m: &[f64]) -> Vec<f64> {
    x.iter().zip(m).map(|(a, b)| a + b).collect()
}

/// Checks that the points share one Euclidean dimension and returns it.
fn common_dim(points: &[&Point]) -> Result<usize, AlgebraError> {
    let n = points[0].dim();
    for p in points {
        check_same_dim(n, p.dim())?;
    }
    Ok(n)
}

/// The accessors that a sphere and a circle share: the dimension, the centre and the radius
/// they store, and the multivector in field `$field` (described by `$doc`), also as
/// `AsRef<Multivector>`.
macro_rules! round_accessors {
    ($t:ident, $field:ident, $doc:literal) => {
        impl $t {
            /// The Euclidean dimension N.
            pub fn dim(&self) -> usize {
                self.centre.len()
            }

            /// The centre.
            pub fn centre(&self) -> &[f64] {
                &self.centre
            }

            /// The radius.
            pub fn radius(&self) -> f64 {
                self.radius
            }

            #[doc = $doc]
            pub fn as_multivector(&self) -> &Multivector {
                &self.$field
            }
        }

        impl AsRef<Multivector> for $t {
            fn as_ref(&self) -> &Multivector {
                &self.$field
            }
        }
    };
}

/// A hypersphere of ℝᴺ (a circle in 2D, a sphere in 3D) with its centre and radius, held as
/// the dual vector σ = up(c) − ½ r² n∞ of Cl(N + 1, 1, 0) ([`sphere`]): a point X lies on it
/// exactly when X · σ = 0.
///
/// ```
/// use rotorflow::algebra::cga::{Point, Sphere};
/// // The unit circle of the plane through three of its points.
/// let pts = [[1.0, 0.0], [0.0, 1.0], [-0.6, -0.8]].map(|x| Point::new(&x).unwrap());
/// let s = Sphere::through(&pts)?;
/// assert!(s.centre().iter().all(|c| c.abs() < 1e-15) && (s.radius() - 1.0).abs() < 1e-15);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    vector: Multivector,
    centre: Vec<f64>,
    radius: f64,
}

impl Sphere {
    /// The sphere with `centre` and `radius`.
    ///
    /// # Errors
    /// As [`sphere`].
    pub fn new(centre: &[f64], radius: f64) -> Result<Sphere, AlgebraError> {
        Ok(Sphere {
            vector: sphere(centre, radius)?,
            centre: centre.to_vec(),
            radius,
        })
    }

    /// The sphere through N + 1 points of ℝᴺ: their outer product P₁ ∧ … ∧ P_(N+1), the
    /// direct sphere, read as a round (centre and radius).
    ///
    /// # Errors
    /// [`AlgebraError::WrongComponentCount`] unless there are N + 1 points;
    /// [`AlgebraError::DimensionMismatch`] for points of different dimensions;
    /// [`AlgebraError::Degenerate`] when the points are not independent (two coincide) or
    /// lie on one hyperplane (the "sphere" is flat).
    pub fn through(points: &[Point]) -> Result<Sphere, AlgebraError> {
        let refs: Vec<&Point> = points.iter().collect();
        let first = refs.first().ok_or(AlgebraError::WrongComponentCount {
            what: "points of a sphere",
            expected: 3,
            found: 0,
        })?;
        let n = first.dim();
        if refs.len() != n + 1 {
            return Err(AlgebraError::WrongComponentCount {
                what: "points of a sphere",
                expected: n + 1,
                found: refs.len(),
            });
        }
        common_dim(&refs)?;
        let (local, mean) = centred(&refs)?;
        let mut blade = local[0].clone();
        for p in &local[1..] {
            blade = blade.wedge(p);
        }
        let (centre, radius) = round_centre_radius(&blade, n + 1, "the sphere through points")?;
        Sphere::new(&shifted(&centre, &mean), radius)
    }

    /// Wraps a dual sphere vector of any weight and sign (a [`sphere`] moved by a versor).
    ///
    /// # Errors
    /// As [`signed_distance`]; [`AlgebraError::NotASphere`] for a plane (a sphere of
    /// infinite radius).
    pub fn from_multivector(m: &Multivector) -> Result<Sphere, AlgebraError> {
        match surface(m)? {
            Surface::Sphere { center, radius } => Sphere::new(&center, radius),
            Surface::Plane { .. } => Err(AlgebraError::NotASphere {
                reason: "it is a plane (a sphere of infinite radius)",
                deviation: 0.0,
            }),
        }
    }

    /// The signed distance |x − c| − r of the point `x` (negative inside), [`signed_distance`].
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`]; [`AlgebraError::NonFinite`].
    pub fn signed_distance(&self, x: &[f64]) -> Result<f64, AlgebraError> {
        signed_distance(&self.vector, x)
    }
}

round_accessors!(Sphere, vector, "The dual vector σ = up(c) − ½ r² n∞.");

/// A circle of ℝᴺ (N ≥ 2) held as the direct 3-blade P₁ ∧ P₂ ∧ P₃ of three of its points,
/// with its centre and radius.
///
/// ```
/// use rotorflow::algebra::cga::{Circle, Point};
/// // The circle of radius 2 about (0, 0, 5) in the plane x₃ = 5.
/// let p = |x: [f64; 3]| Point::new(&x);
/// let c = Circle::through(&p([2.0, 0.0, 5.0])?, &p([0.0, 2.0, 5.0])?, &p([-2.0, 0.0, 5.0])?)?;
/// let centre = c.centre();
/// assert!(centre[0].abs() < 1e-15 && centre[1].abs() < 1e-15 && (centre[2] - 5.0).abs() < 1e-14);
/// assert!((c.radius() - 2.0).abs() < 1e-15);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Circle {
    blade: Multivector,
    centre: Vec<f64>,
    radius: f64,
}

impl Circle {
    /// The circle through three points: the outer product P₁ ∧ P₂ ∧ P₃, read as a round.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`] for points of different dimensions;
    /// [`AlgebraError::Degenerate`] when two points coincide or the three are collinear.
    pub fn through(p1: &Point, p2: &Point, p3: &Point) -> Result<Circle, AlgebraError> {
        let refs = [p1, p2, p3];
        common_dim(&refs)?;
        // The centre and radius are read about the points' mean (their ½ x² terms small
        // there), and the blade kept is the one of the points as given.
        let (local, mean) = centred(&refs)?;
        let local_blade = local[0].wedge(&local[1]).wedge(&local[2]);
        let (centre, radius) = round_centre_radius(&local_blade, 3, "the circle through points")?;
        Ok(Circle {
            blade: p1.0.wedge(&p2.0).wedge(&p3.0),
            centre: shifted(&centre, &mean),
            radius,
        })
    }

    /// A circle of its direct 3-blade, with the centre and radius read from it.
    fn from_blade(blade: Multivector) -> Result<Circle, AlgebraError> {
        let (centre, radius) = round_centre_radius(&blade, 3, "the circle through points")?;
        Ok(Circle {
            blade,
            centre,
            radius,
        })
    }
}

round_accessors!(
    Circle,
    blade,
    "The direct 3-blade P₁ ∧ P₂ ∧ P₃ (a point X lies on the circle exactly when X ∧ C = 0)."
);

impl super::Versor<Point> for Multivector {
    type Output = Result<Point, AlgebraError>;
    /// The point moved by the conformal versor V: V X Ṽ.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`]; as [`Point::from_multivector`] when the image
    /// is not a finite point (a transversion sends one point to infinity).
    fn apply(&self, p: &Point) -> Self::Output {
        Point::from_multivector(super::Versor::<Multivector>::apply(self, &p.0)?)
    }
}

impl super::Versor<Sphere> for Multivector {
    type Output = Result<Sphere, AlgebraError>;
    /// The sphere moved by the conformal versor V: V σ Ṽ.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`]; [`AlgebraError::NotASphere`] when the image is
    /// a plane (a transversion can flatten a sphere through the point it sends to infinity).
    fn apply(&self, s: &Sphere) -> Self::Output {
        Sphere::from_multivector(&super::Versor::<Multivector>::apply(self, &s.vector)?)
    }
}

impl super::Versor<Circle> for Multivector {
    type Output = Result<Circle, AlgebraError>;
    /// The circle moved by the conformal versor V: V C Ṽ.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`]; [`AlgebraError::Degenerate`] when the image is
    /// a line.
    fn apply(&self, c: &Circle) -> Self::Output {
        Circle::from_blade(super::Versor::<Multivector>::apply(self, &c.blade)?.grade(3))
    }
}
