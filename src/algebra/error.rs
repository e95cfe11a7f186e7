//! The error type of the algebra layer.

use super::Signature;
use thiserror::Error;

/// Everything that can go wrong when building or combining elements of the algebra.
///
/// Every variant says what was wrong with the input and, in its documentation, how to fix it.
/// Operations on well-formed values of equal dimension never fail; the errors come from
/// constructors that take user data, from conversions, and from the checked (`try_`) variants
/// of the operators.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum AlgebraError {
    /// Two operands live in spaces of different dimension.
    ///
    /// How to fix: build both operands with the same `dim`, or embed the smaller one first.
    #[error(
        "dimension mismatch: left operand has dimension {left}, right operand has dimension {right}"
    )]
    DimensionMismatch {
        /// Dimension of the left operand.
        left: usize,
        /// Dimension of the right operand.
        right: usize,
    },
    /// Two multivectors belong to algebras with different signatures.
    ///
    /// How to fix: build both in the same [`Signature`].
    #[error("signature mismatch: {left} vs {right}")]
    SignatureMismatch {
        /// Signature of the left operand.
        left: Signature,
        /// Signature of the right operand.
        right: Signature,
    },
    /// A slice of components has the wrong length for the requested dimension.
    ///
    /// How to fix: a vector in N dimensions has N components, a bivector N(N−1)/2 (in the
    /// lexicographic order 12, 13, …, 1N, 23, …), a rotor 2^(N−1), a multivector 2^N.
    #[error("wrong number of components for a {what}: expected {expected}, found {found}")]
    WrongComponentCount {
        /// What was being built ("vector", "bivector", …).
        what: &'static str,
        /// The number of components the dimension requires.
        expected: usize,
        /// The number of components given.
        found: usize,
    },
    /// The requested dimension exceeds what this type supports.
    ///
    /// How to fix: vectors and bivectors go up to [`super::MAX_DIM`]; types that store
    /// 2^N (multivectors) or 2^(N−1) (rotors) coefficients go up to
    /// [`super::MULTIVECTOR_MAX_DIM`].
    #[error("dimension {dim} is too large for a {what} (at most {max})")]
    DimensionTooLarge {
        /// What was being built.
        what: &'static str,
        /// The requested dimension.
        dim: usize,
        /// The largest supported dimension.
        max: usize,
    },
    /// A basis index is not below the dimension (indices in the API are 0-based).
    ///
    /// How to fix: use indices `0..dim`; user-facing text such as `e12` is 1-based.
    #[error("basis index {index} is out of range for dimension {dim} (indices are 0-based)")]
    IndexOutOfRange {
        /// The offending index.
        index: usize,
        /// The dimension.
        dim: usize,
    },
    /// A plane was named by the same index twice (e_i ∧ e_i = 0 is not a plane).
    ///
    /// How to fix: give two distinct indices.
    #[error("a plane needs two distinct basis indices, got {index} twice")]
    RepeatedIndex {
        /// The repeated index.
        index: usize,
    },
    /// An input number is NaN or infinite.
    ///
    /// How to fix: check the data for NaN or infinity before building the element.
    #[error("non-finite value in {what}")]
    NonFinite {
        /// Which input contained the non-finite value.
        what: &'static str,
    },
    /// The element has no inverse.
    ///
    /// How to fix: only elements whose left-multiplication map is non-singular are invertible
    /// (for example non-null vectors and versors).
    #[error("element is not invertible: {reason}")]
    NotInvertible {
        /// Why the inverse does not exist.
        reason: &'static str,
    },
    /// A matrix that should be skew-symmetric is not.
    ///
    /// How to fix: a bivector's matrix satisfies Aᵀ = −A; pass `(A − Aᵀ)/2` if the asymmetry is
    /// round-off.
    #[error(
        "matrix is not skew-symmetric: max |A + Aᵀ| = {deviation:e} exceeds the tolerance {tolerance:e}"
    )]
    NotSkewSymmetric {
        /// max |A_ij + A_ji|.
        deviation: f64,
        /// The tolerance that was applied.
        tolerance: f64,
    },
    /// A matrix is not square.
    ///
    /// How to fix: rotations and bivectors of ℝᴺ are N×N matrices.
    #[error("matrix is not square: {rows}×{cols}")]
    NotSquare {
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
    },
    /// A matrix is not a rotation (orthogonal with determinant +1).
    ///
    /// How to fix: orthonormalise it first (for example with
    /// [`super::Rotor::from_matrix_projected`], which takes the nearest rotation), or check
    /// that it is not a reflection (determinant −1).
    #[error(
        "matrix is not a rotation: max |QᵀQ − 1| = {orthogonality_error:e} (tolerance {tolerance:e}), det = {determinant}"
    )]
    NotARotation {
        /// max |(QᵀQ − 1)_ij|.
        orthogonality_error: f64,
        /// The determinant (must be +1).
        determinant: f64,
        /// The tolerance that was applied to the orthogonality error.
        tolerance: f64,
    },
    /// A multivector is not a rotor: not even, or not on Spin(N).
    ///
    /// How to fix: take `grade(0) + grade(2) + …` parts only, and normalise with
    /// [`super::Rotor::normalize`] if the deviation is drift.
    #[error("multivector is not a rotor: {reason} (deviation {deviation:e})")]
    NotARotor {
        /// What failed.
        reason: &'static str,
        /// Size of the failure.
        deviation: f64,
    },
    /// A multivector has parts of grades other than the one a conversion needs (for example
    /// a scalar part when converting to a [`super::Bivector`]).
    ///
    /// How to fix: take the part you want with `Multivector::grade(k)` first.
    #[error("not a pure {what}: {others} term(s) of grades other than {grade}")]
    MixedGrades {
        /// What was being built ("vector", "bivector").
        what: &'static str,
        /// The grade the conversion needs.
        grade: usize,
        /// How many non-zero terms have another grade.
        others: usize,
    },
    /// A rotor is too far from Spin(N) for a projection back onto it to mean anything.
    ///
    /// How to fix: normalisation removes round-off drift; an element this far away was not
    /// a rotor to begin with (check how it was built), or pass a larger tolerance to
    /// [`super::Rotor::try_normalize_eps`].
    #[error(
        "rotor is too far from Spin(N) to normalise: max |R R̃ − 1| = {distance:e} exceeds the tolerance {tolerance:e}"
    )]
    FarFromGroup {
        /// The measured distance max |R R̃ − 1| (may be NaN or infinite).
        distance: f64,
        /// The tolerance that was applied.
        tolerance: f64,
    },
    /// A bivector is too large for its exponential: beyond |B| = `f64::MAX`/2 a plane angle
    /// may overflow, and an infinite angle has no value mod 2π.
    ///
    /// How to fix: reduce the plane angles mod 2π (mod π for the half-angles of a rotor)
    /// before exponentiating.
    #[error("bivector norm {norm:e} is too large for the exponential (at most f64::MAX/2)")]
    AngleTooLarge {
        /// The norm |B| (may be infinite).
        norm: f64,
    },
    /// A text does not name a basis blade.
    ///
    /// How to fix: write `1` for the scalar and `e` with 1-based indices for the others:
    /// `e13`, `e1e3` or `e₁₃` (from dimension 10 on, `e1_10`).
    #[error("invalid blade name {name:?}: {reason}")]
    InvalidBladeName {
        /// The text that was given.
        name: String,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A zero (or numerically zero) element where a direction was needed.
    ///
    /// How to fix: give a non-zero element.
    #[error("{what} has zero length and cannot be normalised")]
    ZeroLength {
        /// What was being normalised.
        what: &'static str,
    },
    /// The operation is defined here only for a Euclidean signature.
    ///
    /// How to fix: the graded types and rotors model ℝᴺ; use [`super::Multivector`] products
    /// for other signatures.
    #[error("{operation} needs a Euclidean signature, got {signature}")]
    UnsupportedSignature {
        /// The operation.
        operation: &'static str,
        /// The signature that was given.
        signature: Signature,
    },
    /// An operation that needs a bivector got an element with other grades.
    ///
    /// How to fix: take the bivector part with `Multivector::grade(2)` if the other grades
    /// are round-off; the exponential of other elements is not provided.
    #[error("{operation} needs a bivector, but the element has parts of grade {grades:?}")]
    NotABivector {
        /// The operation.
        operation: &'static str,
        /// The grades other than 2 that are present, ascending.
        grades: Vec<usize>,
    },
    /// An element is not an even versor (V Ṽ = 1 with grades 0, 2, 4, … only).
    ///
    /// How to fix: build versors as products or exponentials; if the deviation is drift,
    /// renormalise first.
    #[error("element is not an even versor: {reason} (deviation {deviation:e})")]
    NotAVersor {
        /// What failed.
        reason: &'static str,
        /// Size of the failure.
        deviation: f64,
    },
    /// A versor has no real bivector logarithm (or none the closed form can pick).
    ///
    /// How to fix: such an element is −exp(B) for a B without a rotation part that could
    /// absorb the sign; work with the element itself, or with −V if only the transformation
    /// X ↦ V X Ṽ matters.
    #[error("the versor has no real bivector logarithm: {reason}")]
    NoLogarithm {
        /// Why.
        reason: &'static str,
    },
    /// The logarithm of a versor could not be recovered in f64: the exponential of the
    /// computed bivector differs from the versor by more than round-off.
    ///
    /// This happens only where V's coefficients span many orders of magnitude: boosts of
    /// rapidity beyond about 25 beside rotations (V's small eigenvalues e^(−φ) are then
    /// below the rounding of its large ones), or null parts far larger than the rest in
    /// signatures with several null vectors. How to fix: keep the bivector B you exponentiated
    /// instead of recovering it from V, or split the motion into smaller steps.
    #[error(
        "the logarithm is not determined in f64: exp(log V) differs from V by {residual:e} relative to max |Vᵢ|"
    )]
    LogarithmInaccurate {
        /// max |exp(log V) − V| / max(1, max |Vᵢ|).
        residual: f64,
    },
    /// The operation is implemented for this kind of signature only up to a dimension.
    ///
    /// How to fix: Euclidean Cl(N, 0, 0) and projective Cl(N − 1, 0, 1) signatures go to
    /// [`super::MULTIVECTOR_MAX_DIM`]; other signatures to the `max` given.
    #[error(
        "{operation} in a signature neither Euclidean nor projective is implemented up to N = {max}, got {signature}"
    )]
    UnsupportedDimension {
        /// The operation.
        operation: &'static str,
        /// The signature that was given.
        signature: Signature,
        /// The largest supported dimension.
        max: usize,
    },
    /// A result would exceed the range of f64.
    ///
    /// How to fix: scale the input down (for a boost, a rapidity above ≈ 710 overflows).
    #[error("{what} overflows f64")]
    Overflow {
        /// What overflowed.
        what: &'static str,
    },
    /// An even element is too far from its versor group for a normalisation to mean
    /// anything.
    ///
    /// How to fix: normalisation removes round-off drift; an element this far away was not
    /// a versor to begin with (check how it was built), or pass a larger tolerance to
    /// [`super::Multivector::try_normalize_versor_eps`].
    #[error(
        "element is too far from its versor group to normalise: max |M M̃ − 1| = {distance:e} exceeds the tolerance {tolerance:e}"
    )]
    VersorFarFromGroup {
        /// The measured distance max |M M̃ − 1|.
        distance: f64,
        /// The tolerance that was applied.
        tolerance: f64,
    },
    /// The operation needs another kind of algebra (for example projective Cl(N, 0, 1)).
    ///
    /// How to fix: build the element in the algebra named in the message.
    #[error("{operation} needs {expected}, got {signature}")]
    WrongSignature {
        /// The operation.
        operation: &'static str,
        /// The algebras it accepts.
        expected: &'static str,
        /// The signature that was given.
        signature: Signature,
    },
    /// A projective point has zero weight (a point at infinity, a direction), so it has no
    /// Euclidean coordinates.
    ///
    /// How to fix: a join or meet of parallel elements gives such a point; test the weight
    /// first, or read the direction from the multivector.
    #[error("the point is at infinity (weight {weight:e}) and has no Euclidean coordinates")]
    PointAtInfinity {
        /// The weight, the e₁…N coefficient.
        weight: f64,
    },
    /// A homogeneous matrix does not end in the row (0, …, 0, 1).
    ///
    /// How to fix: a rigid motion's (N+1)×(N+1) matrix is \[\[Q, t\], \[0, 1\]\]; divide by
    /// the corner entry if the matrix is only scaled.
    #[error("matrix is not homogeneous: its last row differs from (0, …, 0, 1) by {deviation:e}")]
    NotHomogeneous {
        /// max |last row − (0, …, 0, 1)|.
        deviation: f64,
    },
    /// A bivector is not a rotation axis: its square is not a negative scalar.
    ///
    /// How to fix: give the meet of N − 1 hyperplanes (a line in 3D, a point in 2D); a screw
    /// (rotation plus translation along the axis) is not simple, use `Multivector::exp`.
    #[error("not a rotation axis: {reason} (deviation {deviation:e})")]
    NotAnAxis {
        /// What failed.
        reason: &'static str,
        /// Size of the failure.
        deviation: f64,
    },
    /// A projective element is not a line: not a blade, or without a direction.
    ///
    /// How to fix: build lines as joins of points or meets of planes
    /// ([`super::pga::Line::through`], [`super::pga::Plane::meet`]).
    #[error("not a line: {reason} (deviation {deviation:e})")]
    NotALine {
        /// What failed.
        reason: &'static str,
        /// Size of the failure.
        deviation: f64,
    },
    /// A join or meet of elements in a special position has no element of the requested
    /// kind: two equal points span no line, parallel planes meet only at infinity, a line
    /// in a plane meets it everywhere.
    ///
    /// How to fix: test the configuration first, or use the untyped [`super::pga::join`]
    /// and [`super::pga::meet`], which return the (possibly zero or ideal) multivector.
    #[error("{operation} is degenerate: {reason}")]
    Degenerate {
        /// The operation.
        operation: &'static str,
        /// Which special position was met.
        reason: &'static str,
    },
    /// A conformal vector is not a point: it is not null (X² ≠ 0, a sphere or a plane).
    ///
    /// How to fix: build points with [`super::cga::up`]; a point moved by a versor stays a
    /// point, so a large deviation means the element was built as something else.
    #[error("not a conformal point: {reason} (deviation {deviation:e})")]
    NotAPoint {
        /// What failed.
        reason: &'static str,
        /// Size of the failure.
        deviation: f64,
    },
    /// A conformal vector is not a real sphere or plane (its square is not positive: a
    /// point or an imaginary sphere).
    ///
    /// How to fix: build spheres and planes with [`super::cga::sphere`] and
    /// [`super::cga::plane`].
    #[error("not a sphere or plane: {reason} (deviation {deviation:e})")]
    NotASphere {
        /// What failed.
        reason: &'static str,
        /// Size of the failure.
        deviation: f64,
    },
    /// A number that must be positive is not (a scale factor, a radius).
    ///
    /// How to fix: pass a finite number above zero.
    #[error("{what} must be positive, got {value}")]
    NotPositive {
        /// What the number is.
        what: &'static str,
        /// The value given.
        value: f64,
    },
}

