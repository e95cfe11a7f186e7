//! The catalogue of N-dimensional bodies: mass, centre of mass, mass tensor and volume.
//!
//! A [`Body`] holds the mass m, the centre of mass c and the mass tensor
//! J = ∫ (x − c)(x − c)ᵀ dm about the centre of mass (DESIGN.md part 1, "Inertia";
//! REFERENCES.md §0). J is the N×N second-moment matrix, not the 3D inertia tensor. In the
//! principal frame J = diag(J_1, …, J_N), and the inertia map is diagonal on the basis
//! planes with plane moments J_i + J_j. In 3D the classical principal moments are
//! I_1 = J_2 + J_3, I_2 = J_1 + J_3 and I_3 = J_1 + J_2.
//!
//! # Table of contents
//!
//! - Point sets: [`Body::point_masses`], [`Body::cuboid_vertices`] (the paper's tesseract,
//!   eq. 69), [`Body::regular_simplex_vertices`], [`Body::pentachoron_eq73`] (the paper's
//!   5-cell, eq. 73), [`Body::cross_polytope_vertices`].
//! - Solids and shells: [`Body::solid_cuboid`], [`Body::solid_ellipsoid`],
//!   [`Body::solid_ball`], [`Body::hypersphere_shell`], [`Body::solid_simplex`].
//! - Meshes and assemblies: [`Body::simplicial_mesh`], [`Body::closed_boundary_mesh`],
//!   [`Body::composite`], [`Body::from_mass_properties`].
//! - Transformations: [`Body::rotated`], [`Body::translated`], [`Body::placed`],
//!   [`Body::with_mass`].
//! - Queries: [`Body::mass_tensor_about`], [`Body::principal_moments`],
//!   [`Body::principal_frame`], [`Body::plane_moments`], [`Body::principal_plane_moments`],
//!   [`Body::flat_directions`], [`Body::check_full_rank`],
//!   [`Body::check_inertia_invertible`].
//!
//! # Formulas (REFERENCES.md §6 unless stated)
//!
//! | body | volume | J (principal) |
//! |---|---|---|
//! | solid cuboid, half-edges a_i | Π 2a_i | m a_i²/3 |
//! | solid ellipsoid, semi-axes a_i | V_N Π a_i | m a_i²/(N+2) |
//! | solid ball, radius R | V_N R^N | m R²/(N+2) |
//! | shell S^{N−1}, radius R | — (area N V_N R^{N−1}) | m R²/N |
//! | solid simplex, vertices v_k | \|det\|/N! | vertex formula below |
//! | 2^N vertices (±a_i) | — | 2^N μ a_i² |
//! | 2N vertices ±r e_i | — | 2 μ r² |
//! | regular simplex, circumradius r | — | (N+1) μ r²/N |
//!
//! Here V_N = π^{N/2}/Γ(N/2 + 1) is the volume of the unit N-ball (paper eq. 99) and μ is the
//! mass of one vertex. The simplex vertex formula is
//! ∫ x xᵀ dV = Vol/((N+1)(N+2)) [Σ v_k v_kᵀ + (Σ v_k)(Σ v_k)ᵀ].

use crate::numeric::{max_abs_matrix as max_abs, sorted_symmetric_eigen as sorted_eigen};
use nalgebra::{DMatrix, DVector};
use smallvec::SmallVec;
use thiserror::Error;

/// Largest allowed entry of |QᵀQ − 1| for a matrix accepted as orthogonal by
/// [`Body::rotated`].
///
/// Products of a few dozen rotation matrices stay below 1e-13; 1e-10 rejects anything that
/// is not meant to be orthogonal while accepting matrices assembled from rounded angles.
pub const ORTHOGONALITY_TOLERANCE: f64 = 1e-10;

/// Relative volume below which a simplex counts as degenerate.
///
/// The relative volume of a simplex is |det[v_1 − v_0, …, v_N − v_0]| / Π_k |v_k − v_0|.
/// It lies in [0, 1] (Hadamard's inequality) and is 1 for a right-angled corner. Rounding
/// makes a truly flat simplex come out near 1e-16; 1e-12 leaves a margin of four orders.
pub const DEGENERACY_TOLERANCE: f64 = 1e-12;

/// Default relative tolerance for [`Body::flat_directions`], [`Body::check_full_rank`] and
/// [`Body::check_inertia_invertible`].
///
/// The symmetric eigensolver returns eigenvalues with absolute error of order
/// ε · max_i J_i (ε = 2.2e-16), so an eigenvalue below 1e-12 · max_i J_i is zero within a
/// margin of about 4500 ulp.
pub const FLATNESS_TOLERANCE: f64 = 1e-12;

/// Tolerance for the symmetry and positive-semidefiniteness checks on a mass tensor given by
/// the caller or assembled from a mesh, relative to its largest entry or eigenvalue.
const MATRIX_CHECK_TOLERANCE: f64 = 1e-9;

/// Why a body could not be built or a query could not be answered.
///
/// Every variant carries the offending data. Quantities are named by the argument they came
/// from (for example `"half_edges"`), and `index` says which element (0-based) when the
/// argument is a list.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum BodyError {
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
    /// N-simplex, and so on; `expected` says how many.
    #[error("`{quantity}`{} has length {found}, expected {expected}", fmt_index(*.index))]
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
    /// A number is NaN or infinite.
    ///
    /// # How to fix
    /// Pass finite numbers only.
    #[error("`{quantity}`{} is not finite: {value}", fmt_index(*.index))]
    NonFinite {
        /// The argument holding the number.
        quantity: &'static str,
        /// Which element of the argument, if it is a list or vector.
        index: Option<usize>,
        /// The offending value.
        value: f64,
    },
    /// A mass, density, length or radius is zero or negative.
    ///
    /// # How to fix
    /// Masses, densities, half-edges, semi-axes and radii must be strictly positive. A body
    /// that is flat in some direction is built from points or a mesh instead.
    #[error("`{quantity}`{} must be positive, got {value}", fmt_index(*.index))]
    NotPositive {
        /// The argument holding the number.
        quantity: &'static str,
        /// Which element of the argument, if it is a list.
        index: Option<usize>,
        /// The offending value.
        value: f64,
    },
    /// A simplex has (numerically) zero volume.
    ///
    /// # How to fix
    /// Make sure the N+1 vertices are affinely independent; `relative_volume` is
    /// |det| / Π|edges| and must exceed [`DEGENERACY_TOLERANCE`].
    #[error("simplex {simplex} is degenerate (relative volume {relative_volume:e})")]
    DegenerateSimplex {
        /// Which simplex (0 for [`Body::solid_simplex`]).
        simplex: usize,
        /// |det[v_1 − v_0, …]| / Π_k |v_k − v_0|, in [0, 1].
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
    /// The signed volumes of a mesh add up to (numerically) zero.
    ///
    /// # How to fix
    /// With [`SimplexOrientation::Signed`] every simplex must have the same orientation
    /// (a tiling) or the facets must form a consistently oriented closed boundary. A tiling
    /// listed in arbitrary vertex order needs [`SimplexOrientation::Unsigned`].
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
    /// The mesh overlaps itself or is inconsistently oriented. Check facet orientation or
    /// use [`SimplexOrientation::Unsigned`] for a tiling.
    #[error(
        "mesh is inconsistent: mass tensor eigenvalues range from {min_moment:e} to {max_moment:e}"
    )]
    InconsistentMesh {
        /// The smallest eigenvalue of the assembled J.
        min_moment: f64,
        /// The largest eigenvalue of the assembled J.
        max_moment: f64,
    },
    /// A matrix given as a rotation is not orthogonal.
    ///
    /// # How to fix
    /// Pass a matrix with QᵀQ = 1 (within [`ORTHOGONALITY_TOLERANCE`]), for example one
    /// re-orthonormalised by a QR or polar decomposition.
    #[error("matrix is not orthogonal: max |QᵀQ − 1| = {deviation:e} (tolerance {tolerance:e})")]
    NotOrthogonal {
        /// The largest entry of |QᵀQ − 1|.
        deviation: f64,
        /// The tolerance that was exceeded.
        tolerance: f64,
    },
    /// A matrix given as a mass tensor is not symmetric or not positive semidefinite.
    ///
    /// # How to fix
    /// A mass tensor is symmetric and has no negative eigenvalue.
    #[error("not a valid mass tensor: {reason:?} (measure {measure:e})")]
    InvalidMassTensor {
        /// Which property failed.
        reason: MassTensorDefect,
        /// The size of the defect: asymmetry or most negative eigenvalue, relative to the
        /// largest entry.
        measure: f64,
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
    /// has an invertible inertia map ([`Body::check_inertia_invertible`]); a body flat in two
    /// directions does not.
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
    /// The inertia map is singular: the plane spanned by `first` and `second` has plane
    /// moment (numerically) zero, so a rotation in that plane costs no energy.
    ///
    /// # How to fix
    /// This is a property of the body: it lies in a subspace of codimension ≥ 2 (a point, a
    /// rod in 3D, a disc in 4D). Give it extent in at least one of the two directions.
    #[error(
        "inertia map is singular: plane spanned by {first:?} and {second:?} has plane moment {plane_moment:e}"
    )]
    DegeneratePlane {
        /// First unit vector spanning the degenerate plane.
        first: DVector<f64>,
        /// Second unit vector spanning the degenerate plane.
        second: DVector<f64>,
        /// The plane moment J_a + J_b of that plane.
        plane_moment: f64,
    },
}

