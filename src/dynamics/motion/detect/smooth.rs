//! The depth of two overlapping shapes one of whose cores is an ellipsoid: exact against
//! an ellipsoid or a point (a ball, whose margin [`super::Penetration`] adds), and against
//! a polytope or a segment the translation along a normal refined from EPA's.
//!
//! The depth is the shortest translation that separates the shapes: the least, over unit
//! directions u from A to B, of f(u) = h_A(u) + h_B(−u), where h is a core's support
//! function. For an ellipsoid with centre c, rotation Q and semi-axes a,
//! h(d) = c·d + √(dᵀ M d) with M = Q diag(a²) Qᵀ, smooth and convex: its gradient is the
//! support point s(d) = c + M d / √(dᵀ M d), and its Hessian M/s − (M d)(M d)ᵀ/s³ (radii
//! of curvature of the surface on the plane orthogonal to d). EPA approximates a curved
//! surface by facets only to the square of their width, so its normal on an ellipsoid is
//! inexact; Newton's method on the sphere of directions, started from it, converges to the
//! minimum quadratically. At the minimum u* the support points' difference
//! s_A(u*) − s_B(−u*) is f(u*) u*: the witnesses of the contact.
//!
//! A polytope's support function is linear on the normal cone of each face, so against a
//! polytope the same Newton steps run face by face ([`polytope_depth`]). The faces make
//! f only piecewise smooth, and the search over them may stop above the least; where EPA's
//! lower bound cannot show it is the least, the least over the feet of the normals from
//! the origin on every face's plane (`face_planes.rs`) is taken, which is exact.

use super::face_planes::{Ellipsoid, enumerable, least_near, least_on_face_planes};
use super::gjk::PlacedShape;
use crate::dynamics::motion::shape::{ConvexCore, Coords};
use crate::numeric::dense::dot;
use crate::numeric::eigen::jacobi_eigen;
use crate::numeric::{cholesky_solve, orthogonalize_twice};
use smallvec::SmallVec;

/// Newton steps at most (it takes about five from EPA's normal).
const MAX_NEWTON_STEPS: usize = 64;
/// Halvings of a Newton step at most, while f does not decrease along it.
const MAX_HALVINGS: usize = 40;
/// The step stops when the gradient's part along the sphere is this small, relative to
/// the size of the pair (the round-off of f).
const CONVERGED: f64 = 1e-14;
/// A minimum within this fraction of the pair's size of EPA's lower bound is the least.
const CERTIFIED: f64 = 1e-9;
/// Curvatures of f below this fraction of the size count as this in a step near a saddle
/// (their directions would take steps beyond reach).
const FLAT_CURVATURE: f64 = 1e-9;
/// A gradient below this fraction of the size, where f curves down, is at a saddle.
const AT_SADDLE: f64 = 1e-8;

/// A smooth core, placed: its centre (relative to an origin near the pair, so that f is
/// not the difference of large numbers), rotation and squared semi-axes (none for a point).
struct SmoothCore<'a> {
    centre: Coords,
    rotation: &'a [f64],
    squared_axes: Option<Coords>,
}

impl<'a> SmoothCore<'a> {
    /// The core of `shape` if it is smooth (a point or an ellipsoid), its centre taken from
    /// `origin`.
    fn of(shape: &PlacedShape<'a>, origin: &[f64]) -> Option<Self> {
        let squared_axes = match shape.shape().core() {
            ConvexCore::Point => None,
            ConvexCore::Ellipsoid(a) => Some(a.iter().map(|x| x * x).collect()),
            _ => return None,
        };
        Some(SmoothCore {
            centre: shape
                .position()
                .iter()
                .zip(origin)
                .map(|(x, o)| x - o)
                .collect(),
            rotation: shape.rotation(),
            squared_axes,
        })
    }

    /// The largest semi-axis (0 for a point).
    fn radius(&self) -> f64 {
        self.squared_axes
            .as_ref()
            .map_or(0.0, |a| a.iter().fold(0.0f64, |m, x| m.max(*x)).sqrt())
    }

    /// The support point s(σ u) in `support`, and the Hessian of h at σ u added to
    /// `hessian` (n × n, row-major) if given (the chain rule's two factors σ cancel).
    fn support(&self, u: &[f64], sigma: f64, support: &mut [f64], hessian: Option<&mut [f64]>) {
        let n = u.len();
        support.copy_from_slice(&self.centre);
        let Some(a2) = &self.squared_axes else {
            return;
        };
        let q = self.rotation;
        // t = diag(a²) Qᵀ d, s = √(dᵀ M d), m = Q t = M d (d = σ u).
        let mut t = Coords::from_elem(0.0, n);
        for (i, ui) in u.iter().enumerate() {
            for (tk, qik) in t.iter_mut().zip(&q[i * n..(i + 1) * n]) {
                *tk += sigma * qik * ui;
            }
        }
        let mut s2 = 0.0;
        for (tk, a2k) in t.iter_mut().zip(a2) {
            s2 += *tk * *tk * a2k;
            *tk *= a2k;
        }
        let s = s2.sqrt();
        let mut m = Coords::from_elem(0.0, n);
        for (i, mi) in m.iter_mut().enumerate() {
            *mi = dot(&q[i * n..(i + 1) * n], &t);
        }
        for (p, mi) in support.iter_mut().zip(&m) {
            *p += mi / s;
        }
        if let Some(h) = hessian {
            let s3 = s * s2;
            for i in 0..n {
                for j in 0..n {
                    let qq: f64 = (0..n).map(|k| q[i * n + k] * q[j * n + k] * a2[k]).sum();
                    h[i * n + j] += qq / s - m[i] * m[j] / s3;
                }
            }
        }
    }
}

/// The refined contact of two overlapping cores: depth, unit normal from A to B, and the
/// witnesses (s_A(u) and s_B(−u) for smooth cores).
pub(super) struct SmoothContact {
    pub depth: f64,
    pub normal: Coords,
    pub witness_a: Coords,
    pub witness_b: Coords,
}

impl SmoothContact {
    /// The contact with its witnesses moved from the origin of the cores' centres back to
    /// space.
    fn moved_by(mut self, origin: &[f64]) -> Self {
        for (w, o) in self.witness_a.iter_mut().zip(origin) {
            *w += o;
        }
        for (w, o) in self.witness_b.iter_mut().zip(origin) {
            *w += o;
        }
        self
    }
}

/// f(u), its gradient s_A(u) − s_B(−u) in `gradient` and, if asked, its Hessian (the
/// support points in `sa`, `sb`).
fn evaluate(
    (a, b): (&SmoothCore, &SmoothCore),
    u: &[f64],
    (sa, sb, gradient): (&mut [f64], &mut [f64], &mut [f64]),
    mut hessian: Option<&mut [f64]>,
) -> f64 {
    if let Some(h) = hessian.as_deref_mut() {
        h.fill(0.0);
    }
    a.support(u, 1.0, sa, hessian.as_deref_mut());
    b.support(u, -1.0, sb, hessian);
    for ((g, x), y) in gradient.iter_mut().zip(sa.iter()).zip(sb.iter()) {
        *g = x - y;
    }
    dot(gradient, u)
}

