//! Penetration depth and contact normal of overlapping convex shapes in any dimension: the
//! expanding polytope algorithm (EPA, van den Bergen, "Collision Detection in Interactive
//! 3D Environments") with facets that are (N − 1)-simplices.
//!
//! The depth of two overlapping shapes is the distance from the origin to the boundary of
//! K = B − A. EPA grows a polytope inside K from GJK's final simplex: it takes the facet
//! nearest the origin, asks K for its support point along that facet's normal, and either
//! stops (the support point lies on the facet: the facet is on K's boundary) or replaces
//! every facet that sees the new point by the cone from it over their horizon.
//!
//! The known failures of EPA are met as follows. GJK may end with fewer than N + 1 points
//! (the origin on a face of its simplex, which box pairs produce): the simplex is completed
//! with support points along directions orthogonal to it, and a direction in which K has
//! no extent (a capsule's segment against a ball's point) is itself the answer, depth 0
//! for the cores. Facet normals are oriented away from a point strictly inside the first
//! simplex, never by the origin, so the origin on a facet (touching shapes) gives depth 0
//! rather than a flipped normal. A new facet that would be degenerate (a support point
//! that repeats, parallel closest faces) ends the expansion with the current nearest
//! facet instead of looping, and the iterations are bounded. Every division is guarded,
//! so no NaN comes out. Round-off on thin facets (heights off by about ε · size² / width)
//! can still bend the polytope; two bounds keep the answer honest: the depth is never
//! below the farthest nearest facet met by more than [`FALL`] of the size, nor above the
//! least reach of a support query along a unit normal (a translation that separates).
//!
//! Margins: EPA runs on the cores and the radii are added to the depth, which is exact
//! for rounded shapes (K's boundary moves out by the sum of the radii). Ball–ball and
//! ball–cuboid pairs have closed forms.

use super::KeyHasher;
use super::face_pairs::{face_witnesses, least_over_face_pairs};
use super::gjk::{
    GjkResult, PlacedShape, Points, Simplex, centre_direction, check_pair, curved, gjk,
    nearest_point, project_onto_face, support_difference,
};
use super::smooth::{FaceScratch, polytope_depth, smooth_depth};
use crate::algebra::Vector;
use crate::dynamics::motion::shape::{ConvexCore, Coords, ShapeError};
use crate::numeric::dense::dot;
use crate::numeric::orthogonalize_twice;
use smallvec::SmallVec;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;

/// EPA iterations at most (each adds one support point).
pub(crate) const MAX_EPA_ITERATIONS: usize = 256;
/// The polytope's facets at most. A polytope of V vertices in N dimensions can have of the
/// order of V^(N/2) facets, so above N = 5 the expansion would otherwise be bounded in
/// iterations but not in time or memory. At the cap EPA stops: up to 4D with the nearest
/// facet so far, whose distance is a lower bound of the depth; above, with the least
/// translation along the normals it queried, which separates the shapes (an upper bound),
/// where the two bounds are more than 1e-9 of the size apart; two polytopes' depth then
/// comes from their faces' directions (`face_pairs.rs`), exact.
pub(crate) const MAX_EPA_FACETS: usize = 4096;
/// The facet planes EPA may compute in all, over its iterations and the retries that merge
/// coplanar facets. In six dimensions each new point can see thousands of facets, and
/// each retry computes the planes of its whole horizon again, so the iteration and facet
/// caps alone let a query run for most of a second (a tiny box at the centre of a rounded
/// simplex 10¹¹ times its size: 0.4 and 0.8 s for the two orders, 262 iterations); at
/// this cap EPA stops as at the facet cap.
pub(crate) const MAX_EPA_MADE: usize = 8 * MAX_EPA_FACETS;
/// EPA stops when the support point along the nearest facet's normal lies within this
/// fraction of the problem's size beyond the facet.
const CONVERGED: f64 = 1e-12;
/// On curved cores (an ellipsoid) EPA also stops when its least support reach (an upper
/// bound of the depth) and its nearest facet (a lower bound) are within this fraction of
/// the size, the precision the detection promises. A polytope of facets approximates a
/// curved surface only to the square of its facets' width over the radius of curvature:
/// to 1e-12 of the size it would need more facets than [`MAX_EPA_FACETS`] allows, and in
/// six dimensions a thin ellipsoid inside a long capsule ran its 256 iterations on 4,096
/// facets for 1.8 s before stopping at the cap.
const CURVED_CONVERGED: f64 = 1e-9;
/// A facet sees a point that lies beyond its plane by more than this fraction of the size.
const VISIBLE: f64 = 1e-13;
/// A facet whose normal is this ill-determined (relative to its size) is degenerate.
const FLAT_FACET: f64 = 1e-12;
/// A new point within this fraction of the size below a facet's plane lies on it, for
/// merging: the heights of thin facets (one edge of the size of the smaller shape, the
/// others of the larger) carry errors of about ε · size² / edge.
const COPLANAR: f64 = 1e-9;

/// An expansion that ends with its nearest facet more than this fraction of the size below
/// the farthest nearest facet it met returns that one: far above the round-off of thin
/// facets (see [`COPLANAR`]), such a fall shows a polytope bent out of shape.
const FALL: f64 = 1e-6;

/// The contact of two placed shapes, from [`penetration`].
#[derive(Clone, Debug, PartialEq)]
pub struct Penetration {
    /// The signed depth: > 0 how far the shapes overlap (moving B by `depth` along
    /// `normal` separates them), ≤ 0 minus their distance.
    pub depth: f64,
    /// The unit contact normal, from A to B.
    pub normal: Vector,
    /// The point of A deepest inside B (or nearest B when separated), space frame.
    pub witness_a: Vector,
    /// The point of B deepest inside A (or nearest A), space frame:
    /// witness_a − witness_b = depth · normal.
    pub witness_b: Vector,
    /// GJK and EPA iterations taken together (0 for the closed forms).
    pub iterations: usize,
}

impl Penetration {
    /// The contact of two margined shapes from that of their cores: the depth grows by both
    /// margins and each witness moves out to its shape's surface along the normal (A's with
    /// it, B's against it), so that witness_a − witness_b = depth · normal still holds.
    fn from_cores(
        core_depth: f64,
        normal: Vector,
        mut witness_a: Vector,
        mut witness_b: Vector,
        (ra, rb): (f64, f64),
        iterations: usize,
    ) -> Self {
        for ((p, q), m) in witness_a
            .as_mut_slice()
            .iter_mut()
            .zip(witness_b.as_mut_slice())
            .zip(normal.as_slice())
        {
            *p += ra * m;
            *q -= rb * m;
        }
        Penetration {
            depth: core_depth + ra + rb,
            normal,
            witness_a,
            witness_b,
            iterations,
        }
    }
}