/// Which check failed in [`BodyError::InvalidMassTensor`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum MassTensorDefect {
    /// The matrix is not symmetric.
    NotSymmetric,
    /// The matrix has a negative eigenvalue.
    NotPositiveSemidefinite,
}

fn fmt_index(index: Option<usize>) -> String {
    match index {
        Some(i) => format!("[{i}]"),
        None => String::new(),
    }
}

/// How the simplices of a mesh are combined by [`Body::simplicial_mesh`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SimplexOrientation {
    /// Each simplex contributes with the sign of det[v_1 − v_0, …, v_N − v_0].
    ///
    /// Use this for consistently oriented meshes: a tiling whose simplices all have the same
    /// orientation, or cones over a closed, consistently oriented boundary, which may be
    /// non-convex and whose apex may lie outside (ten Bosch 2020, REFERENCES.md §1). If the
    /// total comes out negative, the whole mesh is taken with the opposite orientation.
    Signed,
    /// Each simplex contributes its absolute volume.
    ///
    /// Use this for a tiling (simplices that do not overlap) listed in arbitrary vertex
    /// order, such as the Kuhn triangulation of a cube.
    Unsigned,
}

/// A rigid body in N dimensions: mass, centre of mass, mass tensor about the centre of mass,
/// and volume for solids.
///
/// Build one with a constructor from the module table of contents. All constructors
/// validate their input and return [`BodyError`] instead of panicking or producing NaN.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    dim: usize,
    mass: f64,
    center_of_mass: DVector<f64>,
    mass_tensor: DMatrix<f64>,
    volume: Option<f64>,
}

// ---------------------------------------------------------------------------------------
// Free helpers
// ---------------------------------------------------------------------------------------

/// Returns the volume V_N = π^{N/2}/Γ(N/2 + 1) of the unit ball in N dimensions (paper
/// eq. 99).
///
/// Computed by the recurrence V_0 = 1, V_1 = 2, V_N = (2π/N) V_{N−2}, which avoids the gamma
/// function. V_2 = π, V_3 = 4π/3, V_4 = π²/2.
pub fn unit_ball_volume(dim: usize) -> f64 {
    let mut v = if dim.is_multiple_of(2) { 1.0 } else { 2.0 };
    let mut k = if dim.is_multiple_of(2) { 2 } else { 3 };
    while k <= dim {
        v *= 2.0 * std::f64::consts::PI / k as f64;
        k += 2;
    }
    v
}

/// Returns the (N−1)-dimensional area of the unit sphere S^{N−1} ⊂ ℝ^N, which is N V_N
/// (paper eq. 99, ∂V_(N) at R = 1).
///
/// For N = 1 the "sphere" is the two points ±1 and the area is their count, 2.
pub fn unit_sphere_area(dim: usize) -> f64 {
    dim as f64 * unit_ball_volume(dim)
}

/// Returns the planes (i, j), i < j, of N-space in lexicographic order, 0-based:
/// (0,1), (0,2), …, (0,N−1), (1,2), ….
///
/// This is the storage order of bivector components (DESIGN.md part 1), shown 1-based in
/// text as 12, 13, …, 1N, 23, ….
pub fn plane_index_pairs(dim: usize) -> Vec<(usize, usize)> {
    let mut pairs = Vec::with_capacity(dim * dim.saturating_sub(1) / 2);
    for i in 0..dim {
        for j in i + 1..dim {
            pairs.push((i, j));
        }
    }
    pairs
}

/// Returns the N+1 vertices of a regular N-simplex centred at the origin with circumradius
/// `circumradius`.
///
/// Vertex k has coordinates r √((N+1)/N) h_j\[k\], where h_j (j = 1…N) are the rows of the
/// Helmert matrix: h_j = (1, …, 1, −j, 0, …, 0)/√(j(j+1)) with j ones. The rows are
/// orthonormal and orthogonal to (1, …, 1), so the vertices are the images of the standard
/// basis e_0…e_N of ℝ^{N+1}, centred and scaled. The edge is r √(2(N+1)/N).
///
/// # Errors
/// [`BodyError::DimensionTooSmall`] for N = 0; [`BodyError::NonFinite`] or
/// [`BodyError::NotPositive`] for a bad radius.
pub fn regular_simplex_positions(
    dim: usize,
    circumradius: f64,
) -> Result<Vec<DVector<f64>>, BodyError> {
    check_dim(dim, 1)?;
    check_positive("circumradius", None, circumradius)?;
    let n = dim as f64;
    let scale = circumradius * ((n + 1.0) / n).sqrt();
    let mut vertices = vec![DVector::zeros(dim); dim + 1];
    for j in 1..=dim {
        let norm = ((j * (j + 1)) as f64).sqrt();
        for (k, vertex) in vertices.iter_mut().enumerate() {
            let h = if k < j {
                1.0 / norm
            } else if k == j {
                -(j as f64) / norm
            } else {
                0.0
            };
            vertex[j - 1] = scale * h;
        }
    }
    Ok(vertices)
}

/// Returns the five vertices of the paper's 5-cell exactly as printed in its eq. (73):
/// the rows (±a√5/4, ±b√5/4, ±c√5/4, −d/4) with sign patterns (+,+,+), (+,−,−), (−,+,−),
/// (−,−,+), and the fifth vertex (0, 0, 0, d).
///
/// These points are centred at the origin for all a, b, c, d. They form a regular simplex
/// only when a = b = c = d (then the circumradius is a and the edge a√(5/2)); otherwise they
/// are the image of that regular simplex under diag(a, b, c, d)/a, which is not a
/// similarity. See [`Body::pentachoron_eq73`].
///
/// # Errors
/// [`BodyError::NonFinite`] or [`BodyError::NotPositive`] for a bad parameter.
pub fn pentachoron_eq73_positions(
    a: f64,
    b: f64,
    c: f64,
    d: f64,
) -> Result<Vec<DVector<f64>>, BodyError> {
    for (i, v) in [a, b, c, d].into_iter().enumerate() {
        check_positive("pentachoron parameters (a, b, c, d)", Some(i), v)?;
    }
    let s = 5f64.sqrt() / 4.0;
    let signs = [
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ];
    let mut vertices: Vec<DVector<f64>> = signs
        .iter()
        .map(|sg| DVector::from_vec(vec![sg[0] * a * s, sg[1] * b * s, sg[2] * c * s, -d / 4.0]))
        .collect();
    vertices.push(DVector::from_vec(vec![0.0, 0.0, 0.0, d]));
    Ok(vertices)
}

fn factorial(n: usize) -> f64 {
    (1..=n).fold(1.0, |acc, k| acc * k as f64)
}

