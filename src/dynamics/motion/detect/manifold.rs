//! Contact manifolds: the several points at which two bodies touch, so that a box resting
//! on a box is held at the corners of its contact region rather than at one point.
//!
//! For boxes ([`box_manifold`]) the separating-axis query ([`super::box_box`]) names the
//! features in contact. A face axis makes that face the *reference face* and the face of
//! the other box most anti-parallel to it the *incident face*, an (N − 1)-cube. The contact
//! region is the part of the incident face over the reference face: the incident cube cut
//! by the 2(N − 1) side half-spaces of the reference face. Each vertex of that polytope is
//! where a k-face of the incident cube meets an (N − 1 − k)-face of the reference face
//! (k = 0: incident vertices over the face; k = N − 1: reference vertices under the
//! incident face; in between, edges through side planes, and from 4D on, 2-faces through
//! reference edges and so on). All these pairs are solved, so every vertex of the region is
//! found in every dimension ([`box_contact_vertices`]); the points below the reference face
//! (depth ≥ −margin) are kept. A cell axis (an edge–edge axis in 3D) means two cells of
//! complementary dimensions cross: one point, the crossing.
//!
//! For convex hulls given by their vertices ([`hull_manifold`]) the same region is the
//! intersection of the two *support sets* (the vertices within a tolerance of each body's
//! supporting plane across the normal) projected into the contact plane. The manifold needs
//! only the points the reduction below keeps, the region's extremes along its directions
//! and its deepest point, and each is the optimum of a small linear program over the
//! barycentric weights of both faces' vertices (up to 64 of each), whatever the faces'
//! shapes: a hexagonal prism's face of 48 vertices in 6D as a square's. Every vertex of
//! the region ([`hull_contact_vertices`]) is the crossing of a simplex of one set with a
//! simplex of the other whose dimensions add up to at most N − 1, found by brute force
//! over the few points ([`support_set_capacity`]) a support set then takes.
//!
//! **Reduction.** The region may have many vertices; a manifold keeps at most
//! [`manifold_capacity`] of them (4 in 3D, 8 in 4D, 16 from 5D on): the extremes of the
//! region along fixed directions of the contact plane: the diagonals (±1, …, ±1) scaled to
//! the reference face, all 2^(N−1) of them up to 5D (the corners of the face), and from 6D
//! the 16 rows of a Hadamard matrix (16 of the face's corners). The directions sum to zero,
//! so for a region that is a box face (an incident face wholly over the reference face, or
//! the reverse) the kept corners have its centre as mean and hold it, which is where a
//! resting box presses; and the deepest point of the region is
//! kept too (replacing the extreme nearest to it) when it is markedly deeper than every kept
//! point, so that a box landing on a corner is pushed back where it penetrates.

use super::sat::{
    AxisFeature, BoxPairAxis, PlacedBox, Relative, box_box_unchecked, cell_axis, dot,
};
use crate::dynamics::DynamicsError;
use crate::dynamics::motion::shape::{ShapeError, check_placement};
use crate::numeric::simplex::{EqualityLp, LP_MAX_COLUMNS, LP_MAX_ROWS, LP_WIDTH, LpEnd};
use crate::numeric::{lu_apply, lu_factor_above};
use smallvec::SmallVec;

/// The most points a manifold holds in any dimension.
pub const MAX_MANIFOLD_POINTS: usize = 16;

/// The most points a manifold holds in `n` dimensions: 2^(N−1) up to 5D (4 in 3D, 8 in 4D),
/// then [`MAX_MANIFOLD_POINTS`].
pub fn manifold_capacity(n: usize) -> usize {
    if n <= 5 {
        1usize << n.saturating_sub(1)
    } else {
        MAX_MANIFOLD_POINTS
    }
}

/// Identifies a contact point by the features of the two shapes that make it, so that a
/// solver can match a point with the point of the previous step and start from its impulse.
///
/// Two manifolds of the same pair of shapes give equal ids to points made by the same
/// features, as long as the same features are in contact:
///
/// - **box faces** (top bits `01`): which box holds the reference face (bit 61), the
///   reference face (own axis in bits 56–59, bit 60 set for the negative side), the
///   incident face (axis in bits 51–54, bit 55 for the negative side), and for each of the
///   N − 1 side axes of the reference face (bits 2t, 2t + 1) and of the incident face (bits
///   2(N−1) + 2u, …): 0 if the point is free along it, 1 or 2 if it lies on the positive or
///   negative side plane (reference) or face (incident);
/// - **box cells** (top bits `10`): the own axes along A's cell (bits 0–9) and B's cell
///   (bits 10–19), and the sides of the fixed coordinates (bits 20–29 for A, 30–39 for B);
/// - **hulls** (top bits `11`): a 62-bit hash of the vertex indices of the two simplices
///   that cross at the point (equal for equal simplices; distinct ones collide with
///   probability about 2⁻⁶²).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FeatureId(pub u64);

const KIND_FACE: u64 = 1 << 62;
const KIND_CELLS: u64 = 2 << 62;
const KIND_HULL: u64 = 3 << 62;

/// One point of a [`ContactManifold`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactPoint<'a> {
    /// The witness point on A, in space.
    pub point_a: &'a [f64],
    /// The witness point on B, in space.
    pub point_b: &'a [f64],
    /// The penetration depth along the normal, n · (point_a − point_b): > 0 overlap.
    pub depth: f64,
    /// The features that make the point.
    pub id: FeatureId,
}

/// The contact of two shapes: one normal (unit, from A to B) and up to
/// [`manifold_capacity`] points, each with its witness points on A and B (space), its depth
/// and its [`FeatureId`]. Stored inline (no heap) for N ≤ 8.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactManifold {
    dim: usize,
    normal: SmallVec<[f64; 8]>,
    points_a: SmallVec<[f64; 128]>,
    points_b: SmallVec<[f64; 128]>,
    depths: SmallVec<[f64; 16]>,
    ids: SmallVec<[FeatureId; 16]>,
}

impl ContactManifold {
    fn new(normal: &[f64]) -> ContactManifold {
        ContactManifold {
            dim: normal.len(),
            normal: SmallVec::from_slice(normal),
            points_a: SmallVec::new(),
            points_b: SmallVec::new(),
            depths: SmallVec::new(),
            ids: SmallVec::new(),
        }
    }

    fn push(&mut self, point_a: &[f64], point_b: &[f64], depth: f64, id: FeatureId) {
        self.points_a.extend_from_slice(point_a);
        self.points_b.extend_from_slice(point_b);
        self.depths.push(depth);
        self.ids.push(id);
    }

    /// The dimension N.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The unit normal in space, from A towards B.
    pub fn normal(&self) -> &[f64] {
        &self.normal
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.depths.len()
    }

    /// True if the manifold has no point.
    pub fn is_empty(&self) -> bool {
        self.depths.is_empty()
    }

    /// Point `k` (0-based).
    ///
    /// # Panics
    /// If `k ≥ len()`.
    pub fn point(&self, k: usize) -> ContactPoint<'_> {
        let n = self.dim;
        ContactPoint {
            point_a: &self.points_a[k * n..(k + 1) * n],
            point_b: &self.points_b[k * n..(k + 1) * n],
            depth: self.depths[k],
            id: self.ids[k],
        }
    }

    /// The points in order.
    pub fn points(&self) -> impl Iterator<Item = ContactPoint<'_>> + '_ {
        (0..self.len()).map(|k| self.point(k))
    }

    /// The largest depth (−∞ when empty).
    pub fn max_depth(&self) -> f64 {
        self.depths
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
    }
}

/// A vertex of the contact region, as [`box_contact_vertices`] reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionVertex<'a> {
    /// The witness point on A, in space.
    pub point_a: &'a [f64],
    /// The witness point on B, in space.
    pub point_b: &'a [f64],
    /// Its coordinates in the contact plane (N − 1 numbers; for face contacts, along the
    /// reference face's own side axes from the reference box's centre).
    pub plane: &'a [f64],
    /// n · (point_a − point_b).
    pub depth: f64,
    /// The features that make it.
    pub id: FeatureId,
}

/// Checks a pair of boxes.
fn check_pair(a: &PlacedBox<'_>, b: &PlacedBox<'_>, margin: f64) -> Result<(), DynamicsError> {
    a.check()?;
    b.check()?;
    if a.dim() != b.dim() {
        return Err(ShapeError::DimensionMismatch {
            what: "box B",
            expected: a.dim(),
            found: b.dim(),
        }
        .into());
    }
    check_margin(margin)
}

/// Checks a contact margin: finite and ≥ 0.
fn check_margin(margin: f64) -> Result<(), DynamicsError> {
    if !margin.is_finite() {
        return Err(ShapeError::NonFinite {
            what: "contact margin",
            value: margin,
        }
        .into());
    }
    if margin < 0.0 {
        return Err(ShapeError::NegativeMargin { margin }.into());
    }
    Ok(())
}

/// Returns the contact manifold of two boxes, or None when they are apart by more than
/// `margin` (points up to `margin` apart are kept, with negative depth, so that a solver
/// can treat contacts about to close).
///
/// # Errors
/// As [`PlacedBox::check`] for either box; [`ShapeError::DimensionMismatch`] if the
/// dimensions differ; [`ShapeError::NonFinite`] or [`ShapeError::NegativeMargin`] for the
/// margin.
pub fn box_manifold(
    a: &PlacedBox<'_>,
    b: &PlacedBox<'_>,
    margin: f64,
) -> Result<Option<ContactManifold>, DynamicsError> {
    check_pair(a, b, margin)?;
    let axis = box_box_unchecked(a, b);
    if axis.depth < -margin {
        return Ok(None);
    }
    let n = a.dim();
    let mut reducer = Reducer::new(n, &axis.normal);
    let scale = a.size().max(b.size()).max(f64::MIN_POSITIVE);
    region(a, b, &axis, margin, &mut |v| reducer.offer(v, scale));
    Ok(Some(reducer.finish(scale)))
}

/// [`box_manifold`] on the separating axis `axis` of the two boxes, found already and
/// within `margin`; the boxes and margin checked by the caller.
pub(crate) fn box_manifold_on_axis(
    a: &PlacedBox<'_>,
    b: &PlacedBox<'_>,
    axis: &BoxPairAxis,
    margin: f64,
) -> ContactManifold {
    let mut reducer = Reducer::new(a.dim(), &axis.normal);
    let scale = a.size().max(b.size()).max(f64::MIN_POSITIVE);
    region(a, b, axis, margin, &mut |v| reducer.offer(v, scale));
    reducer.finish(scale)
}

