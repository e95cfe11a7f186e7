//! One contact point of a velocity solve: its matrices and its Gauss–Seidel update.

use super::Dense;
use super::body::{BodyState, BodyView};
use super::friction::friction_impulse;
use crate::algebra::Vector;
use crate::dynamics::motion::HalfSpace;
use crate::dynamics::motion::placement::dot;
use crate::numeric::symmetric_eigen_rows as symmetric_eigen;
use smallvec::SmallVec;

/// N numbers of a solve, inline up to 4D: a body's velocity or momentum, a contact row's
/// point, offset or friction impulse.
pub(crate) type Linear = SmallVec<[f64; 4]>;
/// M numbers of a solve, inline up to 4D: a body's angular velocity or momentum.
pub(crate) type Angular = SmallVec<[f64; 6]>;

/// One contact point in a solve.
#[derive(Clone, Debug)]
pub(crate) struct ContactRow {
    pub body: usize,
    pub half_space: usize,
    /// The candidate's number on its body and half-space (from 1).
    pub index: usize,
    /// The point in own axes and its offset from the centre of mass in space.
    pub point: Linear,
    pub r: Linear,
    /// The signed distance of the point from the plane when found.
    pub gap: f64,
    /// The distance up to which the point counts as touching; farther points are
    /// speculative: the body may approach there by the gap within the next flight, no more.
    pub reach: f64,
    /// The normal velocity wanted after the impulse (0, −e u⁻ for an impact, or −gap over
    /// the flight for a speculative point).
    pub target: f64,
    pub normal_impulse: f64,
    pub friction_impulse: Linear,
    /// The normal impulse added in the free flight to keep the point out (position level).
    pub position_impulse: f64,
    /// nᵀ K n and the point's speed (set when the solve starts; the rest of K is in the
    /// solver's row matrices).
    pub knn: f64,
    pub(super) speed: f64,
    /// True if the impulses are the last solve's at the same point (a warm start).
    pub(super) warm: bool,
    /// The generation of the placement `point` and `r` were copied from (0: none).
    pub(super) placed: u64,
}

/// Where the matrices of one contact row lie in the solver's `row_data` (N = n, M planes):
/// W (M × n: the angular velocity per impulse, I⁻¹ (r ∧ ·)), the products with the normal
/// of C (n × M: the velocity at the point per angular velocity, u = v + C w) and W — Cᵀn,
/// which is also R n = r ∧ n for R (M × n: the angular impulse, r ∧ ·), and W n —, the
/// tangent block K_t of K with its eigen-decomposition, nᵀ K n and its inverse, and K_t⁻¹
/// (for the sticking impulse). C and R themselves are not kept: their only entries are
/// ±rⱼ, read through the offset.
#[derive(Clone, Copy, Debug)]
pub(super) struct RowLayout {
    pub(super) n: usize,
    pub(super) m: usize,
    pub(super) w: usize,
    pub(super) cn: usize,
    pub(super) wn: usize,
    pub(super) kt: usize,
    pub(super) values: usize,
    pub(super) vectors: usize,
    pub(super) knn: usize,
    pub(super) inv_knn: usize,
    pub(super) kinv: usize,
    pub(super) stride: usize,
}

impl RowLayout {
    #[inline(always)]
    pub(super) fn new(n: usize) -> RowLayout {
        let m = n * (n - 1) / 2;
        // What every sweep reads first and together, what only sliding contacts read last.
        let w = 0;
        let cn = w + m * n;
        let wn = cn + m;
        let knn = wn + m;
        let inv_knn = knn + 1;
        let kinv = inv_knn + 1;
        let kt = kinv + n * n;
        let values = kt + n * n;
        let vectors = values + n;
        RowLayout {
            n,
            m,
            w,
            cn,
            wn,
            kt,
            values,
            vectors,
            knn,
            inv_knn,
            kinv,
            stride: vectors + n * n,
        }
    }
}

/// What a contact row's matrices were computed for: the generation of its body's inverse
/// inertia (which also fixes the mass), the point's offset from the centre of mass and the
/// normal. The matrices are functions of these alone, so that a row keeps them wherever
/// the same offset comes back, as under a ball rolling on a plane.
#[derive(Clone, Debug, Default)]
pub(super) struct RowKey {
    pub(super) generation: u64,
    pub(super) r: Small,
    pub(super) normal: Small,
}