/// The depth of the overlapping shapes `a` and `b` if both cores are smooth and one is an
/// ellipsoid (else None): Newton's method on the sphere of directions ([`newton`]) from
/// `start`, EPA's unit normal from A to B. `lower` is EPA's depth, a lower bound (its
/// polytope is inscribed in A − B): when the minimum found lies more than 1e-9 of the
/// pair's size above it, another minimum may lie below, and Newton also starts from the
/// direction between the centres and both ways along each ellipsoid's axes, the least
/// minimum taken.
pub(super) fn smooth_depth(
    a: &PlacedShape,
    b: &PlacedShape,
    start: &[f64],
    lower: f64,
) -> Option<SmoothContact> {
    let origin = a.position();
    let (ca, cb) = (SmoothCore::of(a, origin)?, SmoothCore::of(b, origin)?);
    if ca.squared_axes.is_none() && cb.squared_axes.is_none() {
        return None;
    }
    let n = start.len();
    let between = cb.centre.clone();
    let size = dot(&between, &between).sqrt() + ca.radius() + cb.radius();
    let cores = (&ca, &cb);
    let mut best = newton(cores, start, size, &[]);
    if best.depth - lower <= CERTIFIED * size {
        return Some(best.moved_by(origin));
    }
    let mut consider = |u: &[f64]| {
        // Once a start has reached EPA's lower bound, the rest cannot go lower.
        if best.depth - lower > CERTIFIED * size {
            let found = newton(cores, u, size, &[]);
            if found.depth < best.depth {
                best = found;
            }
        }
    };
    consider(&between);
    let mut axis = Coords::from_elem(0.0, n);
    for core in [&ca, &cb] {
        if core.squared_axes.is_some() {
            for k in 0..n {
                for sign in [1.0, -1.0] {
                    for (i, x) in axis.iter_mut().enumerate() {
                        *x = sign * core.rotation[i * n + k];
                    }
                    consider(&axis);
                }
            }
        }
    }
    Some(best.moved_by(origin))
}

/// Newton's method calls at most for the depth of an ellipsoid and a polytope, from one
/// start and in all.
const MAX_FACE_SOLVES: usize = 12;
const MAX_ALL_FACE_SOLVES: usize = 256;
/// Cuboid cores up to this dimension take part by their 2^N corners.
const MAX_CUBOID_DIM: usize = 10;

/// Writes the vertices of a polytope core (a hull, a cuboid up to [`MAX_CUBOID_DIM`], a
/// segment) to `out` (N numbers each, from `origin`); false for other cores.
pub(super) fn polytope_vertices(shape: &PlacedShape, origin: &[f64], out: &mut Vec<f64>) -> bool {
    let n = shape.position().len();
    let (c, q) = (shape.position(), shape.rotation());
    out.clear();
    let mut push = |own: &[f64]| {
        for (i, (ci, oi)) in c.iter().zip(origin).enumerate() {
            out.push(ci - oi + dot(&q[i * n..(i + 1) * n], own));
        }
    };
    let mut own = Coords::from_elem(0.0, n);
    match shape.shape().core() {
        ConvexCore::Hull(v) => v.chunks_exact(n).for_each(push),
        ConvexCore::Cuboid(h) if n <= MAX_CUBOID_DIM => {
            for corner in 0..1usize << n {
                for (i, (x, hi)) in own.iter_mut().zip(h).enumerate() {
                    *x = if corner >> i & 1 == 1 { *hi } else { -hi };
                }
                push(&own);
            }
        }
        ConvexCore::Segment(h) => {
            for end in [*h, -h] {
                own[0] = end;
                push(&own);
            }
        }
        _ => return false,
    }
    true
}

/// The height σ v·u of the highest of `vertices` (N numbers each) along σ u, and its index.
fn highest(vertices: &[f64], sigma: f64, u: &[f64]) -> (f64, usize) {
    let (mut top, mut at) = (f64::NEG_INFINITY, 0);
    for (k, v) in vertices.chunks_exact(u.len()).enumerate() {
        let x = sigma * dot(v, u);
        if x > top {
            (top, at) = (x, k);
        }
    }
    (top, at)
}

/// An orthonormal basis of the directions v − v₀ of the vertices v of `face` (rows of
/// `basis`), at most N − 1 of them: false if the face spans N dimensions (it is then no
/// face, and the basis holds N − 1 of them). `x` is scratch of N numbers.
fn face_basis(
    (vertices, face, v0): (&[f64], &[usize], &[f64]),
    tolerance: f64,
    basis: &mut SmallVec<[f64; 64]>,
    x: &mut [f64],
) -> bool {
    let n = v0.len();
    basis.clear();
    let mut rank = 0;
    for &k in face {
        for (xi, (v, w)) in x
            .iter_mut()
            .zip(vertices[k * n..(k + 1) * n].iter().zip(v0))
        {
            *xi = v - w;
        }
        orthogonalize_twice(x, basis, rank);
        let length = dot(x, x).sqrt();
        if length > tolerance {
            if rank + 1 == n {
                return false;
            }
            basis.extend(x.iter().map(|y| y / length));
            rank += 1;
        }
    }
    true
}

/// Room for [`polytope_depth`], kept in the EPA workspace so that queries do not allocate
/// once it has grown: the polytope's vertices in space and three lists of them.
#[derive(Clone, Debug, Default)]
pub(super) struct FaceScratch {
    vertices: Vec<f64>,
    face: Vec<usize>,
    next: Vec<usize>,
    carry: Vec<usize>,
    /// The vertices near the support along the normal found, for [`least_near`].
    near: Vec<(f64, usize)>,
    points: Vec<f64>,
}

/// How far below the highest along the normal found a vertex still counts as near it, in
/// units of √(tolerance · size): the normal's error, times the polytope's size, and room.
const NEAR: f64 = 16.0;

