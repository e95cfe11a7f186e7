//! Collision detection between placed convex shapes.
//!
//! - Narrow phase: [`distance`] and [`intersects`] (GJK with an exact simplex
//!   sub-algorithm, `gjk.rs`), [`penetration`] (EPA in N dimensions and closed forms,
//!   `epa.rs`), on [`PlacedShape`]s of [`super::shape`].

pub(crate) mod bodies;
mod epa;
mod gjk;

pub use epa::{EpaWorkspace, Penetration, penetration, penetration_with};
pub use gjk::{PlacedShape, Separation, distance, intersects};
