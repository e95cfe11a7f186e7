//! Contact of bodies with half-spaces: the shapes bodies touch with, the planes, and the
//! contacts found at a step.

use super::MotionError;
use super::placement::set_vector;
use super::shape::{CompoundShape, ConvexCore, ConvexShape};
use crate::algebra::Vector;
use crate::dynamics::DynamicsError;
use crate::inertia::spec::Geometry;

/// What a body touches the world with, in its own axes about its centre of mass.
///
/// Contact is between a body's shape and a [`HalfSpace`]; the shape answers one question,
/// "which of my points lie deepest along a direction", so that body–body contact can later
/// use the same shapes (a support function is what GJK needs).
///
/// [`ContactShape::Convex`] takes any shape of [`shape`](super::shape) (capsules, rounded
/// boxes and hulls, cross-polytopes, simplices); the vertices and the ellipsoid are the
/// shapes of the SPEC grammar's bodies.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ContactShape {
    /// No contact: the body passes through planes.
    None,
    /// The convex hull of these points (a polytope's vertices, a mesh's vertices): only
    /// they can touch a plane.
    Vertices(Vec<Vector>),
    /// A solid ellipsoid (a ball when the semi-axes are equal) with these semi-axes along
    /// the own axes.
    Ellipsoid(Vec<f64>),
    /// A convex shape of [`shape`](super::shape), centred on the centre of mass, its own
    /// axes the body's. A plane is touched by the points of the core's vertices (box
    /// corners, a segment's ends, a hull's points) moved by the margin against the plane's
    /// normal, or by the one deepest point of a point or ellipsoid core; other bodies by
    /// the narrow phase of the shapes (one point per pair unless both are hulls or boxes
    /// without margin, which touch by their contact manifold).
    Convex(ConvexShape),
    /// A union of convex pieces ([`CompoundShape`]), each placed in the body's own axes
    /// about the centre of mass: it touches with each piece as a [`ContactShape::Convex`]
    /// does.
    Compound(CompoundShape),
}

impl ContactShape {
    /// Returns the contact shape of a body of the SPEC grammar: the vertices of boxes,
    /// point sets and meshes, the ellipsoid of `ellipsoid:`, `ball:` and `sphere:`, and
    /// [`ContactShape::None`] for bodies given only by their mass tensor or plane moments.
    pub fn from_geometry(geometry: &Geometry) -> ContactShape {
        let vertices = |points: &[Vec<f64>]| {
            ContactShape::Vertices(points.iter().map(|p| vector_of(p)).collect())
        };
        match geometry {
            Geometry::Cuboid { half_lengths, .. } => {
                let n = half_lengths.len();
                let corners = (0..1usize << n)
                    .map(|mask| {
                        let c: Vec<f64> = (0..n)
                            .map(|i| {
                                if mask >> i & 1 == 1 {
                                    half_lengths[i]
                                } else {
                                    -half_lengths[i]
                                }
                            })
                            .collect();
                        vector_of(&c)
                    })
                    .collect();
                ContactShape::Vertices(corners)
            }
            Geometry::Points(points) => vertices(points),
            Geometry::Mesh { vertices: v, .. } => vertices(v),
            Geometry::Ellipsoid { semi_axes, .. } => ContactShape::Ellipsoid(semi_axes.clone()),
            _ => ContactShape::None,
        }
    }

    /// True for a polytope: vertices, or a convex shape whose core is a box or a hull and
    /// that has no margin (a body whose contact points are material points of it, rather
    /// than points that move over its surface as it rolls).
    pub fn is_polytope(&self) -> bool {
        match self {
            ContactShape::Vertices(_) => true,
            ContactShape::Convex(c) => {
                c.margin() == 0.0 && matches!(c.core(), ConvexCore::Cuboid(_) | ConvexCore::Hull(_))
            }
            _ => false,
        }
    }

    /// Returns the radius of the smallest ball about the centre of mass holding the shape
    /// (0 for no shape): the length contact tolerances are relative to.
    pub fn radius(&self) -> f64 {
        match self {
            ContactShape::None => 0.0,
            ContactShape::Vertices(v) => v.iter().map(Vector::norm).fold(0.0, f64::max),
            ContactShape::Ellipsoid(a) => a.iter().copied().fold(0.0, f64::max),
            ContactShape::Convex(c) => c.bounding_radius(),
            ContactShape::Compound(c) => c.bounding_radius(),
        }
    }

