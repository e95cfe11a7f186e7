//! Which bodies touch which: the convex shapes of the bodies' contact shapes, the pairs
//! whose bounding balls come within reach (the broad phase), and for each such pair the
//! signed distance, the contact normal and the contact point (the narrow phase).

use super::epa::box_and_ball;
use super::kept::KeptPairs;
use super::manifold::{SUPPORT_TOLERANCE, box_manifold_on_axis};
use super::sat::{box_box_unchecked, box_box_within};
use super::{
    BroadPhase, ContactManifold, EpaWorkspace, PlacedBox, PlacedHull, PlacedShape, hull_manifold,
    penetration_with,
};
use crate::dynamics::motion::forques::Anchor;
use crate::dynamics::motion::shape::{CompoundShape, ConvexCore, ConvexShape};
use crate::dynamics::motion::{BallJoint, ContactShape, MovingBody};
use crate::numeric::dim;
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
        // Pieces meet piece by piece (`Touching::compound`).
        _ => None,
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

/// The half-lengths (h, 0, …, 0) of a shape's core when it is the segment from −h e₁ to
/// h e₁, as a box with one side.
fn segment_box(c: &ConvexShape) -> Option<SmallVec<[f64; 8]>> {
    match c.core() {
        ConvexCore::Segment(h) => {
            let mut half = SmallVec::from_elem(0.0, c.dim());
            half[0] = *h;
            Some(half)
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

/// How far two boxes may move relative to each other (relative to the sum of their bounding
/// radii, and in the entries of their relative rotation) before a scan with manifolds finds
/// their manifold anew: within that, its points are kept as material points of both boxes,
/// their gaps moving with them. A hundredth of the splitting's contact tolerance (10⁻⁹ of
/// the radius): what a kept manifold misses of the one at the new placement (a clipped point
/// slides along an edge by at most the relative motion) stays that far below what the
/// tolerance allows. A resting stack then clips its faces once in many steps: the cubes of
/// a pyramid at rest turn relative to each other by about 10⁻¹² in a few steps, and a
/// thousandth of the tolerance kept 71 % of its manifolds where this keeps 97 %.
const KEEP_BOX_MANIFOLD: f64 = 1e-11;

/// True if the relative placements `now` and `then` ([`relative_placement`], N = `n`)
/// differ by at most `offset` in the centre and `turn` in the axes' entries. Compared so
/// that a NaN counts as moved.
pub(crate) fn placed_within(
    now: &[f64],
    then: &[f64],
    n: usize,
    (offset, turn): (f64, f64),
) -> bool {
    let within =
        |x: &[f64], y: &[f64], limit: f64| x.iter().zip(y).all(|(p, q)| (p - q).abs() <= limit);
    within(&now[..n], &then[..n], offset) && within(&now[n..], &then[n..], turn)
}

/// Writes into `out` the placement of body b in body a's axes from their own axes
/// (row-major, own axes → space) and centres: b's centre (N numbers), then b's axes
/// (N × N, row-major).
pub(crate) fn relative_placement(q: (&[f64], &[f64]), x: (&[f64], &[f64]), out: &mut Vec<f64>) {
    match x.0.len() {
        3 => relative_placement_n::<3>(q, x, out),
        4 => relative_placement_n::<4>(q, x, out),
        _ => relative_placement_n::<0>(q, x, out),
    }
}

/// [`relative_placement`] with the dimension `N` as in [`dim`].
#[inline(always)]
fn relative_placement_n<const N: usize>(
    (qa, qb): (&[f64], &[f64]),
    (xa, xb): (&[f64], &[f64]),
    out: &mut Vec<f64>,
) {
    let n = dim::<N>(xa.len());
    let (qa, qb, xa, xb) = (&qa[..n * n], &qb[..n * n], &xa[..n], &xb[..n]);
    out.clear();
    out.resize(n + n * n, 0.0);
    let (centre, axes) = out.split_at_mut(n);
    // Each entry a sum from −0.0 (the neutral element of addition) term by term, written
    // in place: an iterator extending the vector checks its room at every entry.
    for (k, c) in centre.iter_mut().enumerate() {
        let mut s = -0.0;
        for i in 0..n {
            s += qa[i * n + k] * (xb[i] - xa[i]);
        }
        *c = s;
    }
    for (r, row) in axes.chunks_exact_mut(n).enumerate() {
        for (c, entry) in row.iter_mut().enumerate() {
            let mut s = -0.0;
            for i in 0..n {
                s += qa[i * n + r] * qb[i * n + c];
            }
            *entry = s;
        }
    }
}

/// Writes `out` = Q v (+ x): a vector `v` of a body's axes (Q row-major, own axes →
/// space) in space, or with the centre `x` a point.
fn in_space((q, v): (&[f64], &[f64]), x: Option<&[f64]>, out: &mut [f64]) {
    match v.len() {
        3 => in_space_n::<3>((q, v), x, out),
        4 => in_space_n::<4>((q, v), x, out),
        _ => in_space_n::<0>((q, v), x, out),
    }
}

/// [`in_space`] with the dimension `N` as in [`dim`].
#[inline(always)]
fn in_space_n<const N: usize>((q, v): (&[f64], &[f64]), x: Option<&[f64]>, out: &mut [f64]) {
    let n = dim::<N>(v.len());
    let (q, v) = (&q[..n * n], &v[..n]);
    for (i, o) in out[..n].iter_mut().enumerate() {
        // A sum from −0.0 term by term, as relative_placement_n's.
        let mut turned = -0.0;
        for (a, b) in q[i * n..(i + 1) * n].iter().zip(v) {
            turned += a * b;
        }
        *o = x.map_or(turned, |x| x[i] + turned);
    }
}

/// Keeps the manifold `m` of the boxes `pair` found at their placement now (centres `x`,
/// axes `q`, and b's placement in a's axes `relative`) for the next scan with manifolds
/// ([`KEEP_BOX_MANIFOLD`]). After the placement its numbers are the normal in a's axes (N),
/// then per point its gap less the normal's component of the witnesses' offset (1), and
/// its witnesses on a and on b, each in its body's axes (N each); the points' features
/// are the entry's features.
fn keep_manifold(
    kept: &mut KeptPairs,
    pair: (usize, usize),
    m: &ContactManifold,
    (xa, xb): (&[f64], &[f64]),
    (qa, qb): (&[f64], &[f64]),
    relative: &[f64],
) {
    let n = xa.len();
    kept.push(pair, relative);
    // Qᵀ v: a vector of space in a body's axes.
    let own = |q: &[f64], v: &[f64], kept: &mut KeptPairs| {
        kept.extend((0..n).map(|k| (0..n).map(|i| q[i * n + k] * v[i]).sum::<f64>()));
    };
    let normal = m.normal();
    own(qa, normal, kept);
    for point in m.points() {
        let (pa, pb) = (point.point_a, point.point_b);
        let along: f64 = (0..n).map(|i| normal[i] * (pb[i] - pa[i])).sum();
        kept.extend([-point.depth - along]);
        let from = |p: &[f64], x: &[f64]| -> SmallVec<[f64; 8]> {
            p.iter().zip(x).map(|(p, x)| p - x).collect()
        };
        own(qa, &from(pa, xa), kept);
        own(qb, &from(pb, xb), kept);
        kept.push_feature(point.id.0);
    }
}

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
    /// How far beyond its share of a scan's reach each body reaches ([`Touching::set_sweeps`];
    /// none: nothing beyond).
    sweep: Vec<f64>,
    /// The bodies whose pairs are found without the sweeps ([`Touching::set_sweeps`]).
    unswept: Vec<bool>,
    /// The half-lengths of the bodies whose shapes are boxes (their corners), which find
    /// their contact normal by separating axes.
    boxes: Vec<Option<Vec<f64>>>,
    /// The vertices of the bodies' cores that are boxes or segments (a capsule's), row-major:
    /// polytopes with a margin touch by the manifold of their cores moved out by the
    /// margins.
    cores: Vec<Option<Vec<f64>>>,
    /// The compound bodies' pieces, with the vertices of each piece's core when it is a
    /// box or a segment.
    compound: Vec<Option<Pieces>>,
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
    /// What the last scan's candidates were found from: the factor, and each body's
    /// position and (for boxes) own axes. A scan that finds them all as they were reuses
    /// the candidates (a step scans again where it scanned before, with the manifolds).
    seen_factor: Option<f64>,
    seen: Vec<f64>,
    /// The pairs found by the last [`Touching::scan`], and those of the last scan of the
    /// other kind (with manifolds or without), each with what it was found from: the
    /// placement's generation, the factor and the manifold's slop. A step scans several
    /// times where it scanned before (its closing solve, the next step's checks and opening
    /// solve), and a full scan of the same kind finds what it found then.
    found: Found,
    found_key: Option<FoundKey>,
    other: Found,
    other_key: Option<FoundKey>,
    /// The placement each list was found at (as `seen` records it): a scan of one kind at a
    /// placement that a scan of the other kind left and came back to (an impact's tries
    /// all start where the step did, and their flights' checks scan elsewhere) finds its
    /// list there.
    found_seen: Vec<f64>,
    other_seen: Vec<f64>,
    /// Each list's serial number: a new one whenever a scan fills a list anew, so that a
    /// caller can tell a list it has seen (the last `serial` handed out).
    found_serial: u64,
    other_serial: u64,
    serial: u64,
    /// Whether `found` is the list of scans with manifolds (`other` the one without).
    found_manifolds: bool,
    /// Two boxes' manifolds of the last scan with manifolds, and those the current scan
    /// finds or keeps ([`KEEP_BOX_MANIFOLD`]); room for a pair's relative placement.
    kept: KeptPairs,
    next_kept: KeptPairs,
    relative: Vec<f64>,
    /// The placement the scans see: counted up whenever a body moved or turned since the
    /// last scan.
    generation: u64,
    /// True to take two boxes' manifold by clipping the incident face against the
    /// reference face (the points of [`box_manifold`](super::box_manifold)) however the
    /// two faces are tilted. False (the splitting, up to 4D) to take the clipped manifold
    /// only where its points lie at one depth within [`SUPPORT_TOLERANCE`] of the smaller
    /// radius (faces flat on each other, as in a stack, where the hull manifold of the
    /// support sets holds the same region and its linear programs cost more than the
    /// velocity solve: a pyramid of 55 cubes steps in 0.79 instead of 1.09 ms), and the hull
    /// manifold otherwise: with tilted faces clipped too, piles of 90 to 110 boxes and
    /// balls landing under the splitting left up to 66 solves unconverged and took up to
    /// three times as long. From 5D on both clip.
    clip_tilted: bool,
}

impl Touching {
    /// No shapes yet; two boxes' manifolds by clipping however their faces are tilted
    /// ([`Touching::clip_tilted`]).
    pub(crate) fn clipping_tilted_boxes() -> Touching {
        Touching {
            clip_tilted: true,
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
            (self.found_key, self.other_key) = (None, None);
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
        self.cores = self
            .convex
            .iter()
            .map(|c| c.as_ref().and_then(core_vertices))
            .collect();
        self.compound = shapes
            .iter()
            .map(|s| match s {
                ContactShape::Compound(c) => Some(Pieces {
                    shape: c.clone(),
                    radii: c
                        .pieces()
                        .iter()
                        .map(|p| p.shape().bounding_radius())
                        .collect(),
                    cores: c
                        .pieces()
                        .iter()
                        .map(|p| core_vertices(p.shape()))
                        .collect(),
                }),
                _ => None,
            })
            .collect();
        self.radius = shapes.iter().map(ContactShape::radius).collect();
        // New shapes, new bounding boxes and new pairs.
        self.seen_factor = None;
        (self.found_key, self.other_key) = (None, None);
        self.kept.clear(None);
    }

    /// Sets how far beyond its share of the reach each body reaches in the scans from now
    /// on (its sweep: the reach of a pair is the scan's factor times the sum of their
    /// bounding radii plus both sweeps), as a step's bodies reach by how far they may move
    /// in it. A pair of which a body is `unswept` (none if it is empty) is found within the
    /// factor's reach alone. The contacts found keep the factor's reach as their touching
    /// distance ([`PairContact::reach`]): a pair that the sweeps bring in is apart. A change
    /// of any sweep finds the pairs anew at the next scan.
    pub(crate) fn set_sweeps(&mut self, sweeps: &[f64], unswept: &[bool]) {
        let same = self.sweep.len() == sweeps.len()
            && self
                .sweep
                .iter()
                .zip(sweeps)
                .all(|(s, t)| s.to_bits() == t.to_bits())
            && self.unswept == unswept;
        if !same {
            self.sweep.clear();
            self.sweep.extend_from_slice(sweeps);
            self.unswept.clear();
            self.unswept.extend_from_slice(unswept);
            self.seen_factor = None;
            (self.found_key, self.other_key) = (None, None);
            // The pairs' reaches change: a kept manifold was within the old one.
            self.kept.clear(None);
        }
    }

    /// Body `i`'s sweep ([`Touching::set_sweeps`]).
    fn sweep(&self, i: usize) -> f64 {
        self.sweep.get(i).copied().unwrap_or(0.0)
    }

    /// True if body `i` touches other bodies.
    fn touches(&self, i: usize) -> bool {
        self.convex[i].is_some() || self.compound[i].is_some()
    }

    /// True if at least two bodies can touch each other.
    pub(crate) fn any_pairs(&self) -> bool {
        (0..self.convex.len())
            .filter(|&i| self.touches(i))
            .nth(1)
            .is_some()
    }

    /// Finds the pairs of bodies whose signed distance is at most `factor` times the sum of
    /// their bounding radii, with each body's own axes `q(i)` (row-major, own axes → space).
    /// The broad phase ([`BroadPhase`]: a hierarchy of the bodies' bounding boxes — a box's
    /// own, else its bounding ball's — kept from step to step) gives the pairs whose boxes
    /// overlap, in increasing order, and pairs
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
        self.scan_with(
            bodies,
            q,
            factor,
            manifold,
            None::<fn((usize, usize)) -> bool>,
        );
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
        self.scan_with(bodies, q, factor, manifold, Some(skip));
    }

    /// [`Touching::scan_except`], or with `skip` None [`Touching::scan`].
    fn scan_with<'q>(
        &mut self,
        bodies: &[MovingBody],
        q: impl Fn(usize) -> &'q [f64],
        factor: f64,
        manifold: Option<f64>,
        skip: Option<impl Fn((usize, usize)) -> bool>,
    ) {
        let key = |generation| FoundKey {
            generation,
            factor: factor.to_bits(),
            slop: manifold.map(f64::to_bits),
        };
        // The list of this kind (with manifolds or without) becomes the current one.
        if self.found_manifolds != manifold.is_some() {
            self.found_manifolds = manifold.is_some();
            std::mem::swap(&mut self.found, &mut self.other);
            std::mem::swap(&mut self.found_key, &mut self.other_key);
            std::mem::swap(&mut self.found_seen, &mut self.other_seen);
            std::mem::swap(&mut self.found_serial, &mut self.other_serial);
        }
        let Some(first) = bodies.first() else {
            self.found.len = 0;
            self.found_key = None;
            self.serial += 1;
            self.found_serial = self.serial;
            return;
        };
        let n = first.dim();
        if self.broad.as_ref().is_none_or(|b| b.dim() != n) {
            self.broad = BroadPhase::new(n).ok();
            self.seen_factor = None;
        }
        let (candidates_stand, placed_as_before) = self.unmoved(bodies, &q, factor);
        if !candidates_stand {
            self.find_candidates(bodies, &q, factor);
        }
        if !placed_as_before {
            self.generation += 1;
        }
        if skip.is_none() && self.found_key == Some(key(self.generation)) {
            return;
        }
        let found_here = self.found_key.is_some_and(|k| {
            k.factor == factor.to_bits()
                && k.slop == manifold.map(f64::to_bits)
                && same_bits(&self.found_seen, &self.seen)
        });
        if skip.is_none() && found_here {
            self.found_key = Some(key(self.generation));
            return;
        }
        self.found.len = 0;
        self.serial += 1;
        self.found_serial = self.serial;
        let kept_key = manifold.map(|slop| (factor.to_bits(), slop.to_bits()));
        if kept_key.is_some() {
            self.next_kept.clear(kept_key);
            if self.kept.key != kept_key {
                self.kept.clear(None);
            }
        }
        let candidates = std::mem::take(&mut self.candidates);
        for &(a, b) in &candidates {
            if self.touches(a) && self.touches(b) && !skip.as_ref().is_some_and(|s| s((a, b))) {
                self.pair(bodies, &q, (a, b), factor, manifold);
            }
        }
        self.candidates = candidates;
        if kept_key.is_some() {
            std::mem::swap(&mut self.kept, &mut self.next_kept);
        }
        // A scan that skipped pairs found only part of what a full scan finds.
        self.found_key = skip.is_none().then(|| key(self.generation));
        self.found_seen.clone_from(&self.seen);
    }

    /// Whether the last scan's candidates stand (it was with `factor` and saw every body
    /// where it is now: its position and, for a box, its axes equal to the bit), and
    /// whether it saw every body placed as now (its axes too, whatever its shape); records
    /// the bodies as they are now for the next scan.
    fn unmoved<'q>(
        &mut self,
        bodies: &[MovingBody],
        q: &impl Fn(usize) -> &'q [f64],
        factor: f64,
    ) -> (bool, bool) {
        // Each body's position, then its axes if it is a box.
        let n = bodies[0].dim();
        let stride = n + n * n;
        let recorded = self.seen.len() == bodies.len() * stride;
        if !recorded {
            self.seen.clear();
            self.seen.resize(bodies.len() * stride, 0.0);
        }
        let mut same = recorded && self.seen_factor == Some(factor);
        let mut placed = recorded;
        self.seen_factor = Some(factor);
        // Compared as bits: a NaN is seen again as itself (the step reports it). Returns
        // whether `now` is what was seen, and records it.
        let keep = |seen: &mut [f64], now: &[f64]| {
            if seen.len() == now.len()
                && seen
                    .iter()
                    .zip(now)
                    .all(|(s, x)| s.to_bits() == x.to_bits())
            {
                return true;
            }
            if seen.len() == now.len() {
                seen.copy_from_slice(now);
            }
            false
        };
        for (i, (b, seen)) in bodies
            .iter()
            .zip(self.seen.chunks_exact_mut(stride))
            .enumerate()
        {
            let (x, axes) = seen.split_at_mut(n);
            let at = keep(x, b.position().as_slice());
            let turned = !keep(axes, q(i));
            same &= at && !(turned && self.boxes[i].is_some());
            placed &= at && !turned;
        }
        (same, placed)
    }

    /// The pairs of bodies whose bounding boxes, padded by their share of the reach
    /// `factor` times their radii, overlap, into `candidates`.
    fn find_candidates<'q>(
        &mut self,
        bodies: &[MovingBody],
        q: &impl Fn(usize) -> &'q [f64],
        factor: f64,
    ) {
        let n = bodies[0].dim();
        self.lower.clear();
        self.upper.clear();
        for (i, (b, r)) in bodies.iter().zip(&self.radius).enumerate() {
            // Each body's box is padded by its share of the reach, factor × its radius and
            // its sweep, so that two boxes apart have a gap beyond the pair's reach.
            let pad = r * factor + self.sweep(i);
            let x = b.position().as_slice();
            // A box's own bounding box: along space axis k it reaches Σⱼ |Q_kj| hⱼ, so a
            // box side by side with another (unturned, faces parallel) stays out of the
            // broad phase's pairs, where its bounding ball's box would not.
            let q = self.boxes[i].as_ref().map(|h| (h, q(i)));
            for (k, &xk) in x.iter().enumerate() {
                let reach = match q {
                    Some((h, q)) => q[k * n..(k + 1) * n]
                        .iter()
                        .zip(h)
                        .map(|(c, h)| c.abs() * h)
                        .sum::<f64>(),
                    None => *r,
                };
                self.lower.push(xk - reach - pad);
                self.upper.push(xk + reach + pad);
            }
        }
        self.candidates.clear();
        // A position that is not finite has no pairs (the step reports it).
        if let Some(Ok(pairs)) = self
            .broad
            .as_mut()
            .map(|b| b.update(&self.lower, &self.upper))
        {
            self.candidates.extend_from_slice(pairs);
        }
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
        if bodies[a].is_fixed() && bodies[b].is_fixed() || self.joined.contains(&(a, b)) {
            return;
        }
        let (xa, xb) = (
            bodies[a].position().as_slice(),
            bodies[b].position().as_slice(),
        );
        let (reach, touch) = (
            self.reach((a, b), factor),
            self.touching_reach((a, b), factor),
        );
        let centres: f64 = xa.iter().zip(xb).map(|(p, q)| (p - q) * (p - q)).sum();
        let bound = self.radius[a] + self.radius[b] + reach;
        if centres > bound * bound {
            return;
        }
        if self.compound[a].is_some() || self.compound[b].is_some() {
            self.pieces(q, (a, b), (xa, xb), (reach, touch), manifold);
            return;
        }
        let boxes = self.boxes[a].is_some() && self.boxes[b].is_some();
        // Whether `self.relative` holds the pair's relative placement now.
        let mut relative_now = false;
        if boxes {
            let least_touching = MANIFOLD_TOUCHING * (self.radius[a] + self.radius[b]);
            let touching = match manifold {
                Some(_) => (reach.max(least_touching), touch.max(least_touching)),
                None => (reach, touch),
            };
            let with_points = manifold.is_some();
            match self.reuse_box_manifold((a, b), (xa, xb), (q(a), q(b)), touching, with_points) {
                Some(true) => return,
                answered => relative_now = answered.is_some(),
            }
        }
        let (Some(ca), Some(cb)) = (&self.convex[a], &self.convex[b]) else {
            return;
        };
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
            // None when some axis separates them by more than the reach (the gap, the
            // largest over the axes, is then larger too).
            let Some(axis) = box_box_within(&pa, &pb, reach) else {
                return;
            };
            let points = manifold.and_then(|slop| {
                let margin = slop * (self.radius[a] + self.radius[b]);
                let clipped = box_manifold_on_axis(&pa, &pb, &axis, margin);
                let spread = clipped.max_depth()
                    - clipped
                        .points()
                        .map(|p| p.depth)
                        .fold(f64::INFINITY, f64::min);
                let flat = spread <= SUPPORT_TOLERANCE * self.radius[a].min(self.radius[b]);
                if self.clip_tilted || xa.len() >= 5 || clipped.len() <= 1 || flat {
                    return Some(clipped);
                }
                let (ConvexCore::Hull(va), ConvexCore::Hull(vb)) = (ca.core(), cb.core()) else {
                    // Cuboid cores: the manifold of their support sets below.
                    return None;
                };
                let hull = |vertices, position, rotation| PlacedHull {
                    vertices,
                    position,
                    rotation,
                };
                hull_manifold(
                    &hull(va, xa, q(a)),
                    &hull(vb, xb, q(b)),
                    &axis.normal,
                    margin,
                )
                .ok()
                .flatten()
            });
            let points = points.filter(|m| !m.is_empty());
            if let Some(m) = points {
                let touching = touch.max(MANIFOLD_TOUCHING * (self.radius[a] + self.radius[b]));
                self.found
                    .push_manifold((a, b), &m, touching, (0.0, 0.0), 0);
                if !relative_now {
                    relative_placement((q(a), q(b)), (xa, xb), &mut self.relative);
                }
                keep_manifold(
                    &mut self.next_kept,
                    (a, b),
                    &m,
                    (xa, xb),
                    (q(a), q(b)),
                    &self.relative,
                );
                return;
            }
            if manifold.is_none() {
                // The gap alone is asked for: the point is the midpoint of the centres.
                let c = self.found.next((a, b), 0, -axis.depth, &axis.normal);
                c.reach = touch;
                c.point
                    .extend(xa.iter().zip(xb).map(|(x, y)| 0.5 * (x + y)));
                return;
            }
        }
        convex_pair(
            (&mut self.workspace, &mut self.found),
            (a, b),
            (
                Solid::new(
                    ca,
                    (xa, q(a)),
                    (self.cores[a].as_deref(), self.boxes[a].as_deref()),
                    self.radius[a],
                ),
                Solid::new(
                    cb,
                    (xb, q(b)),
                    (self.cores[b].as_deref(), self.boxes[b].as_deref()),
                    self.radius[b],
                ),
            ),
            (
                (reach, touch),
                manifold.map(|slop| slop * (self.radius[a] + self.radius[b])),
            ),
            0,
        );
    }

    /// Answers for the boxes (a, b) from their manifold kept from the last scan with
    /// manifolds, if they moved less than [`KEEP_BOX_MANIFOLD`] relative to each other
    /// since it was found (centres `x`, axes `q` now): with `points`, its points at the
    /// placement now (each point's witnesses moved with their bodies, its gap with their
    /// offset along the normal), kept for the next scan; without, the least of those gaps
    /// (the deepest point's: separating axes' gap along the manifold's axis) if it is
    /// `within`; the points found count as touching within `touching`. Returns whether it
    /// answered, or None if the pair kept no manifold (else its relative placement now is in
    /// `self.relative`).
    fn reuse_box_manifold(
        &mut self,
        (a, b): (usize, usize),
        (xa, xb): (&[f64], &[f64]),
        (qa, qb): (&[f64], &[f64]),
        (within, touching): (f64, f64),
        points: bool,
    ) -> Option<bool> {
        let n = xa.len();
        let at = self.kept.find((a, b))?;
        relative_placement((qa, qb), (xa, xb), &mut self.relative);
        let (then, rest) = self.kept.numbers(at).split_at(n + n * n);
        let limit = KEEP_BOX_MANIFOLD * (self.radius[a] + self.radius[b]);
        if !placed_within(&self.relative, then, n, (limit, KEEP_BOX_MANIFOLD)) {
            return Some(false);
        }
        let (normal_own, kept) = rest.split_at(n);
        // The normal and the two material points in space, as slices of one room (read
        // through a small vector, each access would ask where it keeps its numbers).
        let mut room: SmallVec<[f64; 24]> = SmallVec::from_elem(0.0, 3 * n);
        let (normal, ends) = room.split_at_mut(n);
        let (pa, pb) = ends.split_at_mut(n);
        in_space((qa, normal_own), None, normal);
        let normal = &*normal;
        let mut least = f64::INFINITY;
        for (k, point) in kept.chunks_exact(1 + 2 * n).enumerate() {
            let (own_a, own_b) = point[1..].split_at(n);
            in_space((qa, own_a), Some(xa), pa);
            in_space((qb, own_b), Some(xb), pb);
            let along: f64 = (0..n).map(|i| normal[i] * (pb[i] - pa[i])).sum();
            let gap = point[0] + along;
            if !points {
                least = least.min(gap);
                continue;
            }
            let feature = self.kept.features(at)[k];
            let c = self.found.next((a, b), feature, gap, normal);
            c.reach = touching;
            c.point
                .extend(pa.iter().zip(pb.iter()).map(|(x, y)| 0.5 * (x + y)));
        }
        if points {
            self.next_kept.copy_entry(&self.kept, at);
        } else if least <= within {
            // As separating axes answer the gap alone: at the midpoint of the centres.
            let c = self.found.next((a, b), 0, least, normal);
            c.reach = touching;
            c.point
                .extend(xa.iter().zip(xb).map(|(x, y)| 0.5 * (x + y)));
        }
        Some(true)
    }

    /// The pair (a, b) of which one or both are compound: each pair of pieces whose
    /// bounding balls come within `reach` through [`convex_pair`] (touching within `touch`),
    /// its features marked by the pieces' numbers. A body that is not compound is one piece
    /// at its centre.
    fn pieces<'q>(
        &mut self,
        q: &impl Fn(usize) -> &'q [f64],
        (a, b): (usize, usize),
        (xa, xb): (&[f64], &[f64]),
        (reach, touch): (f64, f64),
        manifold: Option<f64>,
    ) {
        let n = xa.len();
        let slop_reach = manifold.map(|slop| slop * (self.radius[a] + self.radius[b]));
        let (ca, cb) = (self.compound[a].take(), self.compound[b].take());
        let buffers = || {
            (
                SmallVec::<[f64; 8]>::from_elem(0.0, n),
                SmallVec::<[f64; 64]>::from_elem(0.0, n * n),
            )
        };
        let (mut place_a, mut place_b) = (buffers(), buffers());
        let count = |c: &Option<Pieces>| c.as_ref().map_or(1, |c| c.shape.pieces().len());
        // A body that is not compound is its own single piece.
        let whole = |i: usize, x, q| {
            let c = self.convex[i].as_ref()?;
            let core = (self.cores[i].as_deref(), self.boxes[i].as_deref());
            Some(Solid::new(c, (x, q), core, self.radius[i]))
        };
        let (whole_a, whole_b) = (whole(a, xa, q(a)), whole(b, xb, q(b)));
        for i in 0..count(&ca) {
            let Some(sa) = piece(&ca, whole_a, i, (xa, q(a)), &mut place_a) else {
                continue;
            };
            for j in 0..count(&cb) {
                let Some(sb) = piece(&cb, whole_b, j, (xb, q(b)), &mut place_b) else {
                    continue;
                };
                let centres: f64 = sa
                    .position
                    .iter()
                    .zip(sb.position)
                    .map(|(p, q)| (p - q) * (p - q))
                    .sum();
                let bound = sa.radius + sb.radius + reach;
                if centres > bound * bound {
                    continue;
                }
                // Distinct pieces, distinct features (the manifold's ids use the low bits).
                let tag = ((i as u64) << 56) ^ ((j as u64) << 48) ^ (1 << 47);
                convex_pair(
                    (&mut self.workspace, &mut self.found),
                    (a, b),
                    (sa, sb),
                    ((reach, touch), slop_reach),
                    tag,
                );
            }
        }
        self.compound[a] = ca;
        self.compound[b] = cb;
    }

    /// `factor` times the sum of the bounding radii of bodies `a` and `b`, plus their
    /// sweeps unless one is unswept ([`Touching::set_sweeps`]): the distance within which
    /// [`Touching::scan`] with that factor reports the pair.
    pub(crate) fn reach(&self, (a, b): (usize, usize), factor: f64) -> f64 {
        let unswept = |i: usize| self.unswept.get(i).copied().unwrap_or(false);
        let sweeps = if unswept(a) || unswept(b) {
            0.0
        } else {
            self.sweep(a) + self.sweep(b)
        };
        self.touching_reach((a, b), factor) + sweeps
    }

    /// `factor` times the sum of the bounding radii of bodies `a` and `b`: the distance
    /// within which a pair that [`Touching::scan`] finds with that factor counts as
    /// touching ([`PairContact::reach`]).
    pub(crate) fn touching_reach(&self, (a, b): (usize, usize), factor: f64) -> f64 {
        factor * (self.radius[a] + self.radius[b])
    }

    /// The pairs the last [`Touching::scan`] found.
    /// The serial number of the list [`Touching::found`] gives: the same as at an earlier
    /// call only if no scan has filled the list anew since (its pairs are those of then).
    pub(crate) fn found_serial(&self) -> u64 {
        self.found_serial
    }

    pub(crate) fn found(&self) -> &[PairContact] {
        &self.found.items[..self.found.len]
    }
}

