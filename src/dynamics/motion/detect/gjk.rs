//! The distance between two placed convex shapes in any dimension: the algorithm of
//! Gilbert, Johnson and Keerthi (GJK) on the Minkowski difference K = B − A, with an exact
//! simplex sub-algorithm.
//!
//! GJK keeps a simplex of at most N + 1 support points of K and replaces it, at each
//! iteration, by the smallest face of simplex ∪ {new support point} that holds the point of
//! the simplex nearest the origin. That sub-problem is where GJK fails in practice (the
//! Johnson sub-algorithm's Gram-determinant tests lose their signs on thin simplices), so
//! it is solved here the way of Montanari, Petrinic & Barbieri, "Improving the GJK
//! algorithm for faster and more reliable distance queries between convex objects" (ACM
//! TOG 36, 2017): the barycentric coordinates of the origin's projection onto the affine
//! hull of a face decide, by their signs alone, which faces can hold the nearest point
//! (a face opposite a vertex whose coordinate is ≤ 0), and only those are searched. The
//! coordinates come from an orthonormal basis of the face's affine hull (Gram–Schmidt run
//! twice, so the basis is orthogonal to working precision) and a triangular solve, rather
//! than from the paper's projection onto the coordinate plane of largest determinant,
//! which would need a search over N-choose-k planes in N dimensions; a face whose edges
//! are dependent to 1e-12 is replaced by its facets. Every candidate is a convex
//! combination of support points, so the smallest one found is exact.
//!
//! Margins are handled the standard way (van den Bergen, "Collision Detection in
//! Interactive 3D Environments"): GJK runs on the cores and the radii are subtracted, so
//! balls and capsules are exact.
//!
//! On curved cores (ellipsoids) GJK converges linearly, and near contact slowly: with the
//! nearest point on a curved patch of the Minkowski difference and the distance going to
//! 0, |v| shrinks by a constant factor per iteration (a decade in about 20 iterations in
//! six dimensions), and |v|² falls below the round-off of v·w, so the relative gap test
//! alone can never pass. Such queries stop on a gap floor proportional to |v| · size, go
//! on past [`MAX_GJK_ITERATIONS`] while the gap still halves, and report whether their
//! bounds met ([`Separation::certified`]). Momentum on the search direction (Montaut et
//! al., "Collision detection accelerated: an optimization perspective", RSS 2022) is not
//! used: on touching curved pairs in six dimensions it left more queries unconverged
//! than the plain iteration.

use super::boxes::within;
use crate::algebra::Vector;
use crate::dynamics::motion::shape::{
    ConvexCore, ConvexShape, Coords, ShapeError, check_placement,
};
use smallvec::SmallVec;

/// Up to N + 1 points of N numbers, inline for N ≤ 8.
pub(crate) type Points = SmallVec<[f64; 72]>;
/// Up to N + 1 barycentric coordinates, inline for N ≤ 8.
pub(crate) type Weights = SmallVec<[f64; 9]>;

/// The gap |v|² − v·w below which GJK stops, relative to |v|²: the distance is then known
/// to this relative precision (|v| is an upper bound and v·w/|v| a lower bound).
pub(crate) const RELATIVE_GAP: f64 = 1e-12;
/// Distances of the cores below this fraction of the problem's size count as contact.
pub(crate) const TOUCHING: f64 = 1e-12;
/// A face whose new edge keeps less than this fraction of its length off the span of the
/// others is degenerate and is replaced by its facets.
pub(crate) const DEGENERATE: f64 = 1e-12;
/// On curved cores the gap |v|² − v·w is also accepted below this fraction of |v| times
/// the problem's size: near contact |v|² is smaller than the round-off of v·w, and the
/// distance is then known to this fraction of the size.
pub(crate) const ABSOLUTE_GAP: f64 = 1e-13;
/// At its iteration bound GJK's answer still counts as certified if its upper bound |v|
/// of the distance and its best lower bound (or 0) are within this fraction of the
/// problem's size.
pub(crate) const BOUNDED_GAP: f64 = 1e-9;
/// GJK iterations at most. Polytopes finish in a few (exactly, when the support point
/// repeats); curved cores converge linearly and mostly stop at the gap well before.
pub(crate) const MAX_GJK_ITERATIONS: usize = 128;
/// GJK iterations at most on curved cores, beyond [`MAX_GJK_ITERATIONS`] only while the
/// gap |v|² − v·w halves every [`PROGRESS_WINDOW`] iterations: touching curved cores (the distance
/// going to 0 with the nearest point on a curved patch of the Minkowski difference) close
/// |v| by a constant factor per iteration, one decade in about 20 iterations in six
/// dimensions, and need up to about 250 to reach the contact tolerance from afar.
pub(crate) const MAX_CURVED_GJK_ITERATIONS: usize = 512;
/// GJK tracks its least gap and best lower bound of the distance only after this many
/// iterations (they matter only at the iteration bound; the bounds of a subset of
/// iterations are still bounds), so that quick queries do not pay for them.
pub(crate) const TRACKED_FROM: usize = MAX_GJK_ITERATIONS - 2 * PROGRESS_WINDOW;
/// The window of iterations over which GJK beyond [`MAX_GJK_ITERATIONS`] must halve the
/// gap.
pub(crate) const PROGRESS_WINDOW: usize = 32;

/// A convex shape placed in space: its centre and its rotation (row-major N × N, own axes
/// → space, x_space = position + Q x_own), borrowed.
#[derive(Clone, Copy, Debug)]
pub struct PlacedShape<'a> {
    shape: &'a ConvexShape,
    position: &'a [f64],
    rotation: &'a [f64],
}

impl<'a> PlacedShape<'a> {
    /// Returns `shape` placed at `position` with `rotation`. The rotation is taken as
    /// given (checking orthonormality costs O(N³) per query); an inexact rotation places a
    /// slightly distorted shape.
    ///
    /// # Errors
    /// [`ShapeError::DimensionMismatch`] unless `position` has N numbers and `rotation`
    /// N × N, [`ShapeError::NonFinite`] for a non-finite number.
    pub fn new(
        shape: &'a ConvexShape,
        position: &'a [f64],
        rotation: &'a [f64],
    ) -> Result<Self, ShapeError> {
        check_placement(shape.dim(), position, rotation)?;
        Ok(PlacedShape {
            shape,
            position,
            rotation,
        })
    }

    /// Returns the shape.
    pub fn shape(&self) -> &'a ConvexShape {
        self.shape
    }

    /// Returns the centre.
    pub fn position(&self) -> &'a [f64] {
        self.position
    }

    /// Returns the rotation (row-major, own axes → space).
    pub fn rotation(&self) -> &'a [f64] {
        self.rotation
    }

    /// Writes the support point of the core along the space direction `d` (space frame).
    #[inline]
    pub(crate) fn core_support(&self, d: &[f64], out: &mut [f64]) {
        let n = d.len();
        if let ConvexCore::Point = self.shape.core() {
            out.copy_from_slice(self.position);
            return;
        }
        let q = self.rotation;
        let mut own = Coords::from_elem(0.0, n);
        for (i, di) in d.iter().enumerate() {
            let row = &q[i * n..(i + 1) * n];
            for (o, qij) in own.iter_mut().zip(row) {
                *o += qij * di;
            }
        }
        let mut s = Coords::from_elem(0.0, n);
        self.shape.core_support(&own, &mut s);
        for (i, o) in out.iter_mut().enumerate() {
            let row = &q[i * n..(i + 1) * n];
            *o = self.position[i] + row.iter().zip(&s).map(|(a, b)| a * b).sum::<f64>();
        }
    }
}

