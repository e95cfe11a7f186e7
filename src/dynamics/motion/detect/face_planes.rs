//! The exact depth of an ellipsoid and an overlapping polytope (a hull, a cuboid, a
//! segment), where the search face by face of `smooth.rs` cannot show that it found the
//! least.
//!
//! The depth is the least over unit directions w of f(w) = h_E(w) + h_P(−w), the support
//! function of K = E ⊕ (−P), whose interior holds the origin: the distance from the origin
//! to K's boundary, reached at p = f(w*) w*. The face of K along w* is s_E(w*) − F, with F
//! the face of P along −w*, so w* is orthogonal to F and, with v₀ a vertex of F and Π the
//! projection onto the complement of F's directions, p = Π(s_E(w*) − v₀): a point of the
//! ellipsoid Π(E − v₀) (in N − k dimensions for a k-face) at which its outward normal w*
//! points along it from the origin, the foot of a normal from the origin. In the projected
//! ellipsoid's principal axes (squared semi-axes λᵢ, centre z) a foot is zᵢ + λᵢ nᵢ with
//! its normal n, nᵢ = zᵢ / (s − λᵢ), for a root s of Σ λᵢ zᵢ² / (s − λᵢ)² = 1
//! ([`secular_roots`]: at most 2(N − k) of them), or s = λⱼ where zⱼ = 0. So w* is among the
//! normals of these feet over the planes of all faces, and f there, evaluated directly, is
//! a translation that separates the shapes at each: their least is the depth, exact to
//! round-off, and never below it.
//!
//! The planes are enumerated: a cuboid's 3^N − 1 faces, a segment's ends and itself, and
//! for a hull the planes through every affinely independent set of at most N of its points
//! (a superset of its faces' planes; the extra ones only add candidates). Polytopes with
//! more than [`MAX_PLANES`] of them are not enumerated.

use crate::dynamics::motion::detect::gjk::PlacedShape;
use crate::dynamics::motion::shape::{ConvexCore, Coords};
use crate::numeric::dense::dot;
use crate::numeric::secular::secular_roots;
use crate::numeric::{orthogonalize_twice, symmetric_eigen_rows};
use smallvec::SmallVec;

/// The face planes at most that a query enumerates: every cuboid up to 8D (3⁸ − 1 = 6,560),
/// a hull of up to 14 points in 6D (6,475 sets of at most 6 of them) or 21 in 4D (7,546).
pub(super) const MAX_PLANES: usize = 8192;

/// A placed ellipsoid core: its centre (relative to the query's origin), rotation (own axes
/// → space, N × N row-major) and squared semi-axes.
pub(super) struct Ellipsoid<'a> {
    pub centre: &'a [f64],
    pub rotation: &'a [f64],
    pub squared_axes: &'a [f64],
}

/// The least of `f` over the normals of the feet of normals from the origin to the
/// ellipsoids Π(E − v₀) of every face plane of `polytope` (whose vertices, relative to the
/// query's origin, are `vertices`, N numbers each, and centre `centre`): the exact depth
/// and its direction w (from the ellipsoid's side, `f(w)` = h_E(w) + h_P(−w)). None if the
/// polytope has more than [`MAX_PLANES`] face planes or `f` is nowhere finite. `tolerance`
/// is the length below which a hull's points count as affinely dependent.
pub(super) fn least_on_face_planes(
    ellipsoid: &Ellipsoid,
    polytope: &PlacedShape,
    (vertices, centre): (&[f64], &[f64]),
    tolerance: f64,
    f: &mut dyn FnMut(&[f64]) -> f64,
) -> Option<(f64, Coords)> {
    let n = ellipsoid.centre.len();
    let mut search = Search::new(ellipsoid, f);
    if !enumerable(polytope, vertices.len() / n) {
        return None;
    }
    match polytope.shape().core() {
        ConvexCore::Cuboid(half) => {
            let planes = 3usize.pow(n as u32);
            let q = polytope.rotation();
            // The corner at the code's fixed axes: digit 0 free, 1 at +h, 2 at −h.
            let mut point = Coords::from_elem(0.0, n);
            let mut complement: SmallVec<[f64; 64]> = SmallVec::new();
            for code in 1..planes {
                point.copy_from_slice(centre);
                complement.clear();
                let mut c = code;
                for (axis, h) in half.iter().enumerate() {
                    let digit = c % 3;
                    c /= 3;
                    if digit == 0 {
                        continue;
                    }
                    let side = if digit == 1 { *h } else { -h };
                    for (i, p) in point.iter_mut().enumerate() {
                        *p += side * q[i * n + axis];
                    }
                    complement.extend((0..n).map(|i| q[i * n + axis]));
                }
                search.plane(&point, &complement);
            }
        }
        ConvexCore::Segment(_) => {
            // Each end alone (the whole space its complement), then the segment.
            let mut identity: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, n * n);
            for i in 0..n {
                identity[i * n + i] = 1.0;
            }
            for end in vertices.chunks_exact(n) {
                search.plane(end, &identity);
            }
            let q = polytope.rotation();
            let complement: SmallVec<[f64; 64]> = (1..n)
                .flat_map(|axis| (0..n).map(move |i| q[i * n + axis]))
                .collect();
            search.plane(centre, &complement);
        }
        ConvexCore::Hull(_) => point_set_planes(&mut search, vertices, tolerance),
        _ => return None,
    }
    let (value, w) = search.best;
    value.is_finite().then_some((value, w))
}