/// Scratch memory of EPA, kept between queries so that they do not allocate once it has
/// grown to the polytopes met.
#[derive(Clone, Debug, Default)]
pub struct EpaWorkspace {
    /// Vertices of the polytope: w, and the support points on A and B (N numbers each).
    w: Vec<f64>,
    a: Vec<f64>,
    b: Vec<f64>,
    /// Each facet's N vertex indices (ascending), unit outward normal and offset.
    facets: Vec<u32>,
    normals: Vec<f64>,
    offsets: Vec<f64>,
    /// Facets seen from the new point, and the horizon's ridges (N − 1 indices each) with
    /// their counts.
    visible: Vec<usize>,
    ridges: Vec<u32>,
    ridge_counts: Vec<u32>,
    /// Each ridge's position in `ridge_counts`, by its vertex indices packed 16 bits each.
    ridge_index: HashMap<u128, u32, BuildHasherDefault<KeyHasher>>,
    new_facets: Vec<u32>,
    new_normals: Vec<f64>,
    new_offsets: Vec<f64>,
    /// Room for the depth of a polytope against an ellipsoid.
    faces: FaceScratch,
}

impl EpaWorkspace {
    /// Returns an empty workspace.
    pub fn new() -> Self {
        Self::default()
    }

    fn clear(&mut self) {
        self.w.clear();
        self.a.clear();
        self.b.clear();
        self.facets.clear();
        self.normals.clear();
        self.offsets.clear();
    }

    fn push_vertex(&mut self, w: &[f64], a: &[f64], b: &[f64]) -> u32 {
        let index = self.w.len() / w.len();
        self.w.extend_from_slice(w);
        self.a.extend_from_slice(a);
        self.b.extend_from_slice(b);
        index as u32
    }
}

/// The unit normal of the facet through the points `vertices` (N indices), oriented away
/// from `inside`, and its offset; None if the facet is degenerate.
fn facet_plane(
    w: &[f64],
    n: usize,
    vertices: &[u32],
    inside: &[f64],
    scale: f64,
    normal: &mut [f64],
) -> Option<f64> {
    let point = |k: u32| &w[k as usize * n..(k as usize + 1) * n];
    let y0 = point(vertices[0]);
    let mut basis: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, (n - 1) * n);
    let mut e = Coords::from_elem(0.0, n);
    for (j, &k) in vertices[1..].iter().enumerate() {
        let mut length = 0.0;
        for ((x, p), q) in e.iter_mut().zip(point(k)).zip(y0) {
            *x = p - q;
            length += *x * *x;
        }
        let length = length.sqrt();
        orthogonalize_twice(&mut e, &basis, j);
        let r = e.iter().map(|x| x * x).sum::<f64>().sqrt();
        if r.is_nan() || r <= FLAT_FACET * length || r <= FLAT_FACET * scale {
            return None;
        }
        basis[j * n..(j + 1) * n]
            .iter_mut()
            .zip(&e)
            .for_each(|(b, x)| *b = x / r);
    }
    for ((x, p), q) in normal.iter_mut().zip(y0).zip(inside) {
        *x = p - q;
    }
    orthogonalize_twice(normal, &basis, n - 1);
    let r = normal.iter().map(|x| x * x).sum::<f64>().sqrt();
    if r.is_nan() || r <= FLAT_FACET * scale {
        return None;
    }
    normal.iter_mut().for_each(|x| *x /= r);
    // The offset from the mean of the vertices, to spread the rounding evenly.
    let mut offset = 0.0;
    for &k in vertices {
        offset += normal.iter().zip(point(k)).map(|(p, q)| p * q).sum::<f64>();
    }
    Some(offset / n as f64)
}

/// Writes the horizon of the facets in `ws.visible` into `ws.ridges` (N − 1 vertex indices
/// each, ascending) with how many seen facets hold each ridge in `ws.ridge_counts`: the
/// ridges held once bound the seen region. Ridges are matched through a hash of their
/// packed indices (N − 1 ≤ 8 indices below 2¹⁶, always the case within the iteration
/// bound for N ≤ 9), else by a linear search.
fn horizon(ws: &mut EpaWorkspace, n: usize) {
    ws.ridges.clear();
    ws.ridge_counts.clear();
    ws.ridge_index.clear();
    let packed = n - 1 <= 8 && ws.w.len() / n < 1 << 16;
    for vi in 0..ws.visible.len() {
        let g = ws.visible[vi];
        for skip in 0..n {
            let start = ws.ridges.len();
            for k in 0..n {
                if k != skip {
                    let x = ws.facets[g * n + k];
                    ws.ridges.push(x);
                }
            }
            let ridge_count = start / (n - 1);
            let found = if packed {
                let key = ws.ridges[start..]
                    .iter()
                    .fold(0u128, |k, &x| k << 16 | x as u128);
                match ws.ridge_index.entry(key) {
                    std::collections::hash_map::Entry::Occupied(e) => Some(*e.get() as usize),
                    std::collections::hash_map::Entry::Vacant(e) => {
                        e.insert(ridge_count as u32);
                        None
                    }
                }
            } else {
                (0..ridge_count).find(|&r| {
                    ws.ridges[r * (n - 1)..(r + 1) * (n - 1)] == ws.ridges[start..start + n - 1]
                })
            };
            match found {
                Some(r) => {
                    ws.ridges.truncate(start);
                    ws.ridge_counts[r] += 1;
                }
                None => ws.ridge_counts.push(1),
            }
        }
    }
}

/// What EPA found on the cores: the depth of the origin inside K, the outward normal of K
/// there (the contact normal is its opposite), and the core witnesses.
struct CoreContact {
    depth: f64,
    normal_k: Coords,
    witness_a: Coords,
    witness_b: Coords,
    iterations: usize,
}