/// The separation of two placed shapes, from [`distance`].
#[derive(Clone, Debug, PartialEq)]
pub struct Separation {
    /// The distance between the shapes, 0 when they touch or overlap.
    pub distance: f64,
    /// The unit direction from A to B along which they are closest (the contact normal:
    /// moving B along it separates them). For overlapping cores it is the direction from
    /// A's centre to B's (the first axis if they coincide) and says nothing about contact:
    /// [`penetration`](super::penetration) gives the contact normal there.
    pub normal: Vector,
    /// The point of A nearest B (space frame); for overlapping shapes a point of both cores.
    pub witness_a: Vector,
    /// The point of B nearest A (space frame); equal to `witness_a` for overlapping cores.
    pub witness_b: Vector,
    /// True if the shapes touch or overlap (distance 0).
    pub intersecting: bool,
    /// The GJK iterations taken (0 for the closed forms; for two boxes in 3 or 4
    /// dimensions, the steps of the bounded least-squares solve that replaces GJK).
    pub iterations: usize,
    /// True if `distance` is known to 1e-9 of the problem's size (the cores' radii and
    /// the centres' distance): always when GJK stops on its gap test (its upper bound |v|
    /// of the cores' distance and lower bound v·w/|v| within 1e-12 relative) or at
    /// contact, and at its iteration bound, or where a support point repeats one it holds
    /// or (unless a core is an ellipsoid) does not bring the simplex nearer (round-off on
    /// sliver simplices of nearly touching polytopes), when the two bounds (the lower one taken as at least 0) are
    /// that close. False otherwise: `distance` is then an upper bound only. Nearly
    /// touching shapes can stop so within about 1.5e-8 (√ε) of the size: there the
    /// round-off of v, about ε times the size, is as large in v·w as |v|² itself.
    /// Near contact the normal is known to about 1e-16 of the size over the distance;
    /// curved cores nearer than 1e-9 of the size whose gap along the normal stays open
    /// count as touching.
    pub certified: bool,
}

/// The simplex of GJK: up to N + 1 points w = b − a of K with the support points a, b of
/// the two shapes they came from, and the barycentric weights of the nearest point.
#[derive(Clone, Debug)]
pub(crate) struct Simplex {
    pub n: usize,
    pub count: usize,
    pub w: Points,
    pub a: Points,
    pub b: Points,
    pub lambda: Weights,
}

impl Simplex {
    pub(crate) fn new(n: usize) -> Self {
        Simplex {
            n,
            count: 0,
            w: Points::from_elem(0.0, (n + 1) * n),
            a: Points::from_elem(0.0, (n + 1) * n),
            b: Points::from_elem(0.0, (n + 1) * n),
            lambda: Weights::from_elem(0.0, n + 1),
        }
    }

    pub(crate) fn push(&mut self, w: &[f64], a: &[f64], b: &[f64]) {
        let (n, k) = (self.n, self.count);
        self.w[k * n..(k + 1) * n].copy_from_slice(w);
        self.a[k * n..(k + 1) * n].copy_from_slice(a);
        self.b[k * n..(k + 1) * n].copy_from_slice(b);
        self.count += 1;
    }

    /// Keeps the points of `mask` with their weights `lambda` (indexed by old position).
    fn keep(&mut self, mask: u128, lambda: &[f64]) {
        let n = self.n;
        let mut k = 0;
        for (i, &weight) in lambda.iter().enumerate().take(self.count) {
            if mask >> i & 1 == 1 {
                if k != i {
                    self.w.copy_within(i * n..(i + 1) * n, k * n);
                    self.a.copy_within(i * n..(i + 1) * n, k * n);
                    self.b.copy_within(i * n..(i + 1) * n, k * n);
                }
                self.lambda[k] = weight;
                k += 1;
            }
        }
        self.count = k;
    }

    /// The witnesses Σ λᵢ aᵢ and Σ λᵢ bᵢ.
    pub(crate) fn witnesses(&self, a: &mut [f64], b: &mut [f64]) {
        let n = self.n;
        a.iter_mut().for_each(|x| *x = 0.0);
        b.iter_mut().for_each(|x| *x = 0.0);
        for k in 0..self.count {
            let l = self.lambda[k];
            for j in 0..n {
                a[j] += l * self.a[k * n + j];
                b[j] += l * self.b[k * n + j];
            }
        }
    }
}

/// The nearest point of a simplex's convex hull to the origin: the face (a bit mask of
/// the points), the barycentric weights (indexed by point) and the point.
pub(crate) struct Nearest {
    pub mask: u128,
    pub lambda: Weights,
    pub v: Coords,
    pub vv: f64,
}

/// The projection of the origin onto the affine hull of the face `mask` of `points`, as
/// barycentric weights (in the order of the mask's bits) and the point; None if the face
/// is degenerate.
pub(crate) fn project_onto_face(points: &[f64], n: usize, mask: u128) -> Option<(Weights, Coords)> {
    let mut index: SmallVec<[usize; 9]> = SmallVec::new();
    for i in 0..128 {
        if mask >> i & 1 == 1 {
            index.push(i);
        }
    }
    let m1 = index.len() - 1;
    let y0 = &points[index[0] * n..(index[0] + 1) * n];
    let mut q: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, m1 * n);
    let mut r: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, m1 * m1);
    let mut e = Coords::from_elem(0.0, n);
    for j in 0..m1 {
        let yj = &points[index[j + 1] * n..(index[j + 1] + 1) * n];
        let mut length = 0.0;
        for ((x, a), b) in e.iter_mut().zip(yj).zip(y0) {
            *x = a - b;
            length += *x * *x;
        }
        let length = length.sqrt();
        // Twice: one pass of Gram–Schmidt leaves components of size ε·cond.
        for _ in 0..2 {
            for l in 0..j {
                let ql = &q[l * n..(l + 1) * n];
                let c: f64 = ql.iter().zip(&e).map(|(a, b)| a * b).sum();
                r[l * m1 + j] += c;
                e.iter_mut().zip(ql).for_each(|(x, y)| *x -= c * y);
            }
        }
        let rjj = e.iter().map(|x| x * x).sum::<f64>().sqrt();
        if rjj.is_nan() || rjj <= DEGENERATE * length {
            return None;
        }
        r[j * m1 + j] = rjj;
        for (qx, x) in q[j * n..(j + 1) * n].iter_mut().zip(&e) {
            *qx = x / rjj;
        }
    }
    // Coordinates of the projection in the basis: c = Qᵀ(0 − y₀).
    let mut c: Weights = (0..m1)
        .map(|j| {
            -q[j * n..(j + 1) * n]
                .iter()
                .zip(y0)
                .map(|(a, b)| a * b)
                .sum::<f64>()
        })
        .collect();
    let mut v = Coords::from_slice(y0);
    for j in 0..m1 {
        for (x, qx) in v.iter_mut().zip(&q[j * n..(j + 1) * n]) {
            *x += c[j] * qx;
        }
    }
    // R μ = c by back substitution, in place.
    for j in (0..m1).rev() {
        let mut s = c[j];
        for l in j + 1..m1 {
            s -= r[j * m1 + l] * c[l];
        }
        c[j] = s / r[j * m1 + j];
    }
    let mut lambda = Weights::with_capacity(m1 + 1);
    lambda.push(1.0 - c.iter().sum::<f64>());
    lambda.extend_from_slice(&c);
    Some((lambda, v))
}

fn search(points: &[f64], n: usize, mask: u128, best: &mut Nearest, visited: &mut [u64; 8]) {
    if mask < 512 {
        let (word, bit) = ((mask >> 6) as usize, mask & 63);
        if visited[word] >> bit & 1 == 1 {
            return;
        }
        visited[word] |= 1 << bit;
    }
    let bits = |m: u128| (0..128).filter(move |i| m >> i & 1 == 1);
    if mask.count_ones() == 1 {
        let i = mask.trailing_zeros() as usize;
        let y = &points[i * n..(i + 1) * n];
        let vv: f64 = y.iter().map(|x| x * x).sum();
        if vv < best.vv {
            best.mask = mask;
            best.lambda.iter_mut().for_each(|x| *x = 0.0);
            best.lambda[i] = 1.0;
            best.v = Coords::from_slice(y);
            best.vv = vv;
        }
        return;
    }
    match project_onto_face(points, n, mask) {
        None => {
            for i in bits(mask) {
                search(points, n, mask & !(1 << i), best, visited);
            }
        }
        Some((lambda, v)) => {
            if lambda.iter().all(|l| *l > 0.0) {
                let vv: f64 = v.iter().map(|x| x * x).sum();
                if vv < best.vv {
                    best.mask = mask;
                    best.lambda.iter_mut().for_each(|x| *x = 0.0);
                    for (l, i) in lambda.iter().zip(bits(mask)) {
                        best.lambda[i] = *l;
                    }
                    best.v = v;
                    best.vv = vv;
                }
                return;
            }
            // The nearest point lies on a facet whose opposite vertex has weight ≤ 0.
            for (l, i) in lambda.iter().zip(bits(mask)) {
                if *l <= 0.0 {
                    search(points, n, mask & !(1 << i), best, visited);
                }
            }
        }
    }
}

