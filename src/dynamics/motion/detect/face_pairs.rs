//! The exact depth of two overlapping polytopes (hulls, cuboids, segments and points) where
//! EPA stopped at one of its caps with its bounds apart (from 5D on, where the facets of
//! A − B outgrow them).
//!
//! The depth is the least over unit directions u of f(u) = h_B(u) + h_A(−u), the support
//! function of the polytope K = B ⊕ (−A), whose interior holds the origin: the distance
//! from the origin to K's nearest facet, whose normal is u*. A facet of K is F_B ⊕ (−F_A)
//! for a face F_A of A and F_B of B, and its N − 1 directions are spanned by theirs, so u*
//! is orthogonal to N − 1 independent directions of which some come from F_A and the rest
//! from F_B: u* is among the unit normals of all such sets, both ways. f at each, evaluated
//! directly, is a translation that separates the shapes; their least is the depth, exact
//! to round-off and never below it. For two boxes these are the separating axes of the
//! generalised separating-axis test (sets of the two boxes' axes: C(2N, N − 1) normals,
//! 792 in 6D); this is that test for any polytopes.
//!
//! A cuboid's face directions are sets of its axes, a segment's its axis or none, a point's
//! none, and a hull's the directions from one of its points to others (every independent
//! set of at most N of its points: a superset of its faces', whose extra sets only add
//! candidates). Pairs with more than [`MAX_NORMALS`] sets are not enumerated. The
//! witnesses are points of the two faces along the normal found, depth · u apart: convex
//! weights of the faces' vertices by a linear program ([`face_witnesses`]).

use super::face_planes::complement_of;
use super::smooth::polytope_vertices;
use crate::dynamics::motion::detect::gjk::PlacedShape;
use crate::dynamics::motion::shape::{ConvexCore, Coords};
use crate::numeric::dense::dot;
use crate::numeric::orthogonalize_twice;
use crate::numeric::simplex::{EqualityLp, LP_WIDTH};
use smallvec::SmallVec;

/// The sets of directions at most that a query enumerates (each a normal to evaluate both
/// ways): two 6D boxes take 792, two hulls of 11 points in 6D about 170,000 and two 6D
/// cross-polytopes (12 points) about 325,000.
pub(super) const MAX_NORMALS: usize = 1 << 19;

/// A direction this much shorter than it was before it was made orthogonal to the ones
/// chosen lies in their span.
const DEPENDENT: f64 = 1e-12;

/// Where a polytope's face directions come from.
enum Directions {
    /// Sets of these orthonormal axes (rows of N numbers).
    Axes(Vec<f64>),
    /// Sets of the directions from one of these points (N numbers each) to others.
    Points(Vec<f64>),
}

impl Directions {
    /// The directions of a placed polytope core, or None for a curved one.
    fn of(shape: &PlacedShape) -> Option<Directions> {
        let q = shape.rotation();
        let n = shape.position().len();
        let column = |k: usize| (0..n).map(move |i| q[i * n + k]);
        Some(match shape.shape().core() {
            ConvexCore::Point => Directions::Axes(Vec::new()),
            ConvexCore::Segment(_) => Directions::Axes(column(0).collect()),
            ConvexCore::Cuboid(_) => Directions::Axes((0..n).flat_map(column).collect()),
            ConvexCore::Hull(points) => Directions::Points(
                points
                    .chunks_exact(n)
                    .flat_map(|p| (0..n).map(|i| dot(&q[i * n..(i + 1) * n], p)))
                    .collect(),
            ),
            ConvexCore::Ellipsoid(_) => return None,
        })
    }

    /// How many sets of `k` directions there are (an upper bound: some are dependent).
    fn sets(&self, n: usize, k: usize) -> usize {
        match self {
            Directions::Axes(rows) => choose(rows.len() / n, k),
            Directions::Points(_) if k == 0 => 1,
            Directions::Points(p) => choose(p.len() / n, k + 1),
        }
    }
}

