//! Projective geometric algebra Cl(N, 0, 1): points, lines, hyperplanes, join and meet, and
//! motors (rigid motions), thin typed wrappers over [`Multivector`].
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
//! | ideal point (direction) d | e₀ d e₁…N (in 3D: d₁ e₂₃₄ − d₂ e₁₃₄ + d₃ e₁₂₄) |
//! | line through p, direction d | P ∨ D, an (N − 1)-vector (in 3D: d₁ e₂₃ − d₂ e₁₃ + d₃ e₁₂ + M₂₃ e₁₄ − M₁₃ e₂₄ + M₁₂ e₃₄ with M = p ∧ d) |
//! | hyperplane a·x = d | Σᵢ aᵢ eᵢ + d e₀ (in 3D: a₁e₁ + a₂e₂ + a₃e₃ + d e₄) |
//! | translation by t | T = 1 − ½ Σᵢ tᵢ eᵢ e₀ = exp(−½ t e₀) |
//! | rotation by θ in eᵢ∧eⱼ | R = cos(θ/2) − sin(θ/2) eᵢⱼ (turns eᵢ toward eⱼ) |
//! | rigid motion x ↦ Q x + t | M = T R |
//!
//! # Typed join and meet
//! [`join`] and [`meet`] take and return plain multivectors, whatever the operands. The
//! typed companions return the element the geometry promises and refuse the special
//! positions where it does not exist, with [`AlgebraError::Degenerate`]:
//!
//! | operation | result | refused |
//! |---|---|---|
//! | [`Point::join`], [`Line::through`] | [`Line`] with direction q − p | equal points; two ideal points (a line at infinity) |
//! | [`Plane::meet`] (3D) | [`Line`] with direction a × b | parallel or equal planes |
//! | [`Line::meet_plane`] | [`Point`]; the ideal point of the line's direction when parallel | a line in the plane |
//! | [`Line::join_point`] (3D) | [`Plane`] | a point on the line |
//!
//! Ideal points (weight 0, [`Point::ideal`]) are accepted as operands everywhere: a point
//! joined with a direction is the line through it along that direction. "Parallel" and
//! "equal" mean: to within the round-off of the operands' coefficients.
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
use super::error::{check_finite, negligible, within};
use super::versor_sqrt::check_unit_even_versor;
use super::{AlgebraError, Bivector, MULTIVECTOR_MAX_DIM, Multivector, Rotor, Signature};
use crate::numeric::scaled_norm;
use nalgebra::DMatrix;

/// The projective algebra Cl(n, 0, 1) of Euclidean ℝⁿ, for 2 ≤ n < [`MULTIVECTOR_MAX_DIM`].
fn pga(n: usize) -> Result<Signature, AlgebraError> {
    AlgebraError::check_dimension("projective algebra", n + 1, MULTIVECTOR_MAX_DIM)?;
    if n < 2 {
        return Err(AlgebraError::WrongSignature {
            operation: "projective geometry",
            expected: "Cl(N, 0, 1) with N ≥ 2",
            signature: Signature::new(n, 0, 1)?,
        });
    }
    Signature::new(n, 0, 1)
}

/// Checks that `sig` is 3D projective GA Cl(3, 0, 1).
fn require_3d(sig: Signature, operation: &'static str) -> Result<(), AlgebraError> {
    if euclidean_dim(sig, operation)? == 3 {
        Ok(())
    } else {
        Err(AlgebraError::WrongSignature {
            operation,
            expected: "3D projective GA Cl(3, 0, 1)",
            signature: sig,
        })
    }
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
    single_term(&e0.geometric(&ei).geometric(&ie))
}

/// The mask and coefficient of a multivector that is a multiple of one basis blade.
fn single_term(m: &Multivector) -> (u64, f64) {
    m.terms().next().expect("a single blade")
}

/// The ideal point (direction) eᵢ, of weight 0: e₀ eᵢ e₁…N.
fn ideal_basis(sig: Signature, n: usize, i: usize) -> Multivector {
    let (mask, sign) = point_blade(sig, n, i);
    Multivector::basis_blade(sig, mask) * sign
}