/// Completes GJK's simplex to N + 1 affinely independent points of K in the workspace;
/// returns Err with the flat direction if K has no extent orthogonal to the simplex.
fn initial_simplex(
    ws: &mut EpaWorkspace,
    a: &PlacedShape,
    b: &PlacedShape,
    simplex: &Simplex,
    scale: f64,
) -> Result<(), Coords> {
    let n = simplex.n;
    ws.clear();
    // An orthonormal basis of the differences from the first point, built as points join.
    let mut basis: SmallVec<[f64; 64]> = SmallVec::new();
    let mut rank = 0;
    let mut e = Coords::from_elem(0.0, n);
    let mut try_add = |ws: &mut EpaWorkspace,
                       basis: &mut SmallVec<[f64; 64]>,
                       rank: &mut usize,
                       w: &[f64],
                       sa: &[f64],
                       sb: &[f64]|
     -> bool {
        if ws.w.is_empty() {
            ws.push_vertex(w, sa, sb);
            return true;
        }
        let y0 = &ws.w[..n];
        for ((x, p), q) in e.iter_mut().zip(w).zip(y0) {
            *x = p - q;
        }
        orthogonalize_twice(&mut e, basis, *rank);
        let r = e.iter().map(|x| x * x).sum::<f64>().sqrt();
        if r > 1e-10 * scale {
            basis.extend(e.iter().map(|x| x / r));
            *rank += 1;
            ws.push_vertex(w, sa, sb);
            true
        } else {
            false
        }
    };
    for k in 0..simplex.count {
        let range = k * n..(k + 1) * n;
        try_add(
            ws,
            &mut basis,
            &mut rank,
            &simplex.w[range.clone()],
            &simplex.a[range.clone()],
            &simplex.b[range],
        );
    }
    let (mut w, mut sa, mut sb) = (
        Coords::from_elem(0.0, n),
        Coords::from_elem(0.0, n),
        Coords::from_elem(0.0, n),
    );
    let mut u = Coords::from_elem(0.0, n);
    while rank < n {
        // The coordinate axis farthest from the span, made orthogonal to it.
        let mut best = (0.0, 0);
        for axis in 0..n {
            let mut s = 1.0;
            for l in 0..rank {
                s -= basis[l * n + axis] * basis[l * n + axis];
            }
            if s > best.0 {
                best = (s, axis);
            }
        }
        u.iter_mut().for_each(|x| *x = 0.0);
        u[best.1] = 1.0;
        orthogonalize_twice(&mut u, &basis, rank);
        let r = u.iter().map(|x| x * x).sum::<f64>().sqrt();
        u.iter_mut().for_each(|x| *x /= r);
        let mut added = false;
        // Both ways along u, the farther first.
        // How far the support point w reaches past the first vertex along u.
        let reach = |u: &[f64], w: &[f64]| -> f64 {
            u.iter()
                .zip(w)
                .zip(&ws.w[..n])
                .map(|((p, q), y)| p * (q - y))
                .sum()
        };
        support_difference(a, b, &u, &mut w, &mut sa, &mut sb);
        let reach_up = reach(&u, &w);
        let (mut w2, mut sa2, mut sb2) = (w.clone(), sa.clone(), sb.clone());
        u.iter_mut().for_each(|x| *x = -*x);
        support_difference(a, b, &u, &mut w2, &mut sa2, &mut sb2);
        let reach_down = reach(&u, &w2);
        let order = if reach_up >= reach_down {
            [(&w, &sa, &sb), (&w2, &sa2, &sb2)]
        } else {
            [(&w2, &sa2, &sb2), (&w, &sa, &sb)]
        };
        for (p, q, s) in order {
            if try_add(ws, &mut basis, &mut rank, p, q, s) {
                added = true;
                break;
            }
        }
        if !added {
            return Err(u);
        }
    }
    widen_flat_facets(ws, a, b, n, scale)
}

/// Points join the first simplex by their distance from the span of those before them, so
/// a later point can leave an earlier one nearly in the plane of the rest. Each facet must
/// stand clear of its opposite vertex by more than [`FLAT_FACET`] of the size (the
/// facets are oriented by it); one that does not is widened: its opposite vertex is
/// replaced by K's support point along the facet's normal, either way, farther from its
/// plane. If K itself is flat across the facet (its width there within 1e-10 of the
/// size, as [`initial_simplex`] asks of each point), Err with that direction.
fn widen_flat_facets(
    ws: &mut EpaWorkspace,
    a: &PlacedShape,
    b: &PlacedShape,
    n: usize,
    scale: f64,
) -> Result<(), Coords> {
    let mut normal = Coords::from_elem(0.0, n);
    let mut vertices: SmallVec<[u32; 9]> = SmallVec::new();
    let (mut w, mut sa, mut sb) = (
        Coords::from_elem(0.0, n),
        Coords::from_elem(0.0, n),
        Coords::from_elem(0.0, n),
    );
    // Each widening moves a vertex at least 1e-10 of the size off its facet's plane, so
    // a facet is widened at most once unless round-off undoes it: the bound ends the loop.
    for _ in 0..2 * (n + 1) {
        let Some(skip) = (0..=n).find(|&skip| {
            vertices.clear();
            vertices.extend((0..=n as u32).filter(|k| *k != skip as u32));
            let opposite = &ws.w[skip * n..(skip + 1) * n];
            facet_plane(&ws.w, n, &vertices, opposite, scale, &mut normal).is_none()
        }) else {
            return Ok(());
        };
        // The facet's normal, up to sign: the complement of its edges.
        let point = |k: u32| &ws.w[k as usize * n..(k as usize + 1) * n];
        let mut basis: SmallVec<[f64; 64]> = SmallVec::new();
        let mut rank = 0;
        let mut e = Coords::from_elem(0.0, n);
        for &k in &vertices[1..] {
            for ((x, p), q) in e.iter_mut().zip(point(k)).zip(point(vertices[0])) {
                *x = p - q;
            }
            orthogonalize_twice(&mut e, &basis, rank);
            let r = e.iter().map(|x| x * x).sum::<f64>().sqrt();
            if r > FLAT_FACET * scale {
                basis.extend(e.iter().map(|x| x / r));
                rank += 1;
            }
        }
        let axis = (0..n)
            .max_by(|&i, &j| {
                let off = |axis: usize| -> f64 {
                    1.0 - (0..rank).map(|l| basis[l * n + axis].powi(2)).sum::<f64>()
                };
                off(i).total_cmp(&off(j))
            })
            .unwrap_or(0);
        normal.iter_mut().for_each(|x| *x = 0.0);
        normal[axis] = 1.0;
        orthogonalize_twice(&mut normal, &basis, rank);
        let r = normal.iter().map(|x| x * x).sum::<f64>().sqrt();
        normal.iter_mut().for_each(|x| *x /= r);
        // K's extent either way from the facet's plane.
        let y0 = Coords::from_slice(point(vertices[0]));
        let height = |u: &[f64], w: &[f64]| -> f64 {
            u.iter()
                .zip(w)
                .zip(&y0)
                .map(|((p, q), y)| p * (q - y))
                .sum()
        };
        support_difference(a, b, &normal, &mut w, &mut sa, &mut sb);
        let up = height(&normal, &w);
        let mut minus = normal.clone();
        minus.iter_mut().for_each(|x| *x = -*x);
        let (mut w2, mut sa2, mut sb2) = (w.clone(), sa.clone(), sb.clone());
        support_difference(a, b, &minus, &mut w2, &mut sa2, &mut sb2);
        let down = height(&minus, &w2);
        if up + down <= 1e-10 * scale {
            return Err(normal);
        }
        let (w, sa, sb) = if up >= down {
            (&w, &sa, &sb)
        } else {
            (&w2, &sa2, &sb2)
        };
        ws.w[skip * n..(skip + 1) * n].copy_from_slice(w);
        ws.a[skip * n..(skip + 1) * n].copy_from_slice(sa);
        ws.b[skip * n..(skip + 1) * n].copy_from_slice(sb);
    }
    Err(normal)
}

