//! Ball joints: constraints that hold a body point on another body's point or on a point
//! of space.

use super::forques::Anchor;
use crate::algebra::Vector;

/// A ball (spherical) joint: the body point `point` of body `body` is held on `other` (a
/// point of space, or a point of another body). It is a constraint, kept by impulses, not a
/// stiff spring: the bodies turn freely about the joint and no energy is stored in it.
#[derive(Clone, Debug)]
pub struct BallJoint {
    /// The body, by index.
    pub body: usize,
    /// The jointed point, in the body's own axes.
    pub point: Vector,
    /// What it is held on.
    pub other: Anchor,
}