/// The mask and sign of the line through the origin with direction eᵢ, O ∨ eᵢ (O = e₁…N):
/// the blades a line's direction is read from.
fn direction_blade(sig: Signature, n: usize, i: usize) -> (u64, f64) {
    let origin = Multivector::basis_blade(sig, (1 << n) - 1);
    single_term(&origin.regressive(&ideal_basis(sig, n, i)))
}

/// The mask and sign of the ideal line eᵢ ∨ eⱼ of two directions: the blades a line's
/// moment p ∧ d is read from.
fn moment_blade(sig: Signature, n: usize, i: usize, j: usize) -> (u64, f64) {
    single_term(&ideal_basis(sig, n, i).regressive(&ideal_basis(sig, n, j)))
}

/// The largest coefficient without e₀ (the weight part: a hyperplane's normal, a point's
/// e₁…N coefficient, a line's direction).
fn weight_norm(m: &Multivector) -> f64 {
    let null = 1u64 << (m.dim() - 1);
    m.terms()
        .filter(|(mask, _)| mask & null == 0)
        .fold(0.0, |acc, (_, c)| acc.max(c.abs()))
}

/// The meet A ∧ B (outer product): two hyperplanes meet in their intersection.
/// [`Plane::meet`] and [`Line::meet_plane`] are the typed forms.
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
/// [`Point::join`] and [`Line::join_point`] are the typed forms.
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

    /// The ideal point (point at infinity) of the direction `d`, of weight 0: where the
    /// lines with direction `d` meet (klein's `direction`). It joins with a point to the line
    /// through that point with direction `d`, and it is what [`Line::meet_plane`] returns for
    /// a line parallel to the plane.
    ///
    /// ```
    /// use rotorflow::algebra::pga::{Line, Point};
    /// let up = Point::ideal(&[0.0, 0.0, 1.0])?;
    /// assert_eq!(up.weight(), 0.0);
    /// let vertical = Point::new(&[1.0, 2.0, 0.0])?.join(&up)?;
    /// assert_eq!(vertical, Line::from_point_direction(&[1.0, 2.0, 0.0], &[0.0, 0.0, 1.0])?);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`]; [`AlgebraError::ZeroLength`] for a zero direction;
    /// [`AlgebraError::WrongSignature`] for N < 2; [`AlgebraError::DimensionTooLarge`].
    #[doc(alias = "direction")]
    pub fn ideal(d: &[f64]) -> Result<Point, AlgebraError> {
        check_finite(d, "direction")?;
        if d.iter().all(|&c| c == 0.0) {
            return Err(AlgebraError::ZeroLength { what: "direction" });
        }
        let n = d.len();
        let sig = pga(n)?;
        let mut m = Multivector::zero(sig);
        for (i, &di) in d.iter().enumerate() {
            let (mask, sign) = point_blade(sig, n, i);
            m.as_mut_slice()[mask as usize] = sign * di;
        }
        Ok(Point(m))
    }

    /// The line through this point and `other` (the join P ∨ Q, klein's `p1 & p2`), with
    /// direction `other − self` for points of weight 1; see [`Line::through`].
    ///
    /// # Errors
    /// As [`Line::through`].
    pub fn join(&self, other: &Point) -> Result<Line, AlgebraError> {
        Line::through(self, other)
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

    /// The direction d of an ideal point (the inverse of [`Point::ideal`]); for a finite
    /// point of weight w, the weighted coordinates w x.
    pub fn direction(&self) -> Vec<f64> {
        let (n, sig) = (self.dim(), self.0.signature());
        (0..n)
            .map(|i| {
                let (mask, sign) = point_blade(sig, n, i);
                sign * self.0.coefficient(mask) + 0.0
            })
            .collect()
    }
}