/// Moves two witnesses half each so that witness_b − witness_a = depth · normal.
fn meet(witness_a: &mut [f64], witness_b: &mut [f64], depth: f64, normal: &[f64]) {
    for ((p, q), m) in witness_a.iter_mut().zip(witness_b.iter_mut()).zip(normal) {
        let half_correction = (depth * m - (*q - *p)) / 2.0;
        *p -= half_correction;
        *q += half_correction;
    }
}

/// EPA on the cores, from GJK's result.
fn epa_cores(
    ws: &mut EpaWorkspace,
    a: &PlacedShape,
    b: &PlacedShape,
    result: &GjkResult,
) -> CoreContact {
    let n = result.simplex.n;
    let scale = result.scale.max(f64::MIN_POSITIVE);
    let curved = curved(a, b);
    let simplex = &result.simplex;
    if let Err(flat) = initial_simplex(ws, a, b, simplex, scale) {
        // K is flat across `flat`: the cores separate by any move along it.
        let mut witness_a = Coords::from_elem(0.0, n);
        let mut witness_b = Coords::from_elem(0.0, n);
        simplex.witnesses(&mut witness_a, &mut witness_b);
        return CoreContact {
            depth: 0.0,
            normal_k: flat,
            witness_a,
            witness_b,
            iterations: 0,
        };
    }
    // A point strictly inside the first simplex (and so inside every later polytope).
    let mut inside = Coords::from_elem(0.0, n);
    for k in 0..=n {
        for (x, y) in inside.iter_mut().zip(&ws.w[k * n..(k + 1) * n]) {
            *x += y / (n + 1) as f64;
        }
    }
    let mut normal = Coords::from_elem(0.0, n);
    let mut vertices: SmallVec<[u32; 9]> = SmallVec::new();
    for skip in 0..=n as u32 {
        vertices.clear();
        vertices.extend((0..=n as u32).filter(|k| *k != skip));
        // Oriented away from the opposite vertex, which `widen_flat_facets` keeps clear.
        let opposite = Coords::from_slice(&ws.w[skip as usize * n..(skip as usize + 1) * n]);
        let offset = facet_plane(&ws.w, n, &vertices, &opposite, scale, &mut normal)
            .expect("widen_flat_facets keeps every first facet clear of its opposite vertex");
        ws.facets.extend_from_slice(&vertices);
        ws.normals.extend_from_slice(&normal);
        ws.offsets.push(offset);
    }
    let (mut w, mut sa, mut sb) = (
        Coords::from_elem(0.0, n),
        Coords::from_elem(0.0, n),
        Coords::from_elem(0.0, n),
    );
    let mut iterations = 0;
    let nearest_facet = |ws: &EpaWorkspace| {
        let mut best = (f64::INFINITY, 0);
        for (f, &o) in ws.offsets.iter().enumerate() {
            if o < best.0 {
                best = (o, f);
            }
        }
        best.1
    };
    let mut f = nearest_facet(ws);
    // The nearest facet's distance never decreases on an exact polytope (each step removes
    // facets and puts ones farther out in their place). Round-off can bend the polytope
    // (thin facets seen wrongly, see below) so that it falls, and the expansion mostly
    // recovers; the farthest nearest facet so far is kept (its vertices, normal and
    // offset) for an expansion that ends below it.
    let mut highest: SmallVec<[u32; 9]> = SmallVec::new();
    let mut highest_normal = Coords::from_elem(0.0, n);
    let mut highest_offset = f64::NEG_INFINITY;
    // Each support query along a unit normal gives an upper bound of the depth, the
    // translation along it that separates the cores; the least one is kept with its
    // normal and support points, for a polytope that round-off has pushed beyond it.
    let mut least_reach = f64::INFINITY;
    let mut least_reach_normal = Coords::from_elem(0.0, n);
    let mut least_reach_facet: SmallVec<[u32; 9]> = SmallVec::new();
    let mut least_reach_offset = 0.0;
    let mut made = 0;
    // Whether the expansion ends at one of its caps (iterations, facets, facet planes)
    // rather than converged or stopped by round-off.
    let mut capped = true;
    while iterations < MAX_EPA_ITERATIONS && made <= MAX_EPA_MADE {
        if ws.offsets[f] > highest_offset {
            highest_offset = ws.offsets[f];
            highest.clear();
            highest.extend_from_slice(&ws.facets[f * n..(f + 1) * n]);
            highest_normal.copy_from_slice(&ws.normals[f * n..(f + 1) * n]);
        }
        let nf = Coords::from_slice(&ws.normals[f * n..(f + 1) * n]);
        let offset = ws.offsets[f];
        support_difference(a, b, &nf, &mut w, &mut sa, &mut sb);
        let reach: f64 = nf.iter().zip(&w).map(|(p, q)| p * q).sum();
        if reach < least_reach {
            least_reach = reach;
            least_reach_normal.copy_from_slice(&nf);
            least_reach_facet.clear();
            least_reach_facet.extend_from_slice(&ws.facets[f * n..(f + 1) * n]);
            least_reach_offset = offset;
        }
        if reach - offset <= CONVERGED * scale
            || curved && least_reach - offset <= CURVED_CONVERGED * scale
        {
            capped = false;
            break;
        }
        iterations += 1;
        // The facets that see w, and their horizon.
        ws.visible.clear();
        for g in 0..ws.offsets.len() {
            let ng = &ws.normals[g * n..(g + 1) * n];
            let height = ng.iter().zip(&w).map(|(p, q)| p * q).sum::<f64>() - ws.offsets[g];
            if height > VISIBLE * scale {
                ws.visible.push(g);
            }
        }
        if !ws.visible.contains(&f) {
            capped = false;
            break;
        }
        // The cone from w over the horizon. A cone facet that would be degenerate (w in
        // the affine hull of its horizon ridge, to round-off) means that w lies in the
        // plane of the facet beyond that ridge as well, which a thin facet's round-off
        // kept from counting as seen: that facet, if w lies on its plane to [`COPLANAR`],
        // is taken as seen (coplanar facets merge) and the horizon is found again. Each
        // retry adds a facet to the seen ones, so the retries end; a degenerate facet with
        // no such neighbour ends the expansion.
        let new_index = (ws.w.len() / n) as u32;
        ws.w.extend_from_slice(&w);
        let mut degenerate = false;
        loop {
            horizon(ws, n);
            ws.new_facets.clear();
            ws.new_normals.clear();
            ws.new_offsets.clear();
            let mut flat_ridge = None;
            for r in 0..ws.ridge_counts.len() {
                if ws.ridge_counts[r] != 1 {
                    continue;
                }
                vertices.clear();
                vertices.extend_from_slice(&ws.ridges[r * (n - 1)..(r + 1) * (n - 1)]);
                vertices.push(new_index);
                made += 1;
                match facet_plane(&ws.w, n, &vertices, &inside, scale, &mut normal) {
                    Some(o) => {
                        ws.new_facets.extend_from_slice(&vertices);
                        ws.new_normals.extend_from_slice(&normal);
                        ws.new_offsets.push(o);
                    }
                    None => {
                        flat_ridge = Some(r);
                        break;
                    }
                }
            }
            let Some(r) = flat_ridge else {
                break;
            };
            if made > MAX_EPA_MADE {
                degenerate = true;
                break;
            }
            let ridge = &ws.ridges[r * (n - 1)..(r + 1) * (n - 1)];
            let beyond = (0..ws.offsets.len()).find(|g| {
                !ws.visible.contains(g)
                    && ridge
                        .iter()
                        .all(|x| ws.facets[g * n..(g + 1) * n].contains(x))
            });
            // Only a facet that w lies on, to round-off, merges: removing one that w lies
            // below would dent the polytope.
            let beyond = beyond.filter(|&g| {
                let ng = &ws.normals[g * n..(g + 1) * n];
                let height = ng.iter().zip(&w).map(|(p, q)| p * q).sum::<f64>() - ws.offsets[g];
                height >= -COPLANAR * scale
            });
            match beyond {
                Some(g) => ws.visible.push(g),
                None => {
                    degenerate = true;
                    break;
                }
            }
        }
        // The polytope holds the origin (GJK found it inside K), so every facet's plane
        // passes beyond it: a new facet with the origin outside shows that round-off has
        // bent the polytope (thin facets seen wrongly), and the expansion stops before it.
        let bent = ws.new_offsets.iter().any(|o| *o < -COPLANAR * scale);
        let facets_after = ws.offsets.len() - ws.visible.len() + ws.new_offsets.len();
        if degenerate || bent || ws.new_offsets.is_empty() || facets_after > MAX_EPA_FACETS {
            ws.w.truncate(new_index as usize * n);
            capped = facets_after > MAX_EPA_FACETS || made > MAX_EPA_MADE;
            break;
        }
        ws.a.extend_from_slice(&sa);
        ws.b.extend_from_slice(&sb);
        // Remove the visible facets (in decreasing order, by swapping in the last) and
        // add the new ones.
        ws.visible.sort_unstable();
        for vi in (0..ws.visible.len()).rev() {
            let g = ws.visible[vi];
            let last = ws.offsets.len() - 1;
            if g != last {
                for k in 0..n {
                    ws.facets[g * n + k] = ws.facets[last * n + k];
                    ws.normals[g * n + k] = ws.normals[last * n + k];
                }
                ws.offsets[g] = ws.offsets[last];
            }
            ws.facets.truncate(last * n);
            ws.normals.truncate(last * n);
            ws.offsets.truncate(last);
        }
        ws.facets.extend_from_slice(&ws.new_facets);
        ws.normals.extend_from_slice(&ws.new_normals);
        ws.offsets.extend_from_slice(&ws.new_offsets);
        f = nearest_facet(ws);
    }
    // The facet EPA ends with: the nearest one, or the farthest nearest facet met if the
    // polytope ended more than [`FALL`] of the size below it.
    let (chosen, nf, offset) = if ws.offsets[f] < highest_offset - FALL * scale {
        (highest, highest_normal, highest_offset)
    } else {
        (
            SmallVec::from_slice(&ws.facets[f * n..(f + 1) * n]),
            Coords::from_slice(&ws.normals[f * n..(f + 1) * n]),
            ws.offsets[f],
        )
    };
    // Above 4D the facets of K outgrow the caps, and an expansion stopped at one can leave
    // its nearest facet far below the depth: a lower bound, and a translation by it along
    // its normal need not separate the cores (on random 6D pairs the translation that does
    // was up to a third of the size longer). The least support reach does separate them
    // (an upper bound of the depth), and is the answer there where the two bounds are
    // farther apart than the precision the detection promises. Up to 4D the caps are met
    // only where round-off bends the polytope of very unequal shapes, whose nearest facet
    // stays within 1e-7 of the size of the depth while the reach may lie farther above
    // (`tests/reliability/fuzz_regressions.rs`). Where the bounds are apart, the least over
    // the normals of the faces' directions taken together is the depth.
    let capped = capped && n >= 5 && !curved && least_reach > offset + CURVED_CONVERGED * scale;
    if capped {
        let mut reach_along = |u: &[f64]| {
            support_difference(a, b, u, &mut w, &mut sa, &mut sb);
            dot(u, &w)
        };
        if let Some((depth, u)) =
            least_over_face_pairs(a, b, &mut reach_along).filter(|(depth, _)| *depth < least_reach)
        {
            let depth = depth.max(0.0);
            // Points of the two faces, else (a face beyond the linear program's size) the
            // support points.
            let (mut witness_a, mut witness_b) = face_witnesses(a, b, (depth, &u), scale)
                .unwrap_or_else(|| {
                    support_difference(a, b, &u, &mut w, &mut sa, &mut sb);
                    (sa.clone(), sb.clone())
                });
            meet(&mut witness_a, &mut witness_b, depth, &u);
            return CoreContact {
                depth,
                normal_k: u,
                witness_a,
                witness_b,
                iterations,
            };
        }
    }
    if capped || offset > least_reach + FALL * scale {
        // The polytope reached beyond K (or stopped at a cap): the least support reach is
        // the answer. The witnesses are those of the facet it was queried from, moved half
        // each so that witness_b − witness_a = depth · normal_k (the facet's plane lies
        // below the reach, and the origin's projection may fall outside the facet).
        let (mut witness_a, mut witness_b) = facet_witnesses(
            ws,
            n,
            &least_reach_facet,
            &least_reach_normal,
            least_reach_offset,
            scale,
        );
        let depth = least_reach.max(0.0);
        meet(&mut witness_a, &mut witness_b, depth, &least_reach_normal);
        return CoreContact {
            depth,
            normal_k: least_reach_normal,
            witness_a,
            witness_b,
            iterations,
        };
    }
    let (mut witness_a, mut witness_b) = facet_witnesses(ws, n, &chosen, &nf, offset, scale);
    if curved {
        // Stopped on its bounds rather than on the facet, the origin's projection may fall
        // outside the facet: the witnesses are moved half each so that witness_b −
        // witness_a = depth · normal_k, as for the least reach above.
        meet(&mut witness_a, &mut witness_b, offset.max(0.0), &nf);
    }
    CoreContact {
        depth: offset.max(0.0),
        normal_k: nf,
        witness_a,
        witness_b,
        iterations,
    }
}