/// The binomial coefficient, saturating.
fn choose(n: usize, k: usize) -> usize {
    if k > n {
        return 0;
    }
    (0..k).fold(1usize, |c, i| c.saturating_mul(n - i) / (i + 1))
}

/// The least of `f` over the unit normals (both ways) of every set of N − 1 independent
/// face directions of the polytope cores of `a` and `b`: the exact depth and its direction
/// (`f(u)` = h_B(u) + h_A(−u), the support function of B − A). None if a core is curved,
/// the sets are more than [`MAX_NORMALS`], or `f` is nowhere finite.
pub(super) fn least_over_face_pairs(
    a: &PlacedShape,
    b: &PlacedShape,
    f: &mut dyn FnMut(&[f64]) -> f64,
) -> Option<(f64, Coords)> {
    let n = a.position().len();
    let (da, db) = (Directions::of(a)?, Directions::of(b)?);
    let mut total = 0usize;
    for k in 0..n {
        total = total.saturating_add(da.sets(n, k).saturating_mul(db.sets(n, n - 1 - k)));
    }
    if total > MAX_NORMALS {
        return None;
    }
    let mut walk = Walk {
        n,
        basis: SmallVec::new(),
        x: Coords::from_elem(0.0, n),
        normal: Coords::from_elem(0.0, n),
        complement: SmallVec::new(),
        f,
        best: (f64::INFINITY, Coords::from_elem(0.0, n)),
    };
    walk.first(&da, &db, 0, None);
    let (value, u) = walk.best;
    value.is_finite().then_some((value, u))
}

/// The enumeration: the directions chosen so far (orthonormal rows) and the least found.
struct Walk<'f> {
    n: usize,
    basis: SmallVec<[f64; 64]>,
    x: Coords,
    normal: Coords,
    complement: SmallVec<[f64; 64]>,
    f: &'f mut dyn FnMut(&[f64]) -> f64,
    best: (f64, Coords),
}

impl Walk<'_> {
    fn rank(&self) -> usize {
        self.basis.len() / self.n
    }

    /// Adds `x` made orthogonal to the basis if it is independent of it.
    fn push(&mut self) -> bool {
        let before = dot(&self.x, &self.x).sqrt();
        let rank = self.rank();
        orthogonalize_twice(&mut self.x, &self.basis, rank);
        let length = dot(&self.x, &self.x).sqrt();
        if length <= DEPENDENT * before || length.is_nan() {
            return false;
        }
        let x = std::mem::take(&mut self.x);
        self.basis.extend(x.iter().map(|y| y / length));
        self.x = x;
        true
    }

    fn pop(&mut self) {
        let rank = self.rank();
        self.basis.truncate((rank - 1) * self.n);
    }

    /// Every set of `a`'s directions that extends the chosen ones from `from` on (with
    /// `anchor`, the point a hull's directions start from), each completed by `b`'s.
    fn first(&mut self, a: &Directions, b: &Directions, from: usize, anchor: Option<usize>) {
        self.second(b, 0, None);
        if self.rank() + 1 == self.n {
            return;
        }
        self.extend(a, from, anchor, &mut |walk, next, anchor| {
            walk.first(a, b, next, anchor)
        });
    }

    /// Every set of `b`'s directions that completes the chosen ones to N − 1: at N − 1, f
    /// along their normal, both ways.
    fn second(&mut self, b: &Directions, from: usize, anchor: Option<usize>) {
        if self.rank() + 1 == self.n {
            self.leaf();
            return;
        }
        self.extend(b, from, anchor, &mut |walk, next, anchor| {
            walk.second(b, next, anchor)
        });
    }

    /// Each direction of `d` from `from` on that is independent of the chosen ones, added
    /// in turn and handed to `then` (with the next index to start from and the anchor).
    fn extend(
        &mut self,
        d: &Directions,
        from: usize,
        anchor: Option<usize>,
        then: &mut dyn FnMut(&mut Self, usize, Option<usize>),
    ) {
        let n = self.n;
        match (d, anchor) {
            (Directions::Axes(rows), _) => {
                for k in from..rows.len() / n {
                    self.x.copy_from_slice(&rows[k * n..(k + 1) * n]);
                    if self.push() {
                        then(self, k + 1, None);
                        self.pop();
                    }
                }
            }
            (Directions::Points(points), None) => {
                let count = points.len() / n;
                for start in 0..count {
                    self.directions_from(points, start, start + 1, then);
                }
            }
            (Directions::Points(points), Some(start)) => {
                self.directions_from(points, start, from, then);
            }
        }
    }

    /// The directions from point `start` to each point from `from` on.
    fn directions_from(
        &mut self,
        points: &[f64],
        start: usize,
        from: usize,
        then: &mut dyn FnMut(&mut Self, usize, Option<usize>),
    ) {
        let n = self.n;
        let origin = &points[start * n..(start + 1) * n];
        for k in from..points.len() / n {
            for (x, (p, o)) in self
                .x
                .iter_mut()
                .zip(points[k * n..(k + 1) * n].iter().zip(origin))
            {
                *x = p - o;
            }
            if self.push() {
                then(self, k + 1, Some(start));
                self.pop();
            }
        }
    }

    /// The unit normal of the N − 1 chosen directions, and f along it both ways.
    fn leaf(&mut self) {
        let n = self.n;
        complement_of(
            &self.basis,
            n - 1,
            n,
            &mut self.complement,
            &mut self.normal,
        );
        self.normal.copy_from_slice(&self.complement[..n]);
        for sign in [1.0, -1.0] {
            self.normal.iter_mut().for_each(|x| *x *= sign);
            let value = (self.f)(&self.normal);
            if value < self.best.0 {
                self.best.0 = value;
                self.best.1.copy_from_slice(&self.normal);
            }
        }
    }
}

