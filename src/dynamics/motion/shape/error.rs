//! [`ShapeError`]: why a convex shape, a compound or a placement was refused.

use thiserror::Error;

/// Why a shape, a compound shape or a placed shape could not be built.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ShapeError {
    /// A shape needs at least two dimensions.
    ///
    /// How to fix: give N ≥ 2 numbers (half-lengths, semi-axes, point coordinates).
    #[error("a shape needs at least 2 dimensions, got {dim}")]
    TooFewDimensions {
        /// The dimension given.
        dim: usize,
    },
    /// Two inputs that must share a dimension do not.
    ///
    /// How to fix: give every point, offset and rotation in the shape's dimension (a
    /// rotation has N × N entries).
    #[error("{what} has {found} numbers where {expected} are needed")]
    DimensionMismatch {
        /// What was given.
        what: &'static str,
        /// The numbers needed.
        expected: usize,
        /// The numbers given.
        found: usize,
    },
    /// A number is NaN or infinite.
    ///
    /// How to fix: give finite numbers.
    #[error("{what} contains a non-finite number ({value})")]
    NonFinite {
        /// What was given.
        what: &'static str,
        /// The offending number.
        value: f64,
    },
    /// A length that must be positive is zero or negative (a half-length, a semi-axis, a
    /// radius).
    ///
    /// How to fix: give a positive length; a flat shape is a hull or a capsule of
    /// positive radius, or any shape `.rounded(margin)`.
    #[error("{what} {value} at index {index} is not positive")]
    NonPositiveLength {
        /// What was given.
        what: &'static str,
        /// Its position in the input.
        index: usize,
        /// The number.
        value: f64,
    },
    /// A margin is negative.
    ///
    /// How to fix: give a margin ≥ 0.
    #[error("margin {margin} is negative")]
    NegativeMargin {
        /// The margin given.
        margin: f64,
    },
    /// The points of a hull do not span N dimensions: its convex hull is flat.
    ///
    /// How to fix: give at least N + 1 affinely independent points, or give the flat hull
    /// a thickness with `.rounded(margin)` of a full-dimensional core.
    #[error(
        "the {points} points of the hull span {rank} dimensions, not {dim} (at least {dim} + 1 affinely independent points are needed)"
    )]
    FlatHull {
        /// The number of points given.
        points: usize,
        /// The dimension of their affine hull.
        rank: usize,
        /// The dimension of space.
        dim: usize,
    },
    /// A rotation is not orthonormal with determinant +1.
    ///
    /// How to fix: give the rotation matrix row-major, own axes → space (for example from
    /// `Attitude::write_matrix`).
    #[error("{what} is not a rotation (QᵀQ differs from I by {error:e}, det {determinant})")]
    NotARotation {
        /// What was given.
        what: &'static str,
        /// The largest entry of |QᵀQ − I|.
        error: f64,
        /// Its determinant.
        determinant: f64,
    },
    /// A compound shape has no piece.
    ///
    /// How to fix: give at least one piece.
    #[error("a compound shape needs at least one piece")]
    EmptyCompound,
    /// A query has more dimensions than it supports (boxes: [`MAX_BOX_DIM`]).
    ///
    /// How to fix: use N ≤ `max`, or a support-function query (GJK) above it.
    ///
    /// [`MAX_BOX_DIM`]: crate::dynamics::motion::detect::sat::MAX_BOX_DIM
    #[error("{what} has {dim} dimensions, at most {max} are supported")]
    TooManyDimensions {
        /// What was given.
        what: &'static str,
        /// Its dimension.
        dim: usize,
        /// The largest dimension supported.
        max: usize,
    },
    /// A query needs at least one dimension.
    ///
    /// How to fix: give N ≥ 1.
    #[error("{what} needs at least one dimension, got 0")]
    ZeroDimension {
        /// What was given.
        what: &'static str,
    },
    /// A length that must be ≥ 0 is negative (a box half-length; zero is a flat box).
    ///
    /// How to fix: give lengths ≥ 0.
    #[error("{what} {value} at index {index} is negative")]
    NegativeLength {
        /// What was given.
        what: &'static str,
        /// Its position in the input.
        index: usize,
        /// The number.
        value: f64,
    },
    /// A matrix that must be a rotation is not orthogonal to the tolerance.
    ///
    /// How to fix: give the rotation row-major, own axes → space (for example from
    /// `Attitude::write_matrix`), orthonormal to `tolerance`.
    #[error("{what} is not orthogonal: |QᵀQ − I| = {error:e} > {tolerance:e}")]
    NotOrthogonal {
        /// What was given.
        what: &'static str,
        /// The largest entry of |QᵀQ − I| (NaN for a matrix with NaN).
        error: f64,
        /// The largest entry allowed.
        tolerance: f64,
    },
    /// A flat list of points or bounds does not hold a whole number of N-vectors.
    ///
    /// How to fix: give N numbers per point (body after body for bounding boxes).
    #[error("{what} has {numbers} numbers, not a multiple of N = {dim}")]
    NotAMultiple {
        /// What was given.
        what: &'static str,
        /// The numbers given.
        numbers: usize,
        /// The dimension N.
        dim: usize,
    },
    /// A placed hull has no vertex.
    ///
    /// How to fix: give at least one vertex (N numbers).
    #[error("a placed hull needs at least one vertex")]
    EmptyHull,
    /// A bounding box whose lower bound exceeds its upper bound on an axis.
    ///
    /// How to fix: give lower ≤ upper on every axis.
    #[error(
        "bounding box of body {body}, axis {axis}: lower bound {lower} exceeds upper bound {upper}"
    )]
    InvertedBounds {
        /// The body.
        body: usize,
        /// The axis.
        axis: usize,
        /// The lower bound.
        lower: f64,
        /// The upper bound.
        upper: f64,
    },
    /// More bodies than the broad phase indexes.
    ///
    /// How to fix: split the system; at most `max` bodies.
    #[error("{bodies} bodies, at most {max} are supported")]
    TooManyBodies {
        /// The bodies given.
        bodies: usize,
        /// The most supported.
        max: usize,
    },
    /// A body pair that is not two distinct indices below 2³¹.
    ///
    /// How to fix: give two different body indices.
    #[error("body pair ({i}, {j}): two distinct body indices below 2³¹ are needed")]
    InvalidBodyPair {
        /// The first index.
        i: usize,
        /// The second index.
        j: usize,
    },
    /// A direction that must be non-zero is zero (a contact normal).
    ///
    /// How to fix: give a non-zero direction.
    #[error("{what} is the zero vector")]
    ZeroVector {
        /// What was given.
        what: &'static str,
    },
}