/// The planes at most that [`least_near`] takes through sets of a hull's near vertices (a
/// 5D simplex's facet has 31 sets of its 5 vertices, a facet of a hull of a 4D box's
/// corners 162 of its 8); beyond, the nested faces of its near vertices by height.
const MAX_NEAR_PLANES: usize = 256;

/// The least of `f` over the feet on the planes of the faces of `polytope` near its
/// support along the unit direction `d` (its vertices relative to the query's origin,
/// `vertices`, and its centre `centre`; near: within `within` of the highest along `d`),
/// as [`least_on_face_planes`] takes them all: a cuboid's faces on its highest face of the
/// axes whose edges drop by more than `within` along `d`, each other axis free or fixed at
/// either end (at most 3⁵ faces), a hull's or a segment's planes through every affinely
/// independent set of at most N near vertices (at most [`MAX_NEAR_PLANES`]; else through
/// the first 1, 2, … of them by height, each plane once). None if `f` is nowhere finite there. Given a direction off
/// the least's by δ, the face the least lies on has its vertices within δ times its size
/// of the highest: with `within` above that it is among these planes. `near` and `points`
/// are room for the near vertices.
pub(super) fn least_near(
    ellipsoid: &Ellipsoid,
    polytope: &PlacedShape,
    (vertices, centre): (&[f64], &[f64]),
    (d, within): (&[f64], f64),
    tolerance: f64,
    f: &mut dyn FnMut(&[f64]) -> f64,
    (near, points): (&mut Vec<(f64, usize)>, &mut Vec<f64>),
) -> Option<(f64, Coords)> {
    let n = ellipsoid.centre.len();
    let mut search = Search::new(ellipsoid, f);
    let mut complement: SmallVec<[f64; 64]> = SmallVec::new();
    match polytope.shape().core() {
        ConvexCore::Cuboid(half) => {
            let q = polytope.rotation();
            // The highest face along d of the axes whose edges drop by more than `within`
            // (its centre `fixed`), and the level axes: each free, or fixed at either end.
            let mut fixed: Coords = centre.iter().copied().collect();
            let mut level: SmallVec<[usize; 8]> = SmallVec::new();
            for (axis, h) in half.iter().enumerate() {
                let along: f64 = (0..n).map(|i| q[i * n + axis] * d[i]).sum();
                if 2.0 * h * along.abs() <= within && level.len() < 5 {
                    level.push(axis);
                    continue;
                }
                let side = if along < 0.0 { -h } else { *h };
                for (i, c) in fixed.iter_mut().enumerate() {
                    *c += side * q[i * n + axis];
                }
            }
            let mut point = fixed.clone();
            for code in 0..3usize.pow(level.len() as u32) {
                point.copy_from_slice(&fixed);
                complement.clear();
                for axis in 0..n {
                    // The k-th level axis takes the k-th ternary digit of the code: 0 free,
                    // 1 at +h, 2 at −h; the other axes are fixed.
                    if let Some(k) = level.iter().position(|&a| a == axis) {
                        let side = match code / 3usize.pow(k as u32) % 3 {
                            0 => continue,
                            1 => half[axis],
                            _ => -half[axis],
                        };
                        for (i, p) in point.iter_mut().enumerate() {
                            *p += side * q[i * n + axis];
                        }
                    }
                    complement.extend((0..n).map(|i| q[i * n + axis]));
                }
                search.plane(&point, &complement);
            }
        }
        ConvexCore::Hull(_) | ConvexCore::Segment(_) => {
            near.clear();
            near.extend(
                vertices
                    .chunks_exact(n)
                    .enumerate()
                    .map(|(k, v)| (dot(v, d), k)),
            );
            let top = near.iter().fold(f64::NEG_INFINITY, |t, x| t.max(x.0));
            near.retain(|x| x.0 >= top - within);
            near.sort_unstable_by(|x, y| y.0.total_cmp(&x.0));
            points.clear();
            for &(_, k) in near.iter() {
                points.extend_from_slice(&vertices[k * n..(k + 1) * n]);
            }
            if point_sets(n, near.len()) <= MAX_NEAR_PLANES {
                point_set_planes(&mut search, points, tolerance);
            } else {
                nested_face_planes(&mut search, points, tolerance);
            }
        }
        _ => return None,
    }
    let (value, w) = search.best;
    value.is_finite().then_some((value, w))
}

