//! The inertia map: a symmetric positive-definite linear operator from angular-velocity
//! bivectors to angular-momentum bivectors, built from real bodies.
//!
//! - [`bodies`]: the catalogue of N-dimensional bodies ([`Body`]): mass, centre of mass,
//!   mass tensor J = ∫ x xᵀ dm and volume.
//! - [`InertiaMap`]: I(ω) = Σ m x∧(x⌋ω) = J\[ω\] + \[ω\]J for physical bodies (DESIGN.md,
//!   "Inertia"), or any symmetric positive-definite map on bivectors for test bodies that no
//!   mass distribution has (the 3D I = (2, 1, 2/3)).
//! - [`tensor`]: the paper's index views of the same object: the rank-4 tensor of its
//!   eq. (22) and the Levi-Civita contracted matrix of eqs. (23)–(31).
//!
//! In the principal frame of J the map is diagonal on the basis planes,
//! I(eᵢ∧eⱼ) = (Jᵢ + Jⱼ) eᵢ∧eⱼ: the plane moment of eᵢ∧eⱼ is ∫(xᵢ² + xⱼ²) dm. In 3D the classical
//! principal moments are I₁ = J₂ + J₃, I₂ = J₁ + J₃, I₃ = J₁ + J₂.
//!
//! Book chapters: `book/src/inertia.md` (the catalogue and the paper's sections 4–6
//! recomputed) and `book/src/errata/inertia.md`.

pub mod bodies;
mod error;
mod map;
pub mod spec;
pub mod tensor;

pub use bodies::{Body, BodyError};
pub use error::InertiaError;
pub use map::InertiaMap;