/// The contact points found by a scan; entries past `len` keep their room.
#[derive(Clone, Debug, Default)]
struct Found {
    items: Vec<PairContact>,
    len: usize,
}

/// True if `a` and `b` hold the same numbers to the bit (a NaN equal to itself).
fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// What a list of found pairs was found from (see [`Touching::found`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct FoundKey {
    generation: u64,
    factor: u64,
    slop: Option<u64>,
}

impl Found {
    /// The next entry, set to the pair, feature, gap and normal given and an empty point.
    fn next(
        &mut self,
        (a, b): (usize, usize),
        feature: u64,
        gap: f64,
        normal: &[f64],
    ) -> &mut PairContact {
        if self.len == self.items.len() {
            self.items.push(PairContact::default());
        }
        let c = &mut self.items[self.len];
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

    /// Records the points of the manifold `m` of (the cores of) the pair (a, b), whose
    /// surfaces lie `margins` further out along the normal: each gap is the cores' less
    /// both margins, each point midway between the surfaces, each feature marked by `tag`
    /// (the pair of pieces of compound bodies).
    fn push_manifold(
        &mut self,
        pair: (usize, usize),
        m: &ContactManifold,
        reach: f64,
        (ra, rb): (f64, f64),
        tag: u64,
    ) {
        let shift = 0.5 * (ra - rb);
        for point in m.points() {
            let c = self.next(pair, point.id.0 ^ tag, -point.depth - ra - rb, m.normal());
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
}

/// A compound shape, with each piece's bounding radius and the vertices of its core when
/// that is a box or a segment (made once).
#[derive(Clone, Debug)]
struct Pieces {
    shape: CompoundShape,
    radii: Vec<f64>,
    cores: Vec<Option<Vec<f64>>>,
}

/// Piece `i` of a body placed at `(x, q)`: of its compound (placed into `buffers`), or
/// `whole`, the body's own convex shape, for a body that is not compound.
fn piece<'s>(
    compound: &'s Option<Pieces>,
    whole: Option<Solid<'s>>,
    i: usize,
    (x, q): (&'s [f64], &'s [f64]),
    buffers: &'s mut (SmallVec<[f64; 8]>, SmallVec<[f64; 64]>),
) -> Option<Solid<'s>> {
    let Some(pieces) = compound else {
        return whole;
    };
    let p = pieces.shape.pieces().get(i)?;
    let (position, rotation) = buffers;
    p.place(x, q, position, rotation).ok()?;
    Some(Solid::new(
        p.shape(),
        (position, rotation),
        (pieces.cores[i].as_deref(), None),
        pieces.radii[i],
    ))
}

/// A convex shape placed in space for the narrow phase, with the vertices of its core when
/// that is a box or a segment (made once by [`core_vertices`]).
#[derive(Clone, Copy)]
struct Solid<'s> {
    shape: &'s ConvexShape,
    position: &'s [f64],
    rotation: &'s [f64],
    core: Option<&'s [f64]>,
    /// The half-lengths of the core when it is a box (also a box given by its corners).
    cuboid: Option<&'s [f64]>,
    /// The shape's bounding radius (made once).
    radius: f64,
}

