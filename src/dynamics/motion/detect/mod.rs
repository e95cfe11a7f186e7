//! Collision detection between bodies: which pairs may touch (the broad phase), whether and
//! how deep two shapes overlap (the narrow phase), and where they touch (contact manifolds).
//!
//! Shapes are placed by plain data: a centre `position` (N numbers, space) and a `rotation`
//! (N × N, row-major, own axes → space). Normals point from body A to body B, depth > 0
//! means overlap, and witness points are in space.

pub mod broad;
pub mod manifold;
pub mod sat;

pub use broad::BroadPhase;
pub use manifold::{
    ContactManifold, ContactPoint, FeatureId, PlacedHull, RegionVertex, box_contact_vertices,
    box_manifold, hull_contact_vertices, hull_manifold,
};
pub use sat::{AxisFeature, BoxPairAxis, PlacedBox, box_box, candidate_axis_count};
