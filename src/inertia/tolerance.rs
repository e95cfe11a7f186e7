//! The tolerances of the inertia layer, defined once: every constructor and query asks
//! "is it a rotation", "is it symmetric", "is a moment negative" and "is a plane singular"
//! with the same number, so a body accepted by [`Body`](super::Body) is accepted by
//! [`InertiaMap::from_body`](super::InertiaMap::from_body) unless its inertia map is singular,
//! and then [`Body::check_inertia_invertible`](super::Body::check_inertia_invertible) says so
//! too.
//!
//! All tolerances are relative to the size of the input (its largest entry or eigenvalue).

/// Largest entry of |QᵀQ − 1| for a matrix accepted as a rotation (with det Q > 0) or as
/// orthogonal. The same number as [`crate::algebra::ROTATION_TOLERANCE`], which
/// [`Rotor::from_matrix`](crate::algebra::Rotor::from_matrix) uses: products of a few dozen
/// rotation matrices stay below 1e-13, so this accepts matrices assembled from rounded
/// angles and refuses anything not meant to be orthogonal.
pub const ORTHOGONALITY_TOLERANCE: f64 = crate::algebra::ROTATION_TOLERANCE;

/// Largest relative asymmetry max |Mᵢⱼ − Mⱼᵢ| / max |Mᵢⱼ| of a matrix accepted as symmetric
/// (a mass tensor, a map on bivectors) or, with a plus sign, as skew-symmetric (\[ω\]).
/// Matrices computed in floating point (Q J Qᵀ) are symmetric to about 1e-16; 1e-10 leaves a
/// wide margin and still refuses anything that is not meant to be symmetric.
pub const SYMMETRY_TOLERANCE: f64 = 1e-10;

/// A principal second moment Jᵢ counts as negative (no mass distribution has it) when
/// Jᵢ < −`MASS_TENSOR_TOLERANCE` · max |Jₖ|. Smaller negative values are round-off of a flat
/// direction: a mass tensor assembled from a mesh cancels large positive and negative
/// simplex contributions, which leaves errors of about 1e-12 relative.
pub const MASS_TENSOR_TOLERANCE: f64 = 1e-9;

/// A plane moment counts as zero (the inertia map is singular) when it is at most this
/// fraction of the largest plane moment. The eigenvalues of J carry an absolute error of a
/// few ε · max Jᵢ, so 64ε (1.4e-14) separates "singular" from "condition number up to
/// ~1e13", which is still invertible. Used by
/// [`InertiaMap`](super::InertiaMap)'s constructors and as the tolerance to pass to
/// [`Body::check_inertia_invertible`](super::Body::check_inertia_invertible).
pub const SINGULAR_PLANE_TOLERANCE: f64 = 64.0 * f64::EPSILON;

/// Relative volume below which a simplex counts as degenerate.
///
/// The relative volume of a simplex is |det\[v₁ − v₀, …, v_N − v₀\]| / Πₖ |vₖ − v₀|. It lies
/// in \[0, 1\] (Hadamard's inequality) and is 1 for a right-angled corner. Rounding makes a
/// truly flat simplex come out near 1e-16; 1e-12 leaves a margin of four orders.
pub const DEGENERACY_TOLERANCE: f64 = 1e-12;

/// Default relative tolerance for [`Body::flat_directions`](super::Body::flat_directions)
/// and [`Body::check_full_rank`](super::Body::check_full_rank): an eigenvalue of J at most
/// this fraction of the largest is zero.
///
/// The symmetric eigensolver returns eigenvalues with absolute error of order
/// ε · max Jᵢ (ε = 2.2e-16), so an eigenvalue below 1e-12 · max Jᵢ is zero within a margin of
/// about 4500 ulp.
pub const FLATNESS_TOLERANCE: f64 = 1e-12;