/// Calls `visit` for every vertex of the contact region of two boxes that lies at depth
/// ≥ −`margin` (all of them, before any reduction), and returns the axis the region was
/// built on; nothing is visited when the boxes are apart by more than `margin`.
///
/// # Errors
/// As [`box_manifold`].
pub fn box_contact_vertices(
    a: &PlacedBox<'_>,
    b: &PlacedBox<'_>,
    margin: f64,
    mut visit: impl FnMut(RegionVertex<'_>),
) -> Result<BoxPairAxis, DynamicsError> {
    check_pair(a, b, margin)?;
    let axis = box_box_unchecked(a, b);
    if axis.depth >= -margin {
        region(a, b, &axis, margin, &mut visit);
    }
    Ok(axis)
}

fn region(
    a: &PlacedBox<'_>,
    b: &PlacedBox<'_>,
    axis: &BoxPairAxis,
    margin: f64,
    visit: &mut dyn FnMut(RegionVertex<'_>),
) {
    match axis.feature {
        AxisFeature::FaceOfA { axis: i } => {
            face_region(a, b, false, i, &axis.normal, margin, visit)
        }
        AxisFeature::FaceOfB { axis: j } => face_region(b, a, true, j, &axis.normal, margin, visit),
        AxisFeature::Cells { axes_a, axes_b } => {
            cell_point(a, b, axes_a, axes_b, &axis.normal, margin, visit)
        }
    }
}

type Small = SmallVec<[f64; 8]>;
type Square = SmallVec<[f64; 64]>;

/// The vertices of the region between the reference face of `r` across own axis `ir` and
/// the most anti-parallel face of `inc`; `normal` is the manifold normal (A → B),
/// `ref_is_b` says which box is the reference.
#[allow(clippy::too_many_arguments)]
fn face_region(
    r: &PlacedBox<'_>,
    inc: &PlacedBox<'_>,
    ref_is_b: bool,
    ir: usize,
    normal: &[f64],
    margin: f64,
    visit: &mut dyn FnMut(RegionVertex<'_>),
) {
    let n = r.dim();
    let d = n - 1;
    // The reference face's outward normal: the manifold normal for A, its opposite for B.
    let flip = if ref_is_b { -1.0 } else { 1.0 };
    let n_ref: Small = normal.iter().map(|x| flip * x).collect();
    let along_ir: f64 = (0..n).map(|k| r.axis(ir, k) * n_ref[k]).sum();
    let sr = if along_ir < 0.0 { -1.0 } else { 1.0 };
    // The incident face: the own axis of `inc` most parallel to the reference normal, on
    // the side facing it.
    let mut ji = 0;
    let mut best = -1.0;
    let mut si = 1.0;
    for j in 0..n {
        let c: f64 = (0..n).map(|k| inc.axis(j, k) * n_ref[k]).sum();
        if c.abs() > best {
            best = c.abs();
            ji = j;
            si = if c > 0.0 { -1.0 } else { 1.0 };
        }
    }
    let sides: SmallVec<[usize; 8]> = (0..n).filter(|&t| t != ir).collect();
    let inc_axes: SmallVec<[usize; 8]> = (0..n).filter(|&u| u != ji).collect();
    // The incident face's centre and its points p(y) = g_c + Σ y_u h_u b_u, y ∈ [−1, 1]^d.
    let g_c: Small = (0..n)
        .map(|k| inc.position[k] + si * inc.half_lengths[ji] * inc.axis(ji, k))
        .collect();
    let offset: Small = (0..n).map(|k| g_c[k] - r.position[k]).collect();
    // Side coordinates x_t = g_t + Σ G_tu y_u; depth = D0 − Σ Dy_u y_u.
    let mut g: Small = SmallVec::from_elem(0.0, d);
    let mut gm: Square = SmallVec::from_elem(0.0, d * d);
    let mut dy: Small = SmallVec::from_elem(0.0, d);
    for (row, &t) in sides.iter().enumerate() {
        g[row] = (0..n).map(|k| r.axis(t, k) * offset[k]).sum();
        for (col, &u) in inc_axes.iter().enumerate() {
            gm[row * d + col] =
                inc.half_lengths[u] * (0..n).map(|k| r.axis(t, k) * inc.axis(u, k)).sum::<f64>();
        }
    }
    let d0 = r.half_lengths[ir] - sr * (0..n).map(|k| r.axis(ir, k) * offset[k]).sum::<f64>();
    for (col, &u) in inc_axes.iter().enumerate() {
        dy[col] =
            sr * inc.half_lengths[u] * (0..n).map(|k| r.axis(ir, k) * inc.axis(u, k)).sum::<f64>();
    }
    let h: Small = sides.iter().map(|&t| r.half_lengths[t]).collect();
    let scale = r.size().max(inc.size()).max(f64::MIN_POSITIVE);
    let x_tol = 1e-9 * scale;
    let y_tol = 1e-9;
    let g_max = gm.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let pivot_tol = 1e-12 * g_max.max(f64::MIN_POSITIVE);
    let ref_bits = KIND_FACE
        | (ref_is_b as u64) << 61
        | ((sr < 0.0) as u64) << 60
        | (ir as u64) << 56
        | ((si < 0.0) as u64) << 55
        | (ji as u64) << 51;

    let full = 1u32 << d;
    // The side planes within reach of the incident face (bit 2t: x_t = +h_t, bit 2t + 1:
    // x_t = −h_t): a plane out of reach holds no vertex, and a set of planes with one out
    // of reach on both sides needs no factorisation.
    let mut reachable = 0u64;
    for t in 0..d {
        let spread: f64 = (0..d).map(|u| gm[t * d + u].abs()).sum();
        for (bit, target) in [(0, h[t]), (1, -h[t])] {
            if (target - g[t]).abs() <= spread + x_tol {
                reachable |= 1 << (2 * t + bit);
            }
        }
    }
    // The loops below index these many times per candidate vertex: as slices, each access
    // is a bounds check, not also a test of where the small vector keeps its numbers.
    let (g, gm, dy, h) = (&g[..], &gm[..], &dy[..], &h[..]);
    let (mut y_room, mut x_room): (Small, Small) =
        (SmallVec::from_elem(0.0, d), SmallVec::from_elem(0.0, d));
    let (y, x) = (&mut y_room[..], &mut x_room[..]);
    let (mut lu_room, mut rhs_room): (Square, Small) =
        (SmallVec::from_elem(0.0, d * d), SmallVec::from_elem(0.0, d));
    let (mut pa_room, mut pb_room): (Small, Small) =
        (SmallVec::from_elem(0.0, n), SmallVec::from_elem(0.0, n));
    let (pa, pb) = (&mut pa_room[..], &mut pb_room[..]);
    let mut pivots = [0usize; 8];
    let (mut rows_room, mut cols_room) = ([0usize; 32], [0usize; 32]);
    // T: the side planes the vertex lies on; F: the incident coordinates fixed at ±1.
    for t_mask in 0..full {
        let k = t_mask.count_ones() as usize;
        for (slot, t) in rows_room
            .iter_mut()
            .zip((0..d).filter(|&t| t_mask >> t & 1 == 1))
        {
            *slot = t;
        }
        let rows = &rows_room[..k];
        if rows.iter().any(|&t| reachable >> (2 * t) & 3 == 0) {
            continue;
        }
        for f_mask in 0..full {
            if f_mask.count_ones() as usize != d - k {
                continue;
            }
            for (slot, u) in cols_room
                .iter_mut()
                .zip((0..d).filter(|&u| f_mask >> u & 1 == 0))
            {
                *slot = u;
            }
            let cols = &cols_room[..k];
            // The k × k system G[T, free] y_free = rhs (column-major), factored once for
            // all sides.
            let lu = &mut lu_room[..k * k];
            for (r, &t) in rows.iter().enumerate() {
                for (c, &u) in cols.iter().enumerate() {
                    lu[c * k + r] = gm[t * d + u];
                }
            }
            let pivots = &mut pivots[..k];
            if !lu_factor_above(k, lu, pivots, pivot_tol) {
                continue;
            }
            let (lu, pivots) = (&lu[..], &pivots[..]);
            // How far the free coordinates in [−1, 1] move each side coordinate of T.
            let mut spread_room = [0.0f64; 32];
            let spread = &mut spread_room[..k];
            for (c, &t) in rows.iter().enumerate() {
                spread[c] = (0..d)
                    .filter(|&u| f_mask >> u & 1 == 0)
                    .map(|u| gm[t * d + u].abs())
                    .sum();
            }
            let spread = &spread[..];
            for t_signs in 0..(1u32 << k) {
                // A side plane out of reach of the incident face cannot hold a vertex.
                let reach = rows
                    .iter()
                    .enumerate()
                    .all(|(c, &t)| reachable >> (2 * t + (t_signs >> c & 1) as usize) & 1 == 1);
                if !reach {
                    continue;
                }
                for f_signs in 0..(1u32 << (d - k)) {
                    // Fixed coordinates.
                    let mut bit = 0;
                    for (u, yu) in y.iter_mut().enumerate() {
                        if f_mask >> u & 1 == 1 {
                            *yu = if f_signs >> bit & 1 == 1 { -1.0 } else { 1.0 };
                            bit += 1;
                        }
                    }
                    let rhs = &mut rhs_room[..k];
                    let mut within = true;
                    for (c, &t) in rows.iter().enumerate() {
                        let target = if t_signs >> c & 1 == 1 { -h[t] } else { h[t] };
                        let fixed: f64 = (0..d)
                            .filter(|&u| f_mask >> u & 1 == 1)
                            .map(|u| gm[t * d + u] * y[u])
                            .sum();
                        rhs[c] = target - g[t] - fixed;
                        // Free coordinates within [−1, 1] (and the solve's tolerance)
                        // cannot reach the side plane: the solve would leave one outside.
                        within &= rhs[c].abs() <= spread[c] * (1.0 + y_tol) + x_tol;
                    }
                    if !within {
                        continue;
                    }
                    lu_apply(k, lu, pivots, rhs, 1);
                    if rhs.iter().any(|v| v.is_nan() || v.abs() > 1.0 + y_tol) {
                        continue;
                    }
                    for (c, &u) in cols.iter().enumerate() {
                        y[u] = rhs[c].clamp(-1.0, 1.0);
                    }
                    let mut inside = true;
                    for t in 0..d {
                        x[t] = g[t] + (0..d).map(|u| gm[t * d + u] * y[u]).sum::<f64>();
                        if x[t].abs() > h[t] + x_tol {
                            inside = false;
                            break;
                        }
                    }
                    if !inside {
                        continue;
                    }
                    let depth = d0 - dot(dy, y);
                    if depth < -margin {
                        continue;
                    }
                    // The id: which side planes and incident faces hold the point.
                    let mut id = ref_bits;
                    for (c, &t) in rows.iter().enumerate() {
                        id |= (1 + (t_signs >> c & 1) as u64) << (2 * t);
                    }
                    for (u, yu) in y.iter().enumerate() {
                        if f_mask >> u & 1 == 1 {
                            id |= (if *yu < 0.0 { 2 } else { 1 }) << (2 * d + 2 * u);
                        }
                    }
                    // p on the incident face; its projection on the reference face.
                    for kk in 0..n {
                        let p = g_c[kk]
                            + inc_axes
                                .iter()
                                .enumerate()
                                .map(|(c, &u)| y[c] * inc.half_lengths[u] * inc.axis(u, kk))
                                .sum::<f64>();
                        let q = p + depth * n_ref[kk];
                        if ref_is_b {
                            pa[kk] = p;
                            pb[kk] = q;
                        } else {
                            pa[kk] = q;
                            pb[kk] = p;
                        }
                    }
                    visit(RegionVertex {
                        point_a: pa,
                        point_b: pb,
                        plane: x,
                        depth,
                        id: FeatureId(id),
                    });
                }
            }
        }
    }
}

/// The crossing of A's cell along `axes_a` and B's cell along `axes_b` (the supporting
/// cells across the cell axis): one point.
fn cell_point(
    a: &PlacedBox<'_>,
    b: &PlacedBox<'_>,
    axes_a: u32,
    axes_b: u32,
    normal: &[f64],
    margin: f64,
    visit: &mut dyn FnMut(RegionVertex<'_>),
) {
    let n = a.dim();
    let rel = Relative::new(a, b);
    let mut u: Small = SmallVec::from_elem(0.0, n);
    cell_axis(&rel, axes_a, axes_b, &mut u);
    // Orient u (A's frame) as the normal.
    let un: f64 = (0..n)
        .map(|k| normal[k] * (0..n).map(|i| a.axis(i, k) * u[i]).sum::<f64>())
        .sum();
    if un < 0.0 {
        u.iter_mut().for_each(|x| *x = -*x);
    }
    // B's axes in A's frame seen along u.
    let w: Small = (0..n)
        .map(|j| (0..n).map(|i| rel.r[i * n + j] * u[i]).sum())
        .collect();
    // A's supporting cell along +u and B's along −u, in A's frame: fixed coordinates.
    let mut sign_bits = 0u64;
    let mut pa0: Small = SmallVec::from_elem(0.0, n);
    for i in 0..n {
        if axes_a >> i & 1 == 0 {
            let s = if u[i] < 0.0 { -1.0 } else { 1.0 };
            pa0[i] = s * a.half_lengths[i];
            sign_bits |= ((s < 0.0) as u64) << (20 + i);
        }
    }
    let mut pb0: Small = rel.d.clone();
    for j in 0..n {
        if axes_b >> j & 1 == 0 {
            let s = if w[j] > 0.0 { -1.0 } else { 1.0 };
            for i in 0..n {
                pb0[i] += s * b.half_lengths[j] * rel.r[i * n + j];
            }
            sign_bits |= ((s < 0.0) as u64) << (30 + j);
        }
    }
    // pa0 + Σ s_i e_i − pb0 − Σ t_j r_j − λ u = 0: N equations in (s, t, λ), column-major.
    let mut m: Square = SmallVec::from_elem(0.0, n * n);
    let mut col = 0;
    let mut which: SmallVec<[(bool, usize); 8]> = SmallVec::new();
    for i in 0..n {
        if axes_a >> i & 1 == 1 {
            m[col * n + i] = 1.0;
            which.push((true, i));
            col += 1;
        }
    }
    for j in 0..n {
        if axes_b >> j & 1 == 1 {
            for i in 0..n {
                m[col * n + i] = -rel.r[i * n + j];
            }
            which.push((false, j));
            col += 1;
        }
    }
    for i in 0..n {
        m[col * n + i] = -u[i];
    }
    let mut rhs: Small = (0..n).map(|i| pb0[i] - pa0[i]).collect();
    let mut pivots: SmallVec<[usize; 8]> = SmallVec::from_elem(0, n);
    let mut pa = pa0.clone();
    let mut pb = pb0.clone();
    if lu_factor_above(n, &mut m, &mut pivots, 1e-12) {
        lu_apply(n, &m, &pivots, &mut rhs, 1);
        for (c, &(on_a, k)) in which.iter().enumerate() {
            if on_a {
                let s = rhs[c].clamp(-a.half_lengths[k], a.half_lengths[k]);
                pa[k] += s;
            } else {
                let t = rhs[c].clamp(-b.half_lengths[k], b.half_lengths[k]);
                for i in 0..n {
                    pb[i] += t * rel.r[i * n + k];
                }
            }
        }
    }
    let depth = dot(&u, &pa) - dot(&u, &pb);
    if depth < -margin {
        return;
    }
    // To space.
    let space = |p: &Small| -> Small {
        (0..n)
            .map(|k| a.position[k] + (0..n).map(|i| a.axis(i, k) * p[i]).sum::<f64>())
            .collect()
    };
    let (sa, sb) = (space(&pa), space(&pb));
    let plane: Small = SmallVec::from_elem(0.0, n - 1);
    visit(RegionVertex {
        point_a: &sa,
        point_b: &sb,
        plane: &plane,
        depth,
        id: FeatureId(KIND_CELLS | axes_a as u64 | (axes_b as u64) << 10 | sign_bits),
    });
}

/// The columns of the Sylvester–Hadamard matrix of order 16 (entry (k, c) = (−1)^|k ∧ c|)
/// that give the reduction's directions from 5 plane dimensions on: the powers of two
/// first, so that the 16 rows differ on the first four coordinates; every column but the
/// first sums to zero, so the 16 corners they pick on a box face have its centre as mean.
const HADAMARD_COLUMNS: [usize; 15] = [1, 2, 4, 8, 3, 5, 6, 7, 9, 10, 11, 12, 13, 14, 15];

/// A vertex of the region the reduction keeps.
#[derive(Clone)]
struct Candidate {
    pa: Small,
    pb: Small,
    depth: f64,
    id: FeatureId,
}

/// The best vertex along one direction so far: its score and where it is in
/// [`Reducer::kept`].
#[derive(Clone, Copy)]
struct Slot {
    score: f64,
    at: usize,
}

/// Room for the vertices the reduction holds: the 16 directions' and the deepest, twice
/// over, so that dropping those that lost their places leaves room again.
const KEPT: usize = 34;
const _: () = assert!(KEPT >= 2 * (MAX_MANIFOLD_POINTS + 1));

/// Keeps the extremes of the region along fixed directions of the contact plane, and its
/// deepest point, as vertices stream in.
struct Reducer {
    n: usize,
    normal: Small,
    slots: SmallVec<[Option<Slot>; 16]>,
    deepest: Option<usize>,
    /// The vertices that led a direction or were the deepest when offered, each stored
    /// once however many directions it leads (a face's corner leads several).
    kept: SmallVec<[Candidate; KEPT]>,
    shallowest: f64,
    /// The contact-plane scale of each coordinate (set by the first vertex's frame).
    directions: usize,
}

/// The number of directions along which the reduction keeps the region's extremes in `n`
/// dimensions: 2^(N−1) up to 5D, then [`MAX_MANIFOLD_POINTS`].
fn reduction_directions(n: usize) -> usize {
    let d = n - 1;
    if d <= 4 {
        1usize << d
    } else {
        MAX_MANIFOLD_POINTS
    }
}

/// The score of plane coordinates `x` (N − 1 of them) along the reduction's direction `k`:
/// the diagonal (±1, …, ±1) whose signs are the bits of `k` up to 4 plane dimensions (every
/// corner of a box face), and from 5 on the k-th row of the Sylvester–Hadamard matrix of
/// order 16 on columns 1, 2, 4, 8, 3, 5, … (16 corners, all distinct, whose mean is the
/// centre).
fn direction_score(k: usize, x: &[f64]) -> f64 {
    let d = x.len();
    if d <= 4 {
        (0..d)
            .map(|t| if k >> t & 1 == 1 { -x[t] } else { x[t] })
            .sum()
    } else {
        (0..d)
            .map(|t| {
                let column = HADAMARD_COLUMNS[t % HADAMARD_COLUMNS.len()];
                if (k & column).count_ones() % 2 == 1 {
                    -x[t]
                } else {
                    x[t]
                }
            })
            .sum()
    }
}

impl Reducer {
    fn new(n: usize, normal: &[f64]) -> Reducer {
        let directions = reduction_directions(n);
        Reducer {
            n,
            normal: SmallVec::from_slice(normal),
            slots: SmallVec::from_elem(None, directions),
            deepest: None,
            kept: SmallVec::new(),
            shallowest: f64::INFINITY,
            directions,
        }
    }

    /// Stores the vertex `v` and returns where; first drops the stored vertices that no
    /// direction and not the deepest hold any longer if there is no room.
    fn store(&mut self, v: &RegionVertex<'_>) -> usize {
        if self.kept.len() == KEPT {
            let mut held = [false; KEPT];
            for slot in self.slots.iter().flatten() {
                held[slot.at] = true;
            }
            if let Some(d) = self.deepest {
                held[d] = true;
            }
            // In place, each held vertex's new place in `to`.
            let mut to = [0usize; KEPT];
            let (mut i, mut next) = (0, 0);
            self.kept.retain(|_| {
                let keep = held[i];
                if keep {
                    to[i] = next;
                    next += 1;
                }
                i += 1;
                keep
            });
            for slot in self.slots.iter_mut().flatten() {
                slot.at = to[slot.at];
            }
            self.deepest = self.deepest.map(|d| to[d]);
        }
        self.kept.push(Candidate {
            pa: SmallVec::from_slice(v.point_a),
            pb: SmallVec::from_slice(v.point_b),
            depth: v.depth,
            id: v.id,
        });
        self.kept.len() - 1
    }

    fn offer(&mut self, v: RegionVertex<'_>, scale: f64) {
        let tie = 1e-12 * scale;
        self.shallowest = self.shallowest.min(v.depth);
        let mut stored = None;
        for k in 0..self.directions {
            let s = direction_score(k, &v.plane[..self.n - 1]);
            let better = match self.slots[k] {
                None => true,
                Some(c) => {
                    s > c.score + tie || (s >= c.score - tie && v.depth > self.kept[c.at].depth)
                }
            };
            if better {
                let at = match stored {
                    Some(at) => at,
                    None => *stored.insert(self.store(&v)),
                };
                self.slots[k] = Some(Slot { score: s, at });
            }
        }
        if self.deepest.is_none_or(|d| v.depth > self.kept[d].depth) {
            let at = match stored {
                Some(at) => at,
                None => self.store(&v),
            };
            self.deepest = Some(at);
        }
    }

    fn finish(self, scale: f64) -> ContactManifold {
        let same = |p: &Candidate, q: &Candidate| {
            p.pa.iter()
                .zip(&q.pa)
                .all(|(x, y)| (x - y).abs() <= 1e-9 * scale)
                && p.pb
                    .iter()
                    .zip(&q.pb)
                    .all(|(x, y)| (x - y).abs() <= 1e-9 * scale)
        };
        let all = &self.kept;
        // The manifold's points, as places in `all`.
        let mut kept: SmallVec<[usize; 17]> = SmallVec::new();
        for slot in self.slots.iter().flatten() {
            if !kept.iter().any(|&k| same(&all[k], &all[slot.at])) {
                kept.push(slot.at);
            }
        }
        if let Some(d) = self.deepest {
            let deep = &all[d];
            let kept_depth = kept
                .iter()
                .map(|&k| all[k].depth)
                .fold(f64::NEG_INFINITY, f64::max);
            let markedly =
                deep.depth - kept_depth > 0.25 * (deep.depth - self.shallowest) + 1e-9 * scale;
            if !kept.iter().any(|&k| same(&all[k], deep)) && markedly {
                let capacity = manifold_capacity(self.n);
                if kept.len() >= capacity {
                    // Replace the extreme nearest to the deepest point.
                    let dist = |k: usize| {
                        all[k]
                            .pb
                            .iter()
                            .zip(&deep.pb)
                            .map(|(x, y)| (x - y) * (x - y))
                            .sum::<f64>()
                    };
                    let nearest = (0..kept.len())
                        .min_by(|&i, &j| dist(kept[i]).total_cmp(&dist(kept[j])))
                        .unwrap_or(0);
                    kept[nearest] = d;
                } else {
                    kept.push(d);
                }
            }
        }
        kept.truncate(manifold_capacity(self.n));
        let mut manifold = ContactManifold::new(&self.normal);
        for &k in &kept {
            let c = &all[k];
            manifold.push(&c.pa, &c.pb, c.depth, c.id);
        }
        manifold
    }
}

/// A convex hull placed in space: its vertices in its own axes (`vertices`, k × N numbers,
/// vertex after vertex), its centre and its rotation (N × N, row-major, own axes → space).
#[derive(Clone, Copy, Debug)]
pub struct PlacedHull<'a> {
    /// The vertices in own axes, flat (k × N numbers).
    pub vertices: &'a [f64],
    /// The position of the own origin in space (N numbers).
    pub position: &'a [f64],
    /// The rotation own axes → space, row-major N × N.
    pub rotation: &'a [f64],
}

impl PlacedHull<'_> {
    /// The dimension N.
    pub fn dim(&self) -> usize {
        self.position.len()
    }

    /// The number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.vertices.len() / self.dim().max(1)
    }

    /// Checks lengths, finiteness and orthogonality.
    ///
    /// # Errors
    /// [`ShapeError::TooFewDimensions`] below N = 2, [`ShapeError::EmptyHull`],
    /// [`ShapeError::NotAMultiple`] for vertices that are not N numbers each,
    /// [`ShapeError::DimensionMismatch`] or [`ShapeError::NonFinite`] for the placement or a
    /// vertex, [`ShapeError::NotOrthogonal`] for the rotation.
    pub fn check(&self) -> Result<(), DynamicsError> {
        let n = self.dim();
        if n < 2 {
            return Err(ShapeError::TooFewDimensions { dim: n }.into());
        }
        if self.vertices.is_empty() {
            return Err(ShapeError::EmptyHull.into());
        }
        if !self.vertices.len().is_multiple_of(n) {
            return Err(ShapeError::NotAMultiple {
                what: "hull vertices",
                numbers: self.vertices.len(),
                dim: n,
            }
            .into());
        }
        check_placement(n, self.position, self.rotation)?;
        if let Some(&value) = self.vertices.iter().find(|x| !x.is_finite()) {
            return Err(ShapeError::NonFinite {
                what: "hull vertex",
                value,
            }
            .into());
        }
        super::sat::check_rotation(n, self.rotation)
    }

    /// Vertex `k` in space.
    fn place(&self, k: usize, out: &mut [f64]) {
        let n = self.dim();
        let v = &self.vertices[k * n..(k + 1) * n];
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.position[i] + (0..n).map(|j| self.rotation[i * n + j] * v[j]).sum::<f64>();
        }
    }

    /// The largest distance of a vertex from the own origin.
    fn radius(&self) -> f64 {
        let n = self.dim();
        self.vertices
            .chunks_exact(n)
            .map(|v| dot(v, v).sqrt())
            .fold(0.0, f64::max)
    }
}

