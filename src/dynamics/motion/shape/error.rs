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
    /// A detection query on plain data (placed boxes and hulls, bounding boxes, a contact
    /// margin or normal, body pairs of the broad phase) was given data it cannot use; the
    /// message names the part and what is wrong with it.
    #[error("invalid {what}: {reason}")]
    InvalidQuery {
        /// The part of the query.
        what: &'static str,
        /// What is wrong with it.
        reason: String,
    },
}
