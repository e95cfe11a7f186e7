//! [`CompoundShape`]: a union of convex pieces, each at its own offset and rotation in the
//! body's axes. Collision runs piece by piece, so a non-convex body is a list of convex
//! ones.

use super::ShapeError;
use super::convex::{ConvexShape, check_placement};
use smallvec::SmallVec;

/// One convex piece of a [`CompoundShape`]: a shape placed in the body's own axes by the
/// offset of its centre and its rotation (row-major N × N, piece axes → body axes).
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    offset: SmallVec<[f64; 8]>,
    rotation: SmallVec<[f64; 64]>,
    shape: ConvexShape,
}

/// Largest |QᵀQ − I| entry accepted for a piece's rotation.
const ROTATION_TOLERANCE: f64 = 1e-9;

impl Piece {
    /// Returns the piece `shape` centred at `offset` and turned by `rotation` (row-major,
    /// piece axes → body axes), all in the body's own axes.
    ///
    /// # Errors
    /// [`ShapeError::DimensionMismatch`], [`ShapeError::NonFinite`], and
    /// [`ShapeError::NotARotation`] unless `rotation` is orthonormal with determinant +1
    /// (to 1e-9).
    pub fn new(shape: ConvexShape, offset: &[f64], rotation: &[f64]) -> Result<Self, ShapeError> {
        let n = shape.dim();
        check_placement(n, offset, rotation)?;
        let q = nalgebra::DMatrix::from_row_slice(n, n, rotation);
        let error = (q.transpose() * &q - nalgebra::DMatrix::identity(n, n)).amax();
        let determinant = q.determinant();
        if error > ROTATION_TOLERANCE || (determinant - 1.0).abs() > ROTATION_TOLERANCE * n as f64 {
            return Err(ShapeError::NotARotation {
                what: "piece rotation",
                error,
                determinant,
            });
        }
        Ok(Piece {
            offset: SmallVec::from_slice(offset),
            rotation: SmallVec::from_slice(rotation),
            shape,
        })
    }

    /// Returns the piece `shape` at `offset`, not turned.
    ///
    /// # Errors
    /// [`ShapeError::DimensionMismatch`] or [`ShapeError::NonFinite`] for the offset.
    pub fn translated(shape: ConvexShape, offset: &[f64]) -> Result<Self, ShapeError> {
        let n = shape.dim();
        let mut identity = SmallVec::<[f64; 64]>::from_elem(0.0, n * n);
        for i in 0..n {
            identity[i * n + i] = 1.0;
        }
        Self::new(shape, offset, &identity)
    }

    /// Returns the shape.
    pub fn shape(&self) -> &ConvexShape {
        &self.shape
    }

    /// Returns the offset of the piece's centre in the body's axes.
    pub fn offset(&self) -> &[f64] {
        &self.offset
    }

    /// Returns the rotation piece axes → body axes (row-major N × N).
    pub fn rotation(&self) -> &[f64] {
        &self.rotation
    }

    /// Writes the placement of the piece in space for a body placed at `position` with
    /// `rotation` (own axes → space): the piece's centre p + Q o and its axes Q R.
    ///
    /// # Errors
    /// [`ShapeError::DimensionMismatch`] for inputs or outputs of the wrong size,
    /// [`ShapeError::NonFinite`] for the placement.
    pub fn place(
        &self,
        position: &[f64],
        rotation: &[f64],
        piece_position: &mut [f64],
        piece_rotation: &mut [f64],
    ) -> Result<(), ShapeError> {
        let n = self.shape.dim();
        check_placement(n, position, rotation)?;
        if piece_position.len() != n || piece_rotation.len() != n * n {
            return Err(ShapeError::DimensionMismatch {
                what: "piece placement output",
                expected: n,
                found: piece_position.len(),
            });
        }
        for i in 0..n {
            let row = &rotation[i * n..(i + 1) * n];
            piece_position[i] = position[i]
                + row
                    .iter()
                    .zip(&self.offset)
                    .map(|(a, b)| a * b)
                    .sum::<f64>();
            for j in 0..n {
                piece_rotation[i * n + j] = (0..n).map(|k| row[k] * self.rotation[k * n + j]).sum();
            }
        }
        Ok(())
    }
}

/// A body's shape as a union of convex [`Piece`]s (a dumbbell, an L, a table): contact
/// with it is contact with any of its pieces.
#[derive(Clone, Debug, PartialEq)]
pub struct CompoundShape {
    dim: usize,
    pieces: Vec<Piece>,
}

impl CompoundShape {
    /// Returns the union of `pieces`.
    ///
    /// # Errors
    /// [`ShapeError::EmptyCompound`] for no piece, [`ShapeError::DimensionMismatch`] if
    /// the pieces differ in dimension.
    pub fn new(pieces: Vec<Piece>) -> Result<Self, ShapeError> {
        let dim = pieces.first().ok_or(ShapeError::EmptyCompound)?.shape.dim();
        if let Some(p) = pieces.iter().find(|p| p.shape.dim() != dim) {
            return Err(ShapeError::DimensionMismatch {
                what: "piece",
                expected: dim,
                found: p.shape.dim(),
            });
        }
        Ok(CompoundShape { dim, pieces })
    }

    /// Returns the dimension N.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Returns the pieces.
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces
    }

    /// Returns the radius of the smallest ball about the body's origin holding every
    /// piece's bounding ball.
    pub fn bounding_radius(&self) -> f64 {
        self.pieces
            .iter()
            .map(|p| p.offset.iter().map(|x| x * x).sum::<f64>().sqrt() + p.shape.bounding_radius())
            .fold(0.0, f64::max)
    }
}