fn check_dim(dim: usize, min: usize) -> Result<(), BodyError> {
    if dim < min {
        Err(BodyError::DimensionTooSmall { dim, min })
    } else {
        Ok(())
    }
}

fn check_finite(quantity: &'static str, index: Option<usize>, value: f64) -> Result<(), BodyError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(BodyError::NonFinite {
            quantity,
            index,
            value,
        })
    }
}

fn check_positive(
    quantity: &'static str,
    index: Option<usize>,
    value: f64,
) -> Result<(), BodyError> {
    check_finite(quantity, index, value)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(BodyError::NotPositive {
            quantity,
            index,
            value,
        })
    }
}

fn check_positive_list(quantity: &'static str, values: &[f64]) -> Result<(), BodyError> {
    if values.is_empty() {
        return Err(BodyError::Empty { quantity });
    }
    for (i, &v) in values.iter().enumerate() {
        check_positive(quantity, Some(i), v)?;
    }
    Ok(())
}

/// Checks that `v` has length `dim` and finite entries.
fn check_point(
    quantity: &'static str,
    index: Option<usize>,
    v: &DVector<f64>,
    dim: usize,
) -> Result<(), BodyError> {
    if v.len() != dim {
        return Err(BodyError::LengthMismatch {
            quantity,
            index,
            expected: dim,
            found: v.len(),
        });
    }
    for &x in v.iter() {
        check_finite(quantity, index, x)?;
    }
    Ok(())
}

fn check_points(quantity: &'static str, points: &[DVector<f64>]) -> Result<usize, BodyError> {
    let first = points.first().ok_or(BodyError::Empty { quantity })?;
    let dim = first.len();
    check_dim(dim, 1)?;
    for (i, p) in points.iter().enumerate() {
        check_point(quantity, Some(i), p, dim)?;
    }
    Ok(dim)
}

fn symmetrize(m: &DMatrix<f64>) -> DMatrix<f64> {
    (m + m.transpose()) * 0.5
}

/// Signed volume, first moment ∫ x dV and second moment ∫ x xᵀ dV of the simplex with the
/// given vertices (already relative to the reference point), all with the sign of
/// det[w_1 − w_0, …, w_N − w_0]. Also returns the relative volume |det| / Π|edges|.
///
/// Formulas: Vol = det/N!, ∫x dV = Vol s/(N+1), ∫ x xᵀ dV = Vol/((N+1)(N+2)) (Σ w wᵀ + s sᵀ)
/// with s = Σ w_k (REFERENCES.md §6).
fn simplex_moments(w: &[&DVector<f64>]) -> (f64, DVector<f64>, DMatrix<f64>, f64) {
    let n = w.len() - 1;
    let mut edges = DMatrix::zeros(n, n);
    let mut edge_product = 1.0;
    for k in 1..=n {
        let e = w[k] - w[0];
        edge_product *= e.norm();
        edges.set_column(k - 1, &e);
    }
    let det = edges.lu().determinant();
    let relative = if edge_product > 0.0 {
        det.abs() / edge_product
    } else {
        0.0
    };
    let volume = det / factorial(n);
    let mut s = DVector::zeros(n);
    let mut second = DMatrix::zeros(n, n);
    for v in w {
        s += *v;
        second.ger(1.0, v, v, 1.0);
    }
    second.ger(1.0, &s, &s, 1.0);
    let nf = n as f64;
    let first = &s * (volume / (nf + 1.0));
    let second = second * (volume / ((nf + 1.0) * (nf + 2.0)));
    (volume, first, second, relative)
}

// ---------------------------------------------------------------------------------------
// Body
// ---------------------------------------------------------------------------------------

impl Body {
    /// Checks the computed fields for overflow, symmetrizes J and builds the body.
    fn new_checked(
        mass: f64,
        center_of_mass: DVector<f64>,
        mass_tensor: DMatrix<f64>,
        volume: Option<f64>,
    ) -> Result<Body, BodyError> {
        if !mass.is_finite() {
            return Err(BodyError::NonFiniteResult { quantity: "mass" });
        }
        if center_of_mass.iter().any(|x| !x.is_finite()) {
            return Err(BodyError::NonFiniteResult {
                quantity: "center_of_mass",
            });
        }
        if mass_tensor.iter().any(|x| !x.is_finite()) {
            return Err(BodyError::NonFiniteResult {
                quantity: "mass_tensor",
            });
        }
        if let Some(v) = volume
            && !v.is_finite()
        {
            return Err(BodyError::NonFiniteResult { quantity: "volume" });
        }
        Ok(Body {
            dim: center_of_mass.len(),
            mass,
            mass_tensor: symmetrize(&mass_tensor),
            center_of_mass,
            volume,
        })
    }

    // ----- construction: point sets -------------------------------------------------------

    /// Returns the body made of point masses `masses[k]` at `positions[k]`.
    ///
    /// The centre of mass is c = Σ m_k x_k / Σ m_k and J = Σ m_k (x_k − c)(x_k − c)ᵀ
    /// (DESIGN.md, "Inertia"). The volume is `None`.
    ///
    /// # Errors
    /// [`BodyError::Empty`] for no points, [`BodyError::LengthMismatch`] if the lists differ in
    /// length or the positions differ in dimension, [`BodyError::NonFinite`] or
    /// [`BodyError::NotPositive`] for bad numbers, [`BodyError::DimensionTooSmall`] for
    /// zero-length positions.
    ///
    /// # Example
    /// ```
    /// use rotorflow::inertia::bodies::Body;
    /// use nalgebra::DVector;
    /// let rod = Body::point_masses(
    ///     &[1.0, 1.0],
    ///     &[DVector::from_vec(vec![-1.0, 0.0]), DVector::from_vec(vec![1.0, 0.0])],
    /// )?;
    /// assert_eq!(rod.mass_tensor()[(0, 0)], 2.0);
    /// assert_eq!(rod.mass_tensor()[(1, 1)], 0.0);
    /// # Ok::<(), rotorflow::inertia::bodies::BodyError>(())
    /// ```
    pub fn point_masses(masses: &[f64], positions: &[DVector<f64>]) -> Result<Body, BodyError> {
        let dim = check_points("positions", positions)?;
        if masses.len() != positions.len() {
            return Err(BodyError::LengthMismatch {
                quantity: "masses",
                index: None,
                expected: positions.len(),
                found: masses.len(),
            });
        }
        for (i, &m) in masses.iter().enumerate() {
            check_positive("masses", Some(i), m)?;
        }
        // Work relative to the unweighted mean to keep cancellation small.
        let reference =
            positions.iter().fold(DVector::zeros(dim), |acc, p| acc + p) / positions.len() as f64;
        let total: f64 = masses.iter().sum();
        let mut first = DVector::zeros(dim);
        for (m, p) in masses.iter().zip(positions) {
            first += (p - &reference) * *m;
        }
        let shift = first / total;
        let center = &reference + &shift;
        let mut j = DMatrix::zeros(dim, dim);
        for (m, p) in masses.iter().zip(positions) {
            let d = p - &center;
            j.ger(*m, &d, &d, 1.0);
        }
        Body::new_checked(total, center, j, None)
    }

    /// Returns 2^N equal point masses `vertex_mass` at the vertices (±a_1, …, ±a_N) of the
    /// hyper-cuboid with half-edges `half_edges` = (a_1, …, a_N), centred at the origin.
    ///
    /// With `vertex_mass = 1` and N = 4 this is the paper's tesseract of unit masses (eq. 69;
    /// the equation itself is missing from our text copy of the paper, which only describes
    /// it; we read its half-edges as a, b, c, d, as in the paper's §5). Mass 2^N μ and
    /// J = diag(2^N μ a_i²) exactly (each coordinate is ±a_i at every vertex, and the
    /// off-diagonal sums cancel by symmetry).
    ///
    /// # Errors
    /// [`BodyError::Empty`] for no half-edges; [`BodyError::NonFinite`],
    /// [`BodyError::NotPositive`] for bad numbers; [`BodyError::NonFiniteResult`] on overflow.
    pub fn cuboid_vertices(half_edges: &[f64], vertex_mass: f64) -> Result<Body, BodyError> {
        check_positive_list("half_edges", half_edges)?;
        check_positive("vertex_mass", None, vertex_mass)?;
        let dim = half_edges.len();
        let mass = 2f64.powi(dim as i32) * vertex_mass;
        let j = DMatrix::from_diagonal(&DVector::from_iterator(
            dim,
            half_edges.iter().map(|a| mass * a * a),
        ));
        Body::new_checked(mass, DVector::zeros(dim), j, None)
    }