    /// Returns the support point of the shape placed with `attitude` (own axes → space):
    /// the point of the shape, in own axes, that reaches furthest along the space
    /// direction `direction` (None for [`ContactShape::None`] or a zero direction). The
    /// support function is all a convex body needs to show for contact: half-spaces use it
    /// along their inward normal, and body–body collision (GJK/EPA) can use it as is.
    ///
    /// # Panics
    /// If the dimensions differ.
    pub fn support_point(
        &self,
        attitude: &crate::dynamics::Attitude,
        direction: &Vector,
    ) -> Option<Vector> {
        let n = direction.dim();
        assert_eq!(attitude.dim(), n, "rotorflow: dimension mismatch");
        let length = direction.norm();
        if !(length > 0.0 && length.is_finite()) {
            return None;
        }
        let mut q = smallvec::SmallVec::<[f64; 64]>::from_elem(0.0, n * n);
        attitude.write_matrix(&mut q);
        // The candidates against −direction are the points furthest along direction.
        let inward = direction * (-1.0 / length);
        let mut best: Option<(f64, Vector)> = None;
        self.candidates(&q, &inward, |r, r_space| {
            let reach = -inward.dot(r_space);
            if best.as_ref().is_none_or(|(b, _)| reach > *b) {
                best = Some((reach, r.clone()));
            }
        });
        best.map(|(_, r)| r)
    }

    /// Checks the shape against the dimension `n`.
    pub(crate) fn check(&self, n: usize) -> Result<(), DynamicsError> {
        match self {
            ContactShape::None => Ok(()),
            ContactShape::Vertices(v) => {
                if v.is_empty() {
                    return Err(MotionError::EmptyShape { what: "shape" }.into());
                }
                for p in v {
                    super::body::check_vector("shape vertex", p, n)?;
                }
                Ok(())
            }
            ContactShape::Ellipsoid(a) => {
                super::body::check_slice("ellipsoid semi-axes", a, n)?;
                match a.iter().find(|x| **x <= 0.0) {
                    Some(&x) => Err(MotionError::OutOfRange {
                        what: "semi-axis",
                        value: x,
                        expected: "a finite positive number",
                    }
                    .into()),
                    None => Ok(()),
                }
            }
            ContactShape::Convex(c) if c.dim() == n => Ok(()),
            ContactShape::Convex(c) => Err(MotionError::WrongDimension {
                what: "convex shape",
                expected: n,
                found: c.dim(),
            }
            .into()),
            ContactShape::Compound(c) if c.dim() == n => Ok(()),
            ContactShape::Compound(c) => Err(MotionError::WrongDimension {
                what: "compound shape",
                expected: n,
                found: c.dim(),
            }
            .into()),
        }
    }