/// Vertices within this fraction of a hull's radius of its supporting plane belong to its
/// support set (a face tilted by less than about this angle counts as flat on the other).
pub const SUPPORT_TOLERANCE: f64 = 1e-3;

/// The most vertices of a support set whose contact region [`hull_contact_vertices`]
/// enumerates by brute force over subsets of them (2^(N−1) up to 4D, then 8). A face with
/// more vertices is seen through a spread-out subset of them: first the vertex farthest
/// from their centroid, then each time the one farthest from those taken. The manifold
/// ([`hull_manifold`]) takes up to 64 vertices of a face the same way.
pub fn support_set_capacity(n: usize) -> usize {
    if n <= 4 { 1usize << (n - 1) } else { 8 }
}

/// The most vertices of a support set the hull manifold's linear programs take
/// ([`hull_region_extremes`]): every corner of a box's face up to 7D (2^(N−1) of them), a
/// spread-out subset of a larger face.
const LP_SUPPORT: usize = 64;

/// A support set: up to [`LP_SUPPORT`] placed vertices with their indices, inline up to 8D.
struct SupportSet {
    n: usize,
    points: SmallVec<[f64; 8 * LP_SUPPORT]>,
    heights: SmallVec<[f64; LP_SUPPORT]>,
    indices: SmallVec<[usize; LP_SUPPORT]>,
}

