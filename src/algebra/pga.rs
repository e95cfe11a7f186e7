//! Projective geometric algebra Cl(N, 0, 1): points, hyperplanes, join and meet, and motors
//! (rigid motions), thin typed wrappers over [`Multivector`].
//!
//! # The plane-based model
//! In projective GA (Gunn, "Geometric algebras for Euclidean geometry", 2017; Gunn &
//! De Keninck, "Geometric algebra for computer graphics", SIGGRAPH course, 2019) the vectors of
//! Cl(N, 0, 1) are hyperplanes (planes in 3D, lines in 2D), the N-vectors are points, and the
//! even versors (motors) are the rigid motions, acting on every element by the sandwich
//! X ↦ M X M̃. The outer product ∧ intersects (the **meet**: two planes meet in a line), the
//! regressive product ∨ spans (the **join**: two points join to a line).
//!
//! # Basis order and the field's e₀
//! rotorflow puts the null vector last: in Cl(N, 0, 1), e₁ … e_N square to +1 and
//! e_(N+1) squares to 0. ganja.js, klein and kingdon call the null vector e₀ and write it
//! first. So rotorflow's e_(N+1) is their e₀, and a blade that holds it is written with
//! e_(N+1) last here and e₀ first there: e₀ A = (−1)ᵏ A e₀ for a k-blade A without e₀, so
//! klein's e₀₁ is −e₁₄ here, e₀₂₃ is e₂₃₄, e₀₁₂₃ is −e₁₂₃₄. The pseudoscalar orientations
//! therefore differ, and the signs of points and planes below are rotorflow's own, fixed by
//! the geometric facts the tests pin down (a point lies on a plane exactly when a·x = d; the
//! translation motor moves the origin to t; a rotation by +θ in e₁∧e₂ turns e₁ toward e₂).
//!
//! | element | rotorflow (Cl(N, 0, 1), e₀ = e_(N+1)) |
//! |---|---|
//! | point x | X = (1 + e₀ x) e₁…N (in 3D: e₁₂₃ + x₁ e₂₃₄ − x₂ e₁₃₄ + x₃ e₁₂₄) |
//! | hyperplane a·x = d | Σᵢ aᵢ eᵢ + d e₀ (in 3D: a₁e₁ + a₂e₂ + a₃e₃ + d e₄) |
//! | translation by t | T = 1 − ½ Σᵢ tᵢ eᵢ e₀ = exp(−½ t e₀) |
//! | rotation by θ in eᵢ∧eⱼ | R = cos(θ/2) − sin(θ/2) eᵢⱼ (turns eᵢ toward eⱼ) |
//! | rigid motion x ↦ Q x + t | M = T R |
//!
//! ```
//! use rotorflow::algebra::pga::{Motor, Plane, Point, join, meet};
//! // A quarter turn in the e1e2 plane, then a translation by (1, 0, 2).
//! let m = Motor::from_plane_angle(3, 0, 1, std::f64::consts::FRAC_PI_2)?
//!     .then(&Motor::from_translation(&[1.0, 0.0, 2.0])?)?;
//! let p = m.apply_point(&Point::new(&[1.0, 0.0, 0.0])?)?;
//! let x = p.coordinates()?;
//! assert!((x[0] - 1.0).abs() < 1e-15 && (x[1] - 1.0).abs() < 1e-15 && (x[2] - 2.0).abs() < 1e-15);
//! // Two planes meet in a line; the line and a point off it join to a plane.
//! let line = meet(&Plane::new(&[1.0, 0.0, 0.0], 0.0)?, &Plane::new(&[0.0, 1.0, 0.0], 0.0)?)?;
//! let plane = Plane::from_multivector(join(&line, &Point::new(&[1.0, 0.0, 0.0])?)?)?;
//! let (normal, d) = plane.equation();
//! assert!(normal[0].abs() < 1e-15 && normal[2].abs() < 1e-15 && d.abs() < 1e-15);
//! # Ok::<(), rotorflow::algebra::AlgebraError>(())
//! ```

use super::check_grade;
use super::error::{check_finite, within};
use super::{AlgebraError, MULTIVECTOR_MAX_DIM, Multivector, Rotor, Signature, VERSOR_TOLERANCE};
use nalgebra::DMatrix;