/// The point of conv(points) nearest the origin (`count` points of `n` numbers).
pub(crate) fn nearest_point(points: &[f64], count: usize, n: usize) -> Nearest {
    let mut best = Nearest {
        mask: 0,
        lambda: Weights::from_elem(0.0, count),
        v: Coords::from_elem(0.0, n),
        vv: f64::INFINITY,
    };
    let mut visited = [0u64; 8];
    search(points, n, (1u128 << count) - 1, &mut best, &mut visited);
    best
}

/// The state GJK ends in: the simplex (with the weights of the nearest point), the
/// nearest point v of K, and whether the cores intersect (|v| at the contact tolerance or
/// the origin inside a full simplex).
pub(crate) struct GjkResult {
    pub simplex: Simplex,
    pub v: Coords,
    pub vv: f64,
    pub intersecting: bool,
    pub iterations: usize,
    /// False if GJK stopped at its iteration bound with its upper and lower bounds of the
    /// distance more than [`BOUNDED_GAP`] of the size apart.
    pub certified: bool,
    /// The size the tolerances are relative to: the cores' radii and the centres' distance.
    pub scale: f64,
    /// Not intersecting, but stuck beside the origin ([`StopRule::stuck_beside_origin`]):
    /// the cores may overlap.
    pub undecided: bool,
    /// Not intersecting, stuck with a lower bound at or below 0 at any size
    /// ([`StopRule::stalled_beside_origin`]): [`either_order`] asks the swapped pair.
    pub stalled: bool,
}

/// Writes the support point of K = B − A along `d`: w = s_B(d) − s_A(−d).
#[inline]
pub(crate) fn support_difference(
    a: &PlacedShape,
    b: &PlacedShape,
    d: &[f64],
    w: &mut [f64],
    sa: &mut [f64],
    sb: &mut [f64],
) {
    let mut minus = Coords::from_slice(d);
    minus.iter_mut().for_each(|x| *x = -*x);
    a.core_support(&minus, sa);
    b.core_support(d, sb);
    for ((x, p), q) in w.iter_mut().zip(sb.iter()).zip(sa.iter()) {
        *x = p - q;
    }
}

/// GJK on the cores of `a` and `b` (same dimension): on stack arrays for N = 3 and 4
/// (`fixed.rs`, the same algorithm), else the general one; both orders where the first
/// stalls ([`either_order`]).
pub(crate) fn gjk(a: &PlacedShape, b: &PlacedShape) -> GjkResult {
    either_order(a, b, gjk_once)
}

/// [`gjk`] in this order.
fn gjk_once(a: &PlacedShape, b: &PlacedShape) -> GjkResult {
    match a.shape.dim() {
        3 => super::fixed::gjk_fixed::<3>(a, b),
        4 => super::fixed::gjk_fixed::<4>(a, b),
        _ => gjk_general_once(a, b),
    }
}

/// GJK by `once` on (a, b), and where it stops apart uncertified or stalled beside the
/// origin, on (b, a) too: the swapped answer, as (a, b)'s, where it overlaps, or where the
/// first is uncertified and it is certified or nearer. The swapped pair starts from other
/// support points, and a stall on one order (a simplex with points far apart beside a
/// feature a hundred millionth of their size, which gains nothing from its next point) is
/// seldom one on the other.
fn either_order(
    a: &PlacedShape,
    b: &PlacedShape,
    once: impl Fn(&PlacedShape, &PlacedShape) -> GjkResult,
) -> GjkResult {
    let first = once(a, b);
    if first.intersecting || first.certified && !first.stalled {
        return first;
    }
    let mut swapped = once(b, a);
    let better =
        swapped.intersecting || !first.certified && (swapped.certified || swapped.vv < first.vv);
    if !better {
        return first;
    }
    // K = A − B for the swapped pair: its points and v negated, the shapes' points swapped.
    let s = &mut swapped.simplex;
    let used = s.count * s.n;
    s.w[..used].iter_mut().for_each(|x| *x = -*x);
    for (p, q) in s.a[..used].iter_mut().zip(&mut s.b[..used]) {
        std::mem::swap(p, q);
    }
    swapped.v.iter_mut().for_each(|x| *x = -*x);
    swapped.iterations += first.iterations;
    swapped
}

/// GJK on the cores of `a` and `b` (same dimension), for any N (both orders where one
/// stalls, as [`gjk`]).
pub(crate) fn gjk_general(a: &PlacedShape, b: &PlacedShape) -> GjkResult {
    either_order(a, b, gjk_general_once)
}

/// GJK on the cores of `a` and `b` in this order.
fn gjk_general_once(a: &PlacedShape, b: &PlacedShape) -> GjkResult {
    let n = a.shape.dim();
    let mut d = Coords::from_elem(0.0, n);
    for ((x, p), q) in d.iter_mut().zip(b.position).zip(a.position) {
        *x = p - q;
    }
    let centres = d.iter().map(|x| x * x).sum::<f64>().sqrt();
    let scale = a.shape.core_radius() + b.shape.core_radius() + centres;
    let touching = TOUCHING * scale;
    if centres == 0.0 {
        d[0] = 1.0;
    }
    let mut simplex = Simplex::new(n);
    let (mut w, mut sa, mut sb) = (
        Coords::from_elem(0.0, n),
        Coords::from_elem(0.0, n),
        Coords::from_elem(0.0, n),
    );
    d.iter_mut().for_each(|x| *x = -*x);
    support_difference(a, b, &d, &mut w, &mut sa, &mut sb);
    simplex.push(&w, &sa, &sb);
    simplex.lambda[0] = 1.0;
    let mut v = w.clone();
    let mut vv: f64 = v.iter().map(|x| x * x).sum();
    let mut iterations = 0;
    let mut intersecting = false;
    let mut previous = simplex.clone();
    let mut rule = StopRule::new(curved(a, b), scale);
    let mut certified = true;
    loop {
        if vv.sqrt() <= touching {
            intersecting = true;
            break;
        }
        if !rule.may_continue(iterations) {
            certified = rule.certified(vv);
            break;
        }
        iterations += 1;
        d.iter_mut().zip(&v).for_each(|(x, y)| *x = -y);
        support_difference(a, b, &d, &mut w, &mut sa, &mut sb);
        let vw: f64 = v.iter().zip(&w).map(|(p, q)| p * q).sum();
        if rule.closed(iterations, vv, vw) {
            break;
        }
        // A support point already in the simplex: no progress is possible.
        let repeated = (0..simplex.count).any(|k| {
            simplex.w[k * n..(k + 1) * n]
                .iter()
                .zip(&w)
                .all(|(p, q)| (p - q).abs() <= 1e-15 * scale)
        });
        if repeated {
            certified = rule.certified_when_stuck(vv, vw);
            break;
        }
        previous.clone_from(&simplex);
        simplex.push(&w, &sa, &sb);
        let nearest = nearest_point(&simplex.w[..simplex.count * n], simplex.count, n);
        if nearest.vv >= vv {
            // The new point did not bring the simplex nearer; keep the old one.
            simplex.clone_from(&previous);
            certified = rule.certified_when_no_nearer(vv, vw);
            break;
        }
        let full = nearest.mask.count_ones() as usize == n + 1;
        simplex.keep(nearest.mask, &nearest.lambda);
        v = nearest.v;
        vv = nearest.vv;
        if full {
            intersecting = true;
            break;
        }
    }
    if vv.sqrt() <= touching {
        intersecting = true;
    }
    if !intersecting && rule.undecided_contact(vv) {
        intersecting = true;
    }
    GjkResult {
        simplex,
        v,
        vv,
        intersecting,
        iterations,
        certified,
        scale,
        undecided: !intersecting && rule.stuck_beside_origin(vv),
        stalled: !intersecting && rule.stalled_beside_origin(),
    }
}

