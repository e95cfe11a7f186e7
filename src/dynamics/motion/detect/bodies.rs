//! Which bodies touch which: the convex shapes of the bodies' contact shapes, the pairs
//! whose bounding balls come within reach (the broad phase), and for each such pair the
//! signed distance, the contact normal and the contact point (the narrow phase).

use super::manifold::{box_manifold_on_axis, support_set_capacity};
use super::sat::{box_box_unchecked, boxes_apart_by_more_than};
use super::{
    BroadPhase, ContactManifold, EpaWorkspace, PlacedBox, PlacedHull, PlacedShape, hull_manifold,
    penetration_with,
};
use crate::dynamics::motion::forques::Anchor;
use crate::dynamics::motion::shape::{ConvexCore, ConvexShape};
use crate::dynamics::motion::{BallJoint, ContactShape, MovingBody};
use smallvec::SmallVec;

/// The convex shape a body collides with other bodies by: the hull of a shape's vertices,
/// its ellipsoid. None for a body without a shape.
pub(crate) fn convex_of(shape: &ContactShape, n: usize) -> Option<ConvexShape> {
    match shape {
        ContactShape::None => None,
        // A ball as a point with a margin: distances and normals between balls are then
        // closed forms, exact to round-off.
        ContactShape::Ellipsoid(a) if a.iter().all(|x| *x == a[0]) => {
            ConvexShape::ball(n, a[0]).ok()
        }
        ContactShape::Ellipsoid(a) => ConvexShape::ellipsoid(a).ok(),
        ContactShape::Vertices(v) => {
            let flat: Vec<f64> = v
                .iter()
                .flat_map(|p| p.as_slice().iter().copied())
                .collect();
            Some(ConvexShape::hull_unchecked(flat, n))
        }
        ContactShape::Convex(c) => Some(c.clone()),
    }
}

/// The vertices of a shape's core when it is a box or a segment (row-major), made once: a
/// hull's own vertices are used as they are ([`core_hull`]).
fn core_vertices(c: &ConvexShape) -> Option<Vec<f64>> {
    let n = c.dim();
    match c.core() {
        ConvexCore::Cuboid(h) if n < 16 => Some(
            (0..1usize << n)
                .flat_map(|mask| {
                    h.iter()
                        .enumerate()
                        .map(move |(i, hi)| if mask >> i & 1 == 1 { *hi } else { -hi })
                })
                .collect(),
        ),
        ConvexCore::Segment(h) => {
            let mut v = vec![0.0; 2 * n];
            v[0] = -h;
            v[n] = *h;
            Some(v)
        }
        _ => None,
    }
}

/// The half-lengths of a shape's core when it is a box.
fn core_box(c: &ConvexShape) -> Option<&[f64]> {
    match c.core() {
        ConvexCore::Cuboid(h) => Some(h),
        _ => None,
    }
}

/// The vertices of a shape's core when it is a hull.
fn core_hull(c: &ConvexShape) -> Option<&[f64]> {
    match c.core() {
        ConvexCore::Hull(v) => Some(v),
        _ => None,
    }
}

/// How far apart (relative to the sum of the bounding radii) the points of a manifold count
/// as touching.
const MANIFOLD_TOUCHING: f64 = 1e-6;

/// The half-lengths of the box whose corners `v` are (each own axis with ±h on it, all 2^N
/// sign patterns once), or None if they are not a box's corners: boxes are then met by
/// separating axes and face clipping, which are exact where a general hull's penetration
/// normal is ill-conditioned (two faces just touching).
fn box_half_lengths(v: &[crate::algebra::Vector], n: usize) -> Option<Vec<f64>> {
    if n >= usize::BITS as usize || v.len() != 1usize << n || v.iter().any(|p| p.dim() != n) {
        return None;
    }
    let h: Vec<f64> = (0..n)
        .map(|i| v.iter().map(|p| p.as_slice()[i].abs()).fold(0.0, f64::max))
        .collect();
    let mut seen = vec![false; v.len()];
    for p in v {
        let mut pattern = 0usize;
        for (i, (&x, &hi)) in p.as_slice().iter().zip(&h).enumerate() {
            if !(hi > 0.0 && (x.abs() - hi).abs() <= 1e-12 * hi) {
                return None;
            }
            if x > 0.0 {
                pattern |= 1 << i;
            }
        }
        if std::mem::replace(&mut seen[pattern], true) {
            return None;
        }
    }
    Some(h)
}