    /// Returns N+1 equal point masses `vertex_mass` at the vertices of a regular N-simplex
    /// centred at the origin with circumradius r (positions from
    /// [`regular_simplex_positions`]).
    ///
    /// Mass (N+1) μ and J = (N+1) μ r²/N · 1: J is isotropic because the symmetry group of
    /// the simplex acts irreducibly, and tr J = Σ |x_k|² = (N+1) r².
    ///
    /// # Errors
    /// [`BodyError::DimensionTooSmall`] for N = 0; [`BodyError::NonFinite`],
    /// [`BodyError::NotPositive`] for bad numbers.
    pub fn regular_simplex_vertices(
        dim: usize,
        circumradius: f64,
        vertex_mass: f64,
    ) -> Result<Body, BodyError> {
        check_dim(dim, 1)?;
        check_positive("circumradius", None, circumradius)?;
        check_positive("vertex_mass", None, vertex_mass)?;
        let n = dim as f64;
        let mass = (n + 1.0) * vertex_mass;
        let j = DMatrix::identity(dim, dim) * (mass * circumradius * circumradius / n);
        Body::new_checked(mass, DVector::zeros(dim), j, None)
    }

    /// Returns the paper's 5-cell: unit point masses at the five points of its eq. (73)
    /// (see [`pentachoron_eq73_positions`]).
    ///
    /// Findings (tested in `tests/paper_errata.rs`, `paper_eq_73_*`):
    /// - the points are centred at the origin for every a, b, c, d (the fourth coordinates
    ///   sum to 4·(−d/4) + d = 0, the others cancel in pairs);
    /// - they form a regular 4-simplex only if a = b = c = d; then all five lie on the
    ///   sphere of radius a and all ten edges are a√(5/2). For unequal parameters the
    ///   figure is a non-regular simplex, the image of the regular one under
    ///   diag(a, b, c, d)/a;
    /// - mass 5 and J = (5/4) diag(a², b², c², d²).
    ///
    /// The paper's section title calls this a "5D-Pentachoron", but it is a 4-simplex in 4D.
    ///
    /// # Errors
    /// [`BodyError::NonFinite`] or [`BodyError::NotPositive`] for a bad parameter.
    pub fn pentachoron_eq73(a: f64, b: f64, c: f64, d: f64) -> Result<Body, BodyError> {
        let positions = pentachoron_eq73_positions(a, b, c, d)?;
        Body::point_masses(&[1.0; 5], &positions)
    }

    /// Returns 2N equal point masses `vertex_mass` at the vertices ±r e_i of the
    /// cross-polytope (orthoplex) centred at the origin.
    ///
    /// Mass 2N μ and J = 2 μ r² · 1 (only the two vertices on axis i contribute to J_ii).
    ///
    /// # Errors
    /// [`BodyError::DimensionTooSmall`] for N = 0; [`BodyError::NonFinite`],
    /// [`BodyError::NotPositive`] for bad numbers.
    pub fn cross_polytope_vertices(
        dim: usize,
        radius: f64,
        vertex_mass: f64,
    ) -> Result<Body, BodyError> {
        check_dim(dim, 1)?;
        check_positive("radius", None, radius)?;
        check_positive("vertex_mass", None, vertex_mass)?;
        let mass = 2.0 * dim as f64 * vertex_mass;
        let j = DMatrix::identity(dim, dim) * (2.0 * vertex_mass * radius * radius);
        Body::new_checked(mass, DVector::zeros(dim), j, None)
    }

    // ----- construction: solids and shells ------------------------------------------------

    /// Returns the solid hyper-cuboid [−a_1, a_1] × … × [−a_N, a_N] of uniform `density`.
    ///
    /// Volume Π 2a_i (paper eqs. 77 and 81 for N = 4, 5), mass ρ·Volume, and
    /// J = diag(m a_i²/3), since (1/2a)∫_{−a}^{a} x² dx = a²/3 (REFERENCES.md §6, with edge
    /// 2a_i: m (2a_i)²/12).
    ///
    /// # Errors
    /// [`BodyError::Empty`], [`BodyError::NonFinite`], [`BodyError::NotPositive`],
    /// [`BodyError::NonFiniteResult`].
    pub fn solid_cuboid(half_edges: &[f64], density: f64) -> Result<Body, BodyError> {
        check_positive_list("half_edges", half_edges)?;
        check_positive("density", None, density)?;
        let dim = half_edges.len();
        let volume: f64 = half_edges.iter().map(|a| 2.0 * a).product();
        let mass = density * volume;
        let j = DMatrix::from_diagonal(&DVector::from_iterator(
            dim,
            half_edges.iter().map(|a| mass * a * a / 3.0),
        ));
        Body::new_checked(mass, DVector::zeros(dim), j, Some(volume))
    }

    /// Returns the solid ellipsoid Σ (x_i/a_i)² ≤ 1 of uniform `density`.
    ///
    /// Volume V_N Π a_i with V_N = π^{N/2}/Γ(N/2 + 1) ([`unit_ball_volume`], paper eq. 99),
    /// mass ρ·Volume, and J = diag(m a_i²/(N+2)) (REFERENCES.md §6: the ellipsoid is the
    /// image of the unit ball under diag(a_i), and the unit ball has ∫x_i² dV/V = 1/(N+2)).
    ///
    /// # Errors
    /// [`BodyError::Empty`], [`BodyError::NonFinite`], [`BodyError::NotPositive`],
    /// [`BodyError::NonFiniteResult`].
    pub fn solid_ellipsoid(semi_axes: &[f64], density: f64) -> Result<Body, BodyError> {
        check_positive_list("semi_axes", semi_axes)?;
        check_positive("density", None, density)?;
        let dim = semi_axes.len();
        let volume = unit_ball_volume(dim) * semi_axes.iter().product::<f64>();
        let mass = density * volume;
        let denominator = dim as f64 + 2.0;
        let j = DMatrix::from_diagonal(&DVector::from_iterator(
            dim,
            semi_axes.iter().map(|a| mass * a * a / denominator),
        ));
        Body::new_checked(mass, DVector::zeros(dim), j, Some(volume))
    }

    /// Returns the solid N-ball of radius R and uniform `density`, centred at the origin.
    ///
    /// Volume V_N R^N (paper eq. 99), J = m R²/(N+2) · 1 (REFERENCES.md §6). The paper's
    /// polar moment tr J/m = N R²/(N+2) is its eq. (102).
    ///
    /// # Errors
    /// [`BodyError::DimensionTooSmall`] for N = 0, [`BodyError::NonFinite`],
    /// [`BodyError::NotPositive`], [`BodyError::NonFiniteResult`].
    pub fn solid_ball(dim: usize, radius: f64, density: f64) -> Result<Body, BodyError> {
        check_dim(dim, 1)?;
        check_positive("radius", None, radius)?;
        Body::solid_ellipsoid(&vec![radius; dim], density)
    }

    /// Returns the hollow hypersphere S^{N−1} of radius R with uniform `surface_density` σ.
    ///
    /// Mass σ · N V_N R^{N−1} (the area ∂V_(N) of paper eq. 99) and J = m R²/N · 1, since
    /// Σ_i x_i² = R² on the sphere and all axes are equivalent (REFERENCES.md §6). The
    /// volume is `None`. For N = 1 the "sphere" is the two points ±R, each of mass σ.
    ///
    /// # Errors
    /// [`BodyError::DimensionTooSmall`] for N = 0, [`BodyError::NonFinite`],
    /// [`BodyError::NotPositive`], [`BodyError::NonFiniteResult`].
    pub fn hypersphere_shell(
        dim: usize,
        radius: f64,
        surface_density: f64,
    ) -> Result<Body, BodyError> {
        check_dim(dim, 1)?;
        check_positive("radius", None, radius)?;
        check_positive("surface_density", None, surface_density)?;
        let area = unit_sphere_area(dim) * radius.powi(dim as i32 - 1);
        let mass = surface_density * area;
        let j = DMatrix::identity(dim, dim) * (mass * radius * radius / dim as f64);
        Body::new_checked(mass, DVector::zeros(dim), j, None)
    }