/// The vertices (in space) of the face of a placed polytope core along `d`: those within
/// `within` of the highest, appended to `out` (N numbers each). False for a curved core or
/// a cuboid of more dimensions than [`polytope_vertices`] takes.
fn face_along(shape: &PlacedShape, d: &[f64], within: f64, out: &mut Vec<f64>) -> bool {
    let n = d.len();
    let mut corners: Vec<f64> = Vec::new();
    if let ConvexCore::Point = shape.shape().core() {
        corners.extend_from_slice(shape.position());
    } else if !polytope_vertices(shape, &Coords::from_elem(0.0, n), &mut corners) {
        return false;
    }
    let top = corners
        .chunks_exact(n)
        .map(|v| dot(v, d))
        .fold(f64::NEG_INFINITY, f64::max);
    for v in corners.chunks_exact(n) {
        if dot(v, d) >= top - within {
            out.extend_from_slice(v);
        }
    }
    true
}

/// Witnesses of the depth `depth` along the unit `u` (f(u) = h_B(u) + h_A(−u)): a point
/// x_a of A's face along −u and x_b of B's face along u with x_b − x_a = depth · u, as
/// convex combinations of the faces' vertices (a linear program), so that both are points
/// of their shapes. `scale` is the pair's size. None if the faces have more vertices than
/// the program takes or it finds no solution.
pub(super) fn face_witnesses(
    a: &PlacedShape,
    b: &PlacedShape,
    (depth, u): (f64, &[f64]),
    scale: f64,
) -> Option<(Coords, Coords)> {
    let n = u.len();
    let within = 1e-9 * scale;
    let minus: Coords = u.iter().map(|x| -x).collect();
    let (mut fa, mut fb) = (Vec::new(), Vec::new());
    if !face_along(a, &minus, within, &mut fa) || !face_along(b, u, within, &mut fb) {
        return None;
    }
    let (ka, kb) = (fa.len() / n, fb.len() / n);
    // Rows: x_b − x_a = depth · u (scaled to the pair's size), Σα = 1, Σβ = 1.
    let entry = |i: usize, j: usize| match (i < n, j < ka) {
        (true, true) => -fa[j * n + i] / scale,
        (true, false) => fb[(j - ka) * n + i] / scale,
        (false, true) => f64::from(u8::from(i == n)),
        (false, false) => f64::from(u8::from(i == n + 1)),
    };
    let mut rhs: SmallVec<[f64; 12]> = u.iter().map(|x| depth * x / scale).collect();
    rhs.extend([1.0, 1.0]);
    let mut lp = EqualityLp::<LP_WIDTH>::new(n + 2, ka + kb, entry, &rhs)?;
    if !lp.find_feasible(1e-9) {
        return None;
    }
    let mut weights = vec![0.0; ka + kb];
    lp.solution(&mut weights);
    let mut xa = Coords::from_elem(0.0, n);
    let mut xb = Coords::from_elem(0.0, n);
    for (j, w) in weights.iter().enumerate() {
        let (x, v) = if j < ka {
            (&mut xa, &fa[j * n..(j + 1) * n])
        } else {
            (&mut xb, &fb[(j - ka) * n..(j - ka + 1) * n])
        };
        x.iter_mut().zip(v).for_each(|(p, q)| *p += w * q);
    }
    Some((xa, xb))
}