/// The feet on the planes of the nested faces that the first 1, 2, … of `points` span (N
/// numbers each), each plane once (a point in the span of those before it adds none).
fn nested_face_planes(search: &mut Search, points: &[f64], tolerance: f64) {
    let n = search.w.len();
    let Some(first) = points.get(..n) else {
        return;
    };
    let (mut directions, mut complement): (SmallVec<[f64; 64]>, SmallVec<[f64; 64]>) =
        (SmallVec::new(), SmallVec::new());
    let mut x = Coords::from_elem(0.0, n);
    complement_of(&directions, 0, n, &mut complement, &mut x);
    search.plane(first, &complement);
    for point in points.chunks_exact(n).skip(1) {
        let rank = directions.len() / n;
        if rank + 1 == n {
            break;
        }
        for (x, (p, o)) in x.iter_mut().zip(point.iter().zip(first)) {
            *x = p - o;
        }
        orthogonalize_twice(&mut x, &directions, rank);
        let length = dot(&x, &x).sqrt();
        if length <= tolerance {
            continue;
        }
        directions.extend(x.iter().map(|y| y / length));
        complement_of(&directions, rank + 1, n, &mut complement, &mut x);
        search.plane(first, &complement);
    }
}

/// The feet on the planes through every affinely independent set of at most N of
/// `points` (N numbers each), as for a hull in [`least_on_face_planes`].
fn point_set_planes(search: &mut Search, points: &[f64], tolerance: f64) {
    let n = search.w.len();
    let mut sets = HullPlanes {
        vertices: points,
        n,
        tolerance,
        chosen: SmallVec::new(),
        directions: SmallVec::new(),
        complement: SmallVec::new(),
        x: Coords::from_elem(0.0, n),
    };
    for first in 0..points.len() / n {
        sets.chosen.clear();
        sets.chosen.push(first);
        sets.directions.clear();
        sets.grow(search, first);
    }
}

/// The sets of at most `n` of `points` points: Σ C(points, k) for k = 1 … n (saturating).
fn point_sets(n: usize, points: usize) -> usize {
    let (mut planes, mut choose) = (0usize, 1usize);
    for size in 1..=n.min(points) {
        // C(points, size) from C(points, size − 1).
        choose = choose.saturating_mul(points + 1 - size) / size;
        planes = planes.saturating_add(choose);
    }
    planes
}

/// Whether the face planes of `polytope` (a hull of `points` points) are at most
/// [`MAX_PLANES`], so that [`least_on_face_planes`] takes them.
pub(super) fn enumerable(polytope: &PlacedShape, points: usize) -> bool {
    let n = polytope.position().len();
    match polytope.shape().core() {
        ConvexCore::Cuboid(_) => 3usize
            .checked_pow(n as u32)
            .is_some_and(|planes| planes - 1 <= MAX_PLANES),
        ConvexCore::Segment(_) => true,
        ConvexCore::Hull(_) => point_sets(n, points) <= MAX_PLANES,
        _ => false,
    }
}

/// The state of a search: the least value so far and its direction.
struct Search<'a, 'f> {
    ellipsoid: &'a Ellipsoid<'a>,
    f: &'f mut dyn FnMut(&[f64]) -> f64,
    best: (f64, Coords),
    w: Coords,
}