/// True if either core is curved (an ellipsoid): GJK then converges linearly, slowest as
/// the distance goes to 0, and stops on [`ABSOLUTE_GAP`] too.
pub(crate) fn curved(a: &PlacedShape, b: &PlacedShape) -> bool {
    [a, b]
        .iter()
        .any(|p| matches!(p.shape.core(), ConvexCore::Ellipsoid(_)))
}

/// GJK's stopping rule and what it tracks: the gap |v|² − v·w against [`gap_tolerance`],
/// and from [`TRACKED_FROM`] on the least gap (for [`go_on`]) and the best lower bound
/// v·w/|v| of the distance (for the certificate at the iteration bound).
pub(crate) struct StopRule {
    pub(crate) curved: bool,
    scale: f64,
    least: f64,
    checkpoint: f64,
    lower: f64,
    open: bool,
    /// True once GJK stopped stuck ([`StopRule::certified_when_stuck`]).
    stalled: bool,
}

impl StopRule {
    pub(crate) fn new(curved: bool, scale: f64) -> Self {
        StopRule {
            curved,
            scale,
            least: f64::INFINITY,
            checkpoint: f64::INFINITY,
            lower: f64::NEG_INFINITY,
            open: false,
            stalled: false,
        }
    }

    /// True if GJK may take another iteration after `iterations` ([`go_on`]).
    #[inline]
    pub(crate) fn may_continue(&mut self, iterations: usize) -> bool {
        go_on(self.curved, iterations, self.least, &mut self.checkpoint)
    }

    /// At the iteration bound: whether the upper bound |v| and the best lower bound lie
    /// within [`BOUNDED_GAP`] of the size.
    #[inline]
    pub(crate) fn certified(&self, vv: f64) -> bool {
        vv.sqrt() - self.lower.max(0.0) <= BOUNDED_GAP * self.scale
    }

    /// Where GJK meets a support point it holds already, or one that does not bring the
    /// simplex nearer, with the gap still open (round-off on a sliver simplex has put v off
    /// its nearest point): whether the upper bound |v|
    /// and the best lower bound, this support point's v·w/|v| included, lie within
    /// [`BOUNDED_GAP`] of the size.
    #[inline]
    pub(crate) fn certified_when_stuck(&mut self, vv: f64, vw: f64) -> bool {
        self.stalled = true;
        self.lower = self.lower.max(vw / vv.sqrt());
        self.certified(vv)
    }

    /// Where a new support point brings the simplex no nearer: between polytopes that is
    /// round-off on a sliver simplex, certified as a stop on a repeated point is
    /// ([`StopRule::certified_when_stuck`]). On curved cores it is also GJK's convergence
    /// near contact, where |v|² is below the round-off of v·w (v carries about ε times the
    /// size, v·w that times the size): certified while the gap |v|² − v·w is within 64 ε
    /// size². A wider gap is a stall, not convergence.
    #[inline]
    pub(crate) fn certified_when_no_nearer(&mut self, vv: f64, vw: f64) -> bool {
        let round_off = 64.0 * f64::EPSILON * self.scale * self.scale;
        let converged = self.curved && vv - vw <= round_off;
        self.certified_when_stuck(vv, vw) || converged
    }

    /// Stopped on a support point held already or one that brought the simplex no nearer,
    /// with the best lower bound of the distance at or below 0: the cores may overlap
    /// however near |v| is to the truth within round-off.
    #[inline]
    pub(crate) fn stalled_beside_origin(&self) -> bool {
        self.stalled && self.lower <= 0.0
    }

    /// Takes the new support point's v·w at iteration `iterations`: true if the gap has
    /// closed (GJK stops), else records it.
    #[inline]
    pub(crate) fn closed(&mut self, iterations: usize, vv: f64, vw: f64) -> bool {
        self.open = vv - vw > gap_tolerance(self.curved, vv, self.scale);
        if !self.open {
            return true;
        }
        if iterations > TRACKED_FROM {
            self.least = self.least.min(vv - vw);
            self.lower = self.lower.max(vw / vv.sqrt());
        }
        false
    }

    /// Curved cores within [`BOUNDED_GAP`] whose gap along v stayed open: contact cannot
    /// be excluded and v's direction says nothing, so this counts as contact.
    #[inline]
    pub(crate) fn undecided_contact(&self, vv: f64) -> bool {
        self.curved && self.open_near_contact(vv)
    }

    /// The gap along v still open with |v| within [`BOUNDED_GAP`] of the size.
    #[inline]
    fn open_near_contact(&self, vv: f64) -> bool {
        self.open && vv.sqrt() <= BOUNDED_GAP * self.scale
    }

    /// Polytopes within [`BOUNDED_GAP`] whose GJK stopped stuck (on a support point held
    /// already, or one that brings the simplex no nearer) with a support point on the
    /// origin's side of v (a lower bound ≤ 0): v's round-off, a few units in the last
    /// place of the size, picks the support point among the vertices of a face, and the
    /// simplex may have stopped on a face of K a hair from the origin while K holds it.
    /// The distance |v| stands (within 1e-9 of the size of the truth either way), but a
    /// penetration query must ask EPA.
    #[inline]
    pub(crate) fn stuck_beside_origin(&self, vv: f64) -> bool {
        !self.curved && self.open_near_contact(vv) && self.lower <= 0.0
    }
}

/// The gap |v|² − v·w below which GJK stops: [`RELATIVE_GAP`] of |v|², and on curved
/// cores at least [`ABSOLUTE_GAP`] of |v| times the size, which the round-off of v·w
/// exceeds the relative gap near contact.
#[inline]
pub(crate) fn gap_tolerance(curved: bool, vv: f64, scale: f64) -> f64 {
    if curved {
        (RELATIVE_GAP * vv).max(ABSOLUTE_GAP * scale * vv.sqrt())
    } else {
        RELATIVE_GAP * vv
    }
}

/// True if GJK may take another iteration after `iterations`: below
/// [`MAX_GJK_ITERATIONS`], and on curved cores up to [`MAX_CURVED_GJK_ITERATIONS`] while
/// the least gap |v|² − v·w since [`TRACKED_FROM`] (`least`) still halves every [`PROGRESS_WINDOW`]
/// iterations (`checkpoint` holds it at the last window's start).
#[inline]
pub(crate) fn go_on(curved: bool, iterations: usize, least: f64, checkpoint: &mut f64) -> bool {
    if iterations < MAX_GJK_ITERATIONS {
        if iterations.is_multiple_of(PROGRESS_WINDOW) {
            *checkpoint = least;
        }
        return true;
    }
    if !curved || iterations >= MAX_CURVED_GJK_ITERATIONS {
        return false;
    }
    if iterations.is_multiple_of(PROGRESS_WINDOW) {
        if least > 0.5 * *checkpoint {
            return false;
        }
        *checkpoint = least;
    }
    true
}

/// Checks that two placed shapes share a dimension.
pub(crate) fn check_pair(a: &PlacedShape, b: &PlacedShape) -> Result<usize, ShapeError> {
    let n = a.shape.dim();
    if b.shape.dim() != n {
        return Err(ShapeError::DimensionMismatch {
            what: "shape B",
            expected: n,
            found: b.shape.dim(),
        });
    }
    Ok(n)
}

/// Returns the unit vector from `a`'s centre to `b`'s (the first axis if they coincide).
pub(crate) fn centre_direction(a: &PlacedShape, b: &PlacedShape) -> Vector {
    let n = a.shape.dim();
    let mut d = Vector::zero(n);
    for ((x, p), q) in d.as_mut_slice().iter_mut().zip(b.position).zip(a.position) {
        *x = p - q;
    }
    let length = d.norm();
    if length > 0.0 && length.is_finite() {
        d.as_mut_slice().iter_mut().for_each(|x| *x /= length);
    } else {
        d = Vector::basis(n, 0);
    }
    d
}