/// A point where two bodies touch: where they come closest or overlap most, or one point of
/// the contact manifold of two polytopes.
#[derive(Clone, Debug, Default)]
pub(crate) struct PairContact {
    /// The two bodies, by index (a < b).
    pub a: usize,
    pub b: usize,
    /// The features of the two shapes that make the point (see
    /// [`FeatureId`](super::FeatureId); 0 for the single point of curved shapes), so that a
    /// solve can start from the impulse of the same point in the last solve.
    pub feature: u64,
    /// The signed distance at the point (negative: overlap depth).
    pub gap: f64,
    /// The distance within which the pair counts as touching (the scan's factor times the
    /// sum of the bounding radii).
    pub reach: f64,
    /// The unit normal from body `a` to body `b`.
    pub normal: SmallVec<[f64; 8]>,
    /// The contact point in space: midway between the two witness points.
    pub point: SmallVec<[f64; 8]>,
}

/// The bodies' convex shapes and what was found of their pairs, kept from one question to
/// the next.
#[derive(Clone, Debug, Default)]
pub(crate) struct Touching {
    /// The system and the version of its shapes the convex shapes are of.
    owner: Option<(u64, u64)>,
    convex: Vec<Option<ConvexShape>>,
    radius: Vec<f64>,
    /// The half-lengths of the bodies whose shapes are boxes (their corners), which find
    /// their contact normal by separating axes.
    boxes: Vec<Option<Vec<f64>>>,
    /// The vertices of the bodies' cores that are boxes or segments (a capsule's), row-major:
    /// polytopes with a margin touch by the manifold of their cores moved out by the
    /// margins.
    rounded: Vec<Option<Vec<f64>>>,
    workspace: EpaWorkspace,
    /// The pairs of bodies held together by a joint (a < b), which do not touch each other:
    /// their shapes meet at the joint by design.
    joined: Vec<(usize, usize)>,
    /// The hierarchy of the bodies' bounding boxes (the boxes of their bounding balls),
    /// kept from step to step, and the boxes and pairs of the last scan (kept for their
    /// room).
    broad: Option<BroadPhase>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    candidates: Vec<(usize, usize)>,
    /// The pairs found by the last [`Touching::scan`]; entries past `len` keep their room.
    found: Vec<PairContact>,
    len: usize,
    /// True to take two boxes' manifold by clipping the incident face against the
    /// reference face (the points of [`box_manifold`](super::box_manifold), about twice as
    /// fast) instead of the hull manifold of their support sets. The splitting keeps the
    /// hull manifold up to 4D: its towers stand to 1e-9 on it and slide by 1e-3 on the
    /// clipped one. From 5D on both clip (the hull manifold sees 8 of a face's 16 corners).
    clip_boxes: bool,
}

impl Touching {
    /// No shapes yet; two boxes' manifolds by clipping ([`Touching::clip_boxes`]).
    pub(crate) fn clipping_boxes() -> Touching {
        Touching {
            clip_boxes: true,
            ..Touching::default()
        }
    }

    /// Takes the convex shapes of `shapes` if they are not those of `owner` already, and
    /// the pairs that `joints` hold together.
    pub(crate) fn update_shapes(
        &mut self,
        shapes: &[ContactShape],
        joints: &[BallJoint],
        n: usize,
        owner: (u64, u64),
    ) {
        if self.joined.len() != joints.len() || self.owner.is_none() {
            self.joined.clear();
            self.joined.extend(joints.iter().map(|j| match &j.other {
                Anchor::Body(k, _) => (j.body.min(*k), j.body.max(*k)),
                // A joint to space pairs the body with no other.
                Anchor::World(_) => (usize::MAX, usize::MAX),
            }));
        }
        if self.owner == Some(owner) && self.convex.len() == shapes.len() {
            return;
        }
        self.owner = Some(owner);
        self.convex = shapes.iter().map(|s| convex_of(s, n)).collect();
        self.boxes = shapes
            .iter()
            .map(|s| match s {
                ContactShape::Vertices(v) => box_half_lengths(v, n),
                ContactShape::Convex(c) => match c.core() {
                    ConvexCore::Cuboid(h) if c.margin() == 0.0 => Some(h.to_vec()),
                    _ => None,
                },
                _ => None,
            })
            .collect();
        self.rounded = self
            .convex
            .iter()
            .map(|c| c.as_ref().and_then(core_vertices))
            .collect();
        self.radius = self
            .convex
            .iter()
            .map(|c| c.as_ref().map_or(0.0, ConvexShape::bounding_radius))
            .collect();
    }