impl RowKey {
    /// True if the matrices of the key are those of `generation`, `r` and `normal`.
    #[inline(always)]
    pub(super) fn is(&self, generation: u64, r: &[f64], normal: &[f64]) -> bool {
        self.generation == generation && self.r[..] == *r && self.normal[..] == *normal
    }

    /// Makes the key that of `generation`, `r` and `normal`.
    pub(super) fn set(&mut self, generation: u64, r: &[f64], normal: &[f64]) {
        self.generation = generation;
        self.r.clear();
        self.r.extend_from_slice(r);
        self.normal.clear();
        self.normal.extend_from_slice(normal);
    }
}

pub(super) use crate::numeric::dim;

/// The planes through each axis in 3D and 4D, in their order: the entries of row i of C
/// (whose column p is r ⌋ e_p) that can be non-zero.
pub(super) const PLANES_THROUGH_3: [[usize; 2]; 3] = [[0, 1], [0, 2], [1, 2]];
pub(super) const PLANES_THROUGH_4: [[usize; 3]; 4] = [[0, 1, 2], [0, 3, 4], [1, 3, 5], [2, 4, 5]];

/// The axes of each plane in 3D and 4D: the entries of row p of R (whose column j is
/// r ∧ e_j) that can be non-zero, and the entries of column p of C.
pub(super) const AXES_OF_3: [[usize; 2]; 3] = [[0, 1], [0, 2], [1, 2]];
pub(super) const AXES_OF_4: [[usize; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];

/// The entries of row `i` of an n × n(n−1)/2 matrix C (columns r ⌋ e_p) that can be
/// non-zero, when the dimension is fixed at 3 or 4 (None: all of them).
#[inline(always)]
pub(super) fn planes_through<const N: usize>(i: usize) -> Option<&'static [usize]> {
    match N {
        3 => Some(&PLANES_THROUGH_3[i]),
        4 => Some(&PLANES_THROUGH_4[i]),
        _ => None,
    }
}

/// The axes of every plane when the dimension is fixed at 3 or 4 (None: any other).
#[inline(always)]
pub(super) fn axes_of<const N: usize>() -> Option<&'static [[usize; 2]]> {
    match N {
        3 => Some(&AXES_OF_3),
        4 => Some(&AXES_OF_4),
        _ => None,
    }
}

/// u += r ⌋ w = C w: column p = (a, b) of C holds −r_b at a and r_a at b
/// (r ⌋ (eₐ ∧ e_b) = rₐ e_b − r_b eₐ), the planes in the order of the bivector's
/// coefficients.
#[inline(always)]
pub(super) fn add_contraction(r: &[f64], w: &[f64], u: &mut [f64]) {
    let n = r.len();
    let mut p = 0;
    for a in 0..n {
        for b in a + 1..n {
            u[b] += r[a] * w[p];
            u[a] -= r[b] * w[p];
            p += 1;
        }
    }
}

/// u = v + C w at a row's point, at `offset` from the centre of mass, C read through the
/// offset (`N` as in [`dim`]).
#[inline(always)]
pub(super) fn point_velocity<const N: usize>(
    l: &RowLayout,
    offset: &[f64],
    v: &[f64],
    w: &[f64],
    u: &mut [f64],
) {
    let n = dim::<N>(l.n);
    let m = n * (n - 1) / 2;
    let w = &w[..m];
    if let Some(axes) = axes_of::<N>() {
        for (i, (ui, vi)) in u[..n].iter_mut().zip(&v[..n]).enumerate() {
            let through = planes_through::<N>(i).unwrap_or(&[]);
            *ui = vi
                + through
                    .iter()
                    .map(|&p| contraction_entry(offset, axes[p], i) * w[p])
                    .sum::<f64>();
        }
        return;
    }
    // C w is summed before v is added, in the order of the fixed-size kernels, which then
    // give the same velocities.
    u[..n].fill(0.0);
    add_contraction(&offset[..n], w, u);
    for (ui, vi) in u[..n].iter_mut().zip(&v[..n]) {
        *ui += vi;
    }
}

/// Entry (i, p) of C (column p: r ⌋ e_p) for the offset r and an axis i of plane p =
/// (a, b), a < b: −r_b for i = a, r_a for i = b. Entry (p, j) of R (column j: r ∧ e_j) is
/// the same for j the other axis of the plane.
#[inline(always)]
pub(super) fn contraction_entry(offset: &[f64], [a, b]: [usize; 2], i: usize) -> f64 {
    if i == a { -offset[b] } else { offset[a] }
}