impl<'a, 'f> Search<'a, 'f> {
    /// No foot yet.
    fn new(ellipsoid: &'a Ellipsoid<'a>, f: &'f mut dyn FnMut(&[f64]) -> f64) -> Self {
        let n = ellipsoid.centre.len();
        Search {
            ellipsoid,
            f,
            best: (f64::INFINITY, Coords::from_elem(0.0, n)),
            w: Coords::from_elem(0.0, n),
        }
    }

    /// The feet on the plane through `point` whose orthogonal complement has the orthonormal
    /// basis `complement` (m rows of N numbers): each foot's normal w, f(w) kept if least.
    fn plane(&mut self, point: &[f64], complement: &[f64]) {
        let n = point.len();
        let m = complement.len() / n;
        if m == 0 {
            return;
        }
        let e = self.ellipsoid;
        // The projected ellipsoid in the complement's coordinates: centre z = Bᵀ(c − v₀),
        // shape S = Bᵀ M B = (Qᵀ B)ᵀ diag(a²) (Qᵀ B).
        let mut z: SmallVec<[f64; 8]> = SmallVec::from_elem(0.0, m);
        let mut g: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, n * m);
        for (j, row) in complement.chunks_exact(n).enumerate() {
            z[j] = row
                .iter()
                .zip(e.centre.iter().zip(point))
                .map(|(b, (c, p))| b * (c - p))
                .sum();
            for k in 0..n {
                g[k * m + j] = (0..n).map(|i| e.rotation[i * n + k] * row[i]).sum();
            }
        }
        let mut shape: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, m * m);
        for j in 0..m {
            for l in j..m {
                let s: f64 = (0..n)
                    .map(|k| e.squared_axes[k] * g[k * m + j] * g[k * m + l])
                    .sum();
                shape[j * m + l] = s;
                shape[l * m + j] = s;
            }
        }
        let (mut lambda, mut v) = (SmallVec::new(), SmallVec::new());
        symmetric_eigen_rows(&shape, m, &mut lambda, &mut v);
        // The centre in the principal axes.
        let zp: SmallVec<[f64; 8]> = (0..m)
            .map(|j| (0..m).map(|i| v[i * m + j] * z[i]).sum())
            .collect();
        let weights: SmallVec<[f64; 8]> = (0..m).map(|j| lambda[j] * zp[j] * zp[j]).collect();
        let mut roots = SmallVec::new();
        secular_roots(&lambda, &weights, &mut roots);
        let mut normal: SmallVec<[f64; 8]> = SmallVec::from_elem(0.0, m);
        for &s in &roots {
            for j in 0..m {
                normal[j] = if zp[j] == 0.0 {
                    0.0
                } else {
                    zp[j] / (s - lambda[j])
                };
            }
            self.consider(&normal, &v, complement);
        }
        // s = λⱼ where zⱼ vanishes (or nearly: the extra candidates cost only their f):
        // the foot's j-th coordinate is free, fixed by the ellipsoid's equation.
        let largest = lambda.iter().fold(0.0f64, |x, l| x.max(*l));
        let centre_size = zp.iter().fold(0.0f64, |x, c| x.max(c.abs()));
        for j in 0..m {
            if zp[j].abs() > 1e-6 * (centre_size + largest.sqrt()) {
                continue;
            }
            let mut rest = 1.0;
            for i in (0..m).filter(|i| *i != j) {
                let apart = lambda[j] - lambda[i];
                let y = if apart.abs() <= 1e-12 * largest {
                    0.0
                } else {
                    zp[i] * lambda[i] / apart
                };
                normal[i] = y / lambda[i];
                rest -= y * y / lambda[i];
            }
            if rest < 0.0 {
                continue;
            }
            for sign in [1.0, -1.0] {
                normal[j] = sign * (rest / lambda[j]).sqrt();
                self.consider(&normal, &v, complement);
            }
        }
    }

    /// f along the direction of the normal `normal` (principal axes `v` of the complement
    /// `complement`), kept if it is the least so far.
    fn consider(&mut self, normal: &[f64], v: &[f64], complement: &[f64]) {
        let m = normal.len();
        let n = self.w.len();
        self.w.iter_mut().for_each(|x| *x = 0.0);
        for (i, row) in complement.chunks_exact(n).enumerate() {
            let coordinate: f64 = (0..m).map(|j| v[i * m + j] * normal[j]).sum();
            for (w, b) in self.w.iter_mut().zip(row) {
                *w += coordinate * b;
            }
        }
        let length = dot(&self.w, &self.w).sqrt();
        if !(length > 0.0 && length.is_finite()) {
            return;
        }
        self.w.iter_mut().for_each(|x| *x /= length);
        let value = (self.f)(&self.w);
        if value < self.best.0 {
            self.best.0 = value;
            self.best.1.copy_from_slice(&self.w);
        }
    }
}