    /// True if at least two bodies can touch each other.
    pub(crate) fn any_pairs(&self) -> bool {
        self.convex.iter().filter(|c| c.is_some()).count() >= 2
    }

    /// Finds the pairs of bodies whose signed distance is at most `factor` times the sum of
    /// their bounding radii, with each body's own axes `q(i)` (row-major, own axes → space).
    /// The broad phase ([`BroadPhase`]: a hierarchy of the bounding balls' boxes, kept from
    /// step to step) gives the pairs whose boxes overlap, in increasing order, and pairs
    /// whose bounding balls are farther apart are not asked.
    ///
    /// With `manifold: Some(slop)`, two polytopes in contact are reported by the points of
    /// their contact manifold (up to `slop` times the sum of their bounding radii apart:
    /// points about to close are kept with their positive gap, so that a box tilting onto
    /// its face is caught by its corner); otherwise, and for curved shapes, by one point.
    pub(crate) fn scan<'q>(
        &mut self,
        bodies: &[MovingBody],
        q: impl Fn(usize) -> &'q [f64],
        factor: f64,
        manifold: Option<f64>,
    ) {
        self.scan_except(bodies, q, factor, manifold, |_| false);
    }

    /// [`Touching::scan`] without asking the narrow phase for the pairs (a, b) for which
    /// `skip` is true (pairs whose contact the caller knows already).
    pub(crate) fn scan_except<'q>(
        &mut self,
        bodies: &[MovingBody],
        q: impl Fn(usize) -> &'q [f64],
        factor: f64,
        manifold: Option<f64>,
        skip: impl Fn((usize, usize)) -> bool,
    ) {
        self.len = 0;
        let Some(first) = bodies.first() else {
            return;
        };
        let n = first.dim();
        if self.broad.as_ref().is_none_or(|b| b.dim() != n) {
            self.broad = BroadPhase::new(n).ok();
        }
        self.lower.clear();
        self.upper.clear();
        for (b, r) in bodies.iter().zip(&self.radius) {
            let e = r * (1.0 + factor);
            for &x in b.position().as_slice() {
                self.lower.push(x - e);
                self.upper.push(x + e);
            }
        }
        let mut candidates = std::mem::take(&mut self.candidates);
        candidates.clear();
        // A position that is not finite has no pairs (the step reports it).
        if let Some(Ok(pairs)) = self
            .broad
            .as_mut()
            .map(|b| b.update(&self.lower, &self.upper))
        {
            candidates.extend_from_slice(pairs);
        }
        for &(a, b) in &candidates {
            if self.convex[a].is_some() && self.convex[b].is_some() && !skip((a, b)) {
                self.pair(bodies, &q, (a, b), factor, manifold);
            }
        }
        self.candidates = candidates;
    }

    /// Asks the narrow phase for the pair (a, b), a < b, and records it if its signed
    /// distance is at most `factor` times the sum of their bounding radii.
    fn pair<'q>(
        &mut self,
        bodies: &[MovingBody],
        q: &impl Fn(usize) -> &'q [f64],
        (a, b): (usize, usize),
        factor: f64,
        manifold: Option<f64>,
    ) {
        let (Some(ca), Some(cb)) = (&self.convex[a], &self.convex[b]) else {
            return;
        };
        if bodies[a].is_fixed() && bodies[b].is_fixed() || self.joined.contains(&(a, b)) {
            return;
        }
        let (xa, xb) = (
            bodies[a].position().as_slice(),
            bodies[b].position().as_slice(),
        );
        let reach = self.reach((a, b), factor);
        let centres: f64 = xa.iter().zip(xb).map(|(p, q)| (p - q) * (p - q)).sum();
        let bound = self.radius[a] + self.radius[b] + reach;
        if centres > bound * bound {
            return;
        }
        if let (Some(ha), Some(hb)) = (&self.boxes[a], &self.boxes[b]) {
            // Two boxes: the normal and gap by separating axes, exact also where two faces
            // just touch and the depth along every nearby direction is nearly the same (a
            // general penetration query's normal is ill-conditioned there).
            let placed = |half_lengths, position, rotation| PlacedBox {
                half_lengths,
                position,
                rotation,
            };
            let (pa, pb) = (placed(ha, xa, q(a)), placed(hb, xb, q(b)));
            if boxes_apart_by_more_than(&pa, &pb, reach) {
                return;
            }
            let axis = box_box_unchecked(&pa, &pb);
            if -axis.depth > reach {
                return;
            }
            let points = match (manifold, ca.core(), cb.core()) {
                // From 5D on a hull's support set holds fewer vertices than a box face
                // has corners (8 of 16): the hull manifold would hold half of the face.
                (Some(slop), _, _)
                    if self.clip_boxes || support_set_capacity(xa.len()) < 1 << (xa.len() - 1) =>
                {
                    let margin = slop * (self.radius[a] + self.radius[b]);
                    let (pa, pb) = (placed(ha, xa, q(a)), placed(hb, xb, q(b)));
                    Some(box_manifold_on_axis(&pa, &pb, &axis, margin))
                }
                (Some(slop), ConvexCore::Hull(va), ConvexCore::Hull(vb)) => {
                    let hull = |vertices, position, rotation| PlacedHull {
                        vertices,
                        position,
                        rotation,
                    };
                    let margin = slop * (self.radius[a] + self.radius[b]);
                    hull_manifold(
                        &hull(va, xa, q(a)),
                        &hull(vb, xb, q(b)),
                        &axis.normal,
                        margin,
                    )
                    .ok()
                    .flatten()
                }
                _ => None,
            };
            let points = points.filter(|m| !m.is_empty());
            if let Some(m) = points {
                self.push_manifold((a, b), &m, reach);
                return;
            }
            if manifold.is_none() {
                // The gap alone is asked for: the point is the midpoint of the centres.
                let c = self.next((a, b), 0, -axis.depth, &axis.normal);
                c.reach = reach;
                c.point
                    .extend(xa.iter().zip(xb).map(|(x, y)| 0.5 * (x + y)));
                return;
            }
        }
        let (Ok(pa), Ok(pb)) = (
            PlacedShape::new(ca, xa, q(a)),
            PlacedShape::new(cb, xb, q(b)),
        ) else {
            return;
        };
        let Ok(p) = penetration_with(&mut self.workspace, &pa, &pb) else {
            return;
        };
        if -p.depth > reach {
            return;
        }
        if let (Some(slop), ConvexCore::Hull(va), ConvexCore::Hull(vb)) =
            (manifold, ca.core(), cb.core())
            && ca.margin() == 0.0
            && cb.margin() == 0.0
        {
            let placed = |vertices, x, q| PlacedHull {
                vertices,
                position: x,
                rotation: q,
            };
            let margin = slop * (self.radius[a] + self.radius[b]);
            if let Ok(Some(m)) = hull_manifold(
                &placed(va, xa, q(a)),
                &placed(vb, xb, q(b)),
                p.normal.as_slice(),
                margin,
            ) && !m.is_empty()
            {
                self.push_manifold((a, b), &m, reach);
                return;
            }
        }
        if let Some(slop) = manifold
            && ca.margin() + cb.margin() > 0.0
            && let Some(ha) = self.boxes[a].as_deref().or(core_box(ca))
            && let Some(hb) = self.boxes[b].as_deref().or(core_box(cb))
        {
            // Rounded boxes: their cores' manifold by separating axes and face clipping,
            // which holds every corner of a face up to 5D (a hull's support set holds 8).
            let placed = |half_lengths, position, rotation| PlacedBox {
                half_lengths,
                position,
                rotation,
            };
            let margins = (ca.margin(), cb.margin());
            let margin = slop * (self.radius[a] + self.radius[b]) + margins.0 + margins.1;
            let (pa, pb) = (placed(ha, xa, q(a)), placed(hb, xb, q(b)));
            let axis = box_box_unchecked(&pa, &pb);
            let m = box_manifold_on_axis(&pa, &pb, &axis, margin);
            if !m.is_empty() {
                self.push_manifold_with_margins((a, b), &m, reach, margins);
                return;
            }
        }
        if let Some(slop) = manifold
            && ca.margin() + cb.margin() > 0.0
            && let Some(va) = self.rounded[a].as_deref().or(core_hull(ca))
            && let Some(vb) = self.rounded[b].as_deref().or(core_hull(cb))
        {
            // Polytopes with margins (a capsule lying on a box, rounded boxes face to
            // face): the manifold of their cores, whose gap is the margins' sum more.
            let placed = |vertices, x, q| PlacedHull {
                vertices,
                position: x,
                rotation: q,
            };
            let margins = (ca.margin(), cb.margin());
            let margin = slop * (self.radius[a] + self.radius[b]) + margins.0 + margins.1;
            if let Ok(Some(m)) = hull_manifold(
                &placed(va, xa, q(a)),
                &placed(vb, xb, q(b)),
                p.normal.as_slice(),
                margin,
            ) && !m.is_empty()
            {
                self.push_manifold_with_margins((a, b), &m, reach, margins);
                return;
            }
        }
        let c = self.next((a, b), 0, -p.depth, p.normal.as_slice());
        c.reach = reach;
        c.point.extend(
            p.witness_a
                .as_slice()
                .iter()
                .zip(p.witness_b.as_slice())
                .map(|(x, y)| 0.5 * (x + y)),
        );
    }

    /// Records the points of the manifold `m` of the pair (a, b).
    fn push_manifold(&mut self, pair: (usize, usize), m: &ContactManifold, reach: f64) {
        self.push_manifold_with_margins(pair, m, reach, (0.0, 0.0));
    }

    /// Records the points of the manifold `m` of the cores of the pair (a, b), whose
    /// surfaces lie `margins` further out along the normal: each gap is the cores' less
    /// both margins, each point midway between the surfaces.
    fn push_manifold_with_margins(
        &mut self,
        (a, b): (usize, usize),
        m: &ContactManifold,
        reach: f64,
        (ra, rb): (f64, f64),
    ) {
        // A face resting on a face touches at all its points, but a tilt of round-off size
        // lifts some of them by more than the pair's reach: points this close count as
        // touching, so that they hold (a resting contact) instead of waiting to land.
        let reach = reach.max(MANIFOLD_TOUCHING * (self.radius[a] + self.radius[b]));
        let shift = 0.5 * (ra - rb);
        for point in m.points() {
            let c = self.next((a, b), point.id.0, -point.depth - ra - rb, m.normal());
            c.reach = reach;
            c.point.extend(
                point
                    .point_a
                    .iter()
                    .zip(point.point_b)
                    .zip(m.normal())
                    .map(|((x, y), n)| 0.5 * (x + y) + shift * n),
            );
        }
    }

    /// The next entry of the found pairs, set to the pair, feature, gap and normal given and
    /// an empty point.
    fn next(
        &mut self,
        (a, b): (usize, usize),
        feature: u64,
        gap: f64,
        normal: &[f64],
    ) -> &mut PairContact {
        if self.len == self.found.len() {
            self.found.push(PairContact::default());
        }
        let c = &mut self.found[self.len];
        self.len += 1;
        c.a = a;
        c.b = b;
        c.feature = feature;
        c.gap = gap;
        c.normal.clear();
        c.normal.extend_from_slice(normal);
        c.point.clear();
        c
    }

    /// `factor` times the sum of the bounding radii of bodies `a` and `b`: the distance
    /// within which [`Touching::scan`] with that factor reports the pair.
    pub(crate) fn reach(&self, (a, b): (usize, usize), factor: f64) -> f64 {
        factor * (self.radius[a] + self.radius[b])
    }

    /// The pairs the last [`Touching::scan`] found.
    pub(crate) fn found(&self) -> &[PairContact] {
        &self.found[..self.len]
    }
}