/// Returns the distance between two placed shapes, the nearest points and the direction
/// from A to B, by GJK on the cores (the margins subtracted). Two boxes in 3 or 4
/// dimensions are solved as a bounded least-squares problem instead (`boxes.rs`), its
/// answer certified by GJK's own stopping rule, GJK taking over if it cannot be; two balls
/// (point cores) by their centres, as GJK answers them, a ball against a box or a capsule
/// (a point core against a cuboid or segment core, up to N = 8) by clamping the centre to
/// the core, and two capsules (segment cores, up to N = 8) by the least of the candidates
/// of their two parameters.
///
/// Touching and overlapping shapes have distance 0 and `intersecting` set; the answer is
/// defined for every input (coincident, nested, flat), never NaN, and GJK stops after at
/// most 128 iterations, or on ellipsoid cores at most 512 while still converging (see
/// [`Separation::certified`]).
///
/// ```
/// use rotorflow::dynamics::motion::detect::{PlacedShape, distance};
/// use rotorflow::dynamics::motion::shape::ConvexShape;
/// let tesseract = ConvexShape::cuboid(&[1.0; 4])?;
/// let ball = ConvexShape::ball(4, 0.5)?;
/// let identity: Vec<f64> = (0..16).map(|k| if k % 5 == 0 { 1.0 } else { 0.0 }).collect();
/// let a = PlacedShape::new(&tesseract, &[0.0; 4], &identity)?;
/// let b = PlacedShape::new(&ball, &[3.0, 0.0, 0.0, 0.0], &identity)?;
/// let s = distance(&a, &b)?;
/// assert!((s.distance - 1.5).abs() < 1e-12);
/// assert!((s.normal.as_slice()[0] - 1.0).abs() < 1e-12 && s.normal.as_slice()[1..].iter().all(|x| x.abs() < 1e-12));
/// # Ok::<(), rotorflow::dynamics::motion::shape::ShapeError>(())
/// ```
///
/// # Errors
/// [`ShapeError::DimensionMismatch`] if the shapes differ in dimension.
#[inline]
pub fn distance(a: &PlacedShape, b: &PlacedShape) -> Result<Separation, ShapeError> {
    // Inlined: the check and the `Ok` are the caller's, and the separation (240 bytes) is
    // returned bare by one call, which the caller's frame holds, rather than inside a
    // `Result` built in the callee's.
    let n = check_pair(a, b)?;
    Ok(checked_distance(a, b, n))
}

/// [`distance`] of two shapes of dimension `n`.
fn checked_distance(a: &PlacedShape, b: &PlacedShape, n: usize) -> Separation {
    // Each path returns its separation as it builds it: a `Separation` holds three inline
    // vectors (240 bytes), and passing it through an `Option` first copied it once more.
    // Closed forms: balls in any N; a ball against a box or a capsule, and two capsules,
    // up to N = 8 (on the stack).
    match (a.shape.core(), b.shape.core()) {
        (ConvexCore::Point, ConvexCore::Point) => return point_separation(a, b),
        (ConvexCore::Cuboid(_) | ConvexCore::Segment(_), ConvexCore::Point) if n <= 8 => {
            return point_box_separation(a, b, false);
        }
        (ConvexCore::Point, ConvexCore::Cuboid(_) | ConvexCore::Segment(_)) if n <= 8 => {
            return point_box_separation(b, a, true);
        }
        (ConvexCore::Segment(_), ConvexCore::Segment(_)) if n <= 8 => {
            return segment_separation(a, b);
        }
        _ => {}
    }
    match n {
        3 => {
            if let Some(gap) = super::boxes::box_distance::<3>(a, b) {
                return core_separation(a, b, gap.core_gap());
            }
        }
        4 => {
            if let Some(gap) = super::boxes::box_distance::<4>(a, b) {
                return core_separation(a, b, gap.core_gap());
            }
        }
        _ => {}
    }
    separation(a, b, gjk(a, b))
}

/// The separation of two shapes whose cores are points (balls, spheres): the centres are
/// the cores' nearest points, which GJK finds with its first support point and certifies
/// in one iteration. Contact as GJK decides it: |v| within [`TOUCHING`] of the size, which
/// for two points is the centres' distance itself (so only coincident centres touch).
fn point_separation(a: &PlacedShape, b: &PlacedShape) -> Separation {
    // v on the stack up to N = 8, written and read in the same widths (see `vector_of`).
    let (mut fixed, mut any) = ([0.0; 8], Coords::new());
    let v: &[f64] = if let Some(v) = fixed.get_mut(..a.position.len()) {
        for ((x, p), q) in v.iter_mut().zip(a.position).zip(b.position) {
            *x = q - p;
        }
        v
    } else {
        any.extend(a.position.iter().zip(b.position).map(|(p, q)| q - p));
        &any
    };
    let vv = v.iter().fold(0.0, |s, x| s + x * x);
    let centres = vv.sqrt();
    core_separation(
        a,
        b,
        CoreGap {
            witness_a: a.position,
            witness_b: b.position,
            v,
            vv,
            intersecting: centres <= TOUCHING * centres,
            iterations: 0,
            certified: true,
        },
    )
}

/// The separation of a shape whose core is a box or a segment (`boxed`: a box, rounded or
/// not, or a capsule) and one whose core is a point (`point`: a ball or sphere), A and B in
/// the order `point_is_a` says: the core's point nearest the centre is the centre clamped
/// to it in its own axes, the answer GJK converges to, here exact. A centre inside or on the box touches,
/// and so does one within GJK's contact distance ([`TOUCHING`] of the size). N ≤ 8.
fn point_box_separation(boxed: &PlacedShape, point: &PlacedShape, point_is_a: bool) -> Separation {
    let n = boxed.shape.dim();
    // A segment (a capsule's core) is the box of half-lengths (h, 0, …, 0).
    let mut segment = [0.0; 8];
    let h: &[f64] = match boxed.shape.core() {
        ConvexCore::Cuboid(h) => h,
        ConvexCore::Segment(length) => {
            segment[0] = *length;
            &segment[..n]
        }
        _ => unreachable!("the caller matched a cuboid or segment core"),
    };
    match n {
        3 => point_box_separation_n::<3>(boxed, h, point, point_is_a),
        4 => point_box_separation_n::<4>(boxed, h, point, point_is_a),
        _ => point_box_separation_n::<0>(boxed, h, point, point_is_a),
    }
}

/// [`point_box_separation`] in N dimensions (N = 0: any up to 8), on the stack, the box's
/// core of half-lengths `h`.
#[inline(always)]
fn point_box_separation_n<const N: usize>(
    boxed: &PlacedShape,
    h: &[f64],
    point: &PlacedShape,
    point_is_a: bool,
) -> Separation {
    let n = if N == 0 { h.len() } else { N };
    let (x, c, q) = (
        &point.position[..n],
        &boxed.position[..n],
        &boxed.rotation[..n * n],
    );
    let (mut d, mut own) = ([0.0; 8], [0.0; 8]);
    let mut centres = 0.0;
    for i in 0..n {
        d[i] = x[i] - c[i];
        centres += d[i] * d[i];
    }
    for i in 0..n {
        for k in 0..n {
            own[k] += q[i * n + k] * d[i];
        }
    }
    // The part of the centre's offset beyond the box, in the box's axes (exactly 0 along
    // an axis where it lies within), turned to space: v from the box to the point.
    let mut beyond = [0.0; 8];
    for k in 0..n {
        beyond[k] = own[k] - within(own[k], h[k]);
    }
    let (mut nearest, mut v) = ([0.0; 8], [0.0; 8]);
    let mut vv = 0.0;
    for i in 0..n {
        let (mut p, mut s) = (c[i], 0.0);
        for k in 0..n {
            p += q[i * n + k] * (own[k] - beyond[k]);
            s += q[i * n + k] * beyond[k];
        }
        (nearest[i], v[i]) = (p, if point_is_a { -s } else { s });
        vv += s * s;
    }
    let scale = boxed.shape.core_radius() + centres.sqrt();
    let intersecting = vv.sqrt() <= TOUCHING * scale;
    let (a, b, witness_a, witness_b): (_, _, &[f64], &[f64]) = if point_is_a {
        (point, boxed, x, &nearest[..n])
    } else {
        (boxed, point, &nearest[..n], x)
    };
    core_separation(
        a,
        b,
        CoreGap {
            witness_a,
            witness_b,
            v: &v[..n],
            vv,
            intersecting,
            iterations: 0,
            certified: true,
        },
    )
}