multivector_newtype!(Point, "N-vector");

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

    /// The line where this plane meets `other` in 3D (the meet A ∧ B, klein's `p1 ^ p2`).
    /// For the planes a·x = d and b·x = e its direction is a × b, so that
    /// [`Motor::from_axis_angle`] about it turns a toward b.
    ///
    /// ```
    /// use rotorflow::algebra::pga::Plane;
    /// // The planes x₁ = 1 and x₂ = 2 meet in the line through (1, 2, 0) along e₃.
    /// let line = Plane::new(&[1.0, 0.0, 0.0], 1.0)?.meet(&Plane::new(&[0.0, 1.0, 0.0], 2.0)?)?;
    /// assert_eq!(line.direction(), vec![0.0, 0.0, 1.0]);
    /// assert_eq!(line.point_nearest_origin(), vec![1.0, 2.0, 0.0]);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::WrongSignature`] outside 3D (in N dimensions two hyperplanes meet in
    /// an (N − 2)-flat, a line only for N = 3; [`meet`] returns it);
    /// [`AlgebraError::SignatureMismatch`]; [`AlgebraError::Degenerate`] for parallel or
    /// equal planes (a × b zero to within round-off: they meet only at infinity).
    pub fn meet(&self, other: &Plane) -> Result<Line, AlgebraError> {
        require_3d(self.0.signature(), "the meet of two planes as a line")?;
        let m = self.0.try_product(&other.0, super::Product::Wedge)?;
        if negligible(
            weight_norm(&m),
            weight_norm(&self.0) * weight_norm(&other.0),
        ) {
            return Err(AlgebraError::Degenerate {
                operation: "the meet of two planes",
                reason: "the planes are parallel",
            });
        }
        Ok(Line(m))
    }

    /// The equation (a, d) of the plane a·x = d, as stored (not normalised).
    pub fn equation(&self) -> (Vec<f64>, f64) {
        let n = self.dim();
        let a = (0..n).map(|i| self.0.coefficient(1 << i)).collect();
        (a, self.0.coefficient(1 << n))
    }
}

multivector_newtype!(Plane, "vector");

/// A line of ℝᴺ as an (N − 1)-vector of Cl(N, 0, 1): the join P ∨ Q of two of its points,
/// or the meet of N − 1 hyperplanes through it (klein's and ganja.js's `line`; in 3D a
/// bivector, in 2D a vector, the same element as a [`Plane`] of 2D).
///
/// A line carries Plücker coordinates: its [`direction`](Line::direction) d and its
/// [`moment`](Line::moment) p ∧ d for any point p on it (in 3D the classical moment vector
/// p × d is the dual (M₂₃, −M₁₃, M₁₂)). The line through p and q has direction q − p; in 3D,
/// with e₄ the projective e₀,
/// L = d₁ e₂₃ − d₂ e₁₃ + d₃ e₁₂ + M₂₃ e₁₄ − M₁₃ e₂₄ + M₁₂ e₃₄.
/// Every `Line` has a non-zero direction (the lines at infinity, which two directions span,
/// are not `Line`s). Dorst & De Keninck, *May the Forque Be With You: Dynamics in PGA*
/// (2022), use such lines for forces and momenta.
///
/// ```
/// use rotorflow::algebra::pga::{Line, Point};
/// let p = Point::new(&[0.0, 0.0, 0.0])?;
/// let q = Point::new(&[1.0, 0.0, 0.0])?;
/// let line = p.join(&q)?; // = Line::through(&p, &q)
/// assert_eq!(line.direction(), vec![1.0, 0.0, 0.0]);
/// assert_eq!(line.distance_to_point(&Point::new(&[5.0, 3.0, 4.0])?)?, 5.0);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Line(Multivector);

impl Line {
    /// The line through `p` and `q` (the join P ∨ Q), with direction w_p w_q (q − p) for
    /// points of weights w_p, w_q (so q − p for points built by [`Point::new`]). One point may
    /// be ideal: a point joined with the ideal point of d is the line through it along ±d.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`]; [`AlgebraError::Degenerate`] when the points
    /// coincide to within round-off, or when both are ideal (they span a line at infinity).
    pub fn through(p: &Point, q: &Point) -> Result<Line, AlgebraError> {
        let m = p.0.try_product(&q.0, super::Product::Regressive)?;
        let scale = p.weight().abs() * q.0.max_abs() + q.weight().abs() * p.0.max_abs();
        if negligible(weight_norm(&m), scale) {
            let reason = if p.weight() == 0.0 && q.weight() == 0.0 {
                "both points are at infinity"
            } else {
                "the points coincide"
            };
            return Err(AlgebraError::Degenerate {
                operation: "the line through two points",
                reason,
            });
        }
        Ok(Line(m))
    }