#[cfg(test)]
mod tests {
    use super::super::gjk::support_difference;
    use super::super::sat::{PlacedBox, box_box};
    use super::super::test_support::{polished_minima, random_rotation};
    use super::*;
    use crate::dynamics::motion::shape::ConvexShape;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// f(u) = h_B(u) + h_A(−u) of two placed shapes.
    fn reach(a: &PlacedShape, b: &PlacedShape, u: &[f64]) -> f64 {
        let n = u.len();
        let (mut w, mut sa, mut sb) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        support_difference(a, b, u, &mut w, &mut sa, &mut sb);
        dot(u, &w)
    }

    /// Two overlapping turned boxes, N = 2 … 6: the least over the face pairs is the
    /// separating-axis test's least overlap (`box_box`, an independent enumeration of the
    /// same axes by blades), and f at its own direction.
    #[test]
    fn two_boxes_give_the_separating_axis_depth() {
        let mut r = ChaCha8Rng::seed_from_u64(41);
        let mut checked = [0usize; 5];
        for n in 2..=6 {
            for _ in 0..40 {
                let (ha, hb): (Vec<f64>, Vec<f64>) = (
                    (0..n).map(|_| r.gen_range(0.2..2.0)).collect(),
                    (0..n).map(|_| r.gen_range(0.2..2.0)).collect(),
                );
                let (qa, qb) = (random_rotation(&mut r, n), random_rotation(&mut r, n));
                let (pa, pb): (Vec<f64>, Vec<f64>) = (
                    (0..n).map(|_| r.gen_range(-0.5..0.5)).collect(),
                    (0..n).map(|_| r.gen_range(-0.5..0.5)).collect(),
                );
                let sat = box_box(
                    &PlacedBox {
                        half_lengths: &ha,
                        position: &pa,
                        rotation: &qa,
                    },
                    &PlacedBox {
                        half_lengths: &hb,
                        position: &pb,
                        rotation: &qb,
                    },
                )
                .unwrap();
                if sat.least_depth <= 0.0 {
                    continue;
                }
                let (sa, sb) = (
                    ConvexShape::cuboid(&ha).unwrap(),
                    ConvexShape::cuboid(&hb).unwrap(),
                );
                let a = PlacedShape::new(&sa, &pa, &qa).unwrap();
                let b = PlacedShape::new(&sb, &pb, &qb).unwrap();
                let (depth, u) = least_over_face_pairs(&a, &b, &mut |u| reach(&a, &b, u)).unwrap();
                let size = ha.iter().chain(&hb).sum::<f64>();
                assert!(
                    (depth - sat.least_depth).abs() <= 1e-12 * size,
                    "N = {n}: {depth} against {}",
                    sat.least_depth
                );
                assert!((reach(&a, &b, &u) - depth).abs() <= 1e-15 * size);
                // The witnesses: in their boxes, depth · u apart.
                let (xa, xb) = face_witnesses(&a, &b, (depth, &u), size).unwrap();
                for (x, h, p, q) in [(&xa, &ha, &pa, &qa), (&xb, &hb, &pb, &qb)] {
                    for k in 0..n {
                        let own: f64 = (0..n).map(|i| q[i * n + k] * (x[i] - p[i])).sum();
                        assert!(
                            own.abs() <= h[k] + 1e-9 * size,
                            "N = {n}: outside by {}",
                            own.abs() - h[k]
                        );
                    }
                }
                for i in 0..n {
                    assert!((xb[i] - xa[i] - depth * u[i]).abs() <= 1e-9 * size);
                }
                checked[n - 2] += 1;
            }
        }
        assert!(checked.iter().all(|c| *c >= 20), "{checked:?}");
    }