/// The separation of two shapes whose cores are segments (capsules): the least |e| of
/// e = Q(t) − P(s) over the points P(s) = c_a + s u_a, |s| ≤ h_a, and Q(t) = c_b + t u_b,
/// |t| ≤ h_b. |e|² is a convex quadratic in (s, t): its least value on the rectangle lies
/// at the stationary point when that is inside (segments not parallel), or on an edge,
/// where one parameter is at a bound and the other the clamp of its best value. Every
/// candidate is computed and the least kept, so that parallel, collinear and crossing
/// segments need no case of their own. N ≤ 8.
fn segment_separation(a: &PlacedShape, b: &PlacedShape) -> Separation {
    match a.shape.dim() {
        3 => segment_separation_n::<3>(a, b),
        4 => segment_separation_n::<4>(a, b),
        _ => segment_separation_n::<0>(a, b),
    }
}

/// [`segment_separation`] in N dimensions (N = 0: any up to 8), on the stack.
#[inline(always)]
fn segment_separation_n<const N: usize>(a: &PlacedShape, b: &PlacedShape) -> Separation {
    let n = if N == 0 { a.shape.dim() } else { N };
    let half = |p: &PlacedShape| match p.shape.core() {
        ConvexCore::Segment(h) => *h,
        _ => unreachable!("the caller matched segment cores"),
    };
    let (ha, hb) = (half(a), half(b));
    let (ca, cb) = (&a.position[..n], &b.position[..n]);
    // The segments' directions: each shape's first own axis in space.
    let (mut ua, mut ub, mut d) = ([0.0; 8], [0.0; 8], [0.0; 8]);
    let (mut c, mut da, mut db, mut dd) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..n {
        (ua[i], ub[i], d[i]) = (a.rotation[i * n], b.rotation[i * n], cb[i] - ca[i]);
        c += ua[i] * ub[i];
        da += d[i] * ua[i];
        db += d[i] * ub[i];
        dd += d[i] * d[i];
    }
    // (s, t) on the edges: t best for s = ±h_a, s best for t = ±h_b.
    let mut candidates = [
        (ha, within(ha * c - db, hb)),
        (-ha, within(-ha * c - db, hb)),
        (within(da + hb * c, ha), hb),
        (within(da - hb * c, ha), -hb),
        (f64::NAN, f64::NAN),
    ];
    // The stationary point, s = (d·u_a − c d·u_b) / (1 − c²) and t = c s − d·u_b, where the
    // segments are not parallel (and it counts only inside the rectangle).
    let sine = 1.0 - c * c;
    if sine > 1e-12 {
        let s = (da - c * db) / sine;
        let t = c * s - db;
        if s.abs() <= ha && t.abs() <= hb {
            candidates[4] = (s, t);
        }
    }
    let gap = |(s, t): (f64, f64), e: &mut [f64; 8]| -> f64 {
        let mut ee = 0.0;
        for i in 0..n {
            e[i] = d[i] + t * ub[i] - s * ua[i];
            ee += e[i] * e[i];
        }
        ee
    };
    let (mut best, mut v, mut vv) = (candidates[0], [0.0; 8], f64::INFINITY);
    let mut e = [0.0; 8];
    for &candidate in &candidates {
        if candidate.0.is_nan() {
            continue;
        }
        let ee = gap(candidate, &mut e);
        if ee < vv {
            (best, v, vv) = (candidate, e, ee);
        }
    }
    let (mut witness_a, mut witness_b) = ([0.0; 8], [0.0; 8]);
    for i in 0..n {
        witness_a[i] = ca[i] + best.0 * ua[i];
        witness_b[i] = cb[i] + best.1 * ub[i];
    }
    let scale = ha + hb + dd.sqrt();
    core_separation(
        a,
        b,
        CoreGap {
            witness_a: &witness_a[..n],
            witness_b: &witness_b[..n],
            v: &v[..n],
            vv,
            intersecting: vv.sqrt() <= TOUCHING * scale,
            iterations: 0,
            certified: true,
        },
    )
}

/// [`distance`] by the dimension-generic GJK alone. For N = 3 and 4, [`distance`] runs
/// the same algorithm on stack arrays of N numbers; this entry point keeps the general
/// implementation reachable, so that the two can be compared in tests and benchmarks.
/// The answers agree to round-off.
///
/// # Errors
/// [`ShapeError::DimensionMismatch`] if the shapes differ in dimension.
pub fn distance_general(a: &PlacedShape, b: &PlacedShape) -> Result<Separation, ShapeError> {
    check_pair(a, b)?;
    Ok(separation(a, b, gjk_general(a, b)))
}

/// The nearest points of two cores: the witnesses (space frame), v = witness_b − witness_a
/// as the query found it, |v|², and whether the cores touch or overlap. Borrowed, so that
/// the box path hands over its stack arrays and the separation is built once.
pub(crate) struct CoreGap<'a> {
    pub witness_a: &'a [f64],
    pub witness_b: &'a [f64],
    pub v: &'a [f64],
    pub vv: f64,
    pub intersecting: bool,
    pub iterations: usize,
    /// Whether the answer met its stopping rule (see [`Separation::certified`]).
    pub certified: bool,
}

/// The separation from GJK's final state on the cores, the margins subtracted.
fn separation(a: &PlacedShape, b: &PlacedShape, result: GjkResult) -> Separation {
    let n = a.shape.dim();
    let mut witness_a = Coords::from_elem(0.0, n);
    let mut witness_b = Coords::from_elem(0.0, n);
    result.simplex.witnesses(&mut witness_a, &mut witness_b);
    core_separation(
        a,
        b,
        CoreGap {
            witness_a: &witness_a,
            witness_b: &witness_b,
            v: &result.v,
            vv: result.vv,
            intersecting: result.intersecting,
            iterations: result.iterations,
            certified: result.certified,
        },
    )
}

/// The separation of the shapes from the nearest points of their cores, the margins
/// subtracted. Inlined, so that for the box path's fixed N the loops unroll.
#[inline(always)]
pub(crate) fn core_separation(a: &PlacedShape, b: &PlacedShape, gap: CoreGap) -> Separation {
    let (ra, rb) = (a.shape.margin(), b.shape.margin());
    let n = gap.v.len();
    if gap.intersecting {
        let witness_a = vector_of(n, |i| gap.witness_a[i]);
        return Separation {
            distance: 0.0,
            normal: centre_direction(a, b),
            witness_b: witness_a.clone(),
            witness_a,
            intersecting: true,
            iterations: gap.iterations,
            certified: gap.certified,
        };
    }
    let core = gap.vv.sqrt();
    // One division, then products (a division per coordinate waits on the divider).
    let inverse = 1.0 / core;
    let normal = |i: usize| gap.v[i] * inverse;
    let distance = (core - ra - rb).max(0.0);
    Separation {
        distance,
        normal: vector_of(n, normal),
        witness_a: vector_of(n, |i| gap.witness_a[i] + ra * normal(i)),
        witness_b: vector_of(n, |i| gap.witness_b[i] - rb * normal(i)),
        intersecting: distance == 0.0,
        iterations: gap.iterations,
        certified: gap.certified,
    }
}

/// The vector (f(0), …, f(n − 1)), for n ≤ 8 filled on the stack and moved in whole:
/// written in place coordinate by coordinate, its storage would be read back in wider
/// words than it was written, which stalls the processor's store forwarding.
#[inline(always)]
fn vector_of(n: usize, f: impl Fn(usize) -> f64) -> Vector {
    let mut buffer = [0.0; 8];
    if n > buffer.len() {
        return Vector::from_storage((0..n).map(f).collect());
    }
    for (i, x) in buffer.iter_mut().enumerate().take(n) {
        *x = f(i);
    }
    Vector::from_storage(Coords::from_buf_and_len(buffer, n))
}