    /// The line through the point at `point` with direction `direction` (N = `point.len()`):
    /// the join of the point and the ideal point of the direction, with
    /// [`direction`](Line::direction) exactly `direction`.
    ///
    /// ```
    /// use rotorflow::algebra::pga::Line;
    /// let line = Line::from_point_direction(&[1.0, 2.0, 3.0], &[0.0, 0.0, 2.0])?;
    /// assert_eq!(line.direction(), vec![0.0, 0.0, 2.0]);
    /// assert_eq!(line.point_nearest_origin(), vec![1.0, 2.0, 0.0]);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`]; [`AlgebraError::NonFinite`];
    /// [`AlgebraError::ZeroLength`] for a zero direction; [`AlgebraError::WrongSignature`]
    /// for N < 2; [`AlgebraError::DimensionTooLarge`].
    pub fn from_point_direction(point: &[f64], direction: &[f64]) -> Result<Line, AlgebraError> {
        super::error::check_same_dim(point.len(), direction.len())?;
        let p = Point::new(point)?;
        let d = Point::ideal(direction)?;
        Ok(Line(p.0.regressive(&d.0)))
    }

    /// Wraps an (N − 1)-vector of Cl(N, 0, 1) that is a finite line.
    ///
    /// # Errors
    /// [`AlgebraError::WrongSignature`]; [`AlgebraError::NonFinite`];
    /// [`AlgebraError::MixedGrades`] for other grades; [`AlgebraError::NotALine`] when the
    /// element is not a blade (in 3D: the Plücker condition d · (p × d) = 0 fails, relative
    /// deviation above 1e-12) or has no direction (zero, or a line at infinity).
    pub fn from_multivector(m: Multivector) -> Result<Line, AlgebraError> {
        let n = euclidean_dim(m.signature(), "a line")?;
        check_finite(m.as_slice(), "line")?;
        check_grade(&m, n - 1, "line")?;
        if weight_norm(&m) == 0.0 {
            return Err(AlgebraError::NotALine {
                reason: "it has no direction (zero, or a line at infinity)",
                deviation: 0.0,
            });
        }
        // An (N − 1)-vector is a blade exactly when its complement, a bivector B, has
        // B ∧ B = 0.
        let b = m.right_complement() * (1.0 / m.max_abs());
        let deviation = b.wedge(&b).max_abs();
        if !within(deviation, 1e-12) {
            return Err(AlgebraError::NotALine {
                reason: "it is not a blade (not the join of two points)",
                deviation,
            });
        }
        Ok(Line(m))
    }

    /// The Euclidean dimension N.
    pub fn dim(&self) -> usize {
        self.0.dim() - 1
    }

    /// The direction d, as stored (its length is the line's weight: q − p for the line
    /// through the points p and q).
    pub fn direction(&self) -> Vec<f64> {
        let (sig, n) = (self.0.signature(), self.dim());
        (0..n)
            .map(|i| {
                let (mask, sign) = direction_blade(sig, n, i);
                // + 0.0 turns the −0.0 of a sign flip into 0.0.
                sign * self.0.coefficient(mask) + 0.0
            })
            .collect()
    }

    /// The moment p ∧ d, for any point p on the line and d its [`direction`](Line::direction):
    /// the bivector whose 3D dual (M₂₃, −M₁₃, M₁₂) is the Plücker moment p × d. It is zero
    /// exactly for lines through the origin.
    pub fn moment(&self) -> Bivector {
        let (sig, n) = (self.0.signature(), self.dim());
        let mut m = Bivector::zero(n);
        for i in 0..n {
            for j in i + 1..n {
                let (mask, sign) = moment_blade(sig, n, i, j);
                m.set(i, j, sign * self.0.coefficient(mask) + 0.0);
            }
        }
        m
    }