impl SupportSet {
    /// The vertices of `hull` within `tolerance` of its support plane along `sign`·`normal`.
    ///
    /// When more than `capacity` of them are, the set takes a spread-out
    /// subset, so that the region found from it still holds the face: first the vertex
    /// farthest from their centroid, then each time the one farthest from those taken
    /// (farthest-point sampling; the first in the hull's order on ties). Taking the ones
    /// nearest the plane instead let round-off choose among the vertices of a flat face:
    /// a hexagonal prism resting on another, whose faces have 6 vertices in 3D and 24 in
    /// 5D, was held along part of its face only; it rocked in 3D and 4D and fell over in 5D.
    fn new(
        hull: &PlacedHull<'_>,
        normal: &[f64],
        sign: f64,
        tolerance: f64,
        capacity: usize,
    ) -> (SupportSet, f64) {
        let n = hull.dim();
        let mut p: Small = SmallVec::from_elem(0.0, n);
        let mut top = f64::NEG_INFINITY;
        for k in 0..hull.vertex_count() {
            hull.place(k, &mut p);
            top = top.max(sign * dot(normal, &p));
        }
        let mut set = SupportSet {
            n,
            points: SmallVec::new(),
            heights: SmallVec::new(),
            indices: SmallVec::new(),
        };
        // One pass takes every vertex of the face while they fit, and sums them for their
        // centroid in case they do not.
        let mut centroid: Small = SmallVec::from_elem(0.0, n);
        let mut count = 0usize;
        for k in 0..hull.vertex_count() {
            hull.place(k, &mut p);
            let below = top - sign * dot(normal, &p);
            if below > tolerance {
                continue;
            }
            count += 1;
            centroid.iter_mut().zip(&p).for_each(|(c, x)| *c += x);
            if count <= capacity {
                set.points.extend_from_slice(&p);
                set.heights.push(below);
                set.indices.push(k);
            }
        }
        if count <= capacity {
            return (set, sign * top);
        }
        set.points.clear();
        set.heights.clear();
        set.indices.clear();
        centroid.iter_mut().for_each(|c| *c /= count as f64);
        // Each pass takes the candidate farthest from what the set holds (from the
        // centroid while it holds nothing).
        while set.indices.len() < capacity {
            let mut pick = None;
            let mut farthest = f64::NEG_INFINITY;
            for k in 0..hull.vertex_count() {
                if set.indices.contains(&k) {
                    continue;
                }
                hull.place(k, &mut p);
                let below = top - sign * dot(normal, &p);
                if below > tolerance {
                    continue;
                }
                let distance = if set.indices.is_empty() {
                    distance_squared(&p, &centroid)
                } else {
                    (0..set.indices.len())
                        .map(|j| distance_squared(&p, set.point(j)))
                        .fold(f64::INFINITY, f64::min)
                };
                if distance > farthest {
                    (farthest, pick) = (distance, Some((k, below)));
                }
            }
            let Some((k, below)) = pick else { break };
            hull.place(k, &mut p);
            set.points.extend_from_slice(&p);
            set.heights.push(below);
            set.indices.push(k);
        }
        (set, sign * top)
    }

    fn point(&self, k: usize) -> &[f64] {
        &self.points[k * self.n..(k + 1) * self.n]
    }

    fn len(&self) -> usize {
        self.indices.len()
    }
}