    /// Returns the solid N-simplex with the given N+1 vertices in ℝ^N and uniform `density`.
    ///
    /// Volume |det[v_1 − v_0, …, v_N − v_0]|/N!, centre of mass the vertex mean c, and, with
    /// w_k = v_k − c (so Σ w_k = 0), J = m/((N+1)(N+2)) Σ_k w_k w_kᵀ. This is the vertex
    /// formula ∫ x xᵀ dV = Vol/((N+1)(N+2)) [Σ v_k v_kᵀ + (Σ v_k)(Σ v_k)ᵀ]
    /// (REFERENCES.md §6) applied about the centroid.
    ///
    /// # Errors
    /// [`BodyError::Empty`], [`BodyError::LengthMismatch`] (the number of vertices must be
    /// N+1 for points in ℝ^N), [`BodyError::NonFinite`], [`BodyError::NotPositive`],
    /// [`BodyError::DegenerateSimplex`] when the vertices are affinely dependent.
    pub fn solid_simplex(vertices: &[DVector<f64>], density: f64) -> Result<Body, BodyError> {
        let dim = check_points("vertices", vertices)?;
        if vertices.len() != dim + 1 {
            return Err(BodyError::LengthMismatch {
                quantity: "vertices",
                index: None,
                expected: dim + 1,
                found: vertices.len(),
            });
        }
        check_positive("density", None, density)?;
        let center =
            vertices.iter().fold(DVector::zeros(dim), |acc, v| acc + v) / vertices.len() as f64;
        let w: Vec<DVector<f64>> = vertices.iter().map(|v| v - &center).collect();
        let refs: Vec<&DVector<f64>> = w.iter().collect();
        let (signed, _first, _second, relative) = simplex_moments(&refs);
        if relative <= DEGENERACY_TOLERANCE || !relative.is_finite() {
            return Err(BodyError::DegenerateSimplex {
                simplex: 0,
                relative_volume: relative,
            });
        }
        let volume = signed.abs();
        let mass = density * volume;
        let nf = dim as f64;
        let mut j = DMatrix::zeros(dim, dim);
        for wk in &w {
            j.ger(1.0, wk, wk, 1.0);
        }
        j *= mass / ((nf + 1.0) * (nf + 2.0));
        Body::new_checked(mass, center, j, Some(volume))
    }

    // ----- construction: meshes and assemblies --------------------------------------------

    /// Returns the uniform-density body filling a mesh of N-simplices.
    ///
    /// # Accepted format
    /// - `vertices`: points in ℝ^N, all of the same length N ≥ 1.
    /// - `simplices`: one entry per N-simplex, each listing N+1 distinct 0-based indices into
    ///   `vertices`. The order of the indices fixes the orientation sign of
    ///   det[v_1 − v_0, …, v_N − v_0].
    /// - `orientation`: [`SimplexOrientation::Signed`] sums signed contributions (a tiling
    ///   with one orientation, or cones over a closed consistently oriented boundary, as in
    ///   ten Bosch 2020; a negative total is flipped); [`SimplexOrientation::Unsigned`] sums
    ///   absolute contributions (a non-overlapping tiling in any vertex order).
    ///
    /// Simplices of zero volume are allowed and contribute nothing. Each simplex
    /// contributes its volume, first moment and second moment from the vertex formula
    /// (REFERENCES.md §6), all taken about the vertex mean for accuracy; then
    /// c = ∫x dV / V and J = ρ (∫ x xᵀ dV − V c cᵀ).
    ///
    /// # Errors
    /// [`BodyError::Empty`], [`BodyError::LengthMismatch`], [`BodyError::NonFinite`],
    /// [`BodyError::NotPositive`] (density), [`BodyError::WrongSimplexSize`],
    /// [`BodyError::VertexIndexOutOfRange`], [`BodyError::ZeroMeshVolume`] when the
    /// (signed) volumes cancel, [`BodyError::InconsistentMesh`] when the result has a
    /// clearly negative second moment.
    pub fn simplicial_mesh<S: AsRef<[usize]>>(
        vertices: &[DVector<f64>],
        simplices: &[S],
        density: f64,
        orientation: SimplexOrientation,
    ) -> Result<Body, BodyError> {
        let dim = check_points("vertices", vertices)?;
        check_positive("density", None, density)?;
        if simplices.is_empty() {
            return Err(BodyError::Empty {
                quantity: "simplices",
            });
        }
        for (s, simplex) in simplices.iter().enumerate() {
            check_indices(s, simplex.as_ref(), dim + 1, vertices.len())?;
        }
        let reference =
            vertices.iter().fold(DVector::zeros(dim), |acc, v| acc + v) / vertices.len() as f64;
        // One flat buffer of shifted vertices: no allocation per vertex or per simplex.
        let mut local = Vec::with_capacity(dim * vertices.len());
        for v in vertices {
            local.extend(v.iter().zip(reference.iter()).map(|(a, b)| a - b));
        }
        if (2..=8).contains(&dim) {
            let mut acc = MeshAccumulator::new(dim);
            for simplex in simplices {
                acc.add_indexed(&local, simplex.as_ref(), orientation);
            }
            return finish_mesh(dim, &reference, acc, density);
        }
        mesh_body(
            dim,
            &reference,
            simplices.iter().map(|s| {
                s.as_ref()
                    .iter()
                    .map(|&k| &local[k * dim..(k + 1) * dim])
                    .collect::<SmallVec<[&[f64]; 9]>>()
            }),
            density,
            orientation,
        )
    }

    /// Returns the uniform-density solid bounded by a closed, consistently oriented boundary
    /// mesh of (N−1)-simplices (ten Bosch 2020, REFERENCES.md §1).
    ///
    /// Each facet lists N vertex indices. The solid is the signed sum of the cones from the
    /// vertex mean (the apex) to each facet, so the solid may be non-convex and the apex may
    /// lie outside it. Facets are consistently oriented when each (N−2)-face is shared by two
    /// facets that induce opposite orientations on it (for N = 2: the polygon's edges
    /// (a, b) all run the same way round). Either global orientation is accepted.
    ///
    /// Closedness is not checked (facets may use separate copies of coincident vertices, so
    /// an index-based check would reject valid input). An open or inconsistently oriented
    /// boundary yields the signed sum of its cones; it is reported only when that sum has
    /// zero volume ([`BodyError::ZeroMeshVolume`]) or a negative second moment
    /// ([`BodyError::InconsistentMesh`]).
    ///
    /// # Errors
    /// As [`Body::simplicial_mesh`], with facets of N indices; N ≥ 2 is required
    /// ([`BodyError::DimensionTooSmall`]).
    pub fn closed_boundary_mesh<S: AsRef<[usize]>>(
        vertices: &[DVector<f64>],
        facets: &[S],
        density: f64,
    ) -> Result<Body, BodyError> {
        let dim = check_points("vertices", vertices)?;
        check_dim(dim, 2)?;
        check_positive("density", None, density)?;
        if facets.is_empty() {
            return Err(BodyError::Empty { quantity: "facets" });
        }
        for (s, facet) in facets.iter().enumerate() {
            check_indices(s, facet.as_ref(), dim, vertices.len())?;
        }
        let reference =
            vertices.iter().fold(DVector::zeros(dim), |acc, v| acc + v) / vertices.len() as f64;
        let local: Vec<DVector<f64>> = vertices.iter().map(|v| v - &reference).collect();
        let apex = DVector::zeros(dim);
        mesh_body(
            dim,
            &reference,
            facets.iter().map(|f| {
                std::iter::once(apex.as_slice())
                    .chain(f.as_ref().iter().map(|&k| local[k].as_slice()))
                    .collect::<SmallVec<[&[f64]; 9]>>()
            }),
            density,
            SimplexOrientation::Signed,
        )
    }