/// value ≤ tolerance, and false when either is NaN: a NaN measure or tolerance never passes.
#[inline]
pub(crate) fn within(value: f64, tolerance: f64) -> bool {
    value <= tolerance
}

/// |value| at the round-off level of sums and differences of numbers of size `scale`: the
/// sign and direction of such a value carry no information, so the geometric constructors
/// treat it as zero (parallel planes, coincident points, a point at infinity).
#[inline]
pub(crate) fn negligible(value: f64, scale: f64) -> bool {
    value.abs() <= 64.0 * f64::EPSILON * scale
}

/// Checks that every number in `values` is finite.
pub(crate) fn check_finite(values: &[f64], what: &'static str) -> Result<(), AlgebraError> {
    if values.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(AlgebraError::NonFinite { what })
    }
}

impl AlgebraError {
    /// Returns `Err(DimensionTooLarge)` for a `what` of dimension `dim` above `max`.
    pub(crate) fn check_dimension(
        what: &'static str,
        dim: usize,
        max: usize,
    ) -> Result<(), AlgebraError> {
        if dim > max {
            Err(AlgebraError::DimensionTooLarge { what, dim, max })
        } else {
            Ok(())
        }
    }
}

/// Panics with a clear message unless (i, j) is a plane of dimension n: both indices in
/// range and different.
#[track_caller]
#[inline]
pub(crate) fn assert_plane(i: usize, j: usize, n: usize) {
    assert!(
        i < n && j < n && i != j,
        "rotorflow: invalid plane ({i}, {j}) in dimension {n}"
    );
}

/// Panics with a clear message when two dimensions differ; used by the operators.
#[track_caller]
#[inline]
pub(crate) fn assert_same_dim(left: usize, right: usize) {
    if left != right {
        panic!(
            "rotorflow: dimension mismatch: left operand has dimension {left}, right operand has dimension {right}"
        );
    }
}

/// Returns `Err(DimensionMismatch)` when two dimensions differ.
#[inline]
pub(crate) fn check_same_dim(left: usize, right: usize) -> Result<(), AlgebraError> {
    if left == right {
        Ok(())
    } else {
        Err(AlgebraError::DimensionMismatch { left, right })
    }
}