/// The planes through the affinely independent sets of at most N of a hull's points, grown
/// point by point in ascending order (a set that depends on fewer points is that set's).
struct HullPlanes<'v> {
    vertices: &'v [f64],
    n: usize,
    tolerance: f64,
    chosen: SmallVec<[usize; 8]>,
    /// An orthonormal basis of the chosen points' directions from the first (rows).
    directions: SmallVec<[f64; 64]>,
    complement: SmallVec<[f64; 64]>,
    x: Coords,
}

impl HullPlanes<'_> {
    /// The plane of the chosen points, then every larger set that adds a later point.
    fn grow(&mut self, search: &mut Search, last: usize) {
        let n = self.n;
        let first = self.chosen[0];
        let origin = &self.vertices[first * n..(first + 1) * n];
        let rank = self.directions.len() / n;
        complement_of(&self.directions, rank, n, &mut self.complement, &mut self.x);
        search.plane(origin, &self.complement);
        if rank + 1 == n {
            return;
        }
        for next in last + 1..self.vertices.len() / n {
            for (x, (p, o)) in self
                .x
                .iter_mut()
                .zip(self.vertices[next * n..(next + 1) * n].iter().zip(origin))
            {
                *x = p - o;
            }
            orthogonalize_twice(&mut self.x, &self.directions, rank);
            let length = dot(&self.x, &self.x).sqrt();
            if length <= self.tolerance {
                continue;
            }
            let x = std::mem::take(&mut self.x);
            self.directions.extend(x.iter().map(|y| y / length));
            self.x = x;
            self.chosen.push(next);
            self.grow(search, next);
            self.chosen.pop();
            self.directions.truncate(rank * n);
        }
    }
}

