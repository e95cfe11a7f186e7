//! The catalogue of named bodies: point sets, solids and shells with closed-form mass
//! properties.
//!
//! # Formulas (standard results, derived in the docs of each constructor)
//!
//! | body | volume | J (principal) |
//! |---|---|---|
//! | solid cuboid, half-edges aᵢ | Π 2aᵢ | m aᵢ²/3 |
//! | solid ellipsoid, semi-axes aᵢ | V_N Π aᵢ | m aᵢ²/(N+2) |
//! | solid ball, radius R | V_N Rᴺ | m R²/(N+2) |
//! | shell Sᴺ⁻¹, radius R | — (area N V_N Rᴺ⁻¹) | m R²/N |
//! | solid simplex, vertices vₖ | \|det\|/N! | vertex formula below |
//! | 2ᴺ vertices (±aᵢ) | — | 2ᴺ μ aᵢ² |
//! | 2N vertices ±r eᵢ | — | 2 μ r² |
//! | regular simplex, circumradius r | — | (N+1) μ r²/N |
//!
//! Here V_N = π^(N/2)/Γ(N/2 + 1) is the volume of the unit N-ball (paper eq. 99) and μ is the
//! mass of one vertex. The simplex vertex formula is
//! ∫ x xᵀ dV = Vol/((N+1)(N+2)) [Σ vₖ vₖᵀ + (Σ vₖ)(Σ vₖ)ᵀ].

use super::InertiaError;
use super::body::Body;
use super::mesh::simplex_moments;
use super::tolerance::DEGENERACY_TOLERANCE;
use super::validate::{check_dim, check_points, check_positive, check_positive_list};
use nalgebra::{DMatrix, DVector};

/// Returns the volume V_N = π^(N/2)/Γ(N/2 + 1) of the unit ball in N dimensions (paper
/// eq. 99).
///
/// Computed by the recurrence V₀ = 1, V₁ = 2, V_N = (2π/N) V_(N−2), which avoids the gamma
/// function. V₂ = π, V₃ = 4π/3, V₄ = π²/2.
pub fn unit_ball_volume(dim: usize) -> f64 {
    let mut v = if dim.is_multiple_of(2) { 1.0 } else { 2.0 };
    let mut k = if dim.is_multiple_of(2) { 2 } else { 3 };
    while k <= dim {
        v *= 2.0 * std::f64::consts::PI / k as f64;
        k += 2;
    }
    v
}

/// Returns the (N−1)-dimensional area of the unit sphere Sᴺ⁻¹ ⊂ ℝᴺ, which is N V_N
/// (paper eq. 99, ∂V_(N) at R = 1).
///
/// For N = 1 the "sphere" is the two points ±1 and the area is their count, 2.
pub fn unit_sphere_area(dim: usize) -> f64 {
    dim as f64 * unit_ball_volume(dim)
}