/// y += a A x for an M × n row-major A.
#[inline(always)]
pub(super) fn add_mat_vec(y: &mut [f64], a_mat: &[f64], a: f64, x: &[f64]) {
    for (yp, row) in y.iter_mut().zip(a_mat.chunks_exact(x.len())) {
        *yp += a * dot(row, x);
    }
}

/// One Gauss–Seidel update of a contact: the normal impulse, then the friction impulse,
/// through the row's matrices `data` laid out by `l` (`N` as in [`dim`]). Returns the
/// largest velocity change it made.
#[inline(always)]
pub(super) fn sweep_contact<const N: usize>(
    row: &mut ContactRow,
    data: &[f64],
    l: &RowLayout,
    plane: &HalfSpace,
    st: &mut BodyView<'_>,
) -> f64 {
    let n = dim::<N>(l.n);
    let m = n * (n - 1) / 2;
    let mut change = 0.0f64;
    let nv = &plane.normal().as_slice()[..n];
    // Normal: the smallest accumulated λ ≥ 0 reaching the target; u·n = v·n + (Cᵀn)·w.
    let un = dot(nv, &st.v[..n]) + dot(&data[l.cn..l.cn + m], &st.w[..m]);
    let lambda = (row.normal_impulse + (row.target - un) * data[l.inv_knn]).max(0.0);
    let dl = lambda - row.normal_impulse;
    if dl != 0.0 {
        st.apply_normal::<N>(data, l, nv, dl);
        row.normal_impulse = lambda;
    }
    change = change.max((dl * row.knn).abs());
    // Friction: maximal dissipation in the disc |J_t| ≤ μλ.
    let limit = plane.friction() * row.normal_impulse;
    let (mut ut_fixed, mut ut_any) = ([0.0; 4], Small::new());
    let ut = scratch::<N>(&mut ut_fixed, &mut ut_any, n);
    let offset = &row.r.as_slice()[..n];
    point_velocity::<N>(l, offset, &st.v[..n], &st.w[..m], ut);
    let normal_part = dot(nv, ut);
    for (u, x) in ut.iter_mut().zip(nv) {
        *u -= normal_part * x;
    }
    let (mut new_fixed, mut new_any) = ([0.0; 4], Small::new());
    let new = scratch::<N>(&mut new_fixed, &mut new_any, n);
    // The sticking impulse old − K_t⁻¹ u_t when it lies in the disc (a resting contact),
    // else the one of maximal dissipation on its rim.
    let old = &row.friction_impulse.as_slice()[..n];
    let kinv = &data[l.kinv..l.kinv + n * n];
    for ((x, o), k) in new.iter_mut().zip(old).zip(kinv.chunks_exact(n)) {
        *x = o - dot(k, ut);
    }
    if limit <= 0.0 {
        new.fill(0.0);
    } else if dot(new, new) > limit * limit {
        friction_impulse::<N>(
            &data[l.values..l.values + n],
            &data[l.vectors..l.vectors + n * n],
            &data[l.kt..l.kt + n * n],
            row.friction_impulse.as_slice(),
            ut,
            limit,
            new,
        );
    }
    let (mut dj_fixed, mut dj_any) = ([0.0; 4], Small::new());
    let dj = scratch::<N>(&mut dj_fixed, &mut dj_any, n);
    let mut largest = 0.0f64;
    for ((d, x), y) in dj.iter_mut().zip(new.iter()).zip(old) {
        *d = x - y;
        largest = largest.max(d.abs());
    }
    if largest > 0.0 {
        st.apply_with::<N>(data, l, offset, dj);
        row.friction_impulse.as_mut_slice().copy_from_slice(new);
        change = change.max(largest * row.knn);
    }
    change
}

/// A short vector on the stack (N ≤ 8).
pub(super) type Small = SmallVec<[f64; 8]>;

/// A zero scratch vector of length n (`N` as in [`dim`]): `fixed` in 3D and 4D, where its
/// length is known and it needs no check of its storage, else `any`.
#[inline(always)]
pub(super) fn scratch<'a, const N: usize>(
    fixed: &'a mut [f64; 4],
    any: &'a mut Small,
    n: usize,
) -> &'a mut [f64] {
    if N != 0 {
        &mut fixed[..n]
    } else {
        any.resize(n, 0.0);
        &mut any[..n]
    }
}