/// An orthonormal basis of the complement of the first `rank` rows of `directions`
/// (orthonormal), N − rank rows into `out`: the coordinate axes orthogonalised against
/// them, each time the one farthest from the rows so far (its remainder's square is
/// 1 − Σ rowᵢ², as the rows are orthonormal). `x` is scratch of N numbers.
pub(super) fn complement_of(
    directions: &[f64],
    rank: usize,
    n: usize,
    out: &mut SmallVec<[f64; 64]>,
    x: &mut [f64],
) {
    let mut all: SmallVec<[f64; 64]> = SmallVec::from_slice(&directions[..rank * n]);
    out.clear();
    for have in rank..n {
        let mut pick: (f64, usize) = (f64::NEG_INFINITY, 0);
        for axis in 0..n {
            let remainder = 1.0
                - all
                    .chunks_exact(n)
                    .map(|row| row[axis] * row[axis])
                    .sum::<f64>();
            if remainder > pick.0 {
                pick = (remainder, axis);
            }
        }
        x.iter_mut().for_each(|y| *y = 0.0);
        x[pick.1] = 1.0;
        orthogonalize_twice(x, &all, have);
        let length = dot(x, x).sqrt();
        x.iter_mut().for_each(|y| *y /= length);
        all.extend_from_slice(x);
        out.extend_from_slice(x);
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{box_corners, polished_minima, random_rotation};
    use super::*;
    use crate::dynamics::motion::shape::ConvexShape;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A placed ellipsoid and polytope, about the origin.
    struct Pair {
        centre: Vec<f64>,
        rotation: Vec<f64>,
        squared_axes: Vec<f64>,
        polytope: ConvexShape,
        position: Vec<f64>,
        turn: Vec<f64>,
        vertices: Vec<f64>,
    }

    impl Pair {
        fn new(
            e: (Vec<f64>, Vec<f64>, Vec<f64>),
            polytope: ConvexShape,
            position: Vec<f64>,
            turn: Vec<f64>,
        ) -> Pair {
            let n = position.len();
            let own: Vec<Vec<f64>> = match polytope.core() {
                ConvexCore::Cuboid(h) => box_corners(h),
                ConvexCore::Hull(v) => v.chunks_exact(n).map(|p| p.to_vec()).collect(),
                ConvexCore::Segment(h) => [*h, -h]
                    .iter()
                    .map(|x| (0..n).map(|i| if i == 0 { *x } else { 0.0 }).collect())
                    .collect(),
                _ => unreachable!(),
            };
            let vertices = own
                .iter()
                .flat_map(|p| {
                    (0..n)
                        .map(|i| position[i] + dot(&turn[i * n..(i + 1) * n], p))
                        .collect::<Vec<_>>()
                })
                .collect();
            Pair {
                centre: e.0,
                rotation: e.1,
                squared_axes: e.2,
                polytope,
                position,
                turn,
                vertices,
            }
        }

        /// f(w) = h_E(w) + h_P(−w), from the definitions.
        fn f(&self, w: &[f64]) -> f64 {
            let n = w.len();
            let quadratic: f64 = (0..n)
                .map(|k| {
                    let t: f64 = (0..n).map(|i| self.rotation[i * n + k] * w[i]).sum();
                    self.squared_axes[k] * t * t
                })
                .sum();
            let polytope = self
                .vertices
                .chunks_exact(n)
                .map(|v| -dot(v, w))
                .fold(f64::NEG_INFINITY, f64::max);
            dot(&self.centre, w) + quadratic.sqrt() + polytope
        }

        fn size(&self) -> f64 {
            let reach = self
                .vertices
                .chunks_exact(self.centre.len())
                .map(|v| dot(v, v).sqrt())
                .fold(0.0, f64::max);
            reach
                + dot(&self.centre, &self.centre).sqrt()
                + self
                    .squared_axes
                    .iter()
                    .fold(0.0f64, |m, a| m.max(*a))
                    .sqrt()
        }

        /// The least over the face planes.
        fn least(&self) -> Option<(f64, Coords)> {
            let placed = PlacedShape::new(&self.polytope, &self.position, &self.turn).unwrap();
            let core = Ellipsoid {
                centre: &self.centre,
                rotation: &self.rotation,
                squared_axes: &self.squared_axes,
            };
            let mut f = |w: &[f64]| self.f(w);
            least_on_face_planes(
                &core,
                &placed,
                (&self.vertices, &self.position),
                1e-9 * self.size(),
                &mut f,
            )
        }
    }

    /// A sphere (an ellipsoid of equal semi-axes r, so every projected ellipsoid is a
    /// sphere and its feet come in families) against a turned box, N = 2 … 6: the depth is
    /// r − d(c, box) with the centre c outside the box and r + min(hᵢ − |cᵢ|) inside.
    #[test]
    fn a_sphere_against_a_box_is_the_closed_form() {
        let mut r = ChaCha8Rng::seed_from_u64(3);
        let mut checked = 0;
        for n in 2..=6 {
            for trial in 0..100 {
                let h: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
                let radius = r.gen_range(0.2..2.0);
                // The first trials put the centre where the feet come in families: at the
                // box's centre, on a face, an edge, a corner (the centre on the face
                // planes, zᵢ = 0); the rest anywhere.
                let own: Vec<f64> = match trial {
                    0..4 => h
                        .iter()
                        .enumerate()
                        .map(|(i, x)| if i < trial { *x } else { 0.0 })
                        .collect(),
                    _ => h.iter().map(|x| r.gen_range(-1.4..1.4) * x).collect(),
                };
                let turn = random_rotation(&mut r, n);
                let position: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
                let centre: Vec<f64> = (0..n)
                    .map(|i| position[i] + dot(&turn[i * n..(i + 1) * n], &own))
                    .collect();
                let outside: f64 = own
                    .iter()
                    .zip(&h)
                    .map(|(c, h)| (c.abs() - h).max(0.0).powi(2))
                    .sum::<f64>()
                    .sqrt();
                let exact = if outside > 0.0 {
                    radius - outside
                } else {
                    radius
                        + own
                            .iter()
                            .zip(&h)
                            .map(|(c, h)| h - c.abs())
                            .fold(f64::INFINITY, f64::min)
                };
                if exact <= 0.0 {
                    continue;
                }
                let pair = Pair::new(
                    (centre, random_rotation(&mut r, n), vec![radius * radius; n]),
                    ConvexShape::cuboid(&h).unwrap(),
                    position,
                    turn,
                );
                let (depth, w) = pair.least().unwrap();
                assert!(
                    (depth - exact).abs() <= 1e-12 * pair.size(),
                    "N = {n}: {depth} against {exact}"
                );
                assert!((pair.f(&w) - depth).abs() <= 1e-15 * pair.size());
                checked += 1;
            }
        }
        assert!(checked >= 300, "{checked}");
    }

    /// A sphere centred on the base of a pyramid (a hull: N points on the plane x₀ = 0,
    /// and an apex), N = 2 … 6: the depth is its radius, along −x₀, which only the base's
    /// plane gives and there z = 0 (the centre on the plane), the foot at s = λ.
    #[test]
    fn a_sphere_on_a_facet_plane_is_pushed_out_through_it() {
        let mut r = ChaCha8Rng::seed_from_u64(7);
        for n in 2..=6 {
            // The base: 1.5 eᵢ (i = 1 … N − 1) and −0.7 (e₁ + … + e_{N−1}), around the origin.
            let mut points: Vec<Vec<f64>> = (1..n)
                .map(|k| (0..n).map(|i| if i == k { 1.5 } else { 0.0 }).collect())
                .collect();
            points.push((0..n).map(|i| if i == 0 { 0.0 } else { -0.7 }).collect());
            // The apex off the base's normal through the centre, so that no vertex's plane
            // gives that normal.
            points.push([3.0, 0.37, 0.23, 0.11, 0.05, 0.02][..n].to_vec());
            let hull = ConvexShape::hull(&points).unwrap();
            let radius = 0.2;
            let identity: Vec<f64> = (0..n * n)
                .map(|k| if k % (n + 1) == 0 { 1.0 } else { 0.0 })
                .collect();
            let pair = Pair::new(
                (
                    vec![0.0; n],
                    random_rotation(&mut r, n),
                    vec![radius * radius; n],
                ),
                hull,
                vec![0.0; n],
                identity,
            );
            let (depth, w) = pair.least().unwrap();
            assert!((depth - radius).abs() <= 1e-14, "N = {n}: {depth}");
            assert!((w[0] - 1.0).abs() <= 1e-12, "N = {n}: {w:?}");
        }
    }

    /// A random ellipsoid against a random hull, box or segment, N = 2 … 6, overlapping:
    /// no direction among 2,000 random ones, each polished by a pattern search on the
    /// sphere, separates them by less than the least on the face planes (which is f at its
    /// own direction, so a translation that separates them).
    #[test]
    fn no_direction_separates_an_ellipsoid_and_a_polytope_by_less() {
        let mut r = ChaCha8Rng::seed_from_u64(17);
        let mut checked = [0usize; 5];
        for n in 2..=6 {
            for trial in 0..24 {
                let polytope = match trial % 3 {
                    0 => ConvexShape::cuboid(
                        &(0..n).map(|_| r.gen_range(0.2..2.0)).collect::<Vec<_>>(),
                    )
                    .unwrap(),
                    1 => loop {
                        let points: Vec<Vec<f64>> = (0..n + 1 + r.gen_range(0..4))
                            .map(|_| (0..n).map(|_| r.gen_range(-1.5..1.5)).collect())
                            .collect();
                        if let Ok(s) = ConvexShape::hull(&points) {
                            break s;
                        }
                    },
                    _ => ConvexShape::capsule(n, r.gen_range(0.2..2.0), 0.1).unwrap(),
                };
                let axes: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0f64).powi(2)).collect();
                let centre: Vec<f64> = (0..n).map(|_| r.gen_range(-0.8..0.8)).collect();
                let pair = Pair::new(
                    (centre, random_rotation(&mut r, n), axes),
                    polytope,
                    (0..n).map(|_| r.gen_range(-0.5..0.5)).collect(),
                    random_rotation(&mut r, n),
                );
                let (depth, w) = pair.least().unwrap();
                let size = pair.size();
                if depth <= 1e-3 * size {
                    continue;
                }
                assert!((pair.f(&w) - depth).abs() <= 1e-15 * size);
                for value in polished_minima(&mut r, n, (2000, 6), &|u| pair.f(u)) {
                    assert!(
                        depth <= value + 1e-12 * size,
                        "N = {n}: {depth} above {value}"
                    );
                }
                checked[n - 2] += 1;
            }
        }
        assert!(checked.iter().all(|c| *c >= 8), "{checked:?}");
    }
}