/// The projective algebra Cl(n, 0, 1) of Euclidean ℝⁿ, for 2 ≤ n < [`MULTIVECTOR_MAX_DIM`].
fn pga(n: usize) -> Result<Signature, AlgebraError> {
    if n >= MULTIVECTOR_MAX_DIM {
        return Err(AlgebraError::DimensionTooLarge {
            what: "projective algebra",
            dim: n + 1,
            max: MULTIVECTOR_MAX_DIM,
        });
    }
    if n < 2 {
        return Err(AlgebraError::WrongSignature {
            operation: "projective geometry",
            expected: "Cl(N, 0, 1) with N ≥ 2",
            signature: Signature::new(n, 0, 1)?,
        });
    }
    Signature::new(n, 0, 1)
}

/// N for a projective signature Cl(N, 0, 1), else an error.
fn euclidean_dim(sig: Signature, operation: &'static str) -> Result<usize, AlgebraError> {
    if sig.q() == 0 && sig.r() == 1 && sig.p() >= 2 {
        Ok(sig.p())
    } else {
        Err(AlgebraError::WrongSignature {
            operation,
            expected: "Cl(N, 0, 1) with N ≥ 2",
            signature: sig,
        })
    }
}

/// The mask and sign of e₀ eᵢ e₁…N in Cl(n, 0, 1).
fn point_blade(sig: Signature, n: usize, i: usize) -> (u64, f64) {
    let ie = Multivector::basis_blade(sig, (1 << n) - 1);
    let ei = Multivector::basis_blade(sig, 1 << i);
    let e0 = Multivector::basis_blade(sig, 1 << n);
    let b = e0.geometric(&ei).geometric(&ie);
    let (mask, c) = b.terms().next().expect("a single blade");
    (mask, c)
}

/// The meet A ∧ B (outer product): two hyperplanes meet in their intersection.
///
/// # Errors
/// [`AlgebraError::SignatureMismatch`] for operands of different algebras.
pub fn meet(
    a: &impl AsRef<Multivector>,
    b: &impl AsRef<Multivector>,
) -> Result<Multivector, AlgebraError> {
    a.as_ref().try_product(b.as_ref(), super::Product::Wedge)
}

/// The join A ∨ B (regressive product): two points join to the line through them.
///
/// # Errors
/// [`AlgebraError::SignatureMismatch`] for operands of different algebras.
pub fn join(
    a: &impl AsRef<Multivector>,
    b: &impl AsRef<Multivector>,
) -> Result<Multivector, AlgebraError> {
    a.as_ref()
        .try_product(b.as_ref(), super::Product::Regressive)
}

/// A point of Euclidean ℝᴺ as an N-vector of Cl(N, 0, 1):
/// X = (1 + e₀ x) e₁…N (ganja.js's and klein's `point`, with the basis order of the
/// [module documentation](self)); in 3D X = e₁₂₃ + x₁ e₂₃₄ − x₂ e₁₃₄ + x₃ e₁₂₄.
///
/// The weight (the e₁…N coefficient) is 1 for points built here; a motor keeps it, a join
/// or meet may scale it, and [`Point::coordinates`] divides by it.
#[derive(Clone, Debug, PartialEq)]
pub struct Point(Multivector);