/// The depth of an ellipsoid and an overlapping polytope (a hull, a cuboid, a segment;
/// either way round), or None for other pairs. f(u) = h_P(±u) + h_E(∓u) is smooth on the
/// normal cone of each face F of the polytope, where h_P(d) = v₀·d for a vertex v₀ of F:
/// there Newton's method runs as for a point against the ellipsoid, with u kept orthogonal
/// to F. From `start` (EPA's normal) the face touched along u is taken (its vertices within
/// f(start) − `lower` of the highest at first, then within 1e-9 of the size), Newton finds
/// the least f on its cone's plane, and the face along the new u is taken again, joined
/// with the last where the step crossed from one to the other, until it stays the same.
/// Unless the least f found lies within 1e-9 of the size of EPA's lower bound `lower`, the
/// least over the feet of normals on every face's plane ([`least_on_face_planes`], exact)
/// is taken where it is lower; for a polytope of more face planes than that takes, the
/// search starts again from a vertex of the face alone (the least may lie on a smaller
/// face) and from the face joined with the next vertex below it, then from the direction
/// between the centres and both ways along the ellipsoid's axes and a box's. Where it does
/// lie within that, f is within 1e-9 of the size of the least in value, but across a face
/// lower than a facet f is smooth, and the normal may be off the least's by the square
/// root of that (10⁻⁵) and the witnesses off their shapes by as much (also where the
/// search ends on a face whose least lies on a smaller face of it): the feet on the planes
/// of the faces near the polytope's support along it ([`least_near`], the least's face
/// among them) give the normal to round-off, taken where f is as low. The depth is f at
/// the normal found, a translation that separates the shapes, so never below the true
/// depth.
pub(super) fn polytope_depth(
    a: &PlacedShape,
    b: &PlacedShape,
    start: &[f64],
    lower: f64,
    scratch: &mut FaceScratch,
) -> Option<SmoothContact> {
    let FaceScratch {
        vertices,
        face,
        next,
        carry,
        near,
        points,
    } = scratch;
    // σ: the polytope's support is asked along σ u (A: +1, B: −1).
    let origin = a.position();
    let (ellipsoid, polytope, sigma) = match (SmoothCore::of(a, origin), SmoothCore::of(b, origin))
    {
        (Some(e), None) if e.squared_axes.is_some() => (e, b, -1.0),
        (None, Some(e)) if e.squared_axes.is_some() => (e, a, 1.0),
        _ => return None,
    };
    if !polytope_vertices(polytope, origin, vertices) {
        return None;
    }
    let n = start.len();
    let vertices = &vertices[..];
    let reach = vertices
        .chunks_exact(n)
        .map(|v| {
            v.iter()
                .zip(polytope.position().iter().zip(origin))
                .map(|(x, (c, o))| (x - (c - o)) * (x - (c - o)))
                .sum::<f64>()
        })
        .fold(0.0f64, f64::max)
        .sqrt();
    let between: Coords = b
        .position()
        .iter()
        .zip(a.position())
        .map(|(x, y)| x - y)
        .collect();
    let size = dot(&between, &between).sqrt() + ellipsoid.radius() + reach;
    let tolerance = CERTIFIED * size;
    let mut support = Coords::from_elem(0.0, n);
    let mut measure = |u: &[f64]| {
        ellipsoid.support(u, -sigma, &mut support, None);
        highest(vertices, sigma, u).0 - sigma * dot(&support, u)
    };
    let mut best: (f64, Coords) = (measure(start), start.iter().copied().collect());
    let mut solves = 0;
    let mut basis: SmallVec<[f64; 64]> = SmallVec::new();
    carry.clear();
    let mut x = Coords::from_elem(0.0, n);
    // The vertices within `within` of the highest along σ u.
    let face_of = |u: &[f64], out: &mut Vec<usize>, within: f64| {
        let (top, _) = highest(vertices, sigma, u);
        out.clear();
        out.extend(
            vertices
                .chunks_exact(n)
                .enumerate()
                .filter(|(_, v)| sigma * dot(v, u) >= top - within)
                .map(|(k, _)| k),
        );
    };
    // EPA's normal is off the least by about as much as f there lies above EPA's bound:
    // the first face takes the vertices within that of the highest, which the least's
    // face is among.
    let first_within = (best.0 - lower).max(tolerance);
    // Starts: a direction, a vertex to take alone as the first face, a vertex to join to
    // the first face.
    type Seed = (Coords, Option<usize>, Option<usize>);
    let mut queue: SmallVec<[Seed; 16]> = SmallVec::new();
    queue.push((start.iter().copied().collect(), None, None));
    // The more starts, taken one by one once the queue is empty: the direction between
    // the centres, then both ways along the ellipsoid's axes and the polytope's if it is
    // a box.
    let boxed = matches!(polytope.shape().core(), ConvexCore::Cuboid(_));
    let more = 1 + 2 * n * (1 + usize::from(boxed));
    let (mut widened, mut alone_starts) = (None::<usize>, 0);
    // Where the face planes can be enumerated, they give the least once the search from
    // EPA's normal has not shown it: no more starts.
    let exact_after = enumerable(polytope, vertices.len() / n);
    loop {
        if queue.is_empty() {
            let k = match widened {
                None if best.0 - lower > tolerance && !exact_after => 0,
                Some(k) if k < more && best.0 - lower > tolerance && !exact_after => k,
                _ => break,
            };
            widened = Some(k + 1);
            let direction: Coords = if k == 0 {
                between.clone()
            } else {
                let (axis, sign) = ((k - 1) / 2, if k % 2 == 1 { 1.0 } else { -1.0 });
                let q = if axis < n {
                    ellipsoid.rotation
                } else {
                    polytope.rotation()
                };
                (0..n).map(|i| sign * q[i * n + axis % n]).collect()
            };
            queue.push((direction, None, None));
        }
        let Some((mut u, mut alone, mut join)) = queue.pop() else {
            break;
        };
        let first = solves;
        while solves < (first + MAX_FACE_SOLVES).min(MAX_ALL_FACE_SOLVES) {
            let (_, top) = highest(vertices, sigma, &u);
            let merged = match alone.take() {
                Some(k) => {
                    face.clear();
                    face.push(k);
                    false
                }
                None => {
                    // The face along u, and the face the last step was solved on (itself
                    // grown so, while the steps keep leaving their faces): a step that
                    // left a face for another may have crossed the least, where both
                    // meet (or, from a start that asks, the next vertex below the face).
                    let within = if solves == 0 { first_within } else { tolerance };
                    face_of(&u, face, within);
                    let wide = solves == 0 && face.len() > 1;
                    carry.extend(join.take());
                    let before = face.len();
                    for &k in carry.iter() {
                        if !face.contains(&k) {
                            face.push(k);
                        }
                    }
                    face.sort_unstable();
                    wide || face.len() > before
                }
            };
            carry.clear();
            // No vertex is highest only along a direction that is not finite.
            if face.is_empty() {
                break;
            }
            let v0 = if face.len() == 1 { face[0] } else { top };
            let v0 = &vertices[v0 * n..(v0 + 1) * n];
            // The faces together (or the wide first face) span the whole space: no face.
            if !face_basis((vertices, face, v0), tolerance, &mut basis, &mut x) {
                if !merged {
                    break;
                }
                face_of(&u, face, tolerance);
                if !face_basis((vertices, face, v0), tolerance, &mut basis, &mut x) {
                    break;
                }
            }
            let point = SmoothCore {
                centre: Coords::from_slice(v0),
                rotation: polytope.rotation(),
                squared_axes: None,
            };
            let cores = if sigma > 0.0 {
                (&point, &ellipsoid)
            } else {
                (&ellipsoid, &point)
            };
            let found = newton(cores, &u, size, &basis);
            solves += 1;
            if !found.depth.is_finite() {
                break;
            }
            let f = measure(&found.normal);
            if f < best.0 {
                best = (f, found.normal.clone());
            }
            face_of(&found.normal, next, tolerance);
            let same = next == face;
            if !same {
                carry.clone_from(face);
            }
            u = found.normal;
            if same {
                // The least on this face's plane: where it lies outside the face, a
                // smaller face holds a lower one, and a vertex alone leads there.
                if best.0 - lower > tolerance && alone_starts < 8 && !exact_after {
                    if face.len() > 1 {
                        for &k in face.iter().take(4) {
                            queue.push((u.clone(), Some(k), None));
                            alone_starts += 1;
                        }
                    }
                    // Or the least lies where the next vertex below meets the face.
                    let below = vertices
                        .chunks_exact(n)
                        .enumerate()
                        .filter(|(k, _)| !face.contains(k))
                        .map(|(k, v)| (sigma * dot(v, &u), k))
                        .max_by(|p, q| p.0.total_cmp(&q.0));
                    if let Some((_, k)) = below {
                        queue.push((u.clone(), None, Some(k)));
                        alone_starts += 1;
                    }
                }
                break;
            }
        }
    }
    let centre: Coords = polytope
        .position()
        .iter()
        .zip(origin)
        .map(|(c, o)| c - o)
        .collect();
    let core = Ellipsoid {
        centre: &ellipsoid.centre,
        rotation: ellipsoid.rotation,
        squared_axes: ellipsoid.squared_axes.as_deref().unwrap_or(&[]),
    };
    // f along w (from the ellipsoid's side), and the direction u it is along.
    let along = |w: &[f64]| -> Coords { w.iter().map(|x| -sigma * x).collect() };
    let mut u = Coords::from_elem(0.0, n);
    let mut f = |w: &[f64]| {
        u.iter_mut().zip(w).for_each(|(x, y)| *x = -sigma * y);
        measure(&u)
    };
    if best.0 - lower > tolerance {
        // Not shown to be the least: the least over the feet on every face's plane is.
        let planes = least_on_face_planes(&core, polytope, (vertices, &centre), tolerance, &mut f);
        if let Some((value, w)) = planes.filter(|(value, _)| *value < best.0) {
            best = (value, along(&w));
        }
    } else if best.0.is_finite()
        && !witness_on_polytope(&ellipsoid, polytope, &centre, &best, sigma, size)
    {
        // f is smooth across a face of the polytope lower than a facet (a vertex against
        // the ellipsoid, say): within `tolerance` of the least in value, the normal may
        // still be off it by about √(tolerance / curvature), and the witnesses then off
        // the shapes by that times the curvature radius. The foot on the plane of the face
        // the least lies on gives the normal to round-off: that face is among the faces
        // near the support along the normal found.
        let near_within = NEAR * (tolerance * size).sqrt();
        let d: Coords = best.1.iter().map(|x| sigma * x).collect();
        let polished = least_near(
            &core,
            polytope,
            (vertices, &centre),
            (&d, near_within),
            tolerance,
            &mut f,
            (near, points),
        );
        // Taken where it is as low, to round-off of the size: it is the same least.
        let rounding = 16.0 * f64::EPSILON * size;
        if let Some((value, w)) = polished.filter(|(value, _)| *value <= best.0 + rounding) {
            best = (value, along(&w));
        }
    }
    let (depth, u) = best;
    if !depth.is_finite() {
        return None;
    }
    // The ellipsoid's witness, and the polytope's at depth · u from it.
    ellipsoid.support(&u, -sigma, &mut support, None);
    let other: Coords = support
        .iter()
        .zip(&u)
        .map(|(s, m)| s + sigma * depth * m)
        .collect();
    let (witness_a, witness_b) = if sigma > 0.0 {
        (other, support)
    } else {
        (support, other)
    };
    let contact = SmoothContact {
        depth,
        normal: u,
        witness_a,
        witness_b,
    };
    Some(contact.moved_by(origin))
}

