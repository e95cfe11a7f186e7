//! The catalogue's free functions (vertex sets and the volumes of unit balls and spheres),
//! and a table of contents of [`Body`], which lives at [`crate::inertia::Body`]; the mesh
//! options are [`crate::inertia::SimplexOrientation`] and the tolerances are in
//! [`crate::inertia::tolerance`].
//!
//! A [`Body`] holds the mass m, the centre of mass c and the mass tensor
//! J = ∫ (x − c)(x − c)ᵀ dm about the centre of mass (see the Conventions chapter of the
//! rotorflow book). J is the N×N second-moment matrix, not the 3D inertia tensor. In the
//! principal frame J = diag(J₁, …, J_N) (the principal second moments), and the inertia map is
//! diagonal on the basis planes with plane moments Jᵢ + Jⱼ. In 3D the classical principal
//! moments of inertia are I₁ = J₂ + J₃, I₂ = J₁ + J₃ and I₃ = J₁ + J₂.
//!
//! # Table of contents
//!
//! - Point sets: [`Body::point_masses`], [`Body::cuboid_vertices`] (the paper's tesseract,
//!   eq. 69), [`Body::regular_simplex_vertices`], [`Body::pentachoron`] (the paper's
//!   5-cell, eq. 73), [`Body::cross_polytope_vertices`].
//! - Solids and shells: [`Body::solid_cuboid`], [`Body::solid_ellipsoid`],
//!   [`Body::solid_ball`], [`Body::hypersphere_shell`], [`Body::solid_simplex`].
//! - Meshes and assemblies: [`Body::simplicial_mesh`], [`Body::closed_boundary_mesh`],
//!   [`Body::composite`], [`Body::from_mass_properties`].
//! - Rigid motions: [`Body::rotated_by`], [`Body::translated_by`], [`Body::placed_by`]
//!   (rotors and vectors), [`Body::rotated`], [`Body::translated`], [`Body::placed`]
//!   (nalgebra matrices), [`Body::orthogonally_transformed`] (mirror images),
//!   [`Body::with_mass`].
//! - Queries: [`Body::mass_tensor_about`], [`Body::principal_second_moments`],
//!   [`Body::principal_moments_of_inertia_3d`], [`Body::principal_frame`],
//!   [`Body::principal_rotor`], [`Body::plane_moments`], [`Body::principal_plane_moments`],
//!   [`Body::flat_directions`], [`Body::check_full_rank`],
//!   [`Body::check_inertia_invertible`].

#[cfg(doc)]
use super::Body;
#[doc(inline)]
pub use super::catalogue::{
    pentachoron_vertices, regular_simplex_positions, unit_ball_volume, unit_sphere_area,
};