    /// The point of the line nearest the origin, p − (p·d̂) d̂ = −(d ⌋ (p ∧ d)) / |d|².
    pub fn point_nearest_origin(&self) -> Vec<f64> {
        let (d, m) = self.unit_scaled();
        let dd: f64 = d.iter().map(|c| c * c).sum();
        (0..self.dim())
            .map(|j| {
                0.0 - d
                    .iter()
                    .enumerate()
                    .map(|(i, di)| di * m.get(i, j))
                    .sum::<f64>()
                    / dd
            })
            .collect()
    }

    /// The Euclidean distance from the point `x` to the line, |(x − p) ∧ d| / |d| =
    /// |x ∧ d − p ∧ d| / |d|.
    ///
    /// # Errors
    /// [`AlgebraError::PointAtInfinity`] for an ideal point; [`AlgebraError::DimensionMismatch`].
    pub fn distance_to_point(&self, x: &Point) -> Result<f64, AlgebraError> {
        super::error::check_same_dim(self.dim(), x.dim())?;
        let x = x.coordinates()?;
        let (d, m) = self.unit_scaled();
        let mut off = Vec::with_capacity(m.as_slice().len());
        for i in 0..d.len() {
            for j in i + 1..d.len() {
                off.push(x[i] * d[j] - x[j] * d[i] - m.get(i, j));
            }
        }
        Ok(scaled_norm(&off) / scaled_norm(&d))
    }

    /// Direction and moment divided by the largest direction component, so that |d| ≥ 1
    /// and neither squares nor ratios underflow or overflow for tiny or huge weights.
    fn unit_scaled(&self) -> (Vec<f64>, Bivector) {
        let d = self.direction();
        let s = d.iter().fold(0.0f64, |a, c| a.max(c.abs()));
        let d: Vec<f64> = d.iter().map(|c| c / s).collect();
        let mut m = self.moment();
        for c in m.as_mut_slice() {
            *c /= s;
        }
        (d, m)
    }

    /// The point where the line meets `plane` (the meet L ∧ A). For a line parallel to the
    /// plane (d · a = 0 to within round-off) it is the ideal point of the line's direction:
    /// weight exactly 0, so [`Point::coordinates`] reports [`AlgebraError::PointAtInfinity`].
    ///
    /// ```
    /// use rotorflow::algebra::pga::{Line, Plane};
    /// let line = Line::from_point_direction(&[1.0, 1.0, 0.0], &[0.0, 0.0, 1.0])?;
    /// let x = line.meet_plane(&Plane::new(&[0.0, 0.0, 1.0], 4.0)?)?.coordinates()?;
    /// assert_eq!(x, vec![1.0, 1.0, 4.0]);
    /// // A parallel plane meets it at infinity.
    /// let ideal = line.meet_plane(&Plane::new(&[1.0, 0.0, 0.0], 4.0)?)?;
    /// assert_eq!(ideal.weight(), 0.0);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`]; [`AlgebraError::Degenerate`] when the line lies
    /// in the plane (the meet vanishes to within round-off).
    pub fn meet_plane(&self, plane: &Plane) -> Result<Point, AlgebraError> {
        let mut x = self.0.try_product(&plane.0, super::Product::Wedge)?;
        if negligible(x.max_abs(), self.0.max_abs() * plane.0.max_abs()) {
            return Err(AlgebraError::Degenerate {
                operation: "the meet of a line and a plane",
                reason: "the line lies in the plane",
            });
        }
        let w = (1usize << self.dim()) - 1;
        if negligible(
            x.as_slice()[w],
            weight_norm(&self.0) * weight_norm(&plane.0),
        ) {
            x.as_mut_slice()[w] = 0.0;
        }
        Ok(Point(x))
    }