/// The witnesses of the facet `chosen` (N vertex indices) with unit normal `nf` and offset
/// `offset`: the weights of the origin's projection onto its plane. Coplanar facets share
/// the plane and the projection lies in one of them; the facet where it lies deepest gives
/// weights ≥ 0 (clamped against round-off), so the witnesses are points of the shapes and
/// witness_a − witness_b = depth · normal.
fn facet_witnesses(
    ws: &EpaWorkspace,
    n: usize,
    chosen: &[u32],
    nf: &[f64],
    offset: f64,
    scale: f64,
) -> (Coords, Coords) {
    let mut points: Points = Points::from_elem(0.0, n * n);
    let mut best: Option<(f64, SmallVec<[u32; 9]>, super::gjk::Weights)> = None;
    let coplanar = (0..ws.offsets.len()).filter(|&g| {
        let parallel: f64 = ws.normals[g * n..(g + 1) * n]
            .iter()
            .zip(nf)
            .map(|(p, q)| p * q)
            .sum();
        parallel >= 1.0 - 1e-9 && ws.offsets[g] <= offset + CONVERGED * scale
    });
    let candidates = std::iter::once(SmallVec::from_slice(chosen))
        .chain(coplanar.map(|g| SmallVec::from_slice(&ws.facets[g * n..(g + 1) * n])));
    for vertices in candidates {
        for (k, &v) in vertices.iter().enumerate() {
            let v = v as usize;
            points[k * n..(k + 1) * n].copy_from_slice(&ws.w[v * n..(v + 1) * n]);
        }
        if let Some((lambda, _)) = project_onto_face(&points, n, (1u128 << n) - 1) {
            let least = lambda.iter().copied().fold(f64::INFINITY, f64::min);
            if best.as_ref().is_none_or(|(l, _, _)| least > *l) {
                best = Some((least, vertices, lambda));
            }
        }
    }
    let (vertices, lambda) = match best {
        Some((_, vertices, mut lambda)) => {
            lambda.iter_mut().for_each(|l| *l = l.max(0.0));
            let total: f64 = lambda.iter().sum();
            lambda.iter_mut().for_each(|l| *l /= total);
            (vertices, lambda)
        }
        None => {
            for (k, &v) in chosen.iter().enumerate() {
                let v = v as usize;
                points[k * n..(k + 1) * n].copy_from_slice(&ws.w[v * n..(v + 1) * n]);
            }
            (
                SmallVec::from_slice(chosen),
                nearest_point(&points, n, n).lambda,
            )
        }
    };
    let mut witness_a = Coords::from_elem(0.0, n);
    let mut witness_b = Coords::from_elem(0.0, n);
    for (&v, &l) in vertices.iter().zip(lambda.iter()) {
        let v = v as usize;
        for j in 0..n {
            witness_a[j] += l * ws.a[v * n + j];
            witness_b[j] += l * ws.b[v * n + j];
        }
    }
    (witness_a, witness_b)
}