/// Returns the N+1 vertices of a regular N-simplex centred at the origin with circumradius
/// `circumradius`.
///
/// Vertex k has coordinates r √((N+1)/N) hⱼ\[k\], where hⱼ (j = 1…N) are the rows of the
/// Helmert matrix: hⱼ = (1, …, 1, −j, 0, …, 0)/√(j(j+1)) with j ones. The rows are
/// orthonormal and orthogonal to (1, …, 1), so the vertices are the images of the standard
/// basis e₀…e_N of ℝᴺ⁺¹, centred and scaled. The edge is r √(2(N+1)/N).
///
/// # Errors
/// [`InertiaError::DimensionTooSmall`] for N = 0; [`InertiaError::NonFinite`] or
/// [`InertiaError::NotPositive`] for a bad radius.
pub fn regular_simplex_positions(
    dim: usize,
    circumradius: f64,
) -> Result<Vec<DVector<f64>>, InertiaError> {
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
/// similarity. See [`Body::pentachoron`].
///
/// # Errors
/// [`InertiaError::NonFinite`] or [`InertiaError::NotPositive`] for a bad parameter.
pub fn pentachoron_vertices(
    a: f64,
    b: f64,
    c: f64,
    d: f64,
) -> Result<Vec<DVector<f64>>, InertiaError> {
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

impl Body {
    /// Returns 2ᴺ equal point masses `vertex_mass` at the vertices (±a₁, …, ±a_N) of the
    /// hyper-cuboid with half-edges `half_edges` = (a₁, …, a_N), centred at the origin.
    ///
    /// With `vertex_mass = 1` and N = 4 this is the paper's tesseract of unit masses (eq. 69,
    /// with half-edges a, b, c, d as in the paper's §5). Mass 2ᴺ μ and
    /// J = diag(2ᴺ μ aᵢ²) exactly (each coordinate is ±aᵢ at every vertex, and the
    /// off-diagonal sums cancel by symmetry).
    ///
    /// # Errors
    /// [`InertiaError::Empty`] for no half-edges; [`InertiaError::NonFinite`],
    /// [`InertiaError::NotPositive`] for bad numbers; [`InertiaError::NonFiniteResult`] on overflow.
    pub fn cuboid_vertices(half_edges: &[f64], vertex_mass: f64) -> Result<Body, InertiaError> {
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
    /// the simplex acts irreducibly, and tr J = Σ |xₖ|² = (N+1) r².
    ///
    /// # Errors
    /// [`InertiaError::DimensionTooSmall`] for N = 0; [`InertiaError::NonFinite`],
    /// [`InertiaError::NotPositive`] for bad numbers.
    pub fn regular_simplex_vertices(
        dim: usize,
        circumradius: f64,
        vertex_mass: f64,
    ) -> Result<Body, InertiaError> {
        isotropic_vertices(dim, ("circumradius", circumradius), vertex_mass, |n| {
            let mass = (n + 1.0) * vertex_mass;
            (mass, mass * circumradius * circumradius / n)
        })
    }

    /// Returns the paper's 5-cell (pentachoron): unit point masses at the five points of its
    /// eq. (73) (see [`pentachoron_vertices`]).
    ///
    /// Properties (tested against the paper in the inertia errata tests):
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
    /// [`InertiaError::NonFinite`] or [`InertiaError::NotPositive`] for a bad parameter.
    pub fn pentachoron(a: f64, b: f64, c: f64, d: f64) -> Result<Body, InertiaError> {
        let positions = pentachoron_vertices(a, b, c, d)?;
        Body::point_masses(&[1.0; 5], &positions)
    }

    /// Returns 2N equal point masses `vertex_mass` at the vertices ±r eᵢ of the
    /// cross-polytope (orthoplex) centred at the origin.
    ///
    /// Mass 2N μ and J = 2 μ r² · 1 (only the two vertices on axis i contribute to Jᵢᵢ).
    ///
    /// # Errors
    /// [`InertiaError::DimensionTooSmall`] for N = 0; [`InertiaError::NonFinite`],
    /// [`InertiaError::NotPositive`] for bad numbers.
    pub fn cross_polytope_vertices(
        dim: usize,
        radius: f64,
        vertex_mass: f64,
    ) -> Result<Body, InertiaError> {
        isotropic_vertices(dim, ("radius", radius), vertex_mass, |n| {
            (2.0 * n * vertex_mass, 2.0 * vertex_mass * radius * radius)
        })
    }

    /// Returns the solid hyper-cuboid [−a₁, a₁] × … × [−a_N, a_N] of uniform `density`.
    ///
    /// Volume Π 2aᵢ (paper eqs. 77 and 81 for N = 4, 5), mass ρ·Volume, and
    /// J = diag(m aᵢ²/3), since (1/2a)∫₋ₐᵃ x² dx = a²/3 (with edge
    /// 2aᵢ: m (2aᵢ)²/12).
    ///
    /// # Errors
    /// [`InertiaError::Empty`], [`InertiaError::NonFinite`], [`InertiaError::NotPositive`],
    /// [`InertiaError::NonFiniteResult`].
    pub fn solid_cuboid(half_edges: &[f64], density: f64) -> Result<Body, InertiaError> {
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

    /// Returns the solid ellipsoid Σ (xᵢ/aᵢ)² ≤ 1 of uniform `density`.
    ///
    /// Volume V_N Π aᵢ with V_N = π^(N/2)/Γ(N/2 + 1) ([`unit_ball_volume`], paper eq. 99),
    /// mass ρ·Volume, and J = diag(m aᵢ²/(N+2)) (the ellipsoid is the
    /// image of the unit ball under diag(aᵢ), and the unit ball has ∫xᵢ² dV/V = 1/(N+2)).
    ///
    /// # Errors
    /// [`InertiaError::Empty`], [`InertiaError::NonFinite`], [`InertiaError::NotPositive`],
    /// [`InertiaError::NonFiniteResult`].
    pub fn solid_ellipsoid(semi_axes: &[f64], density: f64) -> Result<Body, InertiaError> {
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
    /// Volume V_N Rᴺ (paper eq. 99), J = m R²/(N+2) · 1. The paper's
    /// polar moment tr J/m = N R²/(N+2) is its eq. (102).
    ///
    /// # Errors
    /// [`InertiaError::DimensionTooSmall`] for N = 0, [`InertiaError::NonFinite`],
    /// [`InertiaError::NotPositive`], [`InertiaError::NonFiniteResult`].
    pub fn solid_ball(dim: usize, radius: f64, density: f64) -> Result<Body, InertiaError> {
        check_dim(dim, 1)?;
        check_positive("radius", None, radius)?;
        Body::solid_ellipsoid(&vec![radius; dim], density)
    }

    /// Returns the hollow hypersphere Sᴺ⁻¹ of radius R with uniform `surface_density` σ.
    ///
    /// Mass σ · N V_N Rᴺ⁻¹ (the area ∂V_(N) of paper eq. 99) and J = m R²/N · 1, since
    /// Σᵢ xᵢ² = R² on the sphere and all axes are equivalent. The
    /// volume is `None`. For N = 1 the "sphere" is the two points ±R, each of mass σ.
    ///
    /// # Errors
    /// [`InertiaError::DimensionTooSmall`] for N = 0, [`InertiaError::NonFinite`],
    /// [`InertiaError::NotPositive`], [`InertiaError::NonFiniteResult`].
    pub fn hypersphere_shell(
        dim: usize,
        radius: f64,
        surface_density: f64,
    ) -> Result<Body, InertiaError> {
        check_dim(dim, 1)?;
        check_positive("radius", None, radius)?;
        check_positive("surface_density", None, surface_density)?;
        let area = unit_sphere_area(dim) * radius.powi(dim as i32 - 1);
        let mass = surface_density * area;
        let j = DMatrix::identity(dim, dim) * (mass * radius * radius / dim as f64);
        Body::new_checked(mass, DVector::zeros(dim), j, None)
    }

    /// Returns the solid N-simplex with the given N+1 vertices in ℝᴺ and uniform `density`.
    ///
    /// Volume |det[v₁ − v₀, …, v_N − v₀]|/N!, centre of mass the vertex mean c, and, with
    /// wₖ = vₖ − c (so Σ wₖ = 0), J = m/((N+1)(N+2)) Σₖ wₖ wₖᵀ. This is the vertex
    /// formula ∫ x xᵀ dV = Vol/((N+1)(N+2)) [Σ vₖ vₖᵀ + (Σ vₖ)(Σ vₖ)ᵀ]
    /// applied about the centroid.
    ///
    /// # Errors
    /// [`InertiaError::Empty`], [`InertiaError::LengthMismatch`] (the number of vertices must be
    /// N+1 for points in ℝᴺ), [`InertiaError::NonFinite`], [`InertiaError::NotPositive`],
    /// [`InertiaError::DegenerateSimplex`] when the vertices are affinely dependent.
    pub fn solid_simplex(vertices: &[DVector<f64>], density: f64) -> Result<Body, InertiaError> {
        let dim = check_points("vertices", vertices)?;
        if vertices.len() != dim + 1 {
            return Err(InertiaError::LengthMismatch {
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
            return Err(InertiaError::DegenerateSimplex {
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
}

/// The body of equal point masses `vertex_mass` on a sphere of the radius `radius` (named
/// for messages) about the origin, placed so that J is isotropic: `mass_and_j(N)` gives the
/// mass and the common diagonal entry of J.
fn isotropic_vertices(
    dim: usize,
    (radius_name, radius): (&'static str, f64),
    vertex_mass: f64,
    mass_and_j: impl FnOnce(f64) -> (f64, f64),
) -> Result<Body, InertiaError> {
    check_dim(dim, 1)?;
    check_positive(radius_name, None, radius)?;
    check_positive("vertex_mass", None, vertex_mass)?;
    let (mass, j) = mass_and_j(dim as f64);
    Body::new_checked(
        mass,
        DVector::zeros(dim),
        DMatrix::identity(dim, dim) * j,
        None,
    )
}