    /// Returns the union of `parts`, which must not overlap, each already placed (see
    /// [`Body::placed`]).
    ///
    /// Mass Σ m_k, centre c = Σ m_k c_k / M, and J = Σ_k (J_k + m_k d_k d_kᵀ) with
    /// d_k = c_k − c (parallel-axis theorem, REFERENCES.md §6). The volume is the sum of the
    /// parts' volumes if every part has one, else `None`. Overlaps are not detected: they
    /// count twice.
    ///
    /// # Errors
    /// [`BodyError::Empty`]; [`BodyError::LengthMismatch`] if the parts differ in dimension;
    /// [`BodyError::NonFiniteResult`] on overflow.
    pub fn composite(parts: &[Body]) -> Result<Body, BodyError> {
        let first = parts
            .first()
            .ok_or(BodyError::Empty { quantity: "parts" })?;
        let dim = first.dim;
        for (i, p) in parts.iter().enumerate() {
            if p.dim != dim {
                return Err(BodyError::LengthMismatch {
                    quantity: "parts",
                    index: Some(i),
                    expected: dim,
                    found: p.dim,
                });
            }
        }
        let reference = first.center_of_mass.clone();
        let total: f64 = parts.iter().map(|p| p.mass).sum();
        let mut moment = DVector::zeros(dim);
        for p in parts {
            moment += (&p.center_of_mass - &reference) * p.mass;
        }
        let center = &reference + moment / total;
        let mut j = DMatrix::zeros(dim, dim);
        for p in parts {
            let d = &p.center_of_mass - &center;
            j += &p.mass_tensor;
            j.ger(p.mass, &d, &d, 1.0);
        }
        let volume = parts.iter().map(|p| p.volume).sum::<Option<f64>>();
        Body::new_checked(total, center, j, volume)
    }

    /// Returns the body with the given mass properties, after checking them.
    ///
    /// # Errors
    /// [`BodyError::NotPositive`], [`BodyError::NonFinite`], [`BodyError::LengthMismatch`]
    /// when J is not N×N, or [`BodyError::InvalidMassTensor`] when J is not symmetric (relative
    /// asymmetry above 1e-9) or has an eigenvalue below −1e-9 · max|J|.
    pub fn from_mass_properties(
        mass: f64,
        center_of_mass: DVector<f64>,
        mass_tensor: DMatrix<f64>,
        volume: Option<f64>,
    ) -> Result<Body, BodyError> {
        check_positive("mass", None, mass)?;
        let dim = center_of_mass.len();
        check_dim(dim, 1)?;
        check_point("center_of_mass", None, &center_of_mass, dim)?;
        if let Some(v) = volume {
            check_positive("volume", None, v)?;
        }
        if mass_tensor.nrows() != dim || mass_tensor.ncols() != dim {
            return Err(BodyError::LengthMismatch {
                quantity: "mass_tensor",
                index: None,
                expected: dim,
                found: if mass_tensor.nrows() != dim {
                    mass_tensor.nrows()
                } else {
                    mass_tensor.ncols()
                },
            });
        }
        for (i, &x) in mass_tensor.iter().enumerate() {
            check_finite("mass_tensor", Some(i), x)?;
        }
        let scale = max_abs(&mass_tensor).max(f64::MIN_POSITIVE);
        let asymmetry = max_abs(&(&mass_tensor - mass_tensor.transpose())) / scale;
        if asymmetry > MATRIX_CHECK_TOLERANCE {
            return Err(BodyError::InvalidMassTensor {
                reason: MassTensorDefect::NotSymmetric,
                measure: asymmetry,
            });
        }
        let j = symmetrize(&mass_tensor);
        let (values, _) = sorted_eigen(&j);
        if values[0] < -MATRIX_CHECK_TOLERANCE * scale {
            return Err(BodyError::InvalidMassTensor {
                reason: MassTensorDefect::NotPositiveSemidefinite,
                measure: values[0] / scale,
            });
        }
        Body::new_checked(mass, center_of_mass, j, volume)
    }

    // ----- accessors ----------------------------------------------------------------------

    /// Returns the dimension N of the space the body lives in.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Returns the total mass m.
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Returns the centre of mass c (length N).
    pub fn center_of_mass(&self) -> &DVector<f64> {
        &self.center_of_mass
    }

    /// Returns the mass tensor J = ∫ (x − c)(x − c)ᵀ dm about the centre of mass (N×N,
    /// symmetric, positive semidefinite).
    pub fn mass_tensor(&self) -> &DMatrix<f64> {
        &self.mass_tensor
    }

    /// Returns the N-volume for solids, `None` for point sets and shells (and composites with
    /// such parts).
    pub fn volume(&self) -> Option<f64> {
        self.volume
    }

    /// Returns the mean density m / Volume, `None` when the body has no volume.
    pub fn density(&self) -> Option<f64> {
        self.volume.map(|v| self.mass / v)
    }

    // ----- queries ------------------------------------------------------------------------

    /// Returns the mass tensor about `point`: J_O = J + m d dᵀ with d = c − O (parallel-axis
    /// theorem, REFERENCES.md §6).
    ///
    /// # Errors
    /// [`BodyError::LengthMismatch`] or [`BodyError::NonFinite`] for a bad point.
    pub fn mass_tensor_about(&self, point: &DVector<f64>) -> Result<DMatrix<f64>, BodyError> {
        check_point("point", None, point, self.dim)?;
        let d = &self.center_of_mass - point;
        let mut j = self.mass_tensor.clone();
        j.ger(self.mass, &d, &d, 1.0);
        Ok(j)
    }

    /// Returns the principal moments J_1 ≤ … ≤ J_N (the eigenvalues of J, ascending).
    pub fn principal_moments(&self) -> DVector<f64> {
        sorted_eigen(&self.mass_tensor).0
    }

    /// Returns the principal moments (ascending) and the principal axes as the columns of a
    /// rotation matrix P (det P = +1), so that J = P diag(J_i) Pᵀ.
    pub fn principal_frame(&self) -> (DVector<f64>, DMatrix<f64>) {
        let (values, mut axes) = sorted_eigen(&self.mass_tensor);
        if axes.determinant() < 0.0 {
            let last = self.dim - 1;
            let flipped = -axes.column(last);
            axes.set_column(last, &flipped);
        }
        (values, axes)
    }

    /// Returns the plane moments J_ii + J_jj in the body's own axes, one per plane (i, j),
    /// i < j, in lexicographic order 12, 13, …, 1N, 23, … ([`plane_index_pairs`]).
    ///
    /// In the principal frame these are the eigenvalues of the inertia map on bivectors,
    /// I(e_i ∧ e_j) = (J_i + J_j) e_i ∧ e_j (DESIGN.md, "Inertia"). In a general frame they
    /// are its diagonal entries ⟨e_i∧e_j, I(e_i∧e_j)⟩. Empty for N = 1.
    pub fn plane_moments(&self) -> DVector<f64> {
        let pairs = plane_index_pairs(self.dim);
        DVector::from_iterator(
            pairs.len(),
            pairs
                .iter()
                .map(|&(i, j)| self.mass_tensor[(i, i)] + self.mass_tensor[(j, j)]),
        )
    }

    /// Returns the principal plane moments J_i + J_j (principal moments ascending, planes in
    /// lexicographic order), the eigenvalues of the inertia map.
    ///
    /// In 4D they satisfy I_12 + I_34 = I_13 + I_24 = I_14 + I_23 = tr J (REFERENCES.md §0).
    pub fn principal_plane_moments(&self) -> DVector<f64> {
        let moments = self.principal_moments();
        let pairs = plane_index_pairs(self.dim);
        DVector::from_iterator(
            pairs.len(),
            pairs.iter().map(|&(i, j)| moments[i] + moments[j]),
        )
    }