impl Point {
    /// The point at Euclidean coordinates `x` (N = `x.len()`, 2 ≤ N ≤ 15).
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`]; [`AlgebraError::WrongSignature`] for N < 2;
    /// [`AlgebraError::DimensionTooLarge`] for N ≥ 16.
    pub fn new(x: &[f64]) -> Result<Point, AlgebraError> {
        check_finite(x, "point coordinates")?;
        let n = x.len();
        let sig = pga(n)?;
        let mut m = Multivector::zero(sig);
        m.as_mut_slice()[(1 << n) - 1] = 1.0;
        for (i, &xi) in x.iter().enumerate() {
            let (mask, sign) = point_blade(sig, n, i);
            m.as_mut_slice()[mask as usize] = sign * xi;
        }
        Ok(Point(m))
    }

    /// Wraps an N-vector of Cl(N, 0, 1) (any weight; weight 0 is a point at infinity, a
    /// direction).
    ///
    /// # Errors
    /// [`AlgebraError::WrongSignature`]; [`AlgebraError::MixedGrades`] for other grades;
    /// [`AlgebraError::NonFinite`].
    pub fn from_multivector(m: Multivector) -> Result<Point, AlgebraError> {
        let n = euclidean_dim(m.signature(), "a point")?;
        check_finite(m.as_slice(), "point")?;
        check_grade(&m, n, "point")?;
        Ok(Point(m))
    }

    /// The Euclidean dimension N.
    pub fn dim(&self) -> usize {
        self.0.dim() - 1
    }

    /// The weight, the e₁…N coefficient (1 for a point built by [`Point::new`]).
    pub fn weight(&self) -> f64 {
        self.0.coefficient((1 << self.dim()) - 1)
    }

    /// The Euclidean coordinates x (divided by the weight).
    ///
    /// # Errors
    /// [`AlgebraError::PointAtInfinity`] when the weight is zero (an ideal point, a
    /// direction) or so small that a coordinate overflows.
    pub fn coordinates(&self) -> Result<Vec<f64>, AlgebraError> {
        let n = self.dim();
        let w = self.weight();
        let sig = self.0.signature();
        let x: Vec<f64> = (0..n)
            .map(|i| {
                let (mask, sign) = point_blade(sig, n, i);
                sign * self.0.coefficient(mask) / w
            })
            .collect();
        if w == 0.0 || x.iter().any(|c| !c.is_finite()) {
            return Err(AlgebraError::PointAtInfinity { weight: w });
        }
        Ok(x)
    }

    /// The underlying N-vector.
    pub fn as_multivector(&self) -> &Multivector {
        &self.0
    }

    /// The underlying N-vector, by value.
    pub fn into_multivector(self) -> Multivector {
        self.0
    }
}

impl AsRef<Multivector> for Point {
    fn as_ref(&self) -> &Multivector {
        &self.0
    }
}

/// A hyperplane a·x = d of ℝᴺ (a plane in 3D, a line in 2D) as a vector of Cl(N, 0, 1):
/// Σᵢ aᵢ eᵢ + d e₀ (ganja.js's and klein's `plane`, 2D PGA's `line`).
#[derive(Clone, Debug, PartialEq)]
#[doc(alias = "line")]
pub struct Plane(Multivector);

impl Plane {
    /// The hyperplane of the points x with `normal`·x = `d` (N = `normal.len()`). The normal
    /// need not be a unit vector.
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`]; [`AlgebraError::ZeroLength`] for a zero normal;
    /// [`AlgebraError::WrongSignature`] for N < 2; [`AlgebraError::DimensionTooLarge`].
    pub fn new(normal: &[f64], d: f64) -> Result<Plane, AlgebraError> {
        check_finite(normal, "plane normal")?;
        check_finite(&[d], "plane offset")?;
        if normal.iter().all(|&c| c == 0.0) {
            return Err(AlgebraError::ZeroLength {
                what: "plane normal",
            });
        }
        let n = normal.len();
        let mut m = Multivector::zero(pga(n)?);
        for (i, &a) in normal.iter().enumerate() {
            m.as_mut_slice()[1 << i] = a;
        }
        m.as_mut_slice()[1 << n] = d;
        Ok(Plane(m))
    }

    /// Wraps a vector of Cl(N, 0, 1).
    ///
    /// # Errors
    /// [`AlgebraError::WrongSignature`]; [`AlgebraError::MixedGrades`];
    /// [`AlgebraError::NonFinite`].
    pub fn from_multivector(m: Multivector) -> Result<Plane, AlgebraError> {
        euclidean_dim(m.signature(), "a plane")?;
        check_finite(m.as_slice(), "plane")?;
        check_grade(&m, 1, "plane")?;
        Ok(Plane(m))
    }

    /// The Euclidean dimension N.
    pub fn dim(&self) -> usize {
        self.0.dim() - 1
    }

    /// The equation (a, d) of the plane a·x = d, as stored (not normalised).
    pub fn equation(&self) -> (Vec<f64>, f64) {
        let n = self.dim();
        let a = (0..n).map(|i| self.0.coefficient(1 << i)).collect();
        (a, self.0.coefficient(1 << n))
    }

    /// The underlying vector.
    pub fn as_multivector(&self) -> &Multivector {
        &self.0
    }

    /// The underlying vector, by value.
    pub fn into_multivector(self) -> Multivector {
        self.0
    }
}

impl AsRef<Multivector> for Plane {
    fn as_ref(&self) -> &Multivector {
        &self.0
    }
}

/// A rigid motion of ℝᴺ (rotation and translation) as a unit even versor of Cl(N, 0, 1),
/// M M̃ = 1: klein's and ganja.js's `motor`. It acts on points, planes and every other
/// element by the sandwich X ↦ M X M̃; its Euclidean part is a [`Rotor`] R and the rest is
/// −½ t e₀ R for the translation t: M = T R, the motion x ↦ Q x + t with Q R's rotation
/// matrix.
#[derive(Clone, Debug, PartialEq)]
pub struct Motor(Multivector);

