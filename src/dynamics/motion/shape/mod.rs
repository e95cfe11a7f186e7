//! Convex shapes for body–body contact, each known by its support function.
//!
//! - [`ConvexShape`]: balls (and hollow spheres, which touch with their ball),
//!   ellipsoids, cuboids, convex hulls of points (simplices, cross-polytopes, the
//!   tesseract, mesh vertices), capsules, and any of them rounded by a margin, in any
//!   dimension N ≥ 2; support points in O(N) for the closed forms, bounding radii and
//!   axis-aligned boxes for a placement.
//! - [`CompoundShape`]: a union of convex [`Piece`]s, each with its own offset and
//!   rotation in the body's axes.
//! - [`ShapeError`]: why an input was refused.
//!
//! A shape is placed by its centre `position` (N numbers, space) and `rotation`
//! (row-major N × N, own axes → space): x_space = position + Q x_own, the matrix that
//! `Attitude::write_matrix` writes. The narrow phase (`detect`) asks a placed shape for
//! support points only (Gilbert, Johnson & Keerthi; van den Bergen, "Collision Detection
//! in Interactive 3D Environments").

mod compound;
mod convex;
mod error;

pub use compound::{CompoundShape, Piece};
pub use convex::{ConvexCore, ConvexShape};
pub(crate) use convex::{Coords, check_placement};
pub use error::ShapeError;