    /// Random hulls against hulls, boxes, segments and points in 5D and 6D, where EPA meets
    /// its caps: no direction among 2,000 random ones, polished by a pattern search on the
    /// sphere, separates them by less.
    #[test]
    fn no_direction_separates_two_polytopes_by_less() {
        let mut r = ChaCha8Rng::seed_from_u64(43);
        let mut checked = 0;
        for n in [5, 6] {
            for trial in 0..24 {
                let hull = |r: &mut ChaCha8Rng| loop {
                    let points: Vec<Vec<f64>> = (0..n + 1 + r.gen_range(0..3))
                        .map(|_| (0..n).map(|_| r.gen_range(-1.5..1.5)).collect())
                        .collect();
                    if let Ok(s) = ConvexShape::hull(&points) {
                        break s;
                    }
                };
                let sa = hull(&mut r);
                let sb = match trial % 4 {
                    0 => hull(&mut r),
                    1 => ConvexShape::cuboid(
                        &(0..n).map(|_| r.gen_range(0.2..2.0)).collect::<Vec<_>>(),
                    )
                    .unwrap(),
                    2 => ConvexShape::capsule(n, r.gen_range(0.2..2.0), 0.1).unwrap(),
                    _ => ConvexShape::ball(n, 0.5).unwrap(),
                };
                let (qa, qb) = (random_rotation(&mut r, n), random_rotation(&mut r, n));
                let (pa, pb): (Vec<f64>, Vec<f64>) = (
                    vec![0.0; n],
                    (0..n).map(|_| r.gen_range(-0.3..0.3)).collect(),
                );
                let a = PlacedShape::new(&sa, &pa, &qa).unwrap();
                let b = PlacedShape::new(&sb, &pb, &qb).unwrap();
                let f = |u: &[f64]| reach(&a, &b, u);
                let (depth, u) = least_over_face_pairs(&a, &b, &mut |u| f(u)).unwrap();
                if depth <= 1e-2 {
                    continue;
                }
                assert!((f(&u) - depth).abs() <= 1e-14);
                // The witnesses: on the faces along −u and u, depth · u apart.
                let (xa, xb) = face_witnesses(&a, &b, (depth, &u), 4.0).unwrap();
                let minus: Vec<f64> = u.iter().map(|x| -x).collect();
                let (mut sa, mut sb) = (vec![0.0; n], vec![0.0; n]);
                a.core_support(&minus, &mut sa);
                b.core_support(&u, &mut sb);
                assert!((dot(&xa, &minus) - dot(&sa, &minus)).abs() <= 1e-9);
                assert!((dot(&xb, &u) - dot(&sb, &u)).abs() <= 1e-9);
                for i in 0..n {
                    assert!((xb[i] - xa[i] - depth * u[i]).abs() <= 1e-9);
                }
                for value in polished_minima(&mut r, n, (2000, 6), &f) {
                    assert!(depth <= value + 1e-12, "N = {n}: {depth} above {value}");
                }
                checked += 1;
            }
        }
        assert!(checked >= 16, "{checked}");
    }
}