/// Whether the polytope's witness of a depth and normal `(depth, u)` (the ellipsoid's
/// support along ∓u, moved by the depth) lies in the polytope, to round-off of `size`,
/// where that is a closed form (a cuboid, a segment); false for a hull. There both
/// witnesses lie on their shapes, touching once the polytope is moved by the depth, with
/// u the ellipsoid's normal there: the least's condition, so that u is its normal.
fn witness_on_polytope(
    ellipsoid: &SmoothCore,
    polytope: &PlacedShape,
    centre: &[f64],
    (depth, u): &(f64, Coords),
    sigma: f64,
    size: f64,
) -> bool {
    if !matches!(
        polytope.shape().core(),
        ConvexCore::Cuboid(_) | ConvexCore::Segment(_)
    ) {
        return false;
    }
    let n = u.len();
    let mut point = Coords::from_elem(0.0, n);
    ellipsoid.support(u, -sigma, &mut point, None);
    // The witness in the polytope's own axes.
    let q = polytope.rotation();
    let own: Coords = (0..n)
        .map(|j| {
            (0..n)
                .map(|i| q[i * n + j] * (point[i] + sigma * depth * u[i] - centre[i]))
                .sum()
        })
        .collect();
    let slack = 64.0 * f64::EPSILON * size;
    match polytope.shape().core() {
        ConvexCore::Cuboid(half) => own
            .iter()
            .zip(half.iter())
            .all(|(x, h)| x.abs() <= h + slack),
        ConvexCore::Segment(h) => {
            let off = dot(&own[1..], &own[1..]) + (own[0].abs() - h).max(0.0).powi(2);
            off.sqrt() <= slack
        }
        _ => false,
    }
}