/// Computes a contact row's matrices ([`RowLayout`]) for a body state `st`, the offset `r`
/// of the point and the unit normal `nrm`.
pub(super) fn row_matrices(
    st: &BodyState,
    r: &[f64],
    nrm: &Vector,
    l: &RowLayout,
    data: &mut [f64],
) {
    let (n, m) = (l.n, l.m);
    let (r, nv) = (&r[..n], &nrm.as_slice()[..n]);
    // Plane p = (a, b) holds −r_b at a and r_a at b in row p of R (column j: r ∧ e_j) and
    // in column p of C (column p: r ⌋ e_p); nothing else.
    // W = I⁻¹ R, column q of I⁻¹ times row q of R.
    let inv = &st.inv_inertia[..m * m];
    data[l.w..l.w + m * n].fill(0.0);
    let mut q = 0;
    for a in 0..n {
        for b in a + 1..n {
            // Cᵀn = R n = r ∧ n.
            data[l.cn + q] = r[a] * nv[b] - r[b] * nv[a];
            for p in 0..m {
                let x = inv[p * m + q];
                data[l.w + p * n + a] -= x * r[b];
                data[l.w + p * n + b] += x * r[a];
            }
            q += 1;
        }
    }
    for p in 0..m {
        data[l.wn + p] = dot(&data[l.w + p * n..l.w + (p + 1) * n], nv);
    }
    // K = 1/m + C W: row a of K takes −r_b times row p of W, row b takes r_a times it.
    let mut k: Dense = SmallVec::from_elem(0.0, n * n);
    for i in 0..n {
        k[i * n + i] = st.inv_mass;
    }
    let mut p = 0;
    for a in 0..n {
        for b in a + 1..n {
            for j in 0..n {
                let x = data[l.w + p * n + j];
                k[a * n + j] -= r[b] * x;
                k[b * n + j] += r[a] * x;
            }
            p += 1;
        }
    }
    data[l.knn] = (0..n)
        .map(|i| (0..n).map(|j| nv[i] * k[i * n + j] * nv[j]).sum::<f64>())
        .sum();
    // The sweeps multiply by it: a division would lengthen the chain from one row to the next.
    data[l.inv_knn] = 1.0 / data[l.knn];
    tangent_block(&mut k, nrm);
    let (mut values, mut vectors) = (Dense::new(), Dense::new());
    symmetric_eigen(&k, n, &mut values, &mut vectors);
    data[l.kt..l.kt + n * n].copy_from_slice(&k);
    data[l.values..l.values + n].copy_from_slice(&values);
    data[l.vectors..l.vectors + n * n].copy_from_slice(&vectors);
    // K_t⁻¹ = V diag(1/d) Vᵀ.
    for i in 0..n {
        for j in 0..n {
            data[l.kinv + i * n + j] = (0..n)
                .map(|k| vectors[i * n + k] * vectors[j * n + k] / values[k])
                .sum();
        }
    }
}

/// Turns the inverse mass k into its tangent block P k P + n nᵀ (P = 1 − n nᵀ), which maps
/// the tangent space to itself and keeps the normal apart.
pub(super) fn tangent_block(k: &mut [f64], nrm: &Vector) {
    tangent_block_n::<0>(k, nrm.as_slice());
}

/// [`tangent_block`] of the normal `nv` (`N` as in [`dim`]).
#[inline(always)]
pub(super) fn tangent_block_n<const N: usize>(k: &mut [f64], nv: &[f64]) {
    let n = dim::<N>(nv.len());
    let nv = &nv[..n];
    let k = &mut k[..n * n];
    // k n and nᵀ k n.
    let (mut kn_fixed, mut kn_any) = ([0.0; 4], Small::new());
    let kn = scratch::<N>(&mut kn_fixed, &mut kn_any, n);
    for (i, x) in kn.iter_mut().enumerate() {
        *x = (0..n).map(|j| k[i * n + j] * nv[j]).sum();
    }
    let nkn: f64 = (0..n).map(|i| nv[i] * kn[i]).sum();
    for i in 0..n {
        for j in 0..n {
            // P k P = k − n (kn)ᵀ − (kn) nᵀ + (nᵀkn) n nᵀ
            k[i * n + j] += -nv[i] * kn[j] - kn[i] * nv[j] + nkn * nv[i] * nv[j] + nv[i] * nv[j];
        }
    }
}