impl<'s> Solid<'s> {
    /// `shape` of bounding radius `radius` placed at `(position, rotation)`, with the
    /// vertices of its core when that is a box or a segment, and the half-lengths of a box
    /// given by its corners.
    fn new(
        shape: &'s ConvexShape,
        (position, rotation): (&'s [f64], &'s [f64]),
        (core, cuboid): (Option<&'s [f64]>, Option<&'s [f64]>),
        radius: f64,
    ) -> Self {
        Solid {
            shape,
            position,
            rotation,
            core,
            cuboid: cuboid.or(core_box(shape)),
            radius,
        }
    }

    /// The hull of `vertices` (own axes) placed as the shape.
    fn hull(&self, vertices: &'s [f64]) -> PlacedHull<'s> {
        PlacedHull {
            vertices,
            position: self.position,
            rotation: self.rotation,
        }
    }

    /// The box of `half_lengths` placed as the shape.
    fn cuboid(&self, half_lengths: &'s [f64]) -> PlacedBox<'s> {
        PlacedBox {
            half_lengths,
            position: self.position,
            rotation: self.rotation,
        }
    }
}

/// The narrow phase of two convex shapes that are not both boxes without margin (those
/// meet by separating axes first): their penetration (GJK, EPA), then with `slop_reach`
/// (the distance up to which manifold points are kept) the contact manifold of two hulls
/// without margin, or of the cores of polytopes with a margin, else the one point midway
/// between the witness points. Records what is within `reach` in `found`, touching within
/// `touch` ([`PairContact::reach`]), each feature marked by `tag`.
fn convex_pair(
    (workspace, found): (&mut EpaWorkspace, &mut Found),
    (a, b): (usize, usize),
    (sa, sb): (Solid<'_>, Solid<'_>),
    ((reach, touch), slop_reach): ((f64, f64), Option<f64>),
    tag: u64,
) {
    let (ca, cb) = (sa.shape, sb.shape);
    let (xa, xb) = (sa.position, sb.position);
    let (Ok(pa), Ok(pb)) = (
        PlacedShape::new(ca, xa, sa.rotation),
        PlacedShape::new(cb, xb, sb.rotation),
    ) else {
        return;
    };
    // A ball against a box given by its corners: the closed form the query keeps for
    // cuboid cores, instead of GJK on the corners.
    let p = match box_and_ball(&pa, &pb, (sa.cuboid, sb.cuboid)) {
        Some(p) => p,
        None => match penetration_with(workspace, &pa, &pb) {
            Ok(p) => p,
            Err(_) => return,
        },
    };
    if -p.depth > reach {
        return;
    }
    let radii = sa.radius + sb.radius;
    // A face resting on a face touches at all its points, but a tilt of round-off size
    // lifts some of them by more than the pair's reach: points this close count as
    // touching, so that they hold (a resting contact) instead of waiting to land.
    let touching = touch.max(MANIFOLD_TOUCHING * radii);
    if let (Some(margin), ConvexCore::Hull(va), ConvexCore::Hull(vb)) =
        (slop_reach, ca.core(), cb.core())
        && ca.margin() == 0.0
        && cb.margin() == 0.0
        && let Ok(Some(m)) = hull_manifold(&sa.hull(va), &sb.hull(vb), p.normal.as_slice(), margin)
        && !m.is_empty()
    {
        found.push_manifold((a, b), &m, touching, (0.0, 0.0), tag);
        return;
    }
    let margins = (ca.margin(), cb.margin());
    if let Some(slop_reach) = slop_reach
        && (margins.0 + margins.1 > 0.0 || tag != 0)
    {
        // Polytopes with margins (a capsule lying on a box, rounded boxes face to face),
        // and the pieces of compound bodies: the manifold of their cores, whose gap is the
        // margins' sum more. Boxes by separating axes and face clipping, which holds every
        // corner of a face up to 5D (a hull's support set holds 8).
        let margin = slop_reach + margins.0 + margins.1;
        // A segment is a box of one half-length (a capsule on a box: the segment clipped
        // against the box's face, in every dimension).
        let (seg_a, seg_b) = (segment_box(ca), segment_box(cb));
        let (box_a, box_b) = (
            sa.cuboid.or(seg_a.as_deref()),
            sb.cuboid.or(seg_b.as_deref()),
        );
        let m = if let (Some(ha), Some(hb)) = (box_a, box_b) {
            let (pa, pb) = (sa.cuboid(ha), sb.cuboid(hb));
            let axis = box_box_unchecked(&pa, &pb);
            Some(box_manifold_on_axis(&pa, &pb, &axis, margin))
        } else if let (Some(va), Some(vb)) = (sa.core.or(core_hull(ca)), sb.core.or(core_hull(cb)))
        {
            hull_manifold(&sa.hull(va), &sb.hull(vb), p.normal.as_slice(), margin)
                .ok()
                .flatten()
        } else {
            None
        };
        if let Some(m) = m.filter(|m| !m.is_empty()) {
            found.push_manifold((a, b), &m, touching, margins, tag);
            return;
        }
    }
    let c = found.next((a, b), tag, -p.depth, p.normal.as_slice());
    c.reach = touch;
    c.point.extend(
        p.witness_a
            .as_slice()
            .iter()
            .zip(p.witness_b.as_slice())
            .map(|(x, y)| 0.5 * (x + y)),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{Bivector, Rotor, Vector};
    use crate::inertia::spec::parse_body;

    /// Three unit cubes of half-length 0.5 on the x axis, 1.2 apart (0.2 between faces).
    fn cubes() -> (Vec<MovingBody>, Vec<ContactShape>) {
        let parsed = parse_body("cuboid:0.5,0.5,0.5").unwrap();
        let bodies = (0..3)
            .map(|k| {
                let x = Vector::from_components(&[1.2 * k as f64, 0.0, 0.0]).unwrap();
                let zero = Vector::zero(3);
                let still = Bivector::zero(3);
                MovingBody::new(
                    parsed.mass,
                    parsed.inertia.clone(),
                    Rotor::identity(3),
                    &x,
                    &zero,
                    &still,
                )
                .unwrap()
            })
            .collect();
        let shapes = vec![ContactShape::from_geometry(&parsed.geometry); 3];
        (bodies, shapes)
    }

    /// The pairs a scan finds, with their gaps.
    fn pairs(touching: &Touching) -> Vec<(usize, usize, f64)> {
        touching.found().iter().map(|c| (c.a, c.b, c.gap)).collect()
    }

    /// A scan reuses the last scan's broad-phase candidates only where it sees every body
    /// as that scan did: after a body moves, or a box turns in place, or with another
    /// factor, it finds what a fresh scan finds.
    #[test]
    fn a_scan_finds_what_a_fresh_scan_finds_after_bodies_move_or_turn() {
        let (mut bodies, shapes) = cubes();
        let identity = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        // Cube 1 turned by 45° about z: its corners reach 0.707 from its centre along x,
        // past the 0.7 to cube 0's face.
        let (c, s) = (0.5f64.sqrt(), 0.5f64.sqrt());
        let turned = [c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0];
        let mut kept = Touching::default();
        kept.update_shapes(&shapes, &[], 3, (1, 1));
        let mut checked = 0;
        // (what changes before the scan, factor, the pairs expected)
        let steps: [(&str, f64, usize); 6] = [
            ("none", 1e-9, 0),
            ("none", 1e-9, 0),
            ("turn cube 1", 1e-9, 2),
            ("turn cube 1 back", 1e-9, 0),
            ("move cube 2 onto cube 1", 1e-9, 1),
            ("none", 0.5, 2),
        ];
        let mut axes = [identity; 3];
        for (change, factor, expected) in steps {
            match change {
                "turn cube 1" => axes[1] = turned,
                "turn cube 1 back" => axes[1] = identity,
                "move cube 2 onto cube 1" => {
                    let (x, _, _) = bodies[2].state_mut();
                    x.as_mut_slice()[0] = 2.1;
                }
                _ => {}
            }
            kept.scan(&bodies, |i| &axes[i][..], factor, None);
            let mut fresh = Touching::default();
            fresh.update_shapes(&shapes, &[], 3, (1, 1));
            fresh.scan(&bodies, |i| &axes[i][..], factor, None);
            assert_eq!(pairs(&kept), pairs(&fresh), "after '{change}'");
            assert_eq!(
                kept.found().len(),
                expected,
                "after '{change}': {:?}",
                pairs(&kept)
            );
            checked += 1;
        }
        assert_eq!(checked, 6);
    }

    /// Scans at the same placement find what they found (a step scans there with manifolds
    /// and without, in turn, and comes back to a placement it left), and a body that turns
    /// in place, whatever its shape, is seen:
    /// two ellipsoids (0.6 along x, 0.2 across) 1.3 apart along x touch only while the
    /// second points along x; alternating scans with and without manifolds, each finds
    /// what a fresh scan finds.
    #[test]
    fn scans_at_the_same_placement_agree_with_fresh_ones_until_a_body_turns() {
        let parsed = parse_body("ellipsoid:0.6,0.2,0.2").unwrap();
        let mut bodies: Vec<MovingBody> = (0..2)
            .map(|k| {
                MovingBody::new(
                    parsed.mass,
                    parsed.inertia.clone(),
                    Rotor::identity(3),
                    &Vector::from_components(&[1.1 * k as f64, 0.0, 0.0]).unwrap(),
                    &Vector::zero(3),
                    &Bivector::zero(3),
                )
                .unwrap()
            })
            .collect();
        let shapes = vec![ContactShape::from_geometry(&parsed.geometry); 2];
        let identity = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        // The second ellipsoid turned by 90° about z: its long axis along y, 0.2 from its
        // centre along x, apart from the first.
        let across = [0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        let mut kept = Touching::default();
        kept.update_shapes(&shapes, &[], 3, (1, 1));
        let mut axes = [identity; 2];
        let mut checked = 0;
        for (change, expected) in [
            ("none", 1),
            ("none", 1),
            ("turn the second across", 0),
            ("none", 0),
            ("turn it back", 1),
            ("move it away", 0),
        ] {
            match change {
                "turn the second across" => axes[1] = across,
                "turn it back" => axes[1] = identity,
                "move it away" => {
                    let (x, _, _) = bodies[1].state_mut();
                    x.as_mut_slice()[0] = 1.5;
                }
                _ => {}
            }
            for manifold in [Some(1e-2), None, Some(1e-2)] {
                kept.scan(&bodies, |i| &axes[i][..], 1e-9, manifold);
                let mut fresh = Touching::default();
                fresh.update_shapes(&shapes, &[], 3, (1, 1));
                fresh.scan(&bodies, |i| &axes[i][..], 1e-9, manifold);
                assert_eq!(
                    pairs(&kept),
                    pairs(&fresh),
                    "after '{change}', {manifold:?}"
                );
                assert_eq!(kept.found().len(), expected, "after '{change}'");
                checked += 1;
            }
        }
        assert_eq!(checked, 18);
        // Back where a scan with manifolds was made, after a scan without them elsewhere
        // (an impact's try from the step's start, then its flight's check): the list of
        // that placement is found again, the same list (its serial), as a fresh scan finds.
        let (x, _, _) = bodies[1].state_mut();
        x.as_mut_slice()[0] = 1.1;
        kept.scan(&bodies, |i| &axes[i][..], 1e-9, Some(1e-2));
        let serial = kept.found_serial();
        assert_eq!(kept.found().len(), 1);
        let (x, _, _) = bodies[1].state_mut();
        x.as_mut_slice()[0] = 1.15;
        kept.scan(&bodies, |i| &axes[i][..], 1.0, None);
        let (x, _, _) = bodies[1].state_mut();
        x.as_mut_slice()[0] = 1.1;
        kept.scan(&bodies, |i| &axes[i][..], 1e-9, Some(1e-2));
        assert_eq!(kept.found_serial(), serial, "the list found again");
        let mut fresh = Touching::default();
        fresh.update_shapes(&shapes, &[], 3, (1, 1));
        fresh.scan(&bodies, |i| &axes[i][..], 1e-9, Some(1e-2));
        assert_eq!(pairs(&kept), pairs(&fresh));
    }

    /// Two boxes' manifold is kept while they move less than [`KEEP_BOX_MANIFOLD`]
    /// relative to each other, its gaps moving with the bodies: cube 1 leans on cube 0's
    /// face (turned by 10⁻³ about z, 5·10⁻⁴ deep), then moves in steps of 6·10⁻¹² (along
    /// the normal, across it, and turning about z). Each scan gives the features of a fresh
    /// scan, gaps within 10⁻¹⁴ of the fresh ones (a kept gap that did not move with the
    /// bodies would be off by the motion, 6·10⁻¹² a step) and points within 10⁻¹¹; the
    /// manifold is kept (its placement is still the one it was found at) until the motions
    /// add up past the limits (10⁻¹¹ in the axes, 1.7·10⁻¹¹ for the centre: 10⁻¹¹ of the
    /// two radii), and then found anew, as a fresh scan finds it. A scan for the gap alone
    /// in between gives separating axes' gap to 10⁻¹² from the kept points.
    #[test]
    fn a_box_pair_keeps_its_manifold_while_it_moves_less_than_the_limit() {
        let (mut bodies, shapes) = cubes();
        bodies.truncate(2);
        let shapes = &shapes[..2];
        let identity = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let about_z = |angle: f64| {
            let (s, c) = angle.sin_cos();
            [c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0]
        };
        let mut angle = 1e-3;
        let mut axes = [identity, about_z(angle)];
        {
            let (x, _, _) = bodies[1].state_mut();
            x.as_mut_slice()[0] = 0.9995;
        }
        let mut kept = Touching::default();
        kept.update_shapes(shapes, &[], 3, (1, 1));
        let first = |t: &Touching| t.kept.placement(0, 3).to_vec();
        let mut at_first = Vec::new();
        let (mut reused, mut renewed) = (0, 0);
        // The motions before each scan: 0 none, 1 along the normal (x), 2 across it (y),
        // 3 a turn about z.
        let motions = [0, 1, 2, 3, 1, 3, 1, 1, 1];
        for (step, motion) in motions.into_iter().enumerate() {
            let (x, _, _) = bodies[1].state_mut();
            match motion {
                1 => x.as_mut_slice()[0] += 6e-12,
                2 => x.as_mut_slice()[1] += 6e-12,
                3 => {
                    angle += 6e-12;
                    axes[1] = about_z(angle);
                }
                _ => {}
            }
            kept.scan(&bodies, |i| &axes[i][..], 1e-9, Some(1e-2));
            let mut fresh = Touching::default();
            fresh.update_shapes(shapes, &[], 3, (1, 1));
            fresh.scan(&bodies, |i| &axes[i][..], 1e-9, Some(1e-2));
            assert!(kept.found().len() >= 2, "step {step}: {:?}", pairs(&kept));
            assert_eq!(kept.found().len(), fresh.found().len(), "step {step}");
            for (k, f) in kept.found().iter().zip(fresh.found()) {
                assert_eq!((k.a, k.b, k.feature), (f.a, f.b, f.feature), "step {step}");
                assert!(
                    (k.gap - f.gap).abs() <= 1e-14,
                    "step {step}: {} {}",
                    k.gap,
                    f.gap
                );
                let apart = k.point.iter().zip(&f.point).map(|(x, y)| (x - y).abs());
                assert!(apart.fold(0.0, f64::max) <= 1e-11, "step {step}");
                assert!(
                    k.normal
                        .iter()
                        .zip(&f.normal)
                        .all(|(x, y)| (x - y).abs() <= 1e-11)
                );
            }
            if step == 0 {
                at_first = first(&kept);
            } else if first(&kept) == at_first {
                reused += 1;
            } else {
                // Found anew: what a fresh scan finds, to the bit.
                assert_eq!(pairs(&kept), pairs(&fresh), "step {step}");
                renewed += 1;
                at_first = first(&kept);
            }
            // A scan for the gap alone answers from the kept manifold: its deepest point's
            // gap, which is separating axes' to the clipping's round-off (1e-13 here where
            // nothing moved; a gap that did not move with the bodies would be off by up to
            // 1.8e-11).
            kept.scan(&bodies, |i| &axes[i][..], 1e-9, None);
            let mut axes_only = Touching::default();
            axes_only.update_shapes(shapes, &[], 3, (1, 1));
            axes_only.scan(&bodies, |i| &axes[i][..], 1e-9, None);
            let (k, f) = (kept.found(), axes_only.found());
            assert_eq!((k.len(), f.len()), (1, 1), "step {step}");
            assert!(
                (k[0].gap - f[0].gap).abs() <= 1e-12,
                "step {step}: {} {}",
                k[0].gap,
                f[0].gap
            );
            assert!(
                k[0].normal
                    .iter()
                    .zip(&f[0].normal)
                    .all(|(x, y)| (x - y).abs() <= 1e-11)
            );
        }
        // The second turn takes the axes 1.2·10⁻¹¹ from the first scan's (step 5), and the
        // third motion along the normal after it the centre 1.8·10⁻¹¹ from that scan's.
        assert_eq!((reused, renewed), (6, 2));
    }
}