fn vector(x: &[f64]) -> Vector {
    Vector::from_storage(Coords::from_slice(x))
}

/// Ball (core a point) against ball, or against a cuboid; None for other pairs.
fn closed_form(a: &PlacedShape, b: &PlacedShape) -> Option<Penetration> {
    let (ra, rb) = (a.shape().margin(), b.shape().margin());
    match (a.shape().core(), b.shape().core()) {
        (ConvexCore::Point, ConvexCore::Point) => {
            let normal = centre_direction(a, b);
            let gap: f64 = normal
                .as_slice()
                .iter()
                .zip(b.position().iter().zip(a.position()))
                .map(|(m, (p, q))| m * (p - q))
                .sum();
            Some(Penetration::from_cores(
                -gap,
                normal,
                vector(a.position()),
                vector(b.position()),
                (ra, rb),
                0,
            ))
        }
        (ConvexCore::Cuboid(h), _) => box_and_ball(a, b, (Some(h), None)),
        (_, ConvexCore::Cuboid(h)) => box_and_ball(a, b, (None, Some(h))),
        _ => None,
    }
}

/// The closed form of a box and a ball, either way round; `half_lengths` are those of A
/// or B when it is a box (a cuboid core, or a hull that detection knows to hold a box's
/// corners). None unless one is a box and the other's core a point.
pub(crate) fn box_and_ball(
    a: &PlacedShape,
    b: &PlacedShape,
    half_lengths: (Option<&[f64]>, Option<&[f64]>),
) -> Option<Penetration> {
    let n = a.shape().dim();
    match (half_lengths, a.shape().core(), b.shape().core()) {
        ((Some(h), _), _, ConvexCore::Point) => Some(box_ball(a, h, b, n)),
        ((_, Some(h)), ConvexCore::Point, _) => {
            let mut p = box_ball(b, h, a, n);
            p.normal.as_mut_slice().iter_mut().for_each(|x| *x = -*x);
            std::mem::swap(&mut p.witness_a, &mut p.witness_b);
            Some(p)
        }
        _ => None,
    }
}