    /// Calls `visit(r, r_space)` for each point of the shape that can touch a plane of unit
    /// normal `normal` (space frame): every vertex, or the one point of the ellipsoid whose
    /// outward normal is −`normal`. `r` is in own axes, `r_space` = Q r its offset from the
    /// centre of mass in space, with `q` the attitude of the own axes (row-major N × N).
    pub(crate) fn candidates(
        &self,
        q: &[f64],
        normal: &Vector,
        mut visit: impl FnMut(&Vector, &Vector),
    ) {
        let n = normal.dim();
        let place = |r: &Vector| {
            let mut out = Vector::zero(n);
            for (i, o) in out.as_mut_slice().iter_mut().enumerate() {
                *o = (0..n).map(|j| q[i * n + j] * r.as_slice()[j]).sum();
            }
            out
        };
        match self {
            ContactShape::None => {}
            ContactShape::Vertices(v) => {
                for r in v {
                    visit(r, &place(r));
                }
            }
            ContactShape::Ellipsoid(a) => {
                // The support point along −n: r = −A² m / |A m|, m = Qᵀ n in own axes.
                let mut r = Vector::zero(n);
                let mut s = 0.0;
                for (j, x) in r.as_mut_slice().iter_mut().enumerate() {
                    let m: f64 = (0..n).map(|i| q[i * n + j] * normal.as_slice()[i]).sum();
                    s += (a[j] * m) * (a[j] * m);
                    *x = -a[j] * a[j] * m;
                }
                let r = &r * (1.0 / s.sqrt());
                if a.iter().all(|x| *x == a[0]) {
                    // A ball: its point in space is −a n exactly, the same at every attitude
                    // (the solver keeps a row's matrices while its offset stays the same).
                    visit(&r, &(normal * -a[0]));
                } else {
                    visit(&r, &place(&r));
                }
            }
            ContactShape::Convex(c) => convex_candidates(c, q, normal, &mut visit),
            ContactShape::Compound(compound) => {
                // Each piece's candidates, with its axes Q R and its centre Q o in space:
                // r = o + R r_piece in own axes, Q r = Q o + (Q R) r_piece in space.
                let mut q_piece = smallvec::SmallVec::<[f64; 64]>::from_elem(0.0, n * n);
                let mut centre = smallvec::SmallVec::<[f64; 8]>::from_elem(0.0, n);
                let zero = smallvec::SmallVec::<[f64; 8]>::from_elem(0.0, n);
                for piece in compound.pieces() {
                    if piece.place(&zero, q, &mut centre, &mut q_piece).is_err() {
                        continue;
                    }
                    let (o, rot) = (piece.offset(), piece.rotation());
                    convex_candidates(piece.shape(), &q_piece, normal, &mut |r, r_space| {
                        let own = Vector::from_storage(
                            (0..n)
                                .map(|i| {
                                    o[i] + (0..n)
                                        .map(|j| rot[i * n + j] * r.as_slice()[j])
                                        .sum::<f64>()
                                })
                                .collect(),
                        );
                        let space = Vector::from_storage(
                            centre
                                .iter()
                                .zip(r_space.as_slice())
                                .map(|(c, x)| c + x)
                                .collect(),
                        );
                        visit(&own, &space);
                    });
                }
            }
        }
    }
}

/// [`ContactShape::candidates`] of a convex shape whose axes are `q` (row-major N × N, own
/// axes → space): the vertices of its core moved by the margin against the normal, or the
/// one deepest point of a point or ellipsoid core.
fn convex_candidates(
    c: &ConvexShape,
    q: &[f64],
    normal: &Vector,
    visit: &mut impl FnMut(&Vector, &Vector),
) {
    let n = normal.dim();
    let place = |r: &Vector| {
        let mut out = Vector::zero(n);
        for (i, o) in out.as_mut_slice().iter_mut().enumerate() {
            *o = (0..n).map(|j| q[i * n + j] * r.as_slice()[j]).sum();
        }
        out
    };
    // m = Qᵀ n, the normal in own axes; each candidate is a point of the core
    // moved by the margin along −m, the deepest point of the margin's ball
    // around it.
    let m: smallvec::SmallVec<[f64; 8]> = (0..n)
        .map(|j| (0..n).map(|i| q[i * n + j] * normal.as_slice()[i]).sum())
        .collect();
    let r = c.margin();
    let mut visit_core = |p: &[f64]| {
        let own = Vector::from_storage(p.iter().zip(&m).map(|(x, m)| x - r * m).collect());
        visit(&own, &place(&own));
    };
    match c.core() {
        ConvexCore::Cuboid(h) => {
            let mut p: smallvec::SmallVec<[f64; 8]> = h.iter().map(|x| -x).collect();
            for mask in 0..1usize << n {
                for (i, (x, hi)) in p.iter_mut().zip(h.iter()).enumerate() {
                    *x = if mask >> i & 1 == 1 { *hi } else { -hi };
                }
                visit_core(&p);
            }
        }
        ConvexCore::Segment(h) => {
            let mut p = smallvec::SmallVec::<[f64; 8]>::from_elem(0.0, n);
            for end in [-h, *h] {
                p[0] = end;
                visit_core(&p);
            }
        }
        ConvexCore::Hull(v) => v.chunks_exact(n).for_each(&mut visit_core),
        _ => {
            // A point or an ellipsoid: its support point along −m.
            let minus: smallvec::SmallVec<[f64; 8]> = m.iter().map(|x| -x).collect();
            let mut p = smallvec::SmallVec::<[f64; 8]>::from_elem(0.0, n);
            c.core_support(&minus, &mut p);
            visit_core(&p);
        }
    }
}

