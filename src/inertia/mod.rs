//! The inertia map: a symmetric positive-definite linear operator from angular-velocity
//! bivectors to angular-momentum bivectors, built from real bodies.
//!
//! - [`Body`]: mass, centre of mass, mass tensor J = ∫ x xᵀ dm and volume of an
//!   N-dimensional body, from the catalogue of named bodies, meshes, parts or mass properties
//!   (all also under [`bodies`]).
//! - [`InertiaMap`]: I(ω) = Σ m x∧(x⌋ω) = J\[ω\] + \[ω\]J for physical bodies (see the
//!   Conventions chapter of the rotorflow book), or any symmetric positive-definite map on
//!   bivectors for test bodies that no mass distribution has (the 3D I = (2, 1, 2/3)).
//! - [`tensor`]: the paper's index views of the same object: the rank-4 tensor of its
//!   eq. (22) and the Levi-Civita contracted matrix of eqs. (23)–(31).
//! - [`InertiaError`]: the one error type of the layer; [`tolerance`]: the tolerances every
//!   check uses.
//!
//! In the principal frame of J the map is diagonal on the basis planes,
//! I(eᵢ∧eⱼ) = (Jᵢ + Jⱼ) eᵢ∧eⱼ: the plane moment of eᵢ∧eⱼ is ∫(xᵢ² + xⱼ²) dm. The Jᵢ are the
//! principal *second* moments. In 3D the classical principal moments of inertia are
//! I₁ = J₂ + J₃, I₂ = J₁ + J₃, I₃ = J₁ + J₂
//! ([`InertiaMap::from_principal_moments_of_inertia_3d`] takes those).
//!
//! The rotorflow book's Inertia chapter shows the catalogue and recomputes the paper's
//! sections 4–6; its errata chapter lists what differs from the paper.

pub mod bodies;
mod body;
mod catalogue;
mod error;
mod map;
mod mesh;
pub mod spec;
pub mod tensor;
pub mod tolerance;
mod validate;

pub use body::Body;
pub use error::InertiaError;
pub use map::InertiaMap;
pub use mesh::SimplexOrientation;