/// A cuboid (A, half-lengths `h`, any margin) against a ball (B).
fn box_ball(a: &PlacedShape, h: &[f64], b: &PlacedShape, n: usize) -> Penetration {
    let (ra, rb) = (a.shape().margin(), b.shape().margin());
    let q = a.rotation();
    // The ball's centre in the box's axes.
    let mut c = Coords::from_elem(0.0, n);
    for i in 0..n {
        let d = b.position()[i] - a.position()[i];
        for (j, x) in c.iter_mut().enumerate() {
            *x += q[i * n + j] * d;
        }
    }
    let mut nearest = Coords::from_elem(0.0, n);
    for ((p, x), hi) in nearest.iter_mut().zip(&c).zip(h) {
        *p = x.clamp(-hi, *hi);
    }
    let outside: f64 = c
        .iter()
        .zip(&nearest)
        .map(|(x, p)| (x - p) * (x - p))
        .sum::<f64>()
        .sqrt();
    let mut normal_own = Coords::from_elem(0.0, n);
    let core_depth;
    if outside > 0.0 {
        for ((m, x), p) in normal_own.iter_mut().zip(&c).zip(&nearest) {
            *m = (x - p) / outside;
        }
        core_depth = -outside;
    } else {
        // Inside: out through the nearest face.
        let (mut axis, mut room) = (0, f64::INFINITY);
        for (i, (x, hi)) in c.iter().zip(h).enumerate() {
            if hi - x.abs() < room {
                room = hi - x.abs();
                axis = i;
            }
        }
        let side = if c[axis] < 0.0 { -1.0 } else { 1.0 };
        normal_own[axis] = side;
        nearest[axis] = side * h[axis];
        core_depth = room;
    }
    let mut normal = Vector::zero(n);
    let mut witness_a = vector(a.position());
    for i in 0..n {
        let row = &q[i * n..(i + 1) * n];
        normal.as_mut_slice()[i] = row.iter().zip(&normal_own).map(|(p, m)| p * m).sum();
        witness_a.as_mut_slice()[i] += row.iter().zip(&nearest).map(|(p, m)| p * m).sum::<f64>();
    }
    let witness_b = vector(b.position());
    Penetration::from_cores(core_depth, normal, witness_a, witness_b, (ra, rb), 0)
}

/// Returns the signed penetration depth of two placed shapes, the contact normal from A
/// to B and the witness points, with a fresh workspace (see [`penetration_with`] to
/// reuse one).
///
/// # Errors
/// [`ShapeError::DimensionMismatch`] if the shapes differ in dimension.
pub fn penetration(a: &PlacedShape, b: &PlacedShape) -> Result<Penetration, ShapeError> {
    penetration_with(&mut EpaWorkspace::new(), a, b)
}