impl Motor {
    /// The identity motion of ℝⁿ.
    ///
    /// # Errors
    /// [`AlgebraError::WrongSignature`] for n < 2; [`AlgebraError::DimensionTooLarge`].
    pub fn identity(n: usize) -> Result<Motor, AlgebraError> {
        Ok(Motor(Multivector::scalar(pga(n)?, 1.0)))
    }

    /// Wraps an even unit versor of Cl(N, 0, 1).
    ///
    /// # Errors
    /// [`AlgebraError::WrongSignature`]; [`AlgebraError::NonFinite`];
    /// [`AlgebraError::NotAVersor`] for odd grades or max |M M̃ − 1| above
    /// [`VERSOR_TOLERANCE`] · max(1, max |Mᵢ|²) (normalise drift with
    /// [`Multivector::normalize_versor`]).
    pub fn new(m: Multivector) -> Result<Motor, AlgebraError> {
        euclidean_dim(m.signature(), "a motor")?;
        check_finite(m.as_slice(), "motor")?;
        let odd = m.odd().max_abs();
        if odd != 0.0 {
            return Err(AlgebraError::NotAVersor {
                reason: "it has odd grades",
                deviation: odd,
            });
        }
        let mut mm = m.geometric(&m.reverse());
        mm.as_mut_slice()[0] -= 1.0;
        let deviation = mm.max_abs();
        if !deviation.is_finite()
            || !within(deviation, VERSOR_TOLERANCE * m.max_abs().powi(2).max(1.0))
        {
            return Err(AlgebraError::NotAVersor {
                reason: "M M̃ is not 1",
                deviation,
            });
        }
        Ok(Motor(m))
    }

    /// The translation by t: T = 1 − ½ Σᵢ tᵢ eᵢ e₀ (klein's `translator`).
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`]; [`AlgebraError::WrongSignature`] for N < 2;
    /// [`AlgebraError::DimensionTooLarge`].
    pub fn from_translation(t: &[f64]) -> Result<Motor, AlgebraError> {
        check_finite(t, "translation")?;
        let n = t.len();
        let mut m = Multivector::scalar(pga(n)?, 1.0);
        for (i, &ti) in t.iter().enumerate() {
            m.as_mut_slice()[(1 << i) | (1 << n)] = -0.5 * ti;
        }
        Ok(Motor(m))
    }

    /// The rotation of a Euclidean [`Rotor`] of ℝᴺ about the origin (klein's `rotor`).
    ///
    /// # Errors
    /// [`AlgebraError::WrongSignature`] for N < 2; [`AlgebraError::DimensionTooLarge`].
    pub fn from_rotor(r: &Rotor) -> Result<Motor, AlgebraError> {
        let n = r.dim();
        let mut m = Multivector::zero(pga(n)?);
        for (mask, c) in r.to_multivector().terms() {
            m.as_mut_slice()[mask as usize] = c;
        }
        Ok(Motor(m))
    }

    /// The rotation by `angle` in the plane eᵢ∧eⱼ through the origin (0-based indices),
    /// turning eᵢ toward eⱼ: cos(angle/2) − sin(angle/2) eᵢⱼ.
    ///
    /// # Errors
    /// As [`Rotor::from_plane_angle`], and [`AlgebraError::WrongSignature`] for n < 2.
    pub fn from_plane_angle(
        n: usize,
        i: usize,
        j: usize,
        angle: f64,
    ) -> Result<Motor, AlgebraError> {
        pga(n)?;
        Motor::from_rotor(&Rotor::from_plane_angle(n, i, j, angle)?)
    }

    /// The rotation by `angle` about an axis that need not pass through the origin (ganja.js's
    /// `rotor(line, angle)`): M = cos(θ/2) − sin(θ/2) Â with Â = A/√(−A²), for a simple
    /// bivector A with A² < 0 (a line of 3D PGA, such as the meet of two planes; a point of
    /// 2D PGA; in general the meet of N − 1 hyperplanes). The rotation turns in the
    /// orientation of A's Euclidean part: from eᵢ toward eⱼ for A = eᵢⱼ, and
    /// counter-clockwise about a 2D point of positive weight.
    ///
    /// ```
    /// use rotorflow::algebra::pga::{Motor, Point};
    /// // A quarter turn about the 2D point (1, 1) takes (2, 1) to (1, 2).
    /// let m = Motor::from_axis_angle(Point::new(&[1.0, 1.0])?.as_multivector(), std::f64::consts::FRAC_PI_2)?;
    /// let x = m.apply_point(&Point::new(&[2.0, 1.0])?)?.coordinates()?;
    /// assert!((x[0] - 1.0).abs() < 1e-15 && (x[1] - 2.0).abs() < 1e-15);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::WrongSignature`]; [`AlgebraError::NonFinite`];
    /// [`AlgebraError::NotABivector`]; [`AlgebraError::NotAnAxis`] when A² is not a negative
    /// scalar (A ∧ A ≠ 0 or no rotation part).
    pub fn from_axis_angle(axis: &Multivector, angle: f64) -> Result<Motor, AlgebraError> {
        euclidean_dim(axis.signature(), "a rotation axis")?;
        check_finite(axis.as_slice(), "rotation axis")?;
        check_finite(&[angle], "rotation angle")?;
        let grades: Vec<usize> = axis.grades().into_iter().filter(|&k| k != 2).collect();
        if !grades.is_empty() {
            return Err(AlgebraError::NotABivector {
                operation: "a rotation axis",
                grades,
            });
        }
        let sq = axis.geometric(axis);
        let norm2 = -sq.scalar_part();
        if norm2.is_nan() || norm2 <= 0.0 {
            return Err(AlgebraError::NotAnAxis {
                reason: "A² is not negative (no rotation part)",
                deviation: -norm2,
            });
        }
        let wedge = sq.grade(4).max_abs();
        if !within(wedge, 1e-12 * norm2) {
            return Err(AlgebraError::NotAnAxis {
                reason: "A is not simple (A ∧ A ≠ 0)",
                deviation: wedge / norm2,
            });
        }
        let (s, c) = (0.5 * angle).sin_cos();
        let mut m = axis * (-s / norm2.sqrt());
        m.as_mut_slice()[0] = c;
        Ok(Motor(m))
    }