    /// Returns the unit directions (principal axes, in the body's axes) along which the body
    /// has no extent: eigenvectors of J with eigenvalue ≤ `rel_tol` · max eigenvalue.
    ///
    /// A body with k flat directions lies in an (N−k)-dimensional affine subspace through its
    /// centre of mass. A single point is flat in every direction. Use
    /// [`FLATNESS_TOLERANCE`] unless you have a reason not to.
    pub fn flat_directions(&self, rel_tol: f64) -> Vec<DVector<f64>> {
        let (values, vectors) = sorted_eigen(&self.mass_tensor);
        let largest = values[self.dim - 1].max(0.0);
        (0..self.dim)
            .filter(|&k| values[k] <= rel_tol * largest)
            .map(|k| vectors.column(k).into_owned())
            .collect()
    }

    /// Checks that J is non-singular, i.e. the body is not flat in any direction.
    ///
    /// # Errors
    /// [`BodyError::FlatBody`] naming the flattest direction when its second moment is
    /// ≤ `rel_tol` · the largest.
    pub fn check_full_rank(&self, rel_tol: f64) -> Result<(), BodyError> {
        let (values, vectors) = sorted_eigen(&self.mass_tensor);
        let largest = values[self.dim - 1].max(0.0);
        if values[0] <= rel_tol * largest {
            return Err(BodyError::FlatBody {
                direction: vectors.column(0).into_owned(),
                moment: values[0],
                largest_moment: largest,
            });
        }
        Ok(())
    }

    /// Checks that the inertia map I(ω) = J\[ω\] + \[ω\]J is invertible, i.e. every principal
    /// plane moment J_a + J_b is positive. This fails exactly when the body is flat in at
    /// least two directions (or N ≥ 2 and the body is a point).
    ///
    /// In 1D there are no planes and the check passes.
    ///
    /// # Errors
    /// [`BodyError::DegeneratePlane`] naming the plane of the two smallest principal
    /// moments when J_1 + J_2 ≤ `rel_tol` · 2 max J_i.
    pub fn check_inertia_invertible(&self, rel_tol: f64) -> Result<(), BodyError> {
        if self.dim < 2 {
            return Ok(());
        }
        let (values, vectors) = sorted_eigen(&self.mass_tensor);
        let largest = values[self.dim - 1].max(0.0);
        let plane = values[0] + values[1];
        if plane <= rel_tol * 2.0 * largest {
            return Err(BodyError::DegeneratePlane {
                first: vectors.column(0).into_owned(),
                second: vectors.column(1).into_owned(),
                plane_moment: plane,
            });
        }
        Ok(())
    }

    // ----- transformations ----------------------------------------------------------------

    /// Returns the same body with total mass `mass` (J scaled by mass/m, same centre of mass
    /// and volume, so the density scales too).
    ///
    /// # Errors
    /// [`BodyError::NonFinite`], [`BodyError::NotPositive`], [`BodyError::NonFiniteResult`].
    pub fn with_mass(&self, mass: f64) -> Result<Body, BodyError> {
        check_positive("mass", None, mass)?;
        let factor = mass / self.mass;
        Body::new_checked(
            mass,
            self.center_of_mass.clone(),
            &self.mass_tensor * factor,
            self.volume,
        )
    }

    /// Returns the body mapped by the orthogonal matrix Q about the origin of coordinates:
    /// c' = Q c and J' = Q J Qᵀ.
    ///
    /// Reflections (det Q = −1) are accepted too; the mass tensor of a mirror image follows
    /// the same formula.
    ///
    /// # Errors
    /// [`BodyError::LengthMismatch`] if Q is not N×N, [`BodyError::NonFinite`],
    /// [`BodyError::NotOrthogonal`] if max |QᵀQ − 1| > [`ORTHOGONALITY_TOLERANCE`].
    pub fn rotated(&self, rotation: &DMatrix<f64>) -> Result<Body, BodyError> {
        check_rotation(rotation, self.dim)?;
        let j = rotation * &self.mass_tensor * rotation.transpose();
        Body::new_checked(self.mass, rotation * &self.center_of_mass, j, self.volume)
    }

    /// Returns the body moved by `offset`: c' = c + offset, J unchanged.
    ///
    /// # Errors
    /// [`BodyError::LengthMismatch`] or [`BodyError::NonFinite`] for a bad offset.
    pub fn translated(&self, offset: &DVector<f64>) -> Result<Body, BodyError> {
        check_point("offset", None, offset, self.dim)?;
        Body::new_checked(
            self.mass,
            &self.center_of_mass + offset,
            self.mass_tensor.clone(),
            self.volume,
        )
    }

    /// Returns the body rotated by Q about the origin and then moved by `offset`
    /// (`self.rotated(rotation)?.translated(offset)`); the usual way to place a part
    /// before [`Body::composite`].
    ///
    /// # Errors
    /// As [`Body::rotated`] and [`Body::translated`].
    pub fn placed(
        &self,
        rotation: &DMatrix<f64>,
        offset: &DVector<f64>,
    ) -> Result<Body, BodyError> {
        self.rotated(rotation)?.translated(offset)
    }
}

fn check_rotation(rotation: &DMatrix<f64>, dim: usize) -> Result<(), BodyError> {
    if rotation.nrows() != dim || rotation.ncols() != dim {
        return Err(BodyError::LengthMismatch {
            quantity: "rotation",
            index: None,
            expected: dim,
            found: if rotation.nrows() != dim {
                rotation.nrows()
            } else {
                rotation.ncols()
            },
        });
    }
    for (i, &x) in rotation.iter().enumerate() {
        check_finite("rotation", Some(i), x)?;
    }
    let deviation = max_abs(&(rotation.transpose() * rotation - DMatrix::identity(dim, dim)));
    if deviation > ORTHOGONALITY_TOLERANCE {
        return Err(BodyError::NotOrthogonal {
            deviation,
            tolerance: ORTHOGONALITY_TOLERANCE,
        });
    }
    Ok(())
}

fn check_indices(
    simplex: usize,
    indices: &[usize],
    expected: usize,
    vertex_count: usize,
) -> Result<(), BodyError> {
    if indices.len() != expected {
        return Err(BodyError::WrongSimplexSize {
            simplex,
            expected,
            found: indices.len(),
        });
    }
    for &k in indices {
        if k >= vertex_count {
            return Err(BodyError::VertexIndexOutOfRange {
                simplex,
                vertex: k,
                vertex_count,
            });
        }
    }
    Ok(())
}