/// Returns the signed penetration depth of two placed shapes (> 0 overlap, ≤ 0 minus the
/// distance), the contact normal from A to B and the witness points: closed forms for
/// ball–ball and ball–cuboid, GJK for separated cores, EPA on the cores for overlapping
/// ones, the margins added. Bounded (at most 128 GJK iterations, 512 on ellipsoid cores, and
/// 256 EPA iterations, 4096 facets at a time and 32,768 facet planes in all),
/// never NaN. EPA is exact for polytopes up to N = 4, to the round-off of the thin facets
/// of very unequal shapes (a slab 1/16 thick in a polytope of size 4e5 came out 4e-8 of the
/// size short, `tests/reliability/fuzz_regressions.rs`); above, its caps can stop it with
/// its nearest facet more than 1e-9 of the size below its least support reach, and the
/// depth is then the least translation along the normals of every set of N − 1 independent
/// directions of the two polytopes' faces (`face_pairs.rs`: the separating-axis test
/// generalised from boxes, exact; pairs of up to 2¹⁹ such sets, such as two 6D
/// cross-polytopes), else that reach (a translation that separates the shapes: an upper
/// bound of the depth). On 10⁶ random pairs of every kind no polytope pair lies above the
/// least translation among the test's directions by more than 1e-9 of its size.
/// Where one core is an ellipsoid, EPA approximates it by facets and its normal is
/// inexact: it starts Newton's method on the sphere of directions for the least separating
/// translation (`smooth.rs`), which gives the exact depth, normal and witnesses against an
/// ellipsoid or a ball (from more starts when the minimum lies above EPA's lower bound by
/// more than 1e-9 of the size). Against a polytope or a segment the steps run face by
/// face, and where the least they find is not within 1e-9 of the size of EPA's lower bound,
/// the least over the feet of normals on the planes of all the polytope's faces is taken
/// (`face_planes.rs`, exact; polytopes of at most 8,192 face planes); where it is within
/// that, the normal is refined on the planes of the polytope's faces near its support
/// along it (against a vertex or an edge the translation is smooth in the normal, which is
/// then known only to the square root of the tolerance), so that both witnesses lie on
/// their shapes. The depth is the translation along the normal found, never below the
/// least (where it ends below EPA's depth by round-off, as where the shapes only touch,
/// the depth is EPA's and the normal the refined one). On 10⁶ random pairs of every kind
/// (`tests/reliability/narrow_phase.rs` prints the figures) none of the 85,974 such pairs
/// exceeded the least translation among the test's directions by more than 1e-9 of its
/// size (at most 5.7e-16 in 2D to 6D), and every overlapping pair's witnesses lie on
/// their shapes, depth · normal apart, to 1e-9 of the size.
///
/// ```
/// use rotorflow::dynamics::motion::detect::{EpaWorkspace, PlacedShape, penetration_with};
/// use rotorflow::dynamics::motion::shape::ConvexShape;
/// let tesseract = ConvexShape::cuboid(&[1.0; 4])?;
/// let identity: Vec<f64> = (0..16).map(|k| if k % 5 == 0 { 1.0 } else { 0.0 }).collect();
/// let a = PlacedShape::new(&tesseract, &[0.0; 4], &identity)?;
/// let b = PlacedShape::new(&tesseract, &[0.0, 0.0, 1.75, 0.1], &identity)?;
/// let mut workspace = EpaWorkspace::new();
/// let contact = penetration_with(&mut workspace, &a, &b)?;
/// assert!((contact.depth - 0.25).abs() < 1e-12);
/// assert!((contact.normal.as_slice()[2] - 1.0).abs() < 1e-12);
/// # Ok::<(), rotorflow::dynamics::motion::shape::ShapeError>(())
/// ```
///
/// # Errors
/// [`ShapeError::DimensionMismatch`] if the shapes differ in dimension.
pub fn penetration_with(
    workspace: &mut EpaWorkspace,
    a: &PlacedShape,
    b: &PlacedShape,
) -> Result<Penetration, ShapeError> {
    let n = check_pair(a, b)?;
    if let Some(p) = closed_form(a, b) {
        return Ok(p);
    }
    let (ra, rb) = (a.shape().margin(), b.shape().margin());
    let result = gjk(a, b);
    let mut normal = Vector::zero(n);
    let mut witness_a = Vector::zero(n);
    let mut witness_b = Vector::zero(n);
    // A pair GJK left stuck beside the origin is asked of EPA too; an origin outside K
    // gives EPA's polytope a facet behind it and depth 0, and the pair is then apart.
    let overlap = if result.intersecting || result.undecided {
        let core = epa_cores(workspace, a, b, &result);
        (result.intersecting || core.depth > 0.0).then_some(core)
    } else {
        None
    };
    let (core_depth, iterations) = if let Some(core) = overlap {
        for (x, y) in normal.as_mut_slice().iter_mut().zip(&core.normal_k) {
            *x = -y;
        }
        let exact = smooth_depth(a, b, normal.as_slice(), core.depth).or_else(|| {
            let start = normal.as_slice();
            polytope_depth(a, b, start, core.depth, &mut workspace.faces)
        });
        // EPA's depth is a lower bound and Newton's an upper one: one below the other by
        // more than the precision the detection promises is not taken. Below it by less is
        // round-off (cores that only touch): the depth is EPA's, and the normal Newton's,
        // for EPA's facet through a point where a curved core touches may lean far from the
        // surface's normal (a 4D hull touching an ellipsoid: a translation of 3.6e-7 of the
        // size along EPA's normal where Newton's is 3e-16 short of 0).
        let slack = CURVED_CONVERGED * result.scale;
        if let Some(exact) = exact.filter(|e| e.depth.is_finite() && e.depth >= core.depth - slack)
        {
            normal.as_mut_slice().copy_from_slice(&exact.normal);
            witness_a.as_mut_slice().copy_from_slice(&exact.witness_a);
            witness_b.as_mut_slice().copy_from_slice(&exact.witness_b);
            let depth = exact.depth.max(core.depth);
            if depth > exact.depth {
                // witness_a − witness_b = depth · normal, as `meet` keeps it (which takes
                // the normal of K, from B to A).
                let towards_a: Coords = exact.normal.iter().map(|x| -x).collect();
                meet(
                    witness_a.as_mut_slice(),
                    witness_b.as_mut_slice(),
                    depth,
                    &towards_a,
                );
            }
            (depth, result.iterations + core.iterations)
        } else {
            witness_a.as_mut_slice().copy_from_slice(&core.witness_a);
            witness_b.as_mut_slice().copy_from_slice(&core.witness_b);
            (core.depth, result.iterations + core.iterations)
        }
    } else {
        let length = result.vv.sqrt();
        for (x, y) in normal.as_mut_slice().iter_mut().zip(&result.v) {
            *x = y / length;
        }
        result
            .simplex
            .witnesses(witness_a.as_mut_slice(), witness_b.as_mut_slice());
        (-length, result.iterations)
    };
    Ok(Penetration::from_cores(
        core_depth,
        normal,
        witness_a,
        witness_b,
        (ra, rb),
        iterations,
    ))
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{box_corners, random_rotation};
    use super::*;
    use crate::dynamics::motion::shape::ConvexShape;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A ball against a box given by its corners (a hull, as detection meets the catalogue's
    /// cuboids): the closed form detection takes for the pair gives what GJK and EPA give
    /// on the hull, N = 2 … 4, apart and with the centre inside the box, either way round.
    #[test]
    fn a_ball_against_the_corners_of_a_box_is_the_closed_form_of_gjk_and_epa() {
        let mut r = ChaCha8Rng::seed_from_u64(11);
        let mut workspace = EpaWorkspace::new();
        let (mut apart, mut inside) = (0, 0);
        for n in 2..=4usize {
            for _ in 0..300 {
                let h: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..1.5)).collect();
                let hull = ConvexShape::hull(&box_corners(&h)).unwrap();
                let ball = ConvexShape::ball(n, r.gen_range(0.1..1.0)).unwrap();
                let q = random_rotation(&mut r, n);
                let pa: Vec<f64> = (0..n).map(|_| r.gen_range(-0.5..0.5)).collect();
                let pb: Vec<f64> = pa.iter().map(|x| x + r.gen_range(-2.0..2.0)).collect();
                let a = PlacedShape::new(&hull, &pa, &q).unwrap();
                let b = PlacedShape::new(&ball, &pb, &q).unwrap();
                let general = penetration_with(&mut workspace, &a, &b).unwrap();
                assert!(general.iterations > 0, "GJK ran on the hull");
                let fast = box_and_ball(&a, &b, (Some(&h), None)).unwrap();
                let swapped = box_and_ball(&b, &a, (None, Some(&h))).unwrap();
                assert!((fast.depth - general.depth).abs() < 1e-9, "N = {n}");
                assert_eq!(swapped.depth, fast.depth);
                // (closed form, GJK and EPA, sign): the swapped pair's normal is reversed.
                for (x, y, sign) in [
                    (&fast.normal, &general.normal, 1.0),
                    (&swapped.normal, &general.normal, -1.0),
                    (&fast.witness_a, &general.witness_a, 1.0),
                    (&swapped.witness_b, &general.witness_a, 1.0),
                    (&fast.witness_b, &general.witness_b, 1.0),
                ] {
                    let mut pairs = x.as_slice().iter().zip(y.as_slice());
                    assert!(pairs.all(|(p, q)| (p - sign * q).abs() < 1e-9), "N = {n}");
                }
                // Where the ball's centre lies inside the box, both go out through its
                // nearest face.
                let inside_box = fast.depth > ball.margin();
                apart += usize::from(fast.depth < 0.0);
                inside += usize::from(inside_box);
            }
        }
        assert!(
            apart > 200 && inside > 50,
            "{apart} apart, {inside} centres inside"
        );
    }
}