    /// The plane through this line and the point `p` in 3D (the join L ∨ P). Its normal is
    /// d × (x − p₀) for a point x of weight 1 and p₀ on the line. `p` may be ideal: the plane
    /// through the line parallel to that direction.
    ///
    /// ```
    /// use rotorflow::algebra::pga::{Line, Point};
    /// // The e₁ axis and the point (0, 1, 0) span the plane x₃ = 0.
    /// let line = Line::from_point_direction(&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0])?;
    /// let (normal, d) = line.join_point(&Point::new(&[0.0, 1.0, 0.0])?)?.equation();
    /// assert!(normal[0] == 0.0 && normal[1] == 0.0 && normal[2] != 0.0 && d == 0.0);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::WrongSignature`] outside 3D (in N dimensions a line and a point span
    /// a 2-flat; [`join`] returns it); [`AlgebraError::SignatureMismatch`];
    /// [`AlgebraError::Degenerate`] when the point lies on the line (or is its direction).
    pub fn join_point(&self, p: &Point) -> Result<Plane, AlgebraError> {
        require_3d(
            self.0.signature(),
            "the join of a line and a point as a plane",
        )?;
        let y = self.0.try_product(&p.0, super::Product::Regressive)?;
        if negligible(weight_norm(&y), self.0.max_abs() * p.0.max_abs()) {
            return Err(AlgebraError::Degenerate {
                operation: "the join of a line and a point",
                reason: "the point lies on the line",
            });
        }
        Ok(Plane(y))
    }
}