/// Newton's method on the unit sphere for the least f(u) = h_A(u) + h_B(−u) near `start`.
/// Each step solves the Riemannian Newton system (P ∇²f P − f P) ξ = −P ∇f on the tangent
/// plane (P = I − u uᵀ); where that Hessian is not positive definite (near a saddle of f,
/// such as the end of an ellipsoid's middle axis) the step takes its eigenvalues' absolute
/// values instead and, at the saddle itself, moves along the direction of negative
/// curvature. ξ is halved until f decreases: the result separates the shapes by no more
/// than `start` does, to round-off.
fn newton(
    cores: (&SmoothCore, &SmoothCore),
    start: &[f64],
    size: f64,
    fixed: &[f64],
) -> SmoothContact {
    let n = start.len();
    let rank = fixed.len() / n;
    let zeros = || Coords::from_elem(0.0, n);
    let (mut sa, mut sb, mut g) = (zeros(), zeros(), zeros());
    let square = || -> SmallVec<[f64; 64]> { SmallVec::from_elem(0.0, n * n) };
    let (mut hessian, mut system, mut vectors) = (square(), square(), square());
    let (mut projector, mut half) = (square(), square());
    let (mut xi, mut trial, mut hu) = (zeros(), zeros(), zeros());
    let (mut ta, mut tb, mut tg) = (zeros(), zeros(), zeros());
    let mut u: Coords = start.iter().copied().collect();
    orthogonalize_twice(&mut u, fixed, rank);
    let length = dot(&u, &u).sqrt();
    if length.is_nan() || length <= 0.0 {
        return SmoothContact {
            depth: f64::INFINITY,
            normal: u,
            witness_a: sa,
            witness_b: sb,
        };
    }
    u.iter_mut().for_each(|x| *x /= length);
    let mut f = evaluate(cores, &u, (&mut sa, &mut sb, &mut g), Some(&mut hessian));
    let mut steps = 0;
    while steps < MAX_NEWTON_STEPS {
        // The gradient along the sphere and orthogonal to the fixed directions,
        // r = P ∇f with P = I − u uᵀ − B Bᵀ (u·∇f = f: h is of degree 1).
        for ((x, gi), ui) in xi.iter_mut().zip(&g).zip(&u) {
            *x = -(gi - f * ui);
        }
        orthogonalize_twice(&mut xi, fixed, rank);
        let residual = dot(&xi, &xi).sqrt();
        // P H' P + (I − P) with H' = ∇²f − f I: on the tangent plane the Riemannian
        // Hessian, elsewhere the identity, so that ξ stays in the tangent plane.
        for i in 0..n {
            for (j, x) in projector[i * n..(i + 1) * n].iter_mut().enumerate() {
                *x = f64::from(u8::from(i == j)) - u[i] * u[j];
            }
        }
        for b in fixed.chunks_exact(n) {
            for i in 0..n {
                for j in 0..n {
                    projector[i * n + j] -= b[i] * b[j];
                }
            }
        }
        for i in 0..n {
            for j in 0..n {
                let diagonal = if i == j { f } else { 0.0 };
                hu[j] = hessian[i * n + j] - diagonal;
            }
            // Row i of H' P.
            for j in 0..n {
                half[i * n + j] = (0..n).map(|k| hu[k] * projector[k * n + j]).sum();
            }
        }
        let fill = |system: &mut [f64]| {
            for i in 0..n {
                for j in 0..n {
                    let p: f64 = (0..n).map(|k| projector[k * n + i] * half[k * n + j]).sum();
                    let identity = f64::from(u8::from(i == j));
                    system[i * n + j] = p + identity - projector[i * n + j];
                }
            }
        };
        fill(&mut system);
        trial.copy_from_slice(&xi);
        if !cholesky_solve(&mut system, n, &mut trial) {
            fill(&mut system);
            jacobi_eigen(&mut system, n, &mut vectors);
            trial.fill(0.0);
            let (mut least, mut at) = (f64::INFINITY, 0);
            for k in 0..n {
                let value = system[k * n + k];
                // `jacobi_eigen` leaves the eigenvectors by columns: vector k is row k.
                let vector = &vectors[k * n..(k + 1) * n];
                let scale = dot(vector, &xi) / value.abs().max(FLAT_CURVATURE * size);
                for (t, e) in trial.iter_mut().zip(vector) {
                    *t += scale * e;
                }
                if value < least {
                    (least, at) = (value, k);
                }
            }
            if least < 0.0 && residual <= AT_SADDLE * size {
                // At a saddle: half a radian along the negative curvature, downhill.
                let vector = &vectors[at * n..(at + 1) * n];
                let sign = if dot(vector, &xi) < 0.0 { -0.5 } else { 0.5 };
                for (t, e) in trial.iter_mut().zip(vector) {
                    *t = sign * e;
                }
            } else if residual <= CONVERGED * size {
                break;
            }
        } else if residual <= CONVERGED * size {
            break;
        }
        std::mem::swap(&mut xi, &mut trial);
        // Halve the step until f decreases.
        let mut scale = 1.0;
        let mut taken = false;
        for _ in 0..MAX_HALVINGS {
            for ((t, ui), x) in trial.iter_mut().zip(&u).zip(&xi) {
                *t = ui + scale * x;
            }
            let l = dot(&trial, &trial).sqrt();
            trial.iter_mut().for_each(|x| *x /= l);
            let ft = evaluate(cores, &trial, (&mut ta, &mut tb, &mut tg), None);
            // A full step near the minimum changes f by less than its round-off.
            if ft < f || (scale == 1.0 && ft <= f + 4.0 * f64::EPSILON * size) {
                taken = true;
                break;
            }
            scale *= 0.5;
        }
        if !taken {
            break;
        }
        steps += 1;
        std::mem::swap(&mut u, &mut trial);
        f = evaluate(cores, &u, (&mut sa, &mut sb, &mut g), Some(&mut hessian));
    }
    if !f.is_finite() {
        f = f64::INFINITY;
    }
    // witness_a − witness_b = depth · normal, to the last bit of the step's residual.
    for ((b, a), m) in sb.iter_mut().zip(&sa).zip(&u) {
        *b = a - f * m;
    }
    SmoothContact {
        depth: f,
        normal: u,
        witness_a: sa,
        witness_b: sb,
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{box_corners, random_rotation as rotation};
    use super::super::{EpaWorkspace, PlacedShape, penetration_with};
    use crate::dynamics::motion::shape::ConvexShape;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A ball whose centre lies inside an ellipsoid on its shortest axis, at δ from the
    /// centre, leaves through the end of that axis: depth a_min − |δ| + r (the surface's
    /// radii of curvature there, a_j²/a_min, all exceed a_min), N = 2 … 6, either way
    /// round, through the whole query (GJK, EPA, then Newton).
    #[test]
    fn a_ball_on_the_shortest_axis_of_an_ellipsoid_leaves_through_its_end() {
        let mut r = ChaCha8Rng::seed_from_u64(5);
        let mut workspace = EpaWorkspace::new();
        let mut cases = 0;
        for n in 2..=6usize {
            for _ in 0..200 {
                let mut axes: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
                let shortest = r.gen_range(0..n);
                axes[shortest] = 0.2;
                let ellipsoid = ConvexShape::ellipsoid(&axes).unwrap();
                let radius = r.gen_range(0.05..1.0);
                let ball = ConvexShape::ball(n, radius).unwrap();
                let q = rotation(&mut r, n);
                let centre: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
                let delta = r.gen_range(0.01..0.18) * if r.gen_bool(0.5) { 1.0 } else { -1.0 };
                let axis: Vec<f64> = (0..n).map(|i| q[i * n + shortest]).collect();
                let inside: Vec<f64> = centre
                    .iter()
                    .zip(&axis)
                    .map(|(c, e)| c + delta * e)
                    .collect();
                let expected = 0.2 - delta.abs() + radius;
                let a = PlacedShape::new(&ellipsoid, &centre, &q).unwrap();
                let b = PlacedShape::new(&ball, &inside, &q).unwrap();
                for (swapped, p) in [
                    (false, penetration_with(&mut workspace, &a, &b).unwrap()),
                    (true, penetration_with(&mut workspace, &b, &a).unwrap()),
                ] {
                    assert!(
                        (p.depth - expected).abs() < 1e-12,
                        "N = {n}: {} against {expected}",
                        p.depth
                    );
                    let sign = if swapped {
                        -delta.signum()
                    } else {
                        delta.signum()
                    };
                    for (m, e) in p.normal.as_slice().iter().zip(&axis) {
                        assert!((m - sign * e).abs() < 1e-7, "N = {n}: normal");
                    }
                    let (wa, wb) = (p.witness_a.as_slice(), p.witness_b.as_slice());
                    // The ellipsoid's witness is the end of its shortest axis, in space.
                    let end = if swapped { wb } else { wa };
                    for i in 0..n {
                        let gap = wa[i] - wb[i] - p.depth * p.normal.as_slice()[i];
                        assert!(gap.abs() < 1e-12, "N = {n}: witnesses {gap:e}");
                        let tip = centre[i] + 0.2 * delta.signum() * axis[i];
                        assert!((end[i] - tip).abs() < 1e-9, "N = {n}: witness {}", end[i]);
                    }
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 2000);
    }

    /// A face of any dimension k = 0 … N − 1 (a vertex, an edge, …, a facet) of a hull and
    /// of a box in the tangent plane of an ellipsoid at a point p, pushed in by d along the
    /// normal m there (d = 10⁻⁸, 10⁻⁶ or 10⁻⁴), centred at p − d m: the depth is d along m
    /// (the surface's radii of curvature all exceed d), the ellipsoid's witness p and the
    /// polytope's p − d m, N = 2 … 6, either way round; in every other trial m lies within
    /// 10⁻⁶ of the box face's normal cone's boundary (where the search face by face ends
    /// on the larger face). Across a face lower than a facet f is smooth, and a normal
    /// within 1e-9 of the size of the least in value could be off m by 10⁻⁵: normal and
    /// witnesses must be exact to 1e-10.
    #[test]
    fn a_face_touching_an_ellipsoid_gives_exact_normal_and_witnesses() {
        let mut r = ChaCha8Rng::seed_from_u64(17);
        let mut workspace = EpaWorkspace::new();
        let mut cases = 0;
        let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
        for n in 2..=6usize {
            let identity: Vec<f64> = (0..n * n)
                .map(|k| if k % (n + 1) == 0 { 1.0 } else { 0.0 })
                .collect();
            for k in 0..n {
                for trial in 0..30 {
                    let axes: Vec<f64> = (0..n).map(|_| r.gen_range(0.5..1.5)).collect();
                    let ellipsoid = ConvexShape::ellipsoid(&axes).unwrap();
                    let q = rotation(&mut r, n);
                    let centre: Vec<f64> = (0..n).map(|_| r.gen_range(-0.5..0.5)).collect();
                    // A surface point (aᵢyᵢ in its own axes for a unit y) and its normal
                    // (along yᵢ/aᵢ), in space.
                    let y: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
                    let length = dot(&y, &y).sqrt();
                    let own_p: Vec<f64> = (0..n).map(|i| axes[i] * y[i] / length).collect();
                    let own_m: Vec<f64> = (0..n).map(|i| y[i] / axes[i]).collect();
                    let to_space = |v: &[f64]| -> Vec<f64> {
                        (0..n).map(|i| dot(&q[i * n..(i + 1) * n], v)).collect()
                    };
                    let p: Vec<f64> = to_space(&own_p)
                        .iter()
                        .zip(&centre)
                        .map(|(x, c)| x + c)
                        .collect();
                    let m = to_space(&own_m);
                    let m: Vec<f64> = m.iter().map(|x| x / dot(&m, &m).sqrt()).collect();
                    let d = [1e-8, 1e-6, 1e-4][trial % 3];
                    let base: Vec<f64> = p.iter().zip(&m).map(|(x, u)| x - d * u).collect();
                    // The tangent space's orthonormal basis, m first.
                    let mut basis = vec![m.clone()];
                    while basis.len() < n {
                        let mut x: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
                        for _ in 0..2 {
                            for b in &basis {
                                let along = dot(&x, b);
                                x.iter_mut().zip(b).for_each(|(x, b)| *x -= along * b);
                            }
                        }
                        let length = dot(&x, &x).sqrt();
                        basis.push(x.iter().map(|v| v / length).collect());
                    }
                    let at = |offsets: &[(usize, f64)]| -> Vec<f64> {
                        let mut v = base.clone();
                        for &(j, c) in offsets {
                            v.iter_mut().zip(&basis[j]).for_each(|(v, b)| *v += c * b);
                        }
                        v
                    };
                    // The face: base + 0.3 tⱼ (j = 1 … k) and base − 0.3 Σ tⱼ / k, whose
                    // centroid is base; the other points above the tangent plane.
                    let mut points = Vec::new();
                    for j in 1..=k {
                        points.push(at(&[(j, 0.3)]));
                    }
                    let rest: Vec<(usize, f64)> = (1..=k).map(|j| (j, -0.3 / k as f64)).collect();
                    points.push(at(&rest));
                    for _ in 0..n - k {
                        let mut offsets = vec![(0, r.gen_range(0.3..0.8))];
                        offsets.extend((1..n).map(|j| (j, r.gen_range(-0.5..0.5))));
                        points.push(at(&offsets));
                    }
                    let hull = ConvexShape::hull(&points).unwrap();
                    // A box whose face of the last k axes is centred at base, its normal
                    // cone holding m: its other axes qⱼ (j < N − k) with Σ ŵⱼ qⱼ = m for
                    // positive unit weights ŵ, the columns of the reflection that takes
                    // (ŵ, 0) to the first axis, in the basis (m, tangents).
                    let fixed = n - k;
                    let mut weight: Vec<f64> = (0..n)
                        .map(|j| {
                            if j < fixed {
                                r.gen_range(0.3..1.0)
                            } else {
                                0.0
                            }
                        })
                        .collect();
                    if fixed > 1 && trial % 2 == 1 {
                        // m within 10⁻⁶ of the normal cone of the face of one more axis.
                        weight[fixed - 1] = 1e-6;
                    }
                    let length = dot(&weight, &weight).sqrt();
                    weight.iter_mut().for_each(|x| *x /= length);
                    let mut v = weight.clone();
                    v[0] -= 1.0;
                    let vv = dot(&v, &v);
                    let reflect = |i: usize, j: usize| {
                        let e = if i == j { 1.0 } else { 0.0 };
                        if vv > 0.0 {
                            e - 2.0 * v[i] * v[j] / vv
                        } else {
                            e
                        }
                    };
                    let axes_of_box: Vec<Vec<f64>> = (0..n)
                        .map(|j| {
                            (0..n)
                                .map(|c| (0..n).map(|i| reflect(i, j) * basis[i][c]).sum())
                                .collect()
                        })
                        .collect();
                    let half: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..0.5)).collect();
                    let cuboid = ConvexShape::cuboid(&half).unwrap();
                    let box_centre: Vec<f64> = (0..n)
                        .map(|c| {
                            base[c] + (0..fixed).map(|j| half[j] * axes_of_box[j][c]).sum::<f64>()
                        })
                        .collect();
                    let box_rotation: Vec<f64> =
                        (0..n * n).map(|x| axes_of_box[x % n][x / n]).collect();
                    let a = PlacedShape::new(&ellipsoid, &centre, &q).unwrap();
                    let zero = vec![0.0; n];
                    let polytopes = [
                        ("hull", PlacedShape::new(&hull, &zero, &identity).unwrap()),
                        (
                            "box",
                            PlacedShape::new(&cuboid, &box_centre, &box_rotation).unwrap(),
                        ),
                    ];
                    for ((kind, b), swapped) in
                        polytopes.iter().flat_map(|b| [(b, false), (b, true)])
                    {
                        let pen = if swapped {
                            penetration_with(&mut workspace, b, &a).unwrap()
                        } else {
                            penetration_with(&mut workspace, &a, b).unwrap()
                        };
                        let case =
                            format!("N = {n}, a {kind}'s {k}-face, d = {d}, swapped {swapped}");
                        assert!((pen.depth - d).abs() < 1e-12, "{case}: depth {}", pen.depth);
                        let sign = if swapped { -1.0 } else { 1.0 };
                        let (wa, wb) = (pen.witness_a.as_slice(), pen.witness_b.as_slice());
                        let (on_e, on_h) = if swapped { (wb, wa) } else { (wa, wb) };
                        for i in 0..n {
                            let off = (pen.normal.as_slice()[i] - sign * m[i]).abs();
                            assert!(off < 1e-10, "{case}: normal off by {off:e}");
                            let off = (on_e[i] - p[i]).abs().max((on_h[i] - base[i]).abs());
                            assert!(off < 1e-10, "{case}: witnesses off by {off:e}");
                        }
                        cases += 1;
                    }
                }
            }
        }
        // 30 trials × a hull and a box × 2 ways for each face dimension k < N, N = 2 … 6.
        assert_eq!(cases, 120 * (2 + 3 + 4 + 5 + 6));
    }

    /// Two 4D pairs of the reliability run of an ellipsoid against a simplex where the
    /// depth lay within 1e-9 of the size of EPA's lower bound, but a witness off its shape:
    /// touching (depth 9e-10 of the size), the normal off the least's by about 1e-5 and the
    /// simplex's witness 3.8e-6 of the size outside it; overlapping by 0.64 on a facet
    /// whose vertices stand at one height, the least on a face of that facet and a witness
    /// 1.9e-7 of the size outside. Both witnesses must lie on their shapes to 1e-12 of the
    /// size (the simplex's by its barycentric coordinates), depth · normal apart, and the
    /// depth must not rise.
    #[test]
    fn an_ellipsoid_against_a_simplex_has_its_witnesses_on_both() {
        let n = 4;
        // Per pair: the ellipsoid's semi-axes, position and rotation, the simplex's
        // points, position and rotation, whether the ellipsoid is B, and the depth at most.
        type Pair = (
            [f64; 4],
            [f64; 4],
            [f64; 16],
            [f64; 20],
            [f64; 4],
            [f64; 16],
            bool,
            f64,
        );
        let pairs: [Pair; 2] = [
            (
                [
                    0.5163646959682513,
                    1.3183391139309377,
                    1.3747989343297644,
                    0.5511041978839777,
                ],
                [
                    0.5941268539929818,
                    0.14456314082533295,
                    0.9377576309509315,
                    0.22271421948049896,
                ],
                [
                    0.38113063301814454,
                    -0.5870224032601796,
                    0.4018495427937006,
                    -0.5904753031264947,
                    -0.4371778206424843,
                    -0.7176790762779818,
                    0.13690470518128975,
                    0.5244705886036842,
                    0.5737524825420672,
                    -0.331937200358607,
                    -0.7182495989355528,
                    0.2115261152288829,
                    0.5782932495631361,
                    0.17366386083902435,
                    0.5512636032649315,
                    0.5757831368350038,
                ],
                [
                    -0.6035155191426225,
                    -0.6363012121143428,
                    0.563092090737086,
                    -0.15056949353615434,
                    -0.8911590395279583,
                    1.235960675226778,
                    -1.2653547642263923,
                    -1.0116613647928883,
                    -0.4867539171894788,
                    0.7381146770041473,
                    0.7158123037920152,
                    0.10671645685993036,
                    -1.39281217972867,
                    1.4846984529234262,
                    -0.07585245020181941,
                    1.3002249613018408,
                    -0.036610773551752684,
                    -0.29525165742199544,
                    -1.2798047386513716,
                    -1.1964672719072849,
                ],
                [
                    -0.7850142403325484,
                    0.4150001456544715,
                    1.786047992576994,
                    0.8897647932095325,
                ],
                [
                    -0.04673083944141454,
                    0.7882519737930344,
                    0.5551175524851252,
                    -0.2613801013455528,
                    0.7755914620922639,
                    0.364795031184744,
                    -0.23744959320022094,
                    0.457165352844631,
                    0.6268459670852324,
                    -0.36133461875687195,
                    0.2659107770347741,
                    -0.6370187481491958,
                    -0.05777755726633828,
                    0.3391470246399552,
                    -0.7515009329792854,
                    -0.5629275240077217,
                ],
                false,
                4e-9,
            ),
            (
                [
                    1.0241946554798262,
                    0.28228365282953316,
                    1.2019430939644826,
                    1.6944709888005092,
                ],
                [
                    1.0123996883112927,
                    0.6908958945932314,
                    -0.41967591036513013,
                    0.5668100655428341,
                ],
                [
                    -0.28521750326454565,
                    0.16456833144041877,
                    -0.8352460068098871,
                    0.44037750649481816,
                    -0.267356580151601,
                    -0.9556818023648375,
                    -0.11717179261063697,
                    -0.038256015144639915,
                    -0.2574237735538831,
                    0.15053113266045237,
                    -0.35052725738716417,
                    -0.8878085495971941,
                    -0.883687974168744,
                    0.19217162906000018,
                    0.4071431209699864,
                    0.12806290774766185,
                ],
                [
                    1.5212951156984,
                    -0.24395101547759726,
                    -0.24395101547759726,
                    -0.24395101547759726,
                    -0.24395101547759726,
                    1.5212951156984,
                    -0.24395101547759726,
                    -0.24395101547759726,
                    -0.24395101547759726,
                    -0.24395101547759726,
                    1.5212951156984,
                    -0.24395101547759726,
                    -0.24395101547759726,
                    -0.24395101547759726,
                    -0.24395101547759726,
                    1.5212951156984,
                    -0.7894420692656082,
                    -0.7894420692656082,
                    -0.7894420692656082,
                    -0.7894420692656082,
                ],
                [
                    0.7313187968194135,
                    -0.01091945169535169,
                    -0.5516342186692667,
                    -0.025673385960780948,
                ],
                [
                    -0.29642763454224874,
                    0.7367430483044222,
                    0.15057574199379273,
                    0.5887845821502243,
                    -0.3464855452947804,
                    -0.5271176167792893,
                    -0.48169672831461496,
                    0.6083280750661582,
                    -0.2371564387291357,
                    0.3956473437610839,
                    -0.7848792961386885,
                    -0.4137444784368126,
                    -0.8578083981582252,
                    -0.1510624977644331,
                    0.35952704814360303,
                    -0.3347912416290758,
                ],
                true,
                0.6416416557886649,
            ),
        ];
        let mut cases = 0;
        for (axes, pe, qe, points, ph, qh, swapped, most) in pairs {
            let ellipsoid = ConvexShape::ellipsoid(&axes).unwrap();
            let simplex = ConvexShape::hull(&points.chunks_exact(n).collect::<Vec<_>>()).unwrap();
            let e = PlacedShape::new(&ellipsoid, &pe, &qe).unwrap();
            let h = PlacedShape::new(&simplex, &ph, &qh).unwrap();
            let p = if swapped {
                penetration_with(&mut EpaWorkspace::new(), &h, &e).unwrap()
            } else {
                penetration_with(&mut EpaWorkspace::new(), &e, &h).unwrap()
            };
            let size = 4.0;
            assert!(p.depth <= most, "depth {} above {most}", p.depth);
            let (on_e, on_h) = if swapped {
                (p.witness_b.as_slice(), p.witness_a.as_slice())
            } else {
                (p.witness_a.as_slice(), p.witness_b.as_slice())
            };
            let own = |x: &[f64], c: &[f64], q: &[f64]| -> Vec<f64> {
                (0..n)
                    .map(|j| (0..n).map(|i| q[i * n + j] * (x[i] - c[i])).sum())
                    .collect()
            };
            // The ellipsoid's witness on its surface.
            let x = own(on_e, &pe, &qe);
            let level: f64 = x.iter().zip(&axes).map(|(x, a)| (x / a) * (x / a)).sum();
            assert!(
                (level - 1.0).abs() < 1e-12,
                "ellipsoid witness at level {level}"
            );
            // The simplex's: barycentric coordinates t (Σ t = 1) all ≥ 0.
            let y = own(on_h, &ph, &qh);
            let v: Vec<&[f64]> = points.chunks_exact(n).collect();
            let m = nalgebra::DMatrix::from_fn(n, n, |i, j| v[j + 1][i] - v[0][i]);
            let rhs = nalgebra::DVector::from_fn(n, |i, _| y[i] - v[0][i]);
            let t = m.lu().solve(&rhs).unwrap();
            let least = t.iter().fold(1.0 - t.sum(), |l, x| l.min(*x));
            assert!(
                least > -1e-12 * size,
                "simplex witness outside by {least:e}"
            );
            for i in 0..n {
                let gap = p.witness_a[i] - p.witness_b[i] - p.depth * p.normal[i];
                assert!(gap.abs() < 1e-12 * size, "witnesses {gap:e}");
            }
            cases += 1;
        }
        assert_eq!(cases, 2);
    }

    /// Newton's method started exactly at a saddle of f leaves it downhill: a point at the
    /// centre of an ellipsoid has f(u) = √(uᵀ M u), whose critical points on the sphere are
    /// the axes; from the middle one (gradient zero, curving down towards the shortest)
    /// it must reach the shortest axis, in N = 3 … 6 with the axes turned.
    #[test]
    fn newton_leaves_a_saddle_for_the_least() {
        use super::{SmoothCore, newton};
        use crate::dynamics::motion::shape::Coords;
        let mut r = ChaCha8Rng::seed_from_u64(3);
        let mut cases = 0;
        for n in 3..=6usize {
            for _ in 0..20 {
                let q = rotation(&mut r, n);
                // Semi-axes 0.5, 1, 1.5, …: the shortest is axis 0, a middle one axis 1.
                let axes: Coords = (0..n).map(|k| 0.5 * (k + 1) as f64).collect();
                let ellipsoid = SmoothCore {
                    centre: Coords::from_elem(0.0, n),
                    rotation: &q,
                    squared_axes: Some(axes.iter().map(|a| a * a).collect()),
                };
                let point = SmoothCore {
                    centre: Coords::from_elem(0.0, n),
                    rotation: &q,
                    squared_axes: None,
                };
                let middle: Vec<f64> = (0..n).map(|i| q[i * n + 1]).collect();
                let found = newton((&ellipsoid, &point), &middle, 4.0, &[]);
                assert!(
                    (found.depth - 0.5).abs() < 1e-12,
                    "N = {n}: {}",
                    found.depth
                );
                let along: f64 = (0..n).map(|i| q[i * n] * found.normal[i]).sum();
                assert!((along.abs() - 1.0).abs() < 1e-9, "N = {n}: normal");
                cases += 1;
            }
        }
        assert_eq!(cases, 80);
    }

    /// An ellipsoid whose centre lies inside a box and whose axes are the box's: with
    /// p_i = u_i², f = Σ (h_i ∓ δ_i) √p_i + √(Σ a_i² p_i) is concave on each orthant's
    /// simplex of p, so the least translation is along an axis: min_i h_i + a_i − |δ_i|
    /// (δ the centres' offset in the box's axes). N = 2 … 6, the box as a cuboid and as the
    /// hull of its corners, either way round.
    #[test]
    fn an_ellipsoid_inside_a_box_along_its_axes_leaves_along_an_axis() {
        let mut r = ChaCha8Rng::seed_from_u64(21);
        let mut workspace = EpaWorkspace::new();
        let mut cases = 0;
        for n in 2..=6usize {
            for _ in 0..60 {
                let h: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
                let axes: Vec<f64> = (0..n).map(|_| r.gen_range(0.1..1.5)).collect();
                let offset: Vec<f64> = h.iter().map(|x| r.gen_range(-0.9..0.9) * x).collect();
                let expected = (0..n)
                    .map(|i| h[i] + axes[i] - offset[i].abs())
                    .fold(f64::INFINITY, f64::min);
                let q = rotation(&mut r, n);
                let centre: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
                let inside: Vec<f64> = (0..n)
                    .map(|i| centre[i] + (0..n).map(|j| q[i * n + j] * offset[j]).sum::<f64>())
                    .collect();
                let corners = box_corners(&h);
                let ellipsoid = ConvexShape::ellipsoid(&axes).unwrap();
                for solid in [
                    ConvexShape::cuboid(&h).unwrap(),
                    ConvexShape::hull(&corners).unwrap(),
                ] {
                    let a = PlacedShape::new(&solid, &centre, &q).unwrap();
                    let b = PlacedShape::new(&ellipsoid, &inside, &q).unwrap();
                    for (swapped, p) in [
                        (false, penetration_with(&mut workspace, &a, &b).unwrap()),
                        (true, penetration_with(&mut workspace, &b, &a).unwrap()),
                    ] {
                        // The ellipsoid's witness lies on its surface, in space.
                        let w = if swapped { &p.witness_a } else { &p.witness_b };
                        let radial: f64 = (0..n)
                            .map(|k| {
                                let own: f64 =
                                    (0..n).map(|i| q[i * n + k] * (w[i] - inside[i])).sum();
                                (own / axes[k]).powi(2)
                            })
                            .sum();
                        assert!(
                            (radial - 1.0).abs() < 1e-8,
                            "N = {n}: witness off by {radial}"
                        );
                        // The pair's size as the search measures it (the bound it keeps).
                        let length = |x: &[f64]| x.iter().map(|y| y * y).sum::<f64>().sqrt();
                        let widest = axes.iter().fold(0.0f64, |m, x| m.max(*x));
                        let size = length(&offset) + widest + length(&h);
                        assert!(
                            (p.depth - expected).abs() < 1e-9 * size,
                            "N = {n}: {} against {expected}",
                            p.depth
                        );
                        cases += 1;
                    }
                }
            }
        }
        assert_eq!(cases, 1200);
    }

    /// The translation of B along u that separates two ellipses, h_A(u) + h_B(−u), from
    /// the support function's closed form h(d) = c·d + |diag(a) Qᵀ d|.
    fn translation(e: [(&[f64], &[f64], &[f64]); 2], u: [f64; 2]) -> f64 {
        let h = |(c, q, a): (&[f64], &[f64], &[f64]), d: [f64; 2]| {
            let own = [q[0] * d[0] + q[2] * d[1], q[1] * d[0] + q[3] * d[1]];
            c[0] * d[0] + c[1] * d[1] + ((a[0] * own[0]).powi(2) + (a[1] * own[1]).powi(2)).sqrt()
        };
        h(e[0], u) + h(e[1], [-u[0], -u[1]])
    }

    /// Overlapping ellipses: the depth is the least translation over directions, found by
    /// brute force (the best of 3,600 angles, narrowed by golden sections around the best
    /// ten), to 1e-10 of the pair's size.
    #[test]
    fn overlapping_ellipses_take_the_least_translation_over_all_angles() {
        let mut r = ChaCha8Rng::seed_from_u64(9);
        let mut workspace = EpaWorkspace::new();
        let mut overlapping = 0;
        for _ in 0..400 {
            let axes: Vec<[f64; 2]> = (0..2)
                .map(|_| [r.gen_range(0.1..2.0), r.gen_range(0.1..2.0)])
                .collect();
            let shapes: Vec<ConvexShape> = axes
                .iter()
                .map(|a| ConvexShape::ellipsoid(a).unwrap())
                .collect();
            let q = [rotation(&mut r, 2), rotation(&mut r, 2)];
            let c = [[0.0, 0.0], [r.gen_range(-1.5..1.5), r.gen_range(-1.5..1.5)]];
            let a = PlacedShape::new(&shapes[0], &c[0], &q[0]).unwrap();
            let b = PlacedShape::new(&shapes[1], &c[1], &q[1]).unwrap();
            let p = penetration_with(&mut workspace, &a, &b).unwrap();
            if p.depth <= 0.0 {
                continue;
            }
            overlapping += 1;
            let pair = [
                (&c[0][..], &q[0][..], &axes[0][..]),
                (&c[1][..], &q[1][..], &axes[1][..]),
            ];
            let f = |t: f64| translation(pair, [t.cos(), t.sin()]);
            let step = std::f64::consts::TAU / 3600.0;
            let mut angles: Vec<f64> = (0..3600).map(|k| k as f64 * step).collect();
            angles.sort_by(|x, y| f(*x).total_cmp(&f(*y)));
            let mut best = f64::INFINITY;
            for &t in &angles[..10] {
                let (mut lo, mut hi) = (t - step, t + step);
                let g = (5f64.sqrt() - 1.0) / 2.0;
                for _ in 0..80 {
                    let (x, y) = (hi - g * (hi - lo), lo + g * (hi - lo));
                    if f(x) < f(y) {
                        hi = y;
                    } else {
                        lo = x;
                    }
                }
                best = best.min(f(0.5 * (lo + hi)));
            }
            let size = 4.0 + c[1][0].hypot(c[1][1]);
            assert!(
                (p.depth - best).abs() < 1e-10 * size,
                "{} against {best}",
                p.depth
            );
        }
        assert!(overlapping > 200, "{overlapping} overlapping pairs");
    }
}