/// Returns true if the placed shapes touch or overlap.
///
/// # Errors
/// [`ShapeError::DimensionMismatch`] if the shapes differ in dimension.
pub fn intersects(a: &PlacedShape, b: &PlacedShape) -> Result<bool, ShapeError> {
    Ok(distance(a, b)?.intersecting)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::motion::detect::{EpaWorkspace, distance, penetration_with};

    /// An ellipsoid of 4e-4 centred on a vertex of a 4D simplex 1.3e4 across (found by
    /// fuzzing): with the simplex first, GJK's simplex came to hold a vertex 1e4 away beside
    /// the ellipsoid, and from there each support point brought it nearer by less than the
    /// round-off of its projection. It stopped 2.1e-4 apart (1.2e-8 of the size, within
    /// the round-off of v·w there) with a negative lower bound. Such a stall now asks the
    /// swapped order, which meets the overlap in four iterations: both orders overlap, with
    /// one depth.
    #[test]
    fn fuzz_gjk_stall_beside_a_tiny_ellipsoid_asks_the_other_order() {
        let ellipsoid = ConvexShape::ellipsoid(&[
            4.597008228302002e-5,
            0.00038890540599823,
            0.0003883242607116699,
            2.682209014892578e-6,
        ])
        .unwrap();
        let mut points = vec![
            vec![13049.5, 12947.0, -90.0, -0.5],
            vec![1407.5, 0.0, 8192.0, 126.5],
            vec![-0.5, -0.5, 20.0, 0.0],
            vec![0.0, 0.0, 3252.5, 9872.5],
        ];
        points.extend(std::iter::repeat_n(vec![0.0; 4], 4));
        let hull = ConvexShape::hull(&points).unwrap();
        let identity: Vec<f64> = (0..16)
            .map(|k| if k % 5 == 0 { 1.0 } else { 0.0 })
            .collect();
        let a = PlacedShape::new(&ellipsoid, &[0.0; 4], &identity).unwrap();
        let b = PlacedShape::new(&hull, &[0.0; 4], &identity).unwrap();
        // The stall itself, in the order that meets it.
        let stalled = gjk_once(&b, &a);
        assert!(
            !stalled.intersecting && stalled.stalled,
            "{}",
            stalled.vv.sqrt()
        );
        for (p, q) in [(&a, &b), (&b, &a)] {
            let d = distance(p, q).unwrap();
            assert!(d.intersecting && d.certified, "{d:?}");
            assert!(gjk_general(p, q).intersecting);
        }
        let mut workspace = EpaWorkspace::new();
        let mut depth = |p, q| penetration_with(&mut workspace, p, q).unwrap().depth;
        let (ab, ba) = (depth(&a, &b), depth(&b, &a));
        assert!(ab > 0.0 && (ab - ba).abs() <= 1e-12 * ab, "{ab} {ba}");
    }

    /// Two balls are answered by their centres as GJK answers them: apart, touching
    /// (the margins' sum exactly), overlapping and concentric, in N = 2 … 9, every field of
    /// the separation equal to GJK's to round-off, and with no GJK iteration.
    #[test]
    fn balls_are_answered_by_their_centres_as_gjk_answers_them() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let mut counts = [0usize; 4];
        for n in 2..=9 {
            let identity: Vec<f64> = (0..n * n)
                .map(|k| if k % (n + 1) == 0 { 1.0 } else { 0.0 })
                .collect();
            for case in 0..200 {
                let (ra, rb) = (r.gen_range(0.1..2.0), r.gen_range(0.1..2.0));
                let (sa, sb) = (
                    ConvexShape::ball(n, ra).unwrap(),
                    ConvexShape::ball(n, rb).unwrap(),
                );
                let pa: Vec<f64> = (0..n).map(|_| r.gen_range(-3.0..3.0)).collect();
                let mut u: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
                let norm = u.iter().map(|x| x * x).sum::<f64>().sqrt();
                u.iter_mut().for_each(|x| *x /= norm);
                // 0 apart, 1 touching, 2 overlapping, 3 concentric.
                let kind = case % 4;
                let gap = match kind {
                    0 => r.gen_range(0.01..5.0),
                    1 => 0.0,
                    2 => -r.gen_range(0.0..ra.min(rb)),
                    _ => -(ra + rb),
                };
                let pb: Vec<f64> = pa
                    .iter()
                    .zip(&u)
                    .map(|(p, x)| p + (ra + rb + gap) * x)
                    .collect();
                let a = PlacedShape::new(&sa, &pa, &identity).unwrap();
                let b = PlacedShape::new(&sb, &pb, &identity).unwrap();
                let (fast, general) =
                    (distance(&a, &b).unwrap(), distance_general(&a, &b).unwrap());
                let size = ra + rb + 3.0;
                let near = |x: &Vector, y: &Vector| {
                    x.as_slice()
                        .iter()
                        .zip(y.as_slice())
                        .all(|(p, q)| (p - q).abs() <= 1e-14 * size)
                };
                assert_eq!(
                    fast.intersecting, general.intersecting,
                    "N = {n}, case {case}"
                );
                assert_eq!(fast.certified, general.certified, "N = {n}, case {case}");
                assert!(
                    (fast.distance - general.distance).abs() <= 1e-14 * size,
                    "N = {n}, case {case}"
                );
                assert!(near(&fast.normal, &general.normal), "N = {n}, case {case}");
                assert!(
                    near(&fast.witness_a, &general.witness_a),
                    "N = {n}, case {case}"
                );
                assert!(
                    near(&fast.witness_b, &general.witness_b),
                    "N = {n}, case {case}"
                );
                assert_eq!(fast.iterations, 0);
                if kind == 0 {
                    assert!(fast.distance > 0.0 && !fast.intersecting);
                } else {
                    assert!(fast.distance <= 1e-14 * size);
                }
                counts[kind] += 1;
            }
        }
        assert_eq!(counts, [400; 4]);
    }

    /// `distance` of a pair that a closed form answers, and the dimension-generic GJK's
    /// answer: the closed form takes no GJK iteration and is certified, and the two agree
    /// on contact and on the distance to 1e-9 of `size`.
    fn closed_form_as_gjk(
        a: &PlacedShape,
        b: &PlacedShape,
        size: f64,
        what: &str,
    ) -> (Separation, Separation) {
        let (fast, general) = (distance(a, b).unwrap(), distance_general(a, b).unwrap());
        assert!(fast.iterations == 0 && fast.certified, "{what}");
        assert!(
            (fast.distance - general.distance).abs() <= 1e-9 * size,
            "{what}: {} {}",
            fast.distance,
            general.distance
        );
        assert_eq!(fast.intersecting, general.intersecting, "{what}");
        (fast, general)
    }

    /// A ball against a box (rounded or not) or a capsule is answered by clamping the
    /// ball's centre to the core, in either order: in N = 2 … 8, with the centre apart
    /// from the core beyond a face, an edge or a corner (a capsule's side or end), inside
    /// it, and on its surface, the distance and contact agree with the dimension-generic
    /// GJK to 1e-9 of the size, the witness on the box lies on its (rounded) surface, the
    /// other is the centre less the radius along the normal, and no GJK iteration is taken.
    #[test]
    fn a_ball_against_a_box_or_capsule_is_answered_by_clamping_its_centre() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        let (mut counts, mut capsules) = ([0usize; 3], 0);
        for n in 2..=8 {
            for case in 0..300 {
                let mut h: Vec<f64> = (0..n).map(|_| r.gen_range(0.1..2.0)).collect();
                // A box, a fifth of them rounded, and every fourth a capsule: its segment
                // is the box (h₁, 0, …, 0).
                let capsule = case % 4 == 3;
                let (boxed, margin) = if capsule {
                    h[1..].fill(0.0);
                    (ConvexShape::capsule(n, h[0], 0.3).unwrap(), 0.3)
                } else if case % 5 == 0 {
                    (ConvexShape::cuboid(&h).unwrap().rounded(0.2).unwrap(), 0.2)
                } else {
                    (ConvexShape::cuboid(&h).unwrap(), 0.0)
                };
                capsules += usize::from(capsule);
                let radius = r.gen_range(0.05..1.5);
                let ball = ConvexShape::ball(n, radius).unwrap();
                let q = super::super::test_support::random_rotation(&mut r, n);
                let c: Vec<f64> = (0..n).map(|_| r.gen_range(-2.0..2.0)).collect();
                let identity: Vec<f64> = (0..n * n)
                    .map(|k| if k % (n + 1) == 0 { 1.0 } else { 0.0 })
                    .collect();
                // The centre in the box's axes: 0 beyond it, 1 inside, 2 on its surface.
                let kind = case % 3;
                let own: Vec<f64> = h
                    .iter()
                    .enumerate()
                    .map(|(k, &hk)| match kind {
                        0 if k < 1 + case % n => {
                            [-1.0, 1.0][case % 2] * (hk + r.gen_range(0.01..3.0))
                        }
                        _ if k == 0 && kind == 2 => hk,
                        _ if hk == 0.0 => 0.0,
                        _ => r.gen_range(-hk..hk),
                    })
                    .collect();
                let x: Vec<f64> = (0..n)
                    .map(|i| c[i] + (0..n).map(|k| q[i * n + k] * own[k]).sum::<f64>())
                    .collect();
                let pb = PlacedShape::new(&boxed, &c, &q).unwrap();
                let pp = PlacedShape::new(&ball, &x, &identity).unwrap();
                let size = h.iter().map(|v| v * v).sum::<f64>().sqrt() + radius + margin + 3.0;
                for point_first in [false, true] {
                    let (a, b) = if point_first { (pp, pb) } else { (pb, pp) };
                    let what = format!("N = {n}, case {case}, ball first {point_first}");
                    let fast = closed_form_as_gjk(&a, &b, size, &what).0;
                    if kind != 0 {
                        assert!(fast.intersecting, "{what}");
                        continue;
                    }
                    // Beyond the box the cores are apart; the shapes may still overlap
                    // (distance 0), with the witnesses where the margins put them.
                    let apart = !fast.intersecting;
                    let (on_box, on_ball, sign) = if point_first {
                        (&fast.witness_b, &fast.witness_a, -1.0)
                    } else {
                        (&fast.witness_a, &fast.witness_b, 1.0)
                    };
                    // The box's witness in the box's axes: on the rounded surface.
                    let rel: Vec<f64> = (0..n)
                        .map(|k| {
                            (0..n)
                                .map(|i| q[i * n + k] * (on_box.as_slice()[i] - c[i]))
                                .sum()
                        })
                        .collect();
                    let beyond: f64 = rel
                        .iter()
                        .zip(&h)
                        .map(|(o, hk)| (o.abs() - hk).max(0.0).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    assert!((beyond - margin).abs() <= 1e-12 * size, "{what}: {beyond}");
                    for (i, xi) in x.iter().enumerate() {
                        let normal = sign * fast.normal.as_slice()[i];
                        assert!(
                            (on_ball.as_slice()[i] - (xi - radius * normal)).abs() <= 1e-12 * size,
                            "{what}"
                        );
                        let gap = on_ball.as_slice()[i] - on_box.as_slice()[i];
                        if apart {
                            assert!(
                                (gap - fast.distance * normal).abs() <= 1e-12 * size,
                                "{what}"
                            );
                        }
                    }
                }
                counts[kind] += 1;
            }
        }
        assert_eq!((counts, capsules), ([700; 3], 525));
    }

    /// Two capsules are answered by the least of the candidates of their segments'
    /// parameters: in N = 2 … 8, placed at random, parallel (either way), crossing
    /// (through a common point) and collinear (overlapping or end to end apart), the
    /// distance and contact agree with the dimension-generic GJK to 1e-9 of the size, each
    /// witness lies on its capsule's core pushed out by its radius along the normal (a
    /// common point of the cores where they meet), and no GJK iteration is taken.
    #[test]
    fn two_capsules_are_answered_by_the_least_of_their_candidates() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(13);
        let mut counts = [0usize; 4];
        let mut met = 0;
        for n in 2..=8 {
            for case in 0..200 {
                let kind = case % 4;
                let (ha, hb) = (r.gen_range(0.1..2.0), r.gen_range(0.1..2.0));
                let (ra, rb) = (r.gen_range(0.05..0.8), r.gen_range(0.05..0.8));
                let (sa, sb) = (
                    ConvexShape::capsule(n, ha, ra).unwrap(),
                    ConvexShape::capsule(n, hb, rb).unwrap(),
                );
                let qa = super::super::test_support::random_rotation(&mut r, n);
                let mut qb = match kind {
                    0 | 2 => super::super::test_support::random_rotation(&mut r, n),
                    _ => qa.clone(),
                };
                if kind == 1 && case % 8 == 1 {
                    // Antiparallel: the first axis turned round.
                    (0..n).for_each(|i| qb[i * n] = -qb[i * n]);
                }
                let axis = |q: &[f64]| (0..n).map(|i| q[i * n]).collect::<Vec<f64>>();
                let (ua, ub) = (axis(&qa), axis(&qb));
                let ca: Vec<f64> = (0..n).map(|_| r.gen_range(-2.0..2.0)).collect();
                let cb: Vec<f64> = match kind {
                    0 | 1 => (0..n).map(|_| r.gen_range(-3.0..3.0)).collect(),
                    2 => {
                        // Through the point ca + s₀ u_a, which is cb + t₀ u_b.
                        let (s0, t0) = (r.gen_range(-ha..ha), r.gen_range(-hb..hb));
                        (0..n).map(|i| ca[i] + s0 * ua[i] - t0 * ub[i]).collect()
                    }
                    _ => {
                        let along = r.gen_range(-1.5..1.5) * (ha + hb);
                        (0..n).map(|i| ca[i] + along * ua[i]).collect()
                    }
                };
                let a = PlacedShape::new(&sa, &ca, &qa).unwrap();
                let b = PlacedShape::new(&sb, &cb, &qb).unwrap();
                let size = ha + hb + ra + rb + 6.0;
                let what = format!("N = {n}, case {case}");
                let (fast, general) = closed_form_as_gjk(&a, &b, size, &what);
                // The distance of a point to a segment's core.
                let off = |p: &[f64], c: &[f64], u: &[f64], h: f64| -> f64 {
                    let along: f64 = (0..n).map(|i| (p[i] - c[i]) * u[i]).sum();
                    let t = along.clamp(-h, h);
                    (0..n)
                        .map(|i| (p[i] - c[i] - t * u[i]).powi(2))
                        .sum::<f64>()
                        .sqrt()
                };
                let m = fast.normal.as_slice();
                let (wa, wb) = (fast.witness_a.as_slice(), fast.witness_b.as_slice());
                let core_a: Vec<f64> = (0..n).map(|i| wa[i] - ra * m[i]).collect();
                let core_b: Vec<f64> = (0..n).map(|i| wb[i] + rb * m[i]).collect();
                let cores_meet = general.distance == 0.0
                    && off(wa, &ca, &ua, ha) <= 1e-12 * size
                    && off(wa, &cb, &ub, hb) <= 1e-12 * size;
                met += usize::from(cores_meet);
                if !cores_meet {
                    assert!(off(&core_a, &ca, &ua, ha) <= 1e-12 * size, "{what}");
                    assert!(off(&core_b, &cb, &ub, hb) <= 1e-12 * size, "{what}");
                }
                if kind == 2 {
                    assert!(fast.intersecting && cores_meet, "{what}");
                }
                counts[kind] += 1;
            }
        }
        assert_eq!(counts, [350; 4]);
        assert!(met >= 350, "{met}");
    }

    /// Past [`MAX_GJK_ITERATIONS`] only curved cores go on, and only while the least gap
    /// halves in each window, up to [`MAX_CURVED_GJK_ITERATIONS`].
    #[test]
    fn gjk_goes_on_past_its_bound_only_while_the_gap_halves() {
        let run = |curved: bool, ratio: f64| {
            let (mut checkpoint, mut least) = (f64::INFINITY, 1.0);
            let mut iterations = 0;
            while go_on(curved, iterations, least, &mut checkpoint) {
                iterations += 1;
                least *= ratio;
            }
            iterations
        };
        assert_eq!(run(false, 0.9), MAX_GJK_ITERATIONS);
        assert_eq!(run(true, 0.9), MAX_CURVED_GJK_ITERATIONS);
        // 0.99³² ≈ 0.72: not halving, so it stops at the first window past the bound.
        assert_eq!(run(true, 0.99), MAX_GJK_ITERATIONS);
        // |v| = 1e-6 of a size 10: the relative gap 1e-24, the absolute floor 1e-18.
        assert!((gap_tolerance(false, 1e-12, 10.0) - 1e-24).abs() <= 1e-36);
        assert!((gap_tolerance(true, 1e-12, 10.0) - 1e-18).abs() <= 1e-30);
    }
}