multivector_newtype!(Line, "(N − 1)-vector");

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
    /// [`VERSOR_TOLERANCE`](super::VERSOR_TOLERANCE) · max(1, max |Mᵢ|²) (normalise drift with
    /// [`Multivector::normalize_versor`]).
    pub fn new(m: Multivector) -> Result<Motor, AlgebraError> {
        euclidean_dim(m.signature(), "a motor")?;
        check_unit_even_versor(&m, "motor", "M M̃ is not 1")?;
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
    /// bivector A with A² < 0 (a [`Line`] of 3D PGA; a [`Point`] of 2D PGA; in general the
    /// meet of two hyperplanes, an (N − 2)-flat). The axis may be given as a `Line`, a
    /// `Point` or a plain [`Multivector`]. The rotation turns in the orientation of A's
    /// Euclidean part: from eᵢ toward eⱼ for A = eᵢⱼ, right-handed about a 3D line's
    /// [`Line::direction`], and counter-clockwise about a 2D point of positive weight.
    ///
    /// ```
    /// use rotorflow::algebra::pga::{Line, Motor, Point};
    /// // A quarter turn about the vertical line through (1, 0, 0) takes (2, 0, 5) to (1, 1, 5).
    /// let axis = Line::from_point_direction(&[1.0, 0.0, 0.0], &[0.0, 0.0, 1.0])?;
    /// let m = Motor::from_axis_angle(&axis, std::f64::consts::FRAC_PI_2)?;
    /// let x = m.apply_point(&Point::new(&[2.0, 0.0, 5.0])?)?.coordinates()?;
    /// assert!((x[0] - 1.0).abs() < 1e-15 && (x[1] - 1.0).abs() < 1e-15 && (x[2] - 5.0).abs() < 1e-15);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
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
    pub fn from_axis_angle(
        axis: &impl AsRef<Multivector>,
        angle: f64,
    ) -> Result<Motor, AlgebraError> {
        let axis = axis.as_ref();
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
        Ok(Motor::product(
            &Motor::from_translation(t)?,
            &Motor::from_rotor(r)?,
        ))
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

    /// This motion followed by `next`: the motor `next · self`, which is `next * self`.
    /// The product of two motors of one space is always a motor; the only failure is two
    /// motors of different dimensions, which this method reports and the operator `*`
    /// (like every operator) panics on.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`] for motors of different dimensions.
    pub fn then(&self, next: &Motor) -> Result<Motor, AlgebraError> {
        Ok(Motor(
            next.0.try_product(&self.0, super::Product::Geometric)?,
        ))
    }

    /// The geometric product a · b of two motors of one space (the operator `*`).
    #[track_caller]
    pub(crate) fn product(a: &Motor, b: &Motor) -> Motor {
        Motor(a.0.geometric(&b.0))
    }

    /// The inverse motion M̃.
    pub fn inverse(&self) -> Motor {
        Motor(self.0.reverse())
    }

    /// M X M̃ for any element X of the same algebra, typed or not: a [`Point`], [`Line`],
    /// [`Plane`] or [`Motor`] comes back as the same type, a [`Multivector`] as a
    /// multivector (the [`Versor`](super::Versor) trait, callable without importing it).
    ///
    /// ```
    /// use rotorflow::algebra::pga::{Motor, Plane};
    /// let m = Motor::from_translation(&[0.0, 0.0, 2.0])?;
    /// let (normal, d) = m.apply(&Plane::new(&[0.0, 0.0, 1.0], 1.0)?)?.equation();
    /// assert_eq!((normal, d), (vec![0.0, 0.0, 1.0], 3.0));
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`] for an element of another dimension.
    pub fn apply<X>(&self, x: &X) -> <Motor as super::Versor<X>>::Output
    where
        Motor: super::Versor<X>,
    {
        <Motor as super::Versor<X>>::apply(self, x)
    }

    /// M X M̃ on a multivector of the same algebra.
    fn sandwich(&self, x: &Multivector) -> Result<Multivector, AlgebraError> {
        let mx = self.0.try_product(x, super::Product::Geometric)?;
        Ok(mx.geometric(&self.0.reverse()))
    }

    /// The moved point.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`].
    pub fn apply_point(&self, p: &Point) -> Result<Point, AlgebraError> {
        Ok(Point(self.sandwich(&p.0)?.grade(self.dim())))
    }

    /// The moved hyperplane.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`].
    pub fn apply_plane(&self, p: &Plane) -> Result<Plane, AlgebraError> {
        Ok(Plane(self.sandwich(&p.0)?.grade(1)))
    }

    /// The moved line.
    ///
    /// ```
    /// use rotorflow::algebra::pga::{Line, Motor};
    /// // A half turn about e₃ reverses the line along e₁ through (0, 1, 0).
    /// let m = Motor::from_plane_angle(3, 0, 1, std::f64::consts::PI)?;
    /// let l = m.apply_line(&Line::from_point_direction(&[0.0, 1.0, 0.0], &[1.0, 0.0, 0.0])?)?;
    /// let (d, p) = (l.direction(), l.point_nearest_origin());
    /// assert!((d[0] + 1.0).abs() < 1e-15 && (p[1] + 1.0).abs() < 1e-15);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`].
    pub fn apply_line(&self, l: &Line) -> Result<Line, AlgebraError> {
        Ok(Line(self.sandwich(&l.0)?.grade(self.dim() - 1)))
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
}

multivector_newtype!(Motor, "even multivector");

impl AsRef<Multivector> for Multivector {
    /// Lets [`join`] and [`meet`] take plain multivectors (lines, results of other joins)
    /// beside the typed points, planes and motors.
    fn as_ref(&self) -> &Multivector {
        self
    }
}

impl super::Versor<Multivector> for Motor {
    type Output = Result<Multivector, AlgebraError>;
    /// M X M̃ for any element X of the algebra.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`].
    fn apply(&self, x: &Multivector) -> Self::Output {
        self.sandwich(x)
    }
}

/// `Versor<X> for Motor` by the motor's own method for X.
macro_rules! motor_moves {
    ($($t:ident => $method:ident),*) => {$(
        impl super::Versor<$t> for Motor {
            type Output = Result<$t, AlgebraError>;
            #[doc = concat!("[`Motor::", stringify!($method), "`].")]
            ///
            /// # Errors
            /// [`AlgebraError::SignatureMismatch`].
            fn apply(&self, x: &$t) -> Self::Output {
                self.$method(x)
            }
        }
    )*};
}

motor_moves!(Point => apply_point, Line => apply_line, Plane => apply_plane);

impl super::Versor<Motor> for Motor {
    type Output = Result<Motor, AlgebraError>;
    /// M N M̃: the motion N carried by M (the same motion in the moved frame).
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`].
    fn apply(&self, n: &Motor) -> Self::Output {
        Ok(Motor(self.sandwich(&n.0)?.even()))
    }
}
