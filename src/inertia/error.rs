//! The error type of the inertia layer.

use super::BodyError;
use crate::algebra::AlgebraError;
use thiserror::Error;

/// Why an inertia map could not be built or applied.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum InertiaError {
    /// A matrix has the wrong shape for the dimension.
    ///
    /// How to fix: a mass tensor is N×N; a general map on bivectors is k×k with
    /// k = N(N−1)/2, in the lexicographic plane order 12, 13, …
    #[error("{what} has shape {rows}×{cols}, expected {expected}×{expected}")]
    WrongShape {
        /// Which input.
        what: &'static str,
        /// Rows given.
        rows: usize,
        /// Columns given.
        cols: usize,
        /// The required size.
        expected: usize,
    },
    /// A list has the wrong length.
    ///
    /// How to fix: N principal moments, or N(N−1)/2 plane moments in lexicographic order.
    #[error("{what} has {found} entries, expected {expected}")]
    WrongLength {
        /// Which input.
        what: &'static str,
        /// The required length.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// An input number is NaN or infinite.
    ///
    /// How to fix: pass finite numbers.
    #[error("{what} contains a non-finite value")]
    NonFinite {
        /// Which input.
        what: &'static str,
    },
    /// A matrix that must be symmetric is not.
    ///
    /// How to fix: pass (M + Mᵀ)/2 if the asymmetry is round-off.
    #[error("{what} is not symmetric: max |M − Mᵀ| = {deviation:e}")]
    NotSymmetric {
        /// Which input.
        what: &'static str,
        /// max |M_ij − M_ji|.
        deviation: f64,
    },
    /// A mass tensor has a negative eigenvalue: no mass distribution has it.
    ///
    /// How to fix: a physical J = ∫ x xᵀ dm is positive semi-definite. For a test body that
    /// is not physical (such as the 3D I = (2, 1, 2/3), which needs J₁ = −1/6), build the map
    /// from its plane moments with [`super::InertiaMap::from_plane_moments`].
    #[error(
        "mass tensor has a negative principal moment {moment:e} (index {index}, 0-based); no body has it"
    )]
    NegativeMoment {
        /// The principal index (ascending order).
        index: usize,
        /// The eigenvalue.
        moment: f64,
    },
    /// The map is singular: some plane has zero moment, so the angular velocity in that plane
    /// is undetermined by the momentum.
    ///
    /// How to fix: the body is flat in at least two directions (a rod, a point, a flat body
    /// in 2 of its N axes). Give it extent, or leave those planes out of the dynamics.
    #[error("inertia map is singular: plane moment {moment:e} of the principal plane p{}∧p{} (of {largest:e} the largest)", .plane.0 + 1, .plane.1 + 1)]
    DegeneratePlane {
        /// The principal plane (0-based principal axis indices, ascending moments).
        plane: (usize, usize),
        /// Its plane moment.
        moment: f64,
        /// The largest plane moment, for scale.
        largest: f64,
    },
    /// A general map on bivectors is not positive definite.
    ///
    /// How to fix: kinetic energy ½⟨ω, I(ω)⟩ must be positive for every ω ≠ 0.
    #[error("map on bivectors is not positive definite (smallest eigenvalue {smallest:e})")]
    NotPositiveDefinite {
        /// The smallest eigenvalue.
        smallest: f64,
    },
    /// Two objects of different dimension were combined.
    ///
    /// How to fix: use a bivector or rotor of the map's dimension N.
    #[error("dimension mismatch: map has dimension {map}, argument has dimension {argument}")]
    DimensionMismatch {
        /// The map's dimension N.
        map: usize,
        /// The argument's dimension.
        argument: usize,
    },
    /// A body could not be used.
    #[error(transparent)]
    Body(#[from] BodyError),
    /// An algebra operation failed.
    #[error(transparent)]
    Algebra(#[from] AlgebraError),
}