    /// The motion x ↦ Q x + t: first the rotation of `r`, then the translation by `t`
    /// (M = T R).
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`] when `t.len()` is not `r.dim()`; as
    /// [`Motor::from_translation`].
    pub fn from_rotation_translation(r: &Rotor, t: &[f64]) -> Result<Motor, AlgebraError> {
        super::error::check_same_dim(r.dim(), t.len())?;
        Motor::from_rotor(r)?.then(&Motor::from_translation(t)?)
    }

    /// The motor exp(B) of a bivector B of Cl(N, 0, 1) (ganja.js's `Exp`, klein's `exp`):
    /// exp(−½ θ eᵢⱼ) rotates by θ from eᵢ toward eⱼ, exp(−½ t e₀) translates by t.
    ///
    /// # Errors
    /// [`AlgebraError::WrongSignature`]; the errors of [`Multivector::exp`].
    pub fn from_bivector(b: &Multivector) -> Result<Motor, AlgebraError> {
        euclidean_dim(b.signature(), "a motor")?;
        Ok(Motor(b.exp()?))
    }

    /// The bivector log M with exp(log M) = M (ganja.js's `Log`, klein's `log`), see
    /// [`Multivector::log`].
    ///
    /// # Errors
    /// As [`Multivector::log`].
    pub fn log(&self) -> Result<Multivector, AlgebraError> {
        self.0.log()
    }

    /// The Euclidean dimension N.
    pub fn dim(&self) -> usize {
        self.0.dim() - 1
    }

    /// This motion followed by `next`: the motor `next · self`.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`] for motors of different dimensions.
    pub fn then(&self, next: &Motor) -> Result<Motor, AlgebraError> {
        Ok(Motor(
            next.0.try_product(&self.0, super::Product::Geometric)?,
        ))
    }

    /// The inverse motion M̃.
    pub fn inverse(&self) -> Motor {
        Motor(self.0.reverse())
    }

    /// M X M̃ for any element X of the same algebra (point, plane, line, motor …).
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`].
    pub fn apply(&self, x: &Multivector) -> Result<Multivector, AlgebraError> {
        let mx = self.0.try_product(x, super::Product::Geometric)?;
        Ok(mx.geometric(&self.0.reverse()))
    }

    /// The moved point.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`].
    pub fn apply_point(&self, p: &Point) -> Result<Point, AlgebraError> {
        Ok(Point(self.apply(&p.0)?.grade(self.dim())))
    }

    /// The moved hyperplane.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`].
    pub fn apply_plane(&self, p: &Plane) -> Result<Plane, AlgebraError> {
        Ok(Plane(self.apply(&p.0)?.grade(1)))
    }

    /// The rotation part R, a Euclidean rotor of ℝᴺ (the terms without e₀).
    pub fn rotor(&self) -> Rotor {
        let n = self.dim();
        let mut r = Multivector::zero(Signature::euclidean(n));
        for (mask, c) in self.0.terms() {
            if mask & (1 << n) == 0 {
                r.as_mut_slice()[mask as usize] = c;
            }
        }
        Rotor::from_multivector_unchecked(&r)
    }

    /// The translation t of the motion x ↦ Q x + t: t e₀ = −2 ⟨M⟩_e₀ R̃, with ⟨M⟩_e₀ the
    /// terms of M that hold e₀.
    pub fn translation(&self) -> Vec<f64> {
        let n = self.dim();
        let null = 1u64 << n;
        let mut with_null = Multivector::zero(self.0.signature());
        let mut rot = Multivector::zero(self.0.signature());
        for (mask, c) in self.0.terms() {
            if mask & null != 0 {
                with_null.as_mut_slice()[mask as usize] = c;
            } else {
                rot.as_mut_slice()[mask as usize] = c;
            }
        }
        let te = with_null.geometric(&rot.reverse());
        (0..n)
            .map(|i| -2.0 * te.coefficient((1 << i) | null))
            .collect()
    }

    /// The (N+1)×(N+1) homogeneous matrix \[\[Q, t\], \[0, 1\]\] of the motion x ↦ Q x + t,
    /// acting on the column (x, 1).
    pub fn to_matrix(&self) -> DMatrix<f64> {
        let n = self.dim();
        let q = self.rotor().to_matrix();
        let t = self.translation();
        let mut h = DMatrix::zeros(n + 1, n + 1);
        h.view_mut((0, 0), (n, n)).copy_from(&q);
        for i in 0..n {
            h[(i, n)] = t[i];
        }
        h[(n, n)] = 1.0;
        h
    }

    /// The motor of a homogeneous matrix \[\[Q, t\], \[0, 1\]\] with Q a rotation (the
    /// sign of the motor is chosen by [`Rotor::from_matrix`]).
    ///
    /// # Errors
    /// [`AlgebraError::NotSquare`]; [`AlgebraError::NonFinite`];
    /// [`AlgebraError::NotHomogeneous`] when the last row is not (0, …, 0, 1) to within
    /// [`super::ROTATION_TOLERANCE`]; the errors of [`Rotor::from_matrix`] for Q.
    pub fn from_matrix(h: &DMatrix<f64>) -> Result<Motor, AlgebraError> {
        if h.nrows() != h.ncols() {
            return Err(AlgebraError::NotSquare {
                rows: h.nrows(),
                cols: h.ncols(),
            });
        }
        check_finite(h.as_slice(), "homogeneous matrix")?;
        let n = h.nrows().saturating_sub(1);
        pga(n)?;
        let deviation = (0..=n)
            .map(|j| (h[(n, j)] - if j == n { 1.0 } else { 0.0 }).abs())
            .fold(0.0, f64::max);
        if !within(deviation, super::ROTATION_TOLERANCE) {
            return Err(AlgebraError::NotHomogeneous { deviation });
        }
        let r = Rotor::from_matrix(&h.view((0, 0), (n, n)).into_owned())?;
        let t: Vec<f64> = (0..n).map(|i| h[(i, n)]).collect();
        Motor::from_rotation_translation(&r, &t)
    }

    /// The half motion (√M, with √M √M = M), see [`Multivector::sqrt`].
    ///
    /// # Errors
    /// As [`Multivector::sqrt`].
    pub fn sqrt(&self) -> Result<Motor, AlgebraError> {
        Ok(Motor(self.0.sqrt()?))
    }

    /// The underlying even multivector.
    pub fn as_multivector(&self) -> &Multivector {
        &self.0
    }

    /// The underlying even multivector, by value.
    pub fn into_multivector(self) -> Multivector {
        self.0
    }
}

impl AsRef<Multivector> for Motor {
    fn as_ref(&self) -> &Multivector {
        &self.0
    }
}

impl AsRef<Multivector> for Multivector {
    /// Lets [`join`] and [`meet`] take plain multivectors (lines, results of other joins)
    /// beside the typed points, planes and motors.
    fn as_ref(&self) -> &Multivector {
        self
    }
}