/// Sums simplex contributions (vertices relative to `reference`) into a body.
fn mesh_body<'a, I>(
    dim: usize,
    reference: &DVector<f64>,
    simplices: I,
    density: f64,
    orientation: SimplexOrientation,
) -> Result<Body, BodyError>
where
    I: Iterator<Item = SmallVec<[&'a [f64]; 9]>>,
{
    let mut acc = MeshAccumulator::new(dim);
    for vertices in simplices {
        acc.add(&vertices, orientation);
    }
    finish_mesh(dim, reference, acc, density)
}

/// Turns accumulated simplex moments into a body (shift to the centre of mass, checks).
fn finish_mesh(
    dim: usize,
    reference: &DVector<f64>,
    acc: MeshAccumulator,
    density: f64,
) -> Result<Body, BodyError> {
    let (mut volume, unsigned, mut first, mut second) = acc.finish();
    if !volume.is_finite() || volume.abs() <= DEGENERACY_TOLERANCE * unsigned {
        return Err(BodyError::ZeroMeshVolume {
            signed_volume: volume,
            unsigned_volume: unsigned,
        });
    }
    if volume < 0.0 {
        volume = -volume;
        first = -first;
        second = -second;
    }
    let shift = &first / volume;
    let mut j = second;
    j.ger(-volume, &shift, &shift, 1.0);
    j *= density;
    let j = symmetrize(&j);
    let (values, _) = sorted_eigen(&j);
    let largest = values[dim - 1];
    if values[0] < -MATRIX_CHECK_TOLERANCE * largest.abs() || largest <= 0.0 {
        return Err(BodyError::InconsistentMesh {
            min_moment: values[0],
            max_moment: largest,
        });
    }
    Body::new_checked(density * volume, reference + shift, j, Some(volume))
}

/// Sums the signed volume, first and second moments of many simplices without allocating
/// per simplex (stack scratch for N ≤ 16): the hot loop of mesh inertia.
///
/// Per simplex with vertices w₀ … w_N (relative to the reference point): Vol = det/N!,
/// ∫x dV = Vol s/(N+1), ∫x xᵀ dV = Vol/((N+1)(N+2)) (Σ w wᵀ + s sᵀ), s = Σ w_k
/// (REFERENCES.md §6); only the upper triangle is accumulated.
struct MeshAccumulator {
    n: usize,
    inverse_factorial: f64,
    volume: f64,
    unsigned: f64,
    first: Vec<f64>,
    second: Vec<f64>,
}

impl MeshAccumulator {
    fn new(n: usize) -> Self {
        MeshAccumulator {
            n,
            inverse_factorial: 1.0 / factorial(n),
            volume: 0.0,
            unsigned: 0.0,
            first: vec![0.0; n],
            second: vec![0.0; n * n],
        }
    }

    fn add(&mut self, w: &[&[f64]], orientation: SimplexOrientation) {
        let n = self.n;
        if n > 16 {
            let owned: Vec<DVector<f64>> =
                w.iter().map(|v| DVector::from_column_slice(v)).collect();
            let refs: Vec<&DVector<f64>> = owned.iter().collect();
            let (v, f, s, _) = simplex_moments(&refs);
            let sign = orientation_sign(orientation, v);
            self.volume += sign * v;
            self.unsigned += v.abs();
            for r in 0..n {
                self.first[r] += sign * f[r];
                for c in 0..n {
                    self.second[r * n + c] += sign * s[(r, c)];
                }
            }
            return;
        }
        match n {
            2 => return self.add_fixed::<2>(w, orientation),
            3 => return self.add_fixed::<3>(w, orientation),
            4 => return self.add_fixed::<4>(w, orientation),
            5 => return self.add_fixed::<5>(w, orientation),
            6 => return self.add_fixed::<6>(w, orientation),
            7 => return self.add_fixed::<7>(w, orientation),
            8 => return self.add_fixed::<8>(w, orientation),
            _ => {}
        }
        let mut a = [0.0f64; 256];
        for k in 1..=n {
            for r in 0..n {
                a[r * n + (k - 1)] = w[k][r] - w[0][r];
            }
        }
        let volume = determinant_in_place(&mut a[..n * n], n) * self.inverse_factorial;
        let sign = orientation_sign(orientation, volume);
        let f = sign * volume;
        self.volume += f;
        self.unsigned += volume.abs();
        let mut s = [0.0f64; 16];
        for v in w {
            for r in 0..n {
                s[r] += v[r];
            }
        }
        let nf = n as f64;
        let c1 = f / (nf + 1.0);
        let c2 = f / ((nf + 1.0) * (nf + 2.0));
        for r in 0..n {
            self.first[r] += c1 * s[r];
            for c in r..n {
                let mut x = s[r] * s[c];
                for v in w {
                    x += v[r] * v[c];
                }
                self.second[r * n + c] += c2 * x;
            }
        }
    }

    /// Adds the simplex whose vertex `k` is `flat[idx[k]·N ..][..N]` (N = 2 … 8, indices
    /// already validated).
    fn add_indexed(&mut self, flat: &[f64], idx: &[usize], orientation: SimplexOrientation) {
        macro_rules! go {
            ($n:literal) => {{
                let mut v = [[0.0f64; $n]; 9];
                for (row, &k) in v.iter_mut().zip(idx) {
                    row.copy_from_slice(&flat[k * $n..(k + 1) * $n]);
                }
                self.add_rows::<$n>(&v, orientation)
            }};
        }
        match self.n {
            2 => go!(2),
            3 => go!(3),
            4 => go!(4),
            5 => go!(5),
            6 => go!(6),
            7 => go!(7),
            8 => go!(8),
            _ => unreachable!("add_indexed is only called for N = 2 … 8"),
        }
    }

    /// [`MeshAccumulator::add`] for a fixed N: stack arrays the compiler unrolls.
    fn add_fixed<const N: usize>(&mut self, w: &[&[f64]], orientation: SimplexOrientation) {
        let mut v = [[0.0f64; N]; 9];
        for (k, row) in v.iter_mut().enumerate().take(N + 1) {
            row.copy_from_slice(&w[k][..N]);
        }
        self.add_rows::<N>(&v, orientation);
    }

    /// Adds the simplex with vertex rows `v[0..=N]`.
    fn add_rows<const N: usize>(&mut self, v: &[[f64; N]; 9], orientation: SimplexOrientation) {
        let mut a = [[0.0f64; N]; N];
        for k in 1..=N {
            for r in 0..N {
                a[r][k - 1] = v[k][r] - v[0][r];
            }
        }
        // Gaussian elimination with partial pivoting.
        let mut det = 1.0;
        for col in 0..N {
            let mut pivot = col;
            for r in col + 1..N {
                if a[r][col].abs() > a[pivot][col].abs() {
                    pivot = r;
                }
            }
            if a[pivot][col] == 0.0 {
                det = 0.0;
                break;
            }
            if pivot != col {
                a.swap(col, pivot);
                det = -det;
            }
            let p = a[col][col];
            det *= p;
            let inv_p = 1.0 / p;
            let (top, bottom) = a.split_at_mut(col + 1);
            let pivot_row = &top[col];
            for row in bottom.iter_mut() {
                let factor = row[col] * inv_p;
                for (x, &q) in row[col + 1..].iter_mut().zip(&pivot_row[col + 1..]) {
                    *x -= factor * q;
                }
            }
        }
        let volume = det * self.inverse_factorial;
        let sign = orientation_sign(orientation, volume);
        let f = sign * volume;
        self.volume += f;
        self.unsigned += volume.abs();
        let mut s = [0.0f64; N];
        for row in v.iter().take(N + 1) {
            for r in 0..N {
                s[r] += row[r];
            }
        }
        let nf = N as f64;
        let c1 = f / (nf + 1.0);
        let c2 = f / ((nf + 1.0) * (nf + 2.0));
        for r in 0..N {
            self.first[r] += c1 * s[r];
            for c in r..N {
                let mut x = s[r] * s[c];
                for row in v.iter().take(N + 1) {
                    x += row[r] * row[c];
                }
                self.second[r * N + c] += c2 * x;
            }
        }
    }

    /// Returns (signed volume, unsigned volume, ∫x dV, ∫x xᵀ dV).
    fn finish(self) -> (f64, f64, DVector<f64>, DMatrix<f64>) {
        let n = self.n;
        let mut second = DMatrix::from_row_slice(n, n, &self.second);
        if n <= 16 {
            for r in 0..n {
                for c in 0..r {
                    second[(r, c)] = second[(c, r)];
                }
            }
        }
        (
            self.volume,
            self.unsigned,
            DVector::from_vec(self.first),
            second,
        )
    }
}

fn orientation_sign(orientation: SimplexOrientation, volume: f64) -> f64 {
    match orientation {
        SimplexOrientation::Signed => 1.0,
        SimplexOrientation::Unsigned => {
            if volume < 0.0 {
                -1.0
            } else {
                1.0
            }
        }
    }
}

/// Determinant of the row-major n×n matrix `a` by Gaussian elimination with partial
/// pivoting (destroys `a`).
fn determinant_in_place(a: &mut [f64], n: usize) -> f64 {
    let mut det = 1.0;
    for col in 0..n {
        let mut pivot = col;
        let mut best = a[col * n + col].abs();
        for r in col + 1..n {
            let v = a[r * n + col].abs();
            if v > best {
                best = v;
                pivot = r;
            }
        }
        if best == 0.0 {
            return 0.0;
        }
        if pivot != col {
            for c in 0..n {
                a.swap(col * n + c, pivot * n + c);
            }
            det = -det;
        }
        let p = a[col * n + col];
        det *= p;
        for r in col + 1..n {
            let factor = a[r * n + col] / p;
            if factor != 0.0 {
                for c in col + 1..n {
                    a[r * n + c] -= factor * a[col * n + c];
                }
            }
        }
    }
    det
}
