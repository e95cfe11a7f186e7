//! The error type of the inertia layer: bodies, inertia maps and the paper's tensor views.

use crate::algebra::AlgebraError;
use nalgebra::DVector;
use thiserror::Error;

/// Why a body, an inertia map or a tensor view could not be built, or a query could not be
/// answered.
///
/// Every variant carries the offending data. Inputs are named by the argument they came from
/// (`quantity`, for example `"half_edges"` or `"mass_tensor"`), and `index` says which
/// element (0-based) when the argument is a list; for a matrix it is row · ncols + column.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum InertiaError {
    /// The dimension is too small for this body.
    ///
    /// # How to fix
    /// Use at least `min` dimensions, for example `Body::solid_ball(2, r, rho)` for a disc.
    #[error("dimension {dim} is too small: this body needs at least {min}")]
    DimensionTooSmall {
        /// The dimension that was given.
        dim: usize,
        /// The smallest supported dimension.
        min: usize,
    },
    /// The dimension is outside the range a tensor view is defined or evaluated for.
    ///
    /// # How to fix
    /// The paper's contraction (eqs. 23–31) needs N ≥ 3 (eq. 30 has N − 3 extra indices);
    /// the literal Levi-Civita sum is evaluated up to
    /// [`MAX_LITERAL_CONTRACTION_DIM`](super::tensor::MAX_LITERAL_CONTRACTION_DIM); use
    /// [`ContractedInertia::from_mass_tensor`](super::tensor::ContractedInertia::from_mass_tensor)
    /// (closed form) beyond that.
    #[error("dimension {dim} is outside the supported range {min}..={max}")]
    UnsupportedDimension {
        /// The dimension given.
        dim: usize,
        /// The smallest supported dimension.
        min: usize,
        /// The largest supported dimension.
        max: usize,
    },
    /// Two objects of different dimension were combined.
    ///
    /// # How to fix
    /// Use a bivector, rotor or \[ω\] of the map's or tensor's dimension N.
    #[error("`{quantity}` has dimension {found}, expected {expected}")]
    DimensionMismatch {
        /// Which argument.
        quantity: &'static str,
        /// The dimension of the map or tensor.
        expected: usize,
        /// The argument's dimension.
        found: usize,
    },
    /// A list that must not be empty was empty.
    ///
    /// # How to fix
    /// Pass at least one element (point, simplex, facet or part).
    #[error("`{quantity}` is empty")]
    Empty {
        /// The argument that was empty.
        quantity: &'static str,
    },
    /// A list or vector has the wrong length.
    ///
    /// # How to fix
    /// Give one mass per position, N entries per point in N dimensions, N+1 vertices for an
    /// N-simplex, N principal second moments, N(N−1)/2 plane moments in lexicographic order,
    /// and so on; `expected` says how many.
    #[error("{}", length_message(quantity, *index, *expected, *found))]
    LengthMismatch {
        /// The argument with the wrong length.
        quantity: &'static str,
        /// Which element of the argument, if it is a list.
        index: Option<usize>,
        /// The required length.
        expected: usize,
        /// The length that was given.
        found: usize,
    },
    /// A matrix has the wrong shape.
    ///
    /// # How to fix
    /// A mass tensor or rotation is N×N; a general map on bivectors is k×k with
    /// k = N(N−1)/2, in the lexicographic plane order 12, 13, …
    #[error("`{quantity}` is {rows}×{cols}, expected {expected}×{expected}")]
    WrongShape {
        /// Which argument.
        quantity: &'static str,
        /// Rows given.
        rows: usize,
        /// Columns given.
        cols: usize,
        /// The required size.
        expected: usize,
    },
    /// A matrix that must be square is not (and no size is implied by other arguments).
    ///
    /// # How to fix
    /// J and \[ω\] are N×N.
    #[error("`{quantity}` is {rows}×{cols}, expected a square matrix")]
    NotSquare {
        /// Which argument.
        quantity: &'static str,
        /// Number of rows given.
        rows: usize,
        /// Number of columns given.
        cols: usize,
    },
    /// A number is NaN or infinite.
    ///
    /// # How to fix
    /// Pass finite numbers only.
    #[error("`{quantity}`{} is not finite: {value}", fmt_index(*.index))]
    NonFinite {
        /// The argument holding the number.
        quantity: &'static str,
        /// Which element of the argument, if it is a list, vector or matrix.
        index: Option<usize>,
        /// The offending value.
        value: f64,
    },
    /// A mass, density, length, radius or moment is zero or negative.
    ///
    /// # How to fix
    /// Masses, densities, half-edges, semi-axes, radii and moments of inertia must be
    /// strictly positive. A body that is flat in some direction is built from points or a
    /// mesh instead.
    #[error("`{quantity}`{} must be positive, got {value}", fmt_index(*.index))]
    NotPositive {
        /// The argument holding the number.
        quantity: &'static str,
        /// Which element of the argument, if it is a list.
        index: Option<usize>,
        /// The offending value.
        value: f64,
    },
    /// A matrix that must be symmetric is not.
    ///
    /// # How to fix
    /// Pass (M + Mᵀ)/2 if the asymmetry is round-off; the tolerance is
    /// [`SYMMETRY_TOLERANCE`](super::tolerance::SYMMETRY_TOLERANCE).
    #[error("{}", not_symmetric_message(quantity, *asymmetry))]
    NotSymmetric {
        /// Which argument.
        quantity: &'static str,
        /// max |Mᵢⱼ − Mⱼᵢ| / max |Mᵢⱼ|.
        asymmetry: f64,
    },
    /// \[ω\] is not skew-symmetric.
    ///
    /// # How to fix
    /// Pass the skew matrix of a bivector, \[ω\]ⱼᵢ = −\[ω\]ᵢⱼ, zero diagonal.
    #[error("`{quantity}` is not skew-symmetric: relative residual {residual:e}")]
    NotSkewSymmetric {
        /// Which argument.
        quantity: &'static str,
        /// max |ωᵢⱼ + ωⱼᵢ| / max |ωᵢⱼ|.
        residual: f64,
    },
    /// A mass tensor has a negative eigenvalue: no mass distribution has it.
    ///
    /// # How to fix
    /// A physical J = ∫ x xᵀ dm is positive semi-definite. For a test body that is not
    /// physical (such as the 3D I = (2, 1, 2/3), which needs J₁ = −1/6), build the map from
    /// its plane moments with [`InertiaMap::from_plane_moments`](super::InertiaMap::from_plane_moments)
    /// or [`InertiaMap::from_classical_3d`](super::InertiaMap::from_classical_3d).
    #[error(
        "not a valid mass tensor: it has a negative principal second moment {moment:e} (index {index}, 0-based); no body has it"
    )]
    NegativeMoment {
        /// The principal index (ascending order, or the given order for a diagonal J).
        index: usize,
        /// The eigenvalue.
        moment: f64,
    },
    /// Three classical 3D moments of inertia violate the triangle inequality Iᵢ ≤ Iⱼ + Iₖ,
    /// which every mass distribution satisfies (Iᵢ = Jⱼ + Jₖ with Jⱼ, Jₖ ≥ 0).
    ///
    /// # How to fix
    /// Check the moments (they are the moments of inertia about e₁, e₂, e₃, not the second
    /// moments Jᵢ: for those use
    /// [`InertiaMap::from_principal_second_moments`](super::InertiaMap::from_principal_second_moments)).
    /// A test body that no mass distribution has (such as I = (2, 1, 2/3)) is a general map:
    /// [`InertiaMap::from_classical_3d`](super::InertiaMap::from_classical_3d) or
    /// [`InertiaMap::from_plane_moments`](super::InertiaMap::from_plane_moments).
    #[error("{}", not_physical_3d_message(moments, *index))]
    NotPhysical3d {
        /// The moments (I₁, I₂, I₃) given.
        moments: [f64; 3],
        /// The index (0-based) of the moment larger than the sum of the other two.
        index: usize,
    },
    /// A contracted value is negative, so its gyration radius √(𝕀_α/μ) is not real.
    ///
    /// # How to fix
    /// This happens only when J is not positive semidefinite, i.e. not a physical body.
    #[error("contracted value {index} is negative ({value:e}); no real gyration radius")]
    NegativeValue {
        /// Which value (0-based).
        index: usize,
        /// The value.
        value: f64,
    },
    /// The map is singular: a plane has (numerically) zero moment, so the angular velocity in
    /// that plane is undetermined by the momentum and a rotation in it costs no energy.
    ///
    /// # How to fix
    /// The body is flat in at least two directions (a point, a rod in 3D, a disc in 4D). Give
    /// it extent in at least one of the two directions.
    #[error(
        "inertia map is singular: plane moment {plane_moment:e} of the principal plane p{}∧p{} (of {largest:e} the largest)", .plane.0 + 1, .plane.1 + 1
    )]
    DegeneratePlane {
        /// The principal plane (0-based principal axis indices).
        plane: (usize, usize),
        /// First unit vector spanning the degenerate plane (in the body's axes).
        first: DVector<f64>,
        /// Second unit vector spanning the degenerate plane.
        second: DVector<f64>,
        /// Its plane moment Jₖ + Jₗ.
        plane_moment: f64,
        /// The largest plane moment, for scale.
        largest: f64,
    },
    /// A general map on bivectors is not positive definite.
    ///
    /// # How to fix
    /// Kinetic energy ½⟨ω, I(ω)⟩ must be positive for every ω ≠ 0.
    #[error("map on bivectors is not positive definite (smallest eigenvalue {smallest:e})")]
    NotPositiveDefinite {
        /// The smallest eigenvalue.
        smallest: f64,
    },
    /// A simplex has (numerically) zero volume.
    ///
    /// # How to fix
    /// Make sure the N+1 vertices are affinely independent; `relative_volume` is
    /// |det| / Π|edges| and must exceed
    /// [`DEGENERACY_TOLERANCE`](super::tolerance::DEGENERACY_TOLERANCE).
    #[error("simplex {simplex} is degenerate (relative volume {relative_volume:e})")]
    DegenerateSimplex {
        /// Which simplex (0 for [`Body::solid_simplex`](super::Body::solid_simplex)).
        simplex: usize,
        /// |det\[v₁ − v₀, …\]| / Πₖ |vₖ − v₀|, in \[0, 1\].
        relative_volume: f64,
    },
    /// A simplex or facet of a mesh has the wrong number of vertex indices.
    ///
    /// # How to fix
    /// In N dimensions a simplex lists N+1 vertex indices and a boundary facet lists N.
    #[error("simplex {simplex} lists {found} vertices, expected {expected}")]
    WrongSimplexSize {
        /// Which simplex or facet.
        simplex: usize,
        /// The required number of indices.
        expected: usize,
        /// The number given.
        found: usize,
    },
    /// A simplex or facet refers to a vertex that does not exist.
    ///
    /// # How to fix
    /// Indices are 0-based positions in the vertex list.
    #[error("simplex {simplex} refers to vertex {vertex}, but there are only {vertex_count}")]
    VertexIndexOutOfRange {
        /// Which simplex or facet.
        simplex: usize,
        /// The offending index.
        vertex: usize,
        /// Number of vertices given.
        vertex_count: usize,
    },
    /// Two facets of a closed boundary mesh induce the same orientation on a shared
    /// (N−2)-face, so one of them is flipped.
    ///
    /// # How to fix
    /// List the vertices of facet `facet` in the opposite order (swap two of them), so that
    /// every (N−2)-face is traversed in opposite directions by its two facets.
    #[error(
        "facet {facet} is flipped: it induces the same orientation as facet {neighbour} on their shared face {face:?}; swap two of its vertices"
    )]
    InconsistentOrientation {
        /// The facet that disagrees with the majority orientation (0-based).
        facet: usize,
        /// A neighbouring facet it disagrees with.
        neighbour: usize,
        /// The shared (N−2)-face, as sorted vertex indices.
        face: Vec<usize>,
    },
    /// The signed volumes of a mesh add up to (numerically) zero.
    ///
    /// # How to fix
    /// With [`SimplexOrientation::Signed`](super::SimplexOrientation::Signed) every simplex
    /// must have the same orientation (a tiling) or the facets must form a consistently
    /// oriented closed boundary. A tiling listed in arbitrary vertex order needs
    /// [`SimplexOrientation::Unsigned`](super::SimplexOrientation::Unsigned).
    #[error(
        "mesh volume vanishes: signed sum {signed_volume:e}, sum of absolute volumes {unsigned_volume:e}"
    )]
    ZeroMeshVolume {
        /// The sum of signed simplex volumes.
        signed_volume: f64,
        /// The sum of absolute simplex volumes.
        unsigned_volume: f64,
    },
    /// A mesh produced a mass tensor with a clearly negative eigenvalue, which no mass
    /// distribution has.
    ///
    /// # How to fix
    /// The mesh overlaps itself or is inconsistently oriented. Check facet orientation or use
    /// [`SimplexOrientation::Unsigned`](super::SimplexOrientation::Unsigned) for a tiling.
    #[error(
        "mesh is inconsistent: mass tensor eigenvalues range from {min_moment:e} to {max_moment:e}"
    )]
    InconsistentMesh {
        /// The smallest eigenvalue of the assembled J.
        min_moment: f64,
        /// The largest eigenvalue of the assembled J.
        max_moment: f64,
    },
    /// A matrix given as a rotation or orthogonal map is not orthogonal.
    ///
    /// # How to fix
    /// Pass a matrix with QᵀQ = 1 (within
    /// [`ORTHOGONALITY_TOLERANCE`](super::tolerance::ORTHOGONALITY_TOLERANCE)), for example
    /// one re-orthonormalised by a QR or polar decomposition.
    #[error("matrix is not orthogonal: max |QᵀQ − 1| = {deviation:e} (tolerance {tolerance:e})")]
    NotOrthogonal {
        /// The largest entry of |QᵀQ − 1|.
        deviation: f64,
        /// The tolerance that was exceeded.
        tolerance: f64,
    },
    /// An orthogonal matrix given as a rotation is a reflection (det Q = −1).
    ///
    /// # How to fix
    /// Pass a rotation, or use
    /// [`Body::orthogonally_transformed`](super::Body::orthogonally_transformed) for a mirror
    /// image.
    #[error("matrix is a reflection (det = {determinant}), not a rotation")]
    Reflection {
        /// The determinant (close to −1).
        determinant: f64,
    },
    /// The computed mass, centre of mass, mass tensor or volume overflowed.
    ///
    /// # How to fix
    /// Rescale lengths or densities; the result does not fit in an f64.
    #[error("the computed `{quantity}` is not finite (overflow)")]
    NonFiniteResult {
        /// Which computed quantity overflowed.
        quantity: &'static str,
    },
    /// The body is flat: its mass tensor has (numerically) zero second moment along
    /// `direction`, so the body lies in the hyperplane orthogonal to it.
    ///
    /// # How to fix
    /// This is a property of the body, not an input error. A body flat in one direction still
    /// has an invertible inertia map
    /// ([`Body::check_inertia_invertible`](super::Body::check_inertia_invertible)); a body
    /// flat in two directions does not.
    #[error(
        "body is flat along direction {direction:?}: second moment {moment:e} vs largest {largest_moment:e}"
    )]
    FlatBody {
        /// Unit vector (in the body's axes) along which the body has no extent.
        direction: DVector<f64>,
        /// The second moment along `direction` (an eigenvalue of J).
        moment: f64,
        /// The largest eigenvalue of J, for scale.
        largest_moment: f64,
    },
    /// An algebra operation failed.
    #[error(transparent)]
    Algebra(#[from] AlgebraError),
}