/// |a − b|².
fn distance_squared(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Coordinates of `p` in the contact plane of unit normal `normal`, through the Householder
/// reflection that maps e_k to −sign(n_k) n: its other columns are an orthonormal basis of
/// the plane.
fn plane_coordinates(normal: &[f64], p: &[f64], out: &mut Small) {
    let n = normal.len();
    let k = (0..n)
        .max_by(|&i, &j| normal[i].abs().total_cmp(&normal[j].abs()))
        .unwrap_or(0);
    let mut v: Small = SmallVec::from_slice(normal);
    v[k] += if normal[k] < 0.0 { -1.0 } else { 1.0 };
    let vv = dot(&v, &v);
    let vp = dot(&v, p);
    out.clear();
    for j in 0..n {
        if j != k {
            out.push(p[j] - 2.0 * v[j] * vp / vv);
        }
    }
}

/// Returns the contact manifold of two convex hulls along the contact normal `normal` (from
/// A towards B, as a narrow phase such as GJK–EPA reports it; it need not be unit), or None
/// when their supports along it are apart by more than `margin`.
///
/// # Errors
/// As [`PlacedHull::check`] for either hull; [`ShapeError::DimensionMismatch`] if the
/// dimensions differ; [`ShapeError::NonFinite`] or [`ShapeError::ZeroVector`] for the
/// normal; [`ShapeError::NonFinite`] or [`ShapeError::NegativeMargin`] for the margin.
pub fn hull_manifold(
    a: &PlacedHull<'_>,
    b: &PlacedHull<'_>,
    normal: &[f64],
    margin: f64,
) -> Result<Option<ContactManifold>, DynamicsError> {
    let mut reducer = None;
    let scale = a.radius().max(b.radius()).max(f64::MIN_POSITIVE);
    let touching = hull_vertices(a, b, normal, margin, true, &mut |unit, v| {
        reducer
            .get_or_insert_with(|| Reducer::new(unit.len(), unit))
            .offer(v, scale)
    })?;
    Ok(match (touching, reducer) {
        (Some(_), Some(r)) => Some(r.finish(scale)),
        (Some(unit), None) => Some(ContactManifold::new(&unit)),
        (None, _) => None,
    })
}

/// Calls `visit` for every vertex of the contact region of two hulls along `normal` (all
/// of them, before any reduction), at depth ≥ −`margin`.
///
/// # Errors
/// As [`hull_manifold`].
pub fn hull_contact_vertices(
    a: &PlacedHull<'_>,
    b: &PlacedHull<'_>,
    normal: &[f64],
    margin: f64,
    mut visit: impl FnMut(RegionVertex<'_>),
) -> Result<(), DynamicsError> {
    hull_vertices(a, b, normal, margin, false, &mut |_, v| visit(v)).map(|_| ())
}

/// Checks, finds the support sets and visits the region's vertices with the unit normal;
/// returns the unit normal, or None when the supports are apart by more than `margin`.
/// With `extremes`, only the points the reduction keeps are visited (the region's extremes
/// along its directions and its deepest point, by linear programs over up to
/// [`LP_SUPPORT`] vertices of each face); otherwise every vertex of the region of up to
/// [`support_set_capacity`] vertices of each face, by brute force.
fn hull_vertices(
    a: &PlacedHull<'_>,
    b: &PlacedHull<'_>,
    normal: &[f64],
    margin: f64,
    extremes: bool,
    visit: &mut dyn FnMut(&[f64], RegionVertex<'_>),
) -> Result<Option<Small>, DynamicsError> {
    a.check()?;
    b.check()?;
    let n = a.dim();
    for (what, found) in [("hull B", b.dim()), ("contact normal", normal.len())] {
        if found != n {
            return Err(ShapeError::DimensionMismatch {
                what,
                expected: n,
                found,
            }
            .into());
        }
    }
    if let Some(&value) = normal.iter().find(|x| !x.is_finite()) {
        return Err(ShapeError::NonFinite {
            what: "contact normal",
            value,
        }
        .into());
    }
    let length = dot(normal, normal).sqrt();
    if length == 0.0 {
        return Err(ShapeError::ZeroVector {
            what: "contact normal",
        }
        .into());
    }
    if !length.is_finite() {
        return Err(ShapeError::NonFinite {
            what: "contact normal's length",
            value: length,
        }
        .into());
    }
    check_margin(margin)?;
    let unit: Small = normal.iter().map(|x| x / length).collect();
    let taken = if extremes {
        LP_SUPPORT
    } else {
        support_set_capacity(n)
    };
    let (sa, top_a) = SupportSet::new(a, &unit, 1.0, SUPPORT_TOLERANCE * a.radius(), taken);
    let (sb, bottom_b) = SupportSet::new(b, &unit, -1.0, SUPPORT_TOLERANCE * b.radius(), taken);
    if top_a - bottom_b < -margin {
        return Ok(None);
    }
    let scale = a.radius().max(b.radius()).max(f64::MIN_POSITIVE);
    if extremes {
        hull_region_extremes(&sa, &sb, &unit, margin, scale, &mut |v| visit(&unit, v));
    } else {
        hull_region(&sa, &sb, &unit, margin, scale, &mut |v| visit(&unit, v));
    }
    Ok(Some(unit))
}

/// The extremes of the contact region of two support sets along the reduction's directions
/// ([`direction_score`]), and its deepest point, each by a linear program over the
/// barycentric weights of the two sets: a point x of the contact plane is Σ αᵢ aᵢ = Σ βⱼ bⱼ
/// (the sets' vertices in plane coordinates) with α, β ≥ 0 and Σ α = Σ β = 1, at depth
/// Σ αᵢ hᵢ − Σ βⱼ gⱼ ≥ −`margin` (h, g the vertices' heights along the normal). The region
/// is the intersection of the two faces (as the brute force of [`hull_region`] finds it),
/// but the programs need no subsets: a face of any number of vertices is held by the
/// extremes the reduction keeps. Each extreme is taken among ties at its deepest, and its
/// id hashes the vertices of the two faces' simplices that hold it (a simplex spanning the
/// plane left out, as in [`hull_region`]).
fn hull_region_extremes(
    sa: &SupportSet,
    sb: &SupportSet,
    normal: &[f64],
    margin: f64,
    scale: f64,
    visit: &mut dyn FnMut(RegionVertex<'_>),
) {
    let n = normal.len();
    let d = n - 1;
    let (ka, kb) = (sa.len(), sb.len());
    // Plane coordinates and heights in units of the scale, so that the program's entries
    // are of order one.
    let mut plane: SmallVec<[f64; 16 * LP_SUPPORT]> = SmallVec::new();
    let mut height: SmallVec<[f64; 2 * LP_SUPPORT]> = SmallVec::new();
    let mut c: Small = SmallVec::new();
    for (set, sign) in [(sa, 1.0), (sb, -1.0)] {
        for k in 0..set.len() {
            plane_coordinates(normal, set.point(k), &mut c);
            plane.extend(c.iter().map(|x| x / scale));
            height.push(sign * dot(normal, set.point(k)) / scale);
        }
    }
    // The tableau just wide enough for the common faces (a box's, a tesseract's), or the
    // widest: its set-up and copies cost in proportion to its width.
    let width = ka + kb + 1 + (d + 3) + 1;
    let faces = (sa, sb, &plane[..], &height[..]);
    if width <= NARROW_LP {
        region_programs::<NARROW_LP>(faces, normal, margin, scale, visit);
    } else {
        region_programs::<LP_WIDTH>(faces, normal, margin, scale, visit);
    }
}

/// The width of the narrow tableau of [`hull_region_extremes`]: programs of up to two faces
/// of 16 vertices in 5D (the corners of two 5D boxes' faces).
const NARROW_LP: usize = 48;

/// The linear programs of [`hull_region_extremes`] over the faces' vertices in plane
/// coordinates and heights (in units of `scale`), in a tableau of width `W`.
fn region_programs<const W: usize>(
    (sa, sb, plane, height): (&SupportSet, &SupportSet, &[f64], &[f64]),
    normal: &[f64],
    margin: f64,
    scale: f64,
    visit: &mut dyn FnMut(RegionVertex<'_>),
) {
    let n = normal.len();
    let d = n - 1;
    let (ka, kb) = (sa.len(), sb.len());
    // Columns α (ka), β (kb), the depth's slack; rows: the d plane coordinates of
    // Σ α a − Σ β b = 0, Σ α = 1, Σ β = 1, Σ α h − Σ β g − s = −margin.
    let columns = ka + kb + 1;
    let entry = |i: usize, j: usize| -> f64 {
        let sign = if j < ka { 1.0 } else { -1.0 };
        match i {
            _ if i < d => {
                if j < ka + kb {
                    sign * plane[j * d + i]
                } else {
                    0.0
                }
            }
            _ if i == d => f64::from(u8::from(j < ka)),
            _ if i == d + 1 => f64::from(u8::from(j >= ka && j < ka + kb)),
            _ => {
                if j < ka + kb {
                    height[j]
                } else {
                    -1.0
                }
            }
        }
    };
    let mut rhs = [0.0; LP_MAX_ROWS];
    (rhs[d], rhs[d + 1], rhs[d + 2]) = (1.0, 1.0, -margin / scale);
    let Some(mut lp) = EqualityLp::<W>::new(d + 3, columns, entry, &rhs[..d + 3]) else {
        return;
    };
    if !lp.find_feasible(1e-9) {
        return;
    }
    let mut cost = [0.0; LP_MAX_COLUMNS];
    let mut x = [0.0; LP_MAX_COLUMNS];
    let (mut pa, mut pb, mut at): (Small, Small, Small) = (
        SmallVec::from_elem(0.0, n),
        SmallVec::from_elem(0.0, n),
        SmallVec::from_elem(0.0, d),
    );
    // The directions, then the depth alone.
    for k in 0..=reduction_directions(n) {
        let deepest = k == reduction_directions(n);
        for (j, w) in cost[..columns].iter_mut().enumerate() {
            let depth = if j < ka + kb { height[j] } else { 0.0 };
            *w = if deepest {
                depth
            } else if j < ka {
                // Among points as far along the direction, the deepest.
                direction_score(k, &plane[j * d..(j + 1) * d]) + 1e-9 * depth
            } else {
                1e-9 * depth
            };
        }
        if lp.maximize(&cost[..columns]) == LpEnd::Unbounded {
            return;
        }
        lp.solution(&mut x);
        let (alpha, beta) = (&x[..ka], &x[ka..ka + kb]);
        for r in 0..n {
            pa[r] = (0..ka).map(|i| alpha[i] * sa.point(i)[r]).sum();
            pb[r] = (0..kb).map(|j| beta[j] * sb.point(j)[r]).sum();
        }
        for t in 0..d {
            at[t] = scale * (0..ka).map(|i| alpha[i] * plane[i * d + t]).sum::<f64>();
        }
        // The vertices of each face that hold the point, unless they span the plane.
        visit(RegionVertex {
            point_a: &pa,
            point_b: &pb,
            plane: &at,
            depth: dot(normal, &pa) - dot(normal, &pb),
            id: hull_feature(
                held_vertices(alpha, &sa.indices, d),
                held_vertices(beta, &sb.indices, d),
            ),
        });
    }
}

/// The vertices (by `indices`) whose `weights` hold a point of a face, or none if they are
/// more than `d` (they span the contact plane).
fn held_vertices<'a>(
    weights: &'a [f64],
    indices: &'a [usize],
    d: usize,
) -> impl Iterator<Item = usize> + 'a {
    let spans = weights.iter().filter(|&&w| w > 1e-12).count() > d;
    (0..weights.len())
        .filter(move |&i| !spans && weights[i] > 1e-12)
        .map(move |i| indices[i])
}

/// The crossings of simplices of `sa` with simplices of `sb` in the contact plane, in
/// the order of the subsets' bit masks (A's outer, B's inner).
///
/// The brute force stays (it is what finds every vertex of the region in every dimension,
/// degenerate contacts included), but two things that cannot change its answer prune it:
/// a subset of A whose own columns are dependent fails every solve with it, so it is
/// solved once and skipped; and a crossing lies within both subsets' bounding boxes in the
/// plane, up to the solve's tolerances, so pairs whose boxes are apart by more than that
/// are not solved. A's columns are orthogonalised once per subset and B's are added to
/// them, the arithmetic of [`least_squares`] in the same order, so that every accepted
/// crossing is the same to the bit.
fn hull_region(
    sa: &SupportSet,
    sb: &SupportSet,
    normal: &[f64],
    margin: f64,
    scale: f64,
    visit: &mut dyn FnMut(RegionVertex<'_>),
) {
    let n = normal.len();
    let d = n - 1;
    let mut xa: SmallVec<[f64; 64]> = SmallVec::new();
    let mut xb: SmallVec<[f64; 64]> = SmallVec::new();
    let mut c: Small = SmallVec::new();
    for k in 0..sa.len() {
        plane_coordinates(normal, sa.point(k), &mut c);
        xa.extend_from_slice(&c);
    }
    for k in 0..sb.len() {
        plane_coordinates(normal, sb.point(k), &mut c);
        xb.extend_from_slice(&c);
    }
    let tol = 1e-9 * scale;
    let bary_tol = 1e-9;
    // An accepted crossing is within tol of the point of A that barycentric coordinates
    // of at least −1e-9 (at most d + 1 of them) give: within (d + 1)·1e-9 of the subset's
    // extent (at most its diameter, 2 scale) of its box; and the coordinates carry
    // round-off of their size.
    let size = xa.iter().chain(&xb).fold(0.0f64, |m, x| m.max(x.abs()));
    let slack = 2.0 * tol + 4.0 * (d + 1) as f64 * bary_tol * scale + 1e-12 * size;
    let (mut pa, mut pb): (Small, Small) =
        (SmallVec::from_elem(0.0, n), SmallVec::from_elem(0.0, n));
    let mut x: Small = SmallVec::from_elem(0.0, d);
    let mut qr = ColumnQr::default();
    for mask_a in 1u32..(1 << sa.len()) {
        let ka = mask_a.count_ones() as usize;
        if ka > d + 1 {
            continue;
        }
        let ia: SmallVec<[usize; 8]> = (0..sa.len()).filter(|i| mask_a >> i & 1 == 1).collect();
        let a0 = &xa[ia[0] * d..(ia[0] + 1) * d];
        let (mut lo_a, mut hi_a) = ([f64::INFINITY; 8], [f64::NEG_INFINITY; 8]);
        for &i in &ia {
            for t in 0..d {
                lo_a[t] = lo_a[t].min(xa[i * d + t]);
                hi_a[t] = hi_a[t].max(xa[i * d + t]);
            }
        }
        // Columns a_i − a_0 (i ≥ 1), orthogonalised once for every subset of B.
        qr.clear(d, tol);
        let mut column = [0.0; 8];
        let independent = ia[1..].iter().all(|&i| {
            for t in 0..d {
                column[t] = xa[i * d + t] - a0[t];
            }
            qr.push(&column[..d])
        });
        if !independent {
            continue;
        }
        let base = qr.columns;
        for mask_b in 1u32..(1 << sb.len()) {
            let kb = mask_b.count_ones() as usize;
            if ka + kb > d + 2 {
                continue;
            }
            let mut ib = [0usize; 8];
            let mut count = 0;
            for j in 0..sb.len() {
                if mask_b >> j & 1 == 1 {
                    ib[count] = j;
                    count += 1;
                }
            }
            let ib = &ib[..kb];
            let apart = (0..d).any(|t| {
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for &j in ib {
                    lo = lo.min(xb[j * d + t]);
                    hi = hi.max(xb[j * d + t]);
                }
                lo > hi_a[t] + slack || hi < lo_a[t] - slack
            });
            if apart {
                continue;
            }
            let b0 = &xb[ib[0] * d..(ib[0] + 1) * d];
            // Columns −(b_j − b_0) (j ≥ 1) after A's; right side b_0 − a_0.
            qr.truncate(base);
            let independent = ib[1..].iter().all(|&j| {
                for t in 0..d {
                    column[t] = -(xb[j * d + t] - b0[t]);
                }
                qr.push(&column[..d])
            });
            if !independent {
                continue;
            }
            let mut rhs = [0.0; 8];
            for t in 0..d {
                rhs[t] = b0[t] - a0[t];
            }
            let mut z = [0.0; 8];
            if !qr.solve(&mut rhs[..d], &mut z, tol) {
                continue;
            }
            let m = ka + kb - 2;
            let z = &z[..m];
            // Barycentric coordinates within both simplices.
            let sum_a: f64 = z[..ka - 1].iter().sum();
            let sum_b: f64 = z[ka - 1..].iter().sum();
            if z.iter().any(|w| *w < -bary_tol) || sum_a > 1.0 + bary_tol || sum_b > 1.0 + bary_tol
            {
                continue;
            }
            for k in 0..n {
                pa[k] = (1.0 - sum_a) * sa.point(ia[0])[k]
                    + ia[1..]
                        .iter()
                        .zip(&z[..ka - 1])
                        .map(|(&i, w)| w * sa.point(i)[k])
                        .sum::<f64>();
                pb[k] = (1.0 - sum_b) * sb.point(ib[0])[k]
                    + ib[1..]
                        .iter()
                        .zip(&z[ka - 1..])
                        .map(|(&j, w)| w * sb.point(j)[k])
                        .sum::<f64>();
            }
            let depth = dot(normal, &pa) - dot(normal, &pb);
            if depth < -margin {
                continue;
            }
            for t in 0..d {
                x[t] = (1.0 - sum_a) * a0[t]
                    + ia[1..]
                        .iter()
                        .zip(&z[..ka - 1])
                        .map(|(&i, w)| w * xa[i * d + t])
                        .sum::<f64>();
            }
            // A full-dimensional simplex only says "inside": leave it out of the id, so that
            // the id does not depend on which of the simplices holding the point found it.
            let simplex_a = ia.iter().filter(|_| ka <= d).map(|&i| sa.indices[i]);
            let simplex_b = ib.iter().filter(|_| kb <= d).map(|&j| sb.indices[j]);
            visit(RegionVertex {
                point_a: &pa,
                point_b: &pb,
                plane: &x,
                depth,
                id: hull_feature(simplex_a, simplex_b),
            });
        }
    }
}

/// The id of a point where a simplex of A's support set meets one of B's: a hash (FNV-1a)
/// of their vertices' indices (either list empty for a simplex left out).
fn hull_feature(
    a: impl IntoIterator<Item = usize>,
    b: impl IntoIterator<Item = usize>,
) -> FeatureId {
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    let mut mix = |v: u64| {
        hash ^= v;
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    };
    a.into_iter().for_each(|i| mix(i as u64 + 1));
    mix(u64::MAX);
    b.into_iter().for_each(|j| mix(j as u64 + 1));
    FeatureId(KIND_HULL | hash >> 2)
}

/// A QR factorisation of up to 8 columns of dimension d ≤ 8 (the contact plane's), built a
/// column at a time by modified Gram–Schmidt twice, so that the columns of one simplex can
/// be kept while another's are added after them.
#[derive(Default)]
struct ColumnQr {
    d: usize,
    tol: f64,
    /// How many columns are orthogonalised.
    columns: usize,
    /// The orthonormal columns, column j at j·8.
    q: [[f64; 8]; 8],
    /// R, upper triangular: r[i][j] for i ≤ j.
    r: [[f64; 8]; 8],
}

impl ColumnQr {
    fn clear(&mut self, d: usize, tol: f64) {
        (self.d, self.tol, self.columns) = (d, tol, 0);
    }

    /// Drops the columns after the first `columns`.
    fn truncate(&mut self, columns: usize) {
        self.columns = columns;
    }

    /// Adds a column; false when it depends on the others (relative to `tol`).
    fn push(&mut self, column: &[f64]) -> bool {
        let (d, j) = (self.d, self.columns);
        let original = dot(column, column).sqrt();
        let mut qj = [0.0; 8];
        qj[..d].copy_from_slice(column);
        for i in 0..j {
            self.r[i][j] = 0.0;
        }
        for _ in 0..2 {
            for i in 0..j {
                let qi = &self.q[i][..d];
                let p = dot(qi, &qj[..d]);
                self.r[i][j] += p;
                qj[..d].iter_mut().zip(qi).for_each(|(x, y)| *x -= p * y);
            }
        }
        let len = dot(&qj[..d], &qj[..d]).sqrt();
        if len.is_nan() || len <= 1e-9 * original.max(self.tol) {
            return false;
        }
        qj[..d].iter_mut().for_each(|x| *x /= len);
        self.q[j] = qj;
        self.r[j][j] = len;
        self.columns += 1;
        true
    }

    /// The least-squares solution z = R⁻¹ Qᵀ rhs of the columns; false when the residual
    /// rhs − Q Qᵀ rhs exceeds `tol` (the flats do not meet). `rhs` is overwritten.
    fn solve(&self, rhs: &mut [f64], z: &mut [f64; 8], tol: f64) -> bool {
        let m = self.columns;
        for (q, zj) in self.q[..m].iter().zip(z.iter_mut()) {
            let q = &q[..self.d];
            let p = dot(q, rhs);
            *zj = p;
            rhs.iter_mut().zip(q).for_each(|(x, y)| *x -= p * y);
        }
        let residual = dot(rhs, rhs).sqrt();
        if residual.is_nan() || residual > tol {
            return false;
        }
        for j in (0..m).rev() {
            for k in j + 1..m {
                z[j] -= self.r[j][k] * z[k];
            }
            z[j] /= self.r[j][j];
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A rotation of ℝᴺ (row-major): plane rotations by the given angles, plane after plane.
    fn rotation(n: usize, mut angle: impl FnMut(usize, usize) -> f64) -> Vec<f64> {
        let mut q: Vec<f64> = (0..n * n)
            .map(|k| if k / n == k % n { 1.0 } else { 0.0 })
            .collect();
        for i in 0..n {
            for j in i + 1..n {
                let (s, c) = angle(i, j).sin_cos();
                for row in 0..n {
                    let (x, y) = (q[row * n + i], q[row * n + j]);
                    q[row * n + i] = c * x - s * y;
                    q[row * n + j] = s * x + c * y;
                }
            }
        }
        q
    }

    /// Two boxes: half-lengths, centre and rotation of A, then of B.
    type BoxPair = [Vec<f64>; 6];

    /// A random pair of boxes in `n` dimensions (B turned as A if `parallel`), B's centre
    /// within `spread` of the origin on every axis.
    fn random_box_pair(r: &mut ChaCha8Rng, n: usize, parallel: bool, spread: f64) -> BoxPair {
        let ha: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
        let hb: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
        let qa = rotation(n, |_, _| r.gen_range(-3.2..3.2));
        let qb = if parallel {
            qa.clone()
        } else {
            rotation(n, |_, _| r.gen_range(-3.2..3.2))
        };
        let pa: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
        let pb: Vec<f64> = (0..n).map(|_| r.gen_range(-spread..spread)).collect();
        [ha, pa, qa, hb, pb, qb]
    }

    /// The two boxes of a [`BoxPair`].
    fn placed(pair: &BoxPair) -> (PlacedBox<'_>, PlacedBox<'_>) {
        let [ha, pa, qa, hb, pb, qb] = pair;
        let placed = |half_lengths, position, rotation| PlacedBox {
            half_lengths,
            position,
            rotation,
        };
        (placed(ha, pa, qa), placed(hb, pb, qb))
    }

    /// The separating axes of 3D and 4D boxes on arrays (`for_each_axis_fixed`, which
    /// detection uses) are those of the run-time kernel (`for_each_axis`) to the last bit:
    /// the same axes in the same order with the same overlaps, on random boxes in random
    /// poses, parallel (coplanar faces, degenerate cell axes skipped) or not, and the early
    /// stop at the same axis.
    #[test]
    fn fixed_size_separating_axes_are_the_run_time_ones() {
        use super::super::sat::{Relative, for_each_axis, for_each_axis_fixed};
        fn axes<const N: usize>(r: &mut ChaCha8Rng, parallel: bool) -> usize {
            let pair = random_box_pair(r, N, parallel, 3.0);
            let (a, b) = placed(&pair);
            // Each visit as bits: the axis, the feature, the overlap and u · d; the run-time
            // kernel stops where the fixed one did (at a random visit, or at none).
            let stop = r.gen_range(0..80usize);
            let record = |seen: &mut Vec<u64>, u: &[f64], f: AxisFeature, o: f64, along: f64| {
                seen.extend(u.iter().map(|x| x.to_bits()));
                seen.push(match f {
                    AxisFeature::FaceOfA { axis } => axis as u64,
                    AxisFeature::FaceOfB { axis } => 100 + axis as u64,
                    AxisFeature::Cells { axes_a, axes_b } => {
                        1000 + (axes_a as u64) * 64 + axes_b as u64
                    }
                });
                seen.extend([o.to_bits(), along.to_bits()]);
            };
            let (mut fixed, mut general) = (Vec::new(), Vec::new());
            let mut count = 0;
            for_each_axis_fixed::<N>(&a, &b, |u: &[f64], f, o, along| {
                record(&mut fixed, u, f, o, along);
                count += 1;
                count != stop
            });
            let mut again = 0;
            for_each_axis(&a, &b, &Relative::new(&a, &b), |u: &[f64], f, o, along| {
                record(&mut general, u, f, o, along);
                again += 1;
                again != stop
            });
            assert_eq!(fixed, general, "N = {N}, parallel {parallel}");
            count
        }
        let mut r = ChaCha8Rng::seed_from_u64(41);
        let mut visits = [0usize; 2];
        for case in 0..4_000 {
            let parallel = case % 4 == 0;
            visits[0] += axes::<3>(&mut r, parallel);
            visits[1] += axes::<4>(&mut r, parallel);
        }
        // Every pair visits its axes (15 and 56 but the degenerate and the stopped ones).
        assert!(
            visits[0] > 4_000 * 8 && visits[1] > 4_000 * 30,
            "{visits:?}"
        );
    }

    /// `box_box_within(a, b, r)`, which detection asks, is None exactly when the least
    /// overlap over all axes is a gap wider than r, and otherwise `box_box_unchecked`'s
    /// answer, in N = 2 … 5 (the run-time kernel in 2D and 5D, the fixed-size one in 3D and
    /// 4D).
    #[test]
    fn box_pairs_within_a_reach_are_the_unchecked_query_or_none() {
        use super::super::sat::{box_box_unchecked, box_box_within};
        let mut r = ChaCha8Rng::seed_from_u64(43);
        // Pairs answered, and left out as farther than the reach, per dimension.
        let mut counts = [[0usize; 2]; 4];
        for case in 0..8_000 {
            let n = 2 + case % 4;
            let pair = random_box_pair(&mut r, n, false, 4.0);
            let (a, b) = placed(&pair);
            let reach = r.gen_range(0.0..1.5);
            let all = box_box_unchecked(&a, &b);
            match box_box_within(&a, &b, reach) {
                Some(axis) => {
                    assert!(-all.least_depth <= reach, "N = {n}");
                    assert_eq!(axis, all, "N = {n}");
                    counts[n - 2][0] += 1;
                }
                None => {
                    assert!(-all.least_depth > reach, "N = {n}");
                    counts[n - 2][1] += 1;
                }
            }
        }
        for (k, c) in counts.iter().enumerate() {
            assert!(c[0] >= 200 && c[1] >= 200, "N = {}: {c:?}", k + 2);
        }
    }

    type Visit = (Vec<u64>, Vec<u64>, Vec<u64>, u64, u64);
    type Region = fn(&SupportSet, &SupportSet, &[f64], f64, f64, &mut dyn FnMut(RegionVertex<'_>));

    fn visits(
        region: Region,
        (sa, sb): (&SupportSet, &SupportSet),
        normal: &[f64],
        scale: f64,
    ) -> Vec<Visit> {
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        let mut out = Vec::new();
        region(sa, sb, normal, 1e-3 * scale, scale, &mut |v| {
            out.push((
                bits(v.point_a),
                bits(v.point_b),
                bits(v.plane),
                v.depth.to_bits(),
                v.id.0,
            ))
        });
        out
    }

    /// The linear programs find the extremes the brute force finds: for two flat faces of
    /// 4 to 8 random points (2D to 4D contact planes, N = 3 … 5) face to face, shifted, each
    /// point tilted within the support tolerance, the best score along each of the
    /// reduction's directions and the greatest depth over the points of
    /// [`hull_region_extremes`] equal those over every vertex [`hull_region`] finds, to
    /// 1e-9 of the size; with a margin that cuts the region (0 or 1e-4, where the faces'
    /// depths vary by 2e-4), no point is below it or beyond the region's extremes, and the
    /// deepest point stays.
    #[test]
    fn linear_programs_find_the_extremes_the_brute_force_finds() {
        let mut rng = ChaCha8Rng::seed_from_u64(20261201);
        let (mut cases, mut met) = (0, 0);
        for n in 3..=5usize {
            let d = n - 1;
            for case in 0..80 {
                // A prism over a random face: the face's points at own height `top`, and
                // the same points one unit away along −`side`.
                let prism = |rng: &mut ChaCha8Rng, side: f64, shift: f64| -> Vec<f64> {
                    let k = rng.gen_range(4..=8);
                    let face: Vec<Vec<f64>> = (0..k)
                        .map(|_| {
                            let mut p: Vec<f64> =
                                (0..d).map(|_| shift + rng.gen_range(-0.5..0.5)).collect();
                            p.push(side * rng.gen_range(-1e-4..1e-4));
                            p
                        })
                        .collect();
                    let mut v = Vec::new();
                    for p in &face {
                        v.extend_from_slice(p);
                    }
                    for p in &face {
                        v.extend(p[..d].iter().copied());
                        v.push(p[d] - side);
                    }
                    v
                };
                let va = prism(&mut rng, 1.0, 0.0);
                let shift = rng.gen_range(-0.4..0.4);
                let vb = prism(&mut rng, -1.0, shift);
                let identity: Vec<f64> = (0..n * n)
                    .map(|k| if k / n == k % n { 1.0 } else { 0.0 })
                    .collect();
                let origin = vec![0.0; n];
                let a = PlacedHull {
                    vertices: &va,
                    position: &origin,
                    rotation: &identity,
                };
                let b = PlacedHull {
                    vertices: &vb,
                    position: &origin,
                    rotation: &identity,
                };
                let mut normal = vec![0.0; n];
                normal[d] = 1.0;
                let (sa, _) =
                    SupportSet::new(&a, &normal, 1.0, SUPPORT_TOLERANCE * a.radius(), LP_SUPPORT);
                let (sb, _) = SupportSet::new(
                    &b,
                    &normal,
                    -1.0,
                    SUPPORT_TOLERANCE * b.radius(),
                    LP_SUPPORT,
                );
                let scale = a.radius().max(b.radius());
                // Every point as (plane coordinates, depth), with a margin that no point of
                // these faces (whose depths are within 2e-4) is below, and with a margin of
                // 0 or 1e-4 that cuts the region.
                let collect = |region: Region, margin: f64| {
                    let mut out: Vec<(Vec<f64>, f64)> = Vec::new();
                    region(&sa, &sb, &normal, margin, scale, &mut |v| {
                        out.push((v.plane.to_vec(), v.depth))
                    });
                    out
                };
                let (brute, programs) = (
                    collect(hull_region, 1.0),
                    collect(hull_region_extremes, 1.0),
                );
                let cut = if case % 2 == 0 { 0.0 } else { 1e-4 };
                let cut_programs = collect(hull_region_extremes, cut);
                assert_eq!(
                    brute.is_empty(),
                    programs.is_empty(),
                    "N = {n}, case {case}"
                );
                cases += 1;
                if brute.is_empty() {
                    continue;
                }
                met += 1;
                let tol = 1e-9 * scale;
                let best = |points: &[(Vec<f64>, f64)], k: usize| {
                    points
                        .iter()
                        .map(|(x, _)| direction_score(k, x))
                        .fold(f64::NEG_INFINITY, f64::max)
                };
                let deepest = |points: &[(Vec<f64>, f64)]| {
                    points.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max)
                };
                for k in 0..reduction_directions(n) {
                    let (b, p) = (best(&brute, k), best(&programs, k));
                    assert!(
                        (b - p).abs() <= tol,
                        "N = {n}, case {case}, direction {k}: {p} against {b}"
                    );
                    assert!(best(&cut_programs, k) <= b + tol, "N = {n}, case {case}");
                }
                assert!((deepest(&brute) - deepest(&programs)).abs() <= tol);
                // The cut keeps the deepest point if it is above the cut, and nothing below.
                if deepest(&brute) >= -cut + tol {
                    assert!((deepest(&brute) - deepest(&cut_programs)).abs() <= tol);
                }
                assert!(
                    cut_programs.iter().all(|p| p.1 >= -cut - tol),
                    "N = {n}, case {case}"
                );
            }
        }
        assert_eq!(cases, 240);
        // Most pairs of faces meet, so that the comparison is not empty.
        assert!(met > 150, "{met}");
    }

    /// The pruned region search visits exactly the crossings of the brute force, in the
    /// same order and equal to the bit, for N = 2 … 6: boxes face to face (shifted by
    /// random amounts, by exact halves as in a pyramid, not at all, turned about the
    /// normal or tilted within the support tolerance), random hulls, flat hulls and
    /// hulls with repeated points.
    #[test]
    fn pruned_region_search_visits_what_the_brute_force_does() {
        let mut rng = ChaCha8Rng::seed_from_u64(20261130);
        let (mut cases, mut vertices, mut by_kind) = (0, 0, [0usize; 5]);
        for n in 2..=6usize {
            for case in 0..60 {
                let kind = case % 5;
                let corners = |h: &[f64]| -> Vec<f64> {
                    (0..1usize << n)
                        .flat_map(|m| {
                            (0..n).map(move |i| if m >> i & 1 == 1 { h[i] } else { -h[i] })
                        })
                        .collect()
                };
                // Random points, the first n of them on the plane of own last coordinate
                // `face` (a face across the normal), or all on it (a flat hull).
                let random_points = |rng: &mut ChaCha8Rng, face: f64, flat: bool| -> Vec<f64> {
                    let mut v: Vec<f64> = (0..2 * n * n)
                        .map(|_| rng.gen_range(-1.0..1.0) * 0.9)
                        .collect();
                    let on_face = if flat { 2 * n } else { n };
                    v.iter_mut()
                        .skip(n - 1)
                        .step_by(n)
                        .take(on_face)
                        .for_each(|x| *x = face);
                    v
                };
                let ha: Vec<f64> = (0..n).map(|_| rng.gen_range(0.3..1.0)).collect();
                let hb: Vec<f64> = (0..n).map(|_| rng.gen_range(0.3..1.0)).collect();
                let (va, vb, ha, hb) = match kind {
                    0..=2 => (corners(&ha), corners(&hb), ha, hb),
                    3 => (
                        random_points(&mut rng, 1.0, false),
                        random_points(&mut rng, -1.0, false),
                        vec![1.0; n],
                        vec![1.0; n],
                    ),
                    _ => {
                        // Flat hulls, A with a repeated point.
                        let mut a = random_points(&mut rng, 0.0, true);
                        let first: Vec<f64> = a[..n].to_vec();
                        a.extend_from_slice(&first);
                        let mut h = vec![0.5; n];
                        h[n - 1] = 0.0;
                        (a, random_points(&mut rng, 0.0, true), h.clone(), h)
                    }
                };
                let qa = rotation(n, |_, _| rng.gen_range(-3.2..3.2));
                // The normal: A's last axis, so that boxes meet face to face.
                let normal: Vec<f64> = (0..n).map(|i| qa[i * n + n - 1]).collect();
                let qb = match kind {
                    // Turned about the normal only (in A's first n − 1 axes), or not at all.
                    0 | 4 => qa.clone(),
                    1 | 3 => {
                        let turn = rotation(n, |_, j| {
                            if j < n - 1 {
                                rng.gen_range(-3.2..3.2)
                            } else {
                                0.0
                            }
                        });
                        (0..n * n)
                            .map(|k| {
                                (0..n)
                                    .map(|l| qa[k / n * n + l] * turn[l * n + k % n])
                                    .sum()
                            })
                            .collect()
                    }
                    // Tilted within the support tolerance.
                    2 => {
                        let tilt = rotation(n, |_, j| {
                            if j == n - 1 {
                                rng.gen_range(-3e-4..3e-4)
                            } else {
                                0.0
                            }
                        });
                        (0..n * n)
                            .map(|k| {
                                (0..n)
                                    .map(|l| qa[k / n * n + l] * tilt[l * n + k % n])
                                    .sum()
                            })
                            .collect()
                    }
                    _ => unreachable!(),
                };
                let pa: Vec<f64> = (0..n).map(|_| rng.gen_range(-5.0..5.0)).collect();
                // B over A along the normal, shifted in the plane by random amounts or by
                // half of A's side.
                let shift: Vec<f64> = (0..n - 1)
                    .map(|i| {
                        if case % 2 == 0 {
                            ha[i]
                        } else {
                            rng.gen_range(-1.0..1.0) * ha[i]
                        }
                    })
                    .collect();
                let pb: Vec<f64> = (0..n)
                    .map(|r| {
                        pa[r]
                            + (0..n - 1).map(|i| qa[r * n + i] * shift[i]).sum::<f64>()
                            + normal[r] * (ha[n - 1] + hb[n - 1])
                    })
                    .collect();
                let a = PlacedHull {
                    vertices: &va,
                    position: &pa,
                    rotation: &qa,
                };
                let b = PlacedHull {
                    vertices: &vb,
                    position: &pb,
                    rotation: &qb,
                };
                let capacity = support_set_capacity(n);
                let (sa, _) =
                    SupportSet::new(&a, &normal, 1.0, SUPPORT_TOLERANCE * a.radius(), capacity);
                let (sb, _) =
                    SupportSet::new(&b, &normal, -1.0, SUPPORT_TOLERANCE * b.radius(), capacity);
                let scale = a.radius().max(b.radius());
                let fast = visits(hull_region, (&sa, &sb), &normal, scale);
                let brute = visits(reference_region, (&sa, &sb), &normal, scale);
                assert_eq!(fast, brute, "N = {n}, case {case}");
                cases += 1;
                vertices += fast.len();
                by_kind[kind] += fast.len();
            }
        }
        assert_eq!(cases, 300);
        // Every kind of case meets its region somewhere (so the comparison is not empty).
        assert!(by_kind.iter().all(|&k| k > 0), "{by_kind:?}");
        assert!(vertices > 1000, "{vertices}");
    }

    /// The unpruned brute force: every pair of subsets solved from scratch.
    fn reference_region(
        sa: &SupportSet,
        sb: &SupportSet,
        normal: &[f64],
        margin: f64,
        scale: f64,
        visit: &mut dyn FnMut(RegionVertex<'_>),
    ) {
        let n = normal.len();
        let d = n - 1;
        let mut xa: SmallVec<[f64; 64]> = SmallVec::new();
        let mut xb: SmallVec<[f64; 64]> = SmallVec::new();
        let mut c: Small = SmallVec::new();
        for k in 0..sa.len() {
            plane_coordinates(normal, sa.point(k), &mut c);
            xa.extend_from_slice(&c);
        }
        for k in 0..sb.len() {
            plane_coordinates(normal, sb.point(k), &mut c);
            xb.extend_from_slice(&c);
        }
        let tol = 1e-9 * scale;
        let bary_tol = 1e-9;
        let mut columns: SmallVec<[f64; 64]> = SmallVec::new();
        let mut rhs: Small = SmallVec::new();
        let mut z: Small = SmallVec::new();
        let (mut pa, mut pb): (Small, Small) =
            (SmallVec::from_elem(0.0, n), SmallVec::from_elem(0.0, n));
        let mut x: Small = SmallVec::from_elem(0.0, d);
        for mask_a in 1u32..(1 << sa.len()) {
            let ka = mask_a.count_ones() as usize;
            if ka > d + 1 {
                continue;
            }
            for mask_b in 1u32..(1 << sb.len()) {
                let kb = mask_b.count_ones() as usize;
                if ka + kb > d + 2 {
                    continue;
                }
                let ia: SmallVec<[usize; 8]> =
                    (0..sa.len()).filter(|i| mask_a >> i & 1 == 1).collect();
                let ib: SmallVec<[usize; 8]> =
                    (0..sb.len()).filter(|i| mask_b >> i & 1 == 1).collect();
                let a0 = &xa[ia[0] * d..(ia[0] + 1) * d];
                let b0 = &xb[ib[0] * d..(ib[0] + 1) * d];
                // Columns: a_i − a_0 (i ≥ 1), −(b_j − b_0) (j ≥ 1); right side b_0 − a_0.
                columns.clear();
                for &i in &ia[1..] {
                    columns.extend((0..d).map(|t| xa[i * d + t] - a0[t]));
                }
                for &j in &ib[1..] {
                    columns.extend((0..d).map(|t| -(xb[j * d + t] - b0[t])));
                }
                rhs.clear();
                rhs.extend((0..d).map(|t| b0[t] - a0[t]));
                let m = ka + kb - 2;
                if !least_squares(&mut columns, d, m, &mut rhs, &mut z, tol) {
                    continue;
                }
                // Barycentric coordinates within both simplices.
                let sum_a: f64 = z[..ka - 1].iter().sum();
                let sum_b: f64 = z[ka - 1..].iter().sum();
                if z.iter().any(|w| *w < -bary_tol)
                    || sum_a > 1.0 + bary_tol
                    || sum_b > 1.0 + bary_tol
                {
                    continue;
                }
                for k in 0..n {
                    pa[k] = (1.0 - sum_a) * sa.point(ia[0])[k]
                        + ia[1..]
                            .iter()
                            .zip(&z[..ka - 1])
                            .map(|(&i, w)| w * sa.point(i)[k])
                            .sum::<f64>();
                    pb[k] = (1.0 - sum_b) * sb.point(ib[0])[k]
                        + ib[1..]
                            .iter()
                            .zip(&z[ka - 1..])
                            .map(|(&j, w)| w * sb.point(j)[k])
                            .sum::<f64>();
                }
                let depth = dot(normal, &pa) - dot(normal, &pb);
                if depth < -margin {
                    continue;
                }
                for t in 0..d {
                    x[t] = (1.0 - sum_a) * a0[t]
                        + ia[1..]
                            .iter()
                            .zip(&z[..ka - 1])
                            .map(|(&i, w)| w * xa[i * d + t])
                            .sum::<f64>();
                }
                // A full-dimensional simplex only says "inside": leave it out of the id, so that
                // the id does not depend on which of the simplices holding the point found it.
                let mut hash = 0xcbf2_9ce4_8422_2325u64;
                let mut mix = |v: u64| {
                    hash ^= v;
                    hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
                };
                if ka <= d {
                    ia.iter().for_each(|&i| mix(sa.indices[i] as u64 + 1));
                }
                mix(u64::MAX);
                if kb <= d {
                    ib.iter().for_each(|&j| mix(sb.indices[j] as u64 + 1));
                }
                visit(RegionVertex {
                    point_a: &pa,
                    point_b: &pb,
                    plane: &x,
                    depth,
                    id: FeatureId(KIND_HULL | hash >> 2),
                });
            }
        }
    }

    /// Solves the d × m least-squares problem (columns flat, column after column) by
    /// Gram–Schmidt QR; false when the columns are dependent (relative to `tol`) or the residual
    /// exceeds `tol` (the flats do not meet).
    fn least_squares(
        columns: &mut SmallVec<[f64; 64]>,
        d: usize,
        m: usize,
        rhs: &mut Small,
        z: &mut Small,
        tol: f64,
    ) -> bool {
        // R, upper triangular m × m, from modified Gram–Schmidt twice.
        let mut r: SmallVec<[f64; 64]> = SmallVec::from_elem(0.0, m * m);
        for j in 0..m {
            let original = dot(&columns[j * d..(j + 1) * d], &columns[j * d..(j + 1) * d]).sqrt();
            for _ in 0..2 {
                for i in 0..j {
                    let (qi, qj) = columns.split_at_mut(j * d);
                    let qi = &qi[i * d..(i + 1) * d];
                    let qj = &mut qj[..d];
                    let p = dot(qi, qj);
                    r[i * m + j] += p;
                    qj.iter_mut().zip(qi).for_each(|(x, y)| *x -= p * y);
                }
            }
            let qj = &mut columns[j * d..(j + 1) * d];
            let len = dot(qj, qj).sqrt();
            if len.is_nan() || len <= 1e-9 * original.max(tol) {
                return false;
            }
            qj.iter_mut().for_each(|x| *x /= len);
            r[j * m + j] = len;
        }
        // z = R⁻¹ Qᵀ rhs, residual = rhs − Q Qᵀ rhs.
        z.clear();
        for j in 0..m {
            let q = &columns[j * d..(j + 1) * d];
            let p = dot(q, rhs);
            z.push(p);
            rhs.iter_mut().zip(q).for_each(|(x, y)| *x -= p * y);
        }
        let residual = dot(rhs, rhs).sqrt();
        if residual.is_nan() || residual > tol {
            return false;
        }
        for j in (0..m).rev() {
            for k in j + 1..m {
                z[j] -= r[j * m + k] * z[k];
            }
            z[j] /= r[j * m + j];
        }
        true
    }
}