/// A vector from components already known to be finite and few.
fn vector_of(components: &[f64]) -> Vector {
    Vector::from_storage(smallvec::SmallVec::from_slice(components))
}

/// A half-space {x : n·x ≤ d} of solid world (a floor, a wall, a slope) bounded by the plane
/// n·x = d, with the coefficients of its contacts: Coulomb friction μ and restitution e.
///
/// The normal n points out of the solid, into the free side. It is stored unit: a normal
/// of length s and offset d describe the plane n·x = d, that is (n/s)·x = d/s.
#[derive(Clone, Debug, PartialEq)]
pub struct HalfSpace {
    normal: Vector,
    offset: f64,
    friction: f64,
    restitution: f64,
}

impl HalfSpace {
    /// Returns the half-space below the plane `normal`·x = `offset`, with friction
    /// coefficient `friction` (≥ 0) and restitution `restitution` (in [0, 1]).
    ///
    /// # Errors
    /// [`MotionError`] naming the bad parameter: a zero or non-finite normal
    /// ([`MotionError::ZeroVector`], [`MotionError::NonFinite`]), a non-finite offset, a
    /// negative friction, a restitution outside [0, 1] ([`MotionError::OutOfRange`]).
    pub fn new(
        normal: &Vector,
        offset: f64,
        friction: f64,
        restitution: f64,
    ) -> Result<HalfSpace, DynamicsError> {
        let s = normal.norm();
        if let Some(&value) = normal.as_slice().iter().find(|x| !x.is_finite()) {
            return Err(MotionError::NonFinite {
                what: "normal",
                value,
            }
            .into());
        }
        if !(s.is_finite() && s > 0.0) {
            return Err(MotionError::ZeroVector { what: "normal" }.into());
        }
        let range = |what, value: f64, ok: bool, expected| {
            if ok {
                Ok(())
            } else {
                Err(MotionError::OutOfRange {
                    what,
                    value,
                    expected,
                })
            }
        };
        range("offset", offset, offset.is_finite(), "finite")?;
        range(
            "friction",
            friction,
            friction.is_finite() && friction >= 0.0,
            "a finite number ≥ 0",
        )?;
        range(
            "restitution",
            restitution,
            (0.0..=1.0).contains(&restitution),
            "in [0, 1]",
        )?;
        Ok(HalfSpace {
            normal: normal * (1.0 / s),
            offset: offset / s,
            friction,
            restitution,
        })
    }

    /// Returns the unit normal n (out of the solid).
    pub fn normal(&self) -> &Vector {
        &self.normal
    }

    /// Returns the offset d of the plane n·x = d (n unit).
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// Returns the Coulomb friction coefficient μ.
    pub fn friction(&self) -> f64 {
        self.friction
    }

    /// Returns the restitution e.
    pub fn restitution(&self) -> f64 {
        self.restitution
    }

    /// Returns the signed distance n·x − d of a point from the plane (negative inside the
    /// solid).
    pub fn distance(&self, x: &Vector) -> f64 {
        self.normal.dot(x) - self.offset
    }
}

/// One contact of a velocity solve of the last step: where a body touched a half-space,
/// the impulse the half-space gave it there in that solve, and the slip it left (see
/// [`System::contacts`](super::System::contacts)).
#[derive(Clone, Debug, PartialEq)]
pub struct Contact {
    /// The body, by index.
    pub body: usize,
    /// The half-space, by index.
    pub half_space: usize,
    /// The contact point, in the body's own axes.
    pub point: Vector,
    /// The normal impulse (≥ 0) of the solve.
    pub normal_impulse: f64,
    /// The friction impulse of the solve (space frame, in the plane).
    pub friction_impulse: Vector,
    /// The sliding velocity of the contact point in the plane after the solve's impulses
    /// (space frame): zero while the contact sticks or rolls.
    pub slip: Vector,
}