fn fmt_index(index: Option<usize>) -> String {
    match index {
        Some(i) => format!("[{i}]"),
        None => String::new(),
    }
}

fn not_symmetric_message(quantity: &str, asymmetry: f64) -> String {
    if quantity == "mass_tensor" {
        format!("not a valid mass tensor: it is not symmetric (relative asymmetry {asymmetry:e})")
    } else {
        format!("`{quantity}` is not symmetric: relative asymmetry {asymmetry:e}")
    }
}

/// A list named by its argument (`masses`) has a length; a list named in words
/// (`plane moments`) has entries.
fn length_message(quantity: &str, index: Option<usize>, expected: usize, found: usize) -> String {
    if quantity.contains(' ') {
        format!("{quantity} has {found} entries, expected {expected}")
    } else {
        format!(
            "`{quantity}`{} has length {found}, expected {expected}",
            fmt_index(index)
        )
    }
}

fn not_physical_3d_message(moments: &[f64; 3], index: usize) -> String {
    let (j, k) = ((index + 1) % 3, (index + 2) % 3);
    let (lo, hi) = (j.min(k), j.max(k));
    format!(
        "moments of inertia ({}, {}, {}) violate the triangle inequality: I{} = {} exceeds I{} + I{} = {}, so no body has them (they are not second moments either: for those use InertiaMap::from_principal_second_moments); for a test body use InertiaMap::from_classical_3d or InertiaMap::from_plane_moments",
        moments[0],
        moments[1],
        moments[2],
        index + 1,
        moments[index],
        lo + 1,
        hi + 1,
        moments[lo] + moments[hi]
    )
}