/// One contact between two bodies in a velocity solve of the last step: where body `a`
/// touched body `b` (a < b) and the impulse of that solve there (see
/// [`System::body_contacts`](super::System::body_contacts)).
#[derive(Clone, Debug, PartialEq)]
pub struct BodyContact {
    /// The first body, by index.
    pub a: usize,
    /// The second body, by index (greater than `a`).
    pub b: usize,
    /// The contact point in space.
    pub point: Vector,
    /// The unit normal in space, from `a` towards `b`.
    pub normal: Vector,
    /// The normal impulse (≥ 0) body `b` received (body `a` the opposite).
    pub normal_impulse: f64,
    /// The friction impulse body `b` received (space frame; body `a` the opposite).
    pub friction_impulse: Vector,
}

/// The contacts of the last step. Entries past the length stay allocated, so that the
/// contacts of the next step are written over them instead of being built and moved.
#[derive(Clone, Debug, Default)]
pub(crate) struct ContactLog {
    entries: Vec<Contact>,
    len: usize,
    pairs: Vec<BodyContact>,
    pairs_len: usize,
}

/// How many contacts of each kind a [`ContactLog`] holds, to come back to.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ContactMark(usize, usize);

impl ContactLog {
    /// The contacts with half-spaces recorded.
    pub(crate) fn as_slice(&self) -> &[Contact] {
        &self.entries[..self.len]
    }

    /// The contacts between bodies recorded.
    pub(crate) fn pairs(&self) -> &[BodyContact] {
        &self.pairs[..self.pairs_len]
    }

    /// Forgets every contact.
    pub(crate) fn clear(&mut self) {
        self.len = 0;
        self.pairs_len = 0;
    }

    /// How many contacts of each kind are recorded now.
    pub(crate) fn mark(&self) -> ContactMark {
        ContactMark(self.len, self.pairs_len)
    }

    /// Keeps the contacts recorded up to `mark`.
    pub(crate) fn truncate(&mut self, mark: ContactMark) {
        self.len = self.len.min(mark.0);
        self.pairs_len = self.pairs_len.min(mark.1);
    }

    /// Records a contact between bodies `a` and `b` at `point` (space) with unit normal
    /// `normal` (from `a` to `b`) and the impulses body `b` received.
    pub(crate) fn record_pair(
        &mut self,
        (a, b): (usize, usize),
        point: &Vector,
        normal: &Vector,
        normal_impulse: f64,
        friction_impulse: &Vector,
    ) {
        if self.pairs_len == self.pairs.len() {
            self.pairs.push(BodyContact {
                a,
                b,
                point: point.clone(),
                normal: normal.clone(),
                normal_impulse,
                friction_impulse: friction_impulse.clone(),
            });
        } else {
            let c = &mut self.pairs[self.pairs_len];
            c.a = a;
            c.b = b;
            c.point.clone_from(point);
            c.normal.clone_from(normal);
            c.normal_impulse = normal_impulse;
            c.friction_impulse.clone_from(friction_impulse);
        }
        self.pairs_len += 1;
    }

    /// Records a contact: the point of body `body` (own axes) touching half-space
    /// `half_space`, its impulses, and `slip`, its velocity after them (projected into the
    /// plane of unit normal `normal` here). All slices have the length N.
    #[inline(always)]
    pub(crate) fn record(
        &mut self,
        (body, half_space): (usize, usize),
        point: &[f64],
        normal_impulse: f64,
        friction_impulse: &[f64],
        slip: &[f64],
        normal: &[f64],
    ) {
        let n = point.len();
        if self.len == self.entries.len() {
            self.entries.push(Contact {
                body,
                half_space,
                point: Vector::zero(n),
                normal_impulse,
                friction_impulse: Vector::zero(n),
                slip: Vector::zero(n),
            });
        }
        let c = &mut self.entries[self.len];
        c.body = body;
        c.half_space = half_space;
        set_vector(&mut c.point, point);
        c.normal_impulse = normal_impulse;
        set_vector(&mut c.friction_impulse, friction_impulse);
        if c.slip.dim() != n {
            c.slip = Vector::zero(n);
        }
        let along: f64 = slip.iter().zip(normal).map(|(u, x)| u * x).sum();
        for ((s, u), x) in c.slip.as_mut_slice().iter_mut().zip(slip).zip(normal) {
            *s = u - along * x;
        }
        self.len += 1;
    }
}
