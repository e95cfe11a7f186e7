//! Impulses that keep joints together and bodies out of half-spaces: the velocity-level
//! solve (Signorini's condition with restitution and Coulomb's friction cone at each
//! contact, the ball joints' relative velocity) and the position-level solve of the joints.
//!
//! Each contact or joint acts on body points through impulses J; the point's velocity
//! answers linearly, Δu = K J, with the contact's effective inverse mass
//! K = (1/m) 1 + (r ⌋ I_s⁻¹ (r ∧ ·)) (for a joint between two bodies the sum of both). The
//! solve is projected Gauss–Seidel over the contacts and joints, each solved exactly as a
//! block: the normal impulse is the smallest λ ≥ 0 that stops the approach (or reverses it
//! by e for an impact), and the friction impulse is the one of maximal dissipation in the
//! disc |J_t| ≤ μ λ — the sticking impulse when it fits, else the one on the rim whose
//! remaining slip is exactly opposite to it (a trust-region problem in the (N−1)-dimensional
//! tangent space, solved by Newton's method on its multiplier, Moré–Sorensen).

use super::contact::ContactLog;
use super::forques::Anchor;
use super::placement::{Placements, attitudes_close, dot, set_vector};
use super::{BallJoint, ContactShape, HalfSpace, MovingBody};
use crate::algebra::{Bivector, Vector};
use crate::dynamics::Attitude;
use smallvec::SmallVec;

/// Up to N = 8 the matrices live on the stack.
type Dense = SmallVec<[f64; 64]>;

/// Gauss–Seidel sweeps of the velocity solve, at most.
const MAX_SWEEPS: usize = 20_000;

/// One body during a solve: its velocity and angular velocity (space) as the impulses so
/// far leave them, its inverse mass and inverse inertia in space, and the impulses to hand
/// back to its momenta when the solve ends.
#[derive(Clone, Debug)]
pub(crate) struct BodyState {
    inv_mass: f64,
    /// I⁻¹ in space, M × M row-major on the bivector components.
    inv_inertia: Vec<f64>,
    /// The rotation of the principal frame on bivectors, M × M row-major (columns: the
    /// images of the basis planes).
    frame: Vec<f64>,
    v: Vector,
    w: Bivector,
    dp: Vector,
    dl: Bivector,
    pub used: bool,
    /// The attitude of the principal frame, the mass and the inverse plane moments that
    /// `frame` and `inv_inertia` were computed for (None when they must be computed anew):
    /// a body at the same placement as at the last solve reuses them.
    key: Option<(Attitude, f64)>,
    key_moments: SmallVec<[f64; 28]>,
    /// Changes whenever `frame` and `inv_inertia` are computed anew.
    generation: u64,
}

impl BodyState {
    fn empty(n: usize) -> BodyState {
        BodyState {
            inv_mass: 0.0,
            inv_inertia: Vec::new(),
            frame: Vec::new(),
            v: Vector::zero(n),
            w: Bivector::zero(n),
            dp: Vector::zero(n),
            dl: Bivector::zero(n),
            used: false,
            key: None,
            key_moments: SmallVec::new(),
            generation: 0,
        }
    }

    /// Loads body `b`: the rotation of the planes by its principal frame P, I⁻¹ in space
    /// (P I⁻¹ Pᵀ on bivectors), its velocities, no impulse yet. Returns true if the frame
    /// and the inverse inertia were computed anew (false: the body has not turned since
    /// they were).
    fn load(&mut self, b: &MovingBody, work: &mut Dense) -> bool {
        let n = b.dim();
        let m = n * (n - 1) / 2;
        let attitude = b.rotation().principal_frame_attitude();
        let inertia = b.rotation().inertia();
        let diagonal = inertia.diagonal_inverse_plane_moments();
        let same = match (&self.key, diagonal) {
            (Some((a, mass)), Some(inv)) => {
                attitudes_close(a, attitude) && *mass == b.mass() && self.key_moments[..] == inv[..]
            }
            _ => false,
        };
        if !same {
            self.place(b, work);
            match diagonal {
                Some(inv) => {
                    self.key = Some((attitude.clone(), b.mass()));
                    self.key_moments.clear();
                    self.key_moments.extend_from_slice(inv);
                }
                None => self.key = None,
            }
        }
        self.inv_mass = 1.0 / b.mass();
        set_vector(&mut self.v, b.linear_momentum().as_slice());
        self.v *= self.inv_mass;
        match diagonal {
            // ω in space = P (I⁻¹ L), I⁻¹ diagonal in the principal frame.
            Some(inv) => {
                let (l, w) = (b.rotation().momentum().as_slice(), self.w.as_mut_slice());
                match m {
                    3 => frame_diagonal::<3>(&self.frame, inv, l, w),
                    6 => frame_diagonal::<6>(&self.frame, inv, l, w),
                    _ => frame_diagonal::<0>(&self.frame, inv, l, w),
                }
            }
            None => self.w = b.space_omega(),
        }
        self.dp.as_mut_slice().fill(0.0);
        self.dl.as_mut_slice().fill(0.0);
        self.used = true;
        !same
    }

    /// Computes the rotation of the planes by the principal frame and I⁻¹ in space.
    fn place(&mut self, b: &MovingBody, work: &mut Dense) {
        let n = b.dim();
        let m = n * (n - 1) / 2;
        work.clear();
        work.resize(n * n, 0.0);
        b.rotation().principal_frame_attitude().write_matrix(work);
        let p = &work[..];
        self.frame.clear();
        self.frame.resize(m * m, 0.0);
        for (k, (a, bb)) in crate::algebra::pairs(n).enumerate() {
            for (row, (c, d)) in crate::algebra::pairs(n).enumerate() {
                self.frame[row * m + k] =
                    p[c * n + a] * p[d * n + bb] - p[d * n + a] * p[c * n + bb];
            }
        }
        let inertia = b.rotation().inertia();
        self.inv_inertia.clear();
        self.inv_inertia.resize(m * m, 0.0);
        if let Some(inv) = inertia.diagonal_inverse_plane_moments() {
            // F diag(1/I) Fᵀ.
            for i in 0..m {
                for j in 0..m {
                    self.inv_inertia[i * m + j] = (0..m)
                        .map(|k| self.frame[i * m + k] * inv[k] * self.frame[j * m + k])
                        .sum();
                }
            }
            return;
        }
        // I⁻¹ in the principal frame, column by column, then F I⁻¹ Fᵀ.
        let mut ip: SmallVec<[f64; 784]> = SmallVec::from_elem(0.0, m * m);
        let mut e = Bivector::zero(n);
        for k in 0..m {
            e.as_mut_slice().fill(0.0);
            e.as_mut_slice()[k] = 1.0;
            let col = inertia.apply_inverse(&e);
            for (row, x) in col.as_slice().iter().enumerate() {
                ip[row * m + k] = *x;
            }
        }
        let mut fi: SmallVec<[f64; 784]> = SmallVec::from_elem(0.0, m * m);
        for i in 0..m {
            for j in 0..m {
                fi[i * m + j] = (0..m).map(|k| self.frame[i * m + k] * ip[k * m + j]).sum();
            }
        }
        for i in 0..m {
            for j in 0..m {
                self.inv_inertia[i * m + j] =
                    (0..m).map(|k| fi[i * m + k] * self.frame[j * m + k]).sum();
            }
        }
    }

    /// I⁻¹ B (space).
    fn inverse_inertia(&self, b: &Bivector) -> Bivector {
        let m = b.as_slice().len();
        let mut out = Bivector::zero(b.dim());
        for (i, o) in out.as_mut_slice().iter_mut().enumerate() {
            *o = (0..m)
                .map(|k| self.inv_inertia[i * m + k] * b.as_slice()[k])
                .sum();
        }
        out
    }

    /// The velocity change at offset `q` for an impulse `j` at offset `r`.
    fn response(&self, r: &Vector, j: &Vector, q: &Vector) -> Vector {
        let mut du = j * self.inv_mass;
        du += &q.left_contract(&self.inverse_inertia(&r.wedge(j)));
        du
    }

    /// The velocity of the point at offset `r`.
    fn velocity_at(&self, r: &Vector) -> Vector {
        let mut u = self.v.clone();
        u += &r.left_contract(&self.w);
        u
    }

    /// Takes an impulse `j` at offset `r`.
    fn apply(&mut self, r: &Vector, j: &Vector) {
        let dl = r.wedge(j);
        self.v += &(j * self.inv_mass);
        self.w += &self.inverse_inertia(&dl);
        self.dp += j;
        self.dl += &dl;
    }

    /// Its velocities and impulses as slices of length N and M (`N` as in [`dim`]): taken
    /// once for all the rows of a body, they spare each row the checks of the vectors'
    /// storage.
    #[inline(always)]
    fn view<const N: usize>(&mut self) -> BodyView<'_> {
        let n = dim::<N>(self.v.dim());
        let m = n * (n - 1) / 2;
        BodyView {
            inv_mass: self.inv_mass,
            v: &mut self.v.as_mut_slice()[..n],
            w: &mut self.w.as_mut_slice()[..m],
            dp: &mut self.dp.as_mut_slice()[..n],
            dl: &mut self.dl.as_mut_slice()[..m],
        }
    }

    /// Hands the impulses to body `b`: p += Σ J, L += Pᵀ (Σ r ∧ J) in the principal frame.
    fn store(&mut self, b: &mut MovingBody) {
        let m = self.dl.as_slice().len();
        let (_, p, rotation) = b.state_mut();
        *p += &self.dp;
        let (_, l) = rotation.state_mut();
        let (dl, l) = (self.dl.as_slice(), l.as_mut_slice());
        match m {
            3 => add_frame_transpose::<3>(&self.frame, dl, l),
            6 => add_frame_transpose::<6>(&self.frame, dl, l),
            _ => add_frame_transpose::<0>(&self.frame, dl, l),
        }
        self.used = false;
    }
}

/// w = F diag(`inv`) `l` for the rotation F of the planes (M × M row-major; `M` fixed, or 0
/// for `w.len()`).
#[inline(always)]
fn frame_diagonal<const M: usize>(frame: &[f64], inv: &[f64], l: &[f64], w: &mut [f64]) {
    let m = if M == 0 { w.len() } else { M };
    let (frame, inv, l) = (&frame[..m * m], &inv[..m], &l[..m]);
    for (i, w) in w[..m].iter_mut().enumerate() {
        *w = (0..m).map(|k| frame[i * m + k] * inv[k] * l[k]).sum();
    }
}

/// l += Fᵀ `dl` for the rotation F of the planes (M × M row-major; `M` fixed, or 0 for
/// `l.len()`).
#[inline(always)]
fn add_frame_transpose<const M: usize>(frame: &[f64], dl: &[f64], l: &mut [f64]) {
    let m = if M == 0 { l.len() } else { M };
    let (frame, dl) = (&frame[..m * m], &dl[..m]);
    for (i, x) in l[..m].iter_mut().enumerate() {
        *x += (0..m).map(|k| frame[k * m + i] * dl[k]).sum::<f64>();
    }
}

/// A body's velocities and impulses during a contact solve ([`BodyState::view`]).
struct BodyView<'a> {
    inv_mass: f64,
    v: &'a mut [f64],
    w: &'a mut [f64],
    dp: &'a mut [f64],
    dl: &'a mut [f64],
}

impl BodyView<'_> {
    /// Takes an impulse `j` at the point of a contact row with matrices `data` (`N` as in
    /// [`dim`]).
    #[inline(always)]
    fn apply_with<const N: usize>(
        &mut self,
        data: &[f64],
        l: &RowLayout,
        offset: &[f64],
        j: &[f64],
    ) {
        let n = dim::<N>(self.v.len());
        let m = n * (n - 1) / 2;
        let j = &j[..n];
        for ((v, dp), x) in self.v[..n].iter_mut().zip(&mut self.dp[..n]).zip(j) {
            *v += x * self.inv_mass;
            *dp += x;
        }
        add_mat_vec(&mut self.w[..m], &data[l.w..l.w + m * n], 1.0, j);
        if let Some(axes) = axes_of::<N>() {
            // Row p of R holds −r_b at a and r_a at b (plane p = (a, b)).
            for (d, &[a, b]) in self.dl[..m].iter_mut().zip(axes) {
                *d += [
                    contraction_entry(offset, [a, b], a) * j[a],
                    offset[a] * j[b],
                ]
                .iter()
                .sum::<f64>();
            }
            return;
        }
        let r = &data[l.r..l.r + m * n];
        for (d, row) in self.dl[..m].iter_mut().zip(r.chunks_exact(n)) {
            *d += dot(row, j);
        }
    }

    /// Takes the normal impulse λ n at the point of a contact row with matrices `data`
    /// (`N` as in [`dim`]).
    #[inline(always)]
    fn apply_normal<const N: usize>(
        &mut self,
        data: &[f64],
        l: &RowLayout,
        nrm: &[f64],
        lambda: f64,
    ) {
        let n = dim::<N>(self.v.len());
        let m = n * (n - 1) / 2;
        for ((v, dp), x) in self.v[..n].iter_mut().zip(&mut self.dp[..n]).zip(&nrm[..n]) {
            *v += lambda * x * self.inv_mass;
            *dp += lambda * x;
        }
        for (w, x) in self.w[..m].iter_mut().zip(&data[l.wn..l.wn + m]) {
            *w += lambda * x;
        }
        for (d, x) in self.dl[..m].iter_mut().zip(&data[l.rn..l.rn + m]) {
            *d += lambda * x;
        }
    }
}

/// A body's velocities and impulses copied out of its state in 3D or 4D, so that over the
/// rows of a one-body group they stay in registers instead of going through the state's
/// storage after every impulse.
struct LocalBody {
    inv_mass: f64,
    n: usize,
    m: usize,
    v: [f64; 4],
    w: [f64; 6],
    dp: [f64; 4],
    dl: [f64; 6],
}

impl LocalBody {
    #[inline(always)]
    fn new(st: &BodyView<'_>) -> LocalBody {
        let (n, m) = (st.v.len(), st.w.len());
        let mut b = LocalBody {
            inv_mass: st.inv_mass,
            n,
            m,
            v: [0.0; 4],
            w: [0.0; 6],
            dp: [0.0; 4],
            dl: [0.0; 6],
        };
        b.v[..n].copy_from_slice(st.v);
        b.w[..m].copy_from_slice(st.w);
        b.dp[..n].copy_from_slice(st.dp);
        b.dl[..m].copy_from_slice(st.dl);
        b
    }

    #[inline(always)]
    fn view(&mut self) -> BodyView<'_> {
        BodyView {
            inv_mass: self.inv_mass,
            v: &mut self.v[..self.n],
            w: &mut self.w[..self.m],
            dp: &mut self.dp[..self.n],
            dl: &mut self.dl[..self.m],
        }
    }

    /// Writes the velocities and impulses back.
    #[inline(always)]
    fn store(&self, st: &mut BodyView<'_>) {
        st.v.copy_from_slice(&self.v[..self.n]);
        st.w.copy_from_slice(&self.w[..self.m]);
        st.dp.copy_from_slice(&self.dp[..self.n]);
        st.dl.copy_from_slice(&self.dl[..self.m]);
    }
}

/// The effective inverse mass of a body state at offset `r`, added to `k` (n × n, row-major).
fn add_inverse_mass(b: &BodyState, r: &Vector, k: &mut [f64]) {
    let n = r.dim();
    for c in 0..n {
        let col = b.response(r, &Vector::basis(n, c), r);
        for (row, x) in col.as_slice().iter().enumerate() {
            k[row * n + c] += x;
        }
    }
}

/// Solves a x = b in place for a symmetric positive definite n × n `a` (row-major,
/// overwritten by its Cholesky factor). Returns false if `a` is not positive definite.
pub(crate) fn cholesky_solve(a: &mut [f64], n: usize, b: &mut [f64]) -> bool {
    if !cholesky_factor(a, n) {
        return false;
    }
    cholesky_substitute(a, n, b);
    true
}

/// Overwrites the lower triangle of a symmetric positive definite n × n `a` (row-major) by
/// its Cholesky factor. Returns false if `a` is not positive definite.
fn cholesky_factor(a: &mut [f64], n: usize) -> bool {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    true
}

/// Solves L Lᵀ x = b in place, L the factor [`cholesky_factor`] left in `l`.
fn cholesky_substitute(l: &[f64], n: usize, b: &mut [f64]) {
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i * n + k] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[k * n + i] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
}

/// One contact point in a solve.
#[derive(Clone, Debug)]
pub(crate) struct ContactRow {
    pub body: usize,
    pub half_space: usize,
    /// The candidate's number on its body and half-space (from 1).
    pub index: usize,
    /// The point in own axes and its offset from the centre of mass in space.
    pub point: Vector,
    pub r: Vector,
    /// The normal velocity wanted after the impulse (0, or −e u⁻ for an impact).
    pub target: f64,
    pub normal_impulse: f64,
    pub friction_impulse: Vector,
    /// The normal impulse added in the free flight to keep the point out (position level).
    pub position_impulse: f64,
    /// nᵀ K n and the point's speed (set when the solve starts; the rest of K is in the
    /// solver's row matrices).
    pub knn: f64,
    speed: f64,
    /// True if the impulses are the last solve's at the same point (a warm start).
    warm: bool,
    /// The generation of the placement `point` and `r` were copied from (0: none).
    placed: u64,
}

/// Where the matrices of one contact row lie in the solver's `row_data` (N = n, M planes):
/// C (n × M: the velocity at the point per angular velocity, u = v + C w), W (M × n: the
/// angular velocity per impulse, I⁻¹ (r ∧ ·)), R (M × n: the angular impulse, r ∧ ·), their
/// products with the normal (Cᵀn, W n, R n), the tangent block K_t of K with its
/// eigen-decomposition, nᵀ K n and its inverse, and K_t⁻¹ (for the sticking impulse).
#[derive(Clone, Copy, Debug)]
struct RowLayout {
    n: usize,
    m: usize,
    c: usize,
    w: usize,
    r: usize,
    cn: usize,
    wn: usize,
    rn: usize,
    kt: usize,
    values: usize,
    vectors: usize,
    knn: usize,
    inv_knn: usize,
    kinv: usize,
    stride: usize,
}

impl RowLayout {
    #[inline(always)]
    fn new(n: usize) -> RowLayout {
        let m = n * (n - 1) / 2;
        // What every sweep reads first and together (in 3D and 4D C and R are read through
        // the offset instead), what only sliding contacts read last.
        let w = 0;
        let cn = w + m * n;
        let wn = cn + m;
        let rn = wn + m;
        let knn = rn + m;
        let inv_knn = knn + 1;
        let kinv = inv_knn + 1;
        let c = kinv + n * n;
        let r = c + n * m;
        let kt = r + m * n;
        let values = kt + n * n;
        let vectors = values + n;
        RowLayout {
            n,
            m,
            c,
            w,
            r,
            cn,
            wn,
            rn,
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

/// What a contact row's matrices were computed for: the row's point (body, half-space,
/// candidate), the generation of the placement its offset was taken from, and the generation
/// of its body's inverse inertia. A placement's generation changes whenever the body's
/// offsets in space change and when the placements are redone for another system, so that
/// with the half-space's number (a system's half-spaces do not change) it fixes the offset
/// and the normal.
#[derive(Clone, Debug, Default)]
struct RowKey {
    body: usize,
    half_space: usize,
    index: usize,
    placed: u64,
    generation: u64,
}

/// The dimension of a kernel: `N` when it is fixed at compile time (3 and 4: loops of known
/// length, unrolled), else `n` (`N` = 0).
#[inline(always)]
fn dim<const N: usize>(n: usize) -> usize {
    debug_assert!(
        N == 0 || N == n,
        "rotorflow: kernel of dimension {N} for {n}"
    );
    if N == 0 { n } else { N }
}

/// The planes through each axis in 3D and 4D, in their order: the entries of row i of C
/// (whose column p is r ⌋ e_p) that can be non-zero.
const PLANES_THROUGH_3: [[usize; 2]; 3] = [[0, 1], [0, 2], [1, 2]];
const PLANES_THROUGH_4: [[usize; 3]; 4] = [[0, 1, 2], [0, 3, 4], [1, 3, 5], [2, 4, 5]];

/// The axes of each plane in 3D and 4D: the entries of row p of R (whose column j is
/// r ∧ e_j) that can be non-zero, and the entries of column p of C.
const AXES_OF_3: [[usize; 2]; 3] = [[0, 1], [0, 2], [1, 2]];
const AXES_OF_4: [[usize; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];

/// The entries of row `i` of an n × n(n−1)/2 matrix C (columns r ⌋ e_p) that can be
/// non-zero, when the dimension is fixed at 3 or 4 (None: all of them).
#[inline(always)]
fn planes_through<const N: usize>(i: usize) -> Option<&'static [usize]> {
    match N {
        3 => Some(&PLANES_THROUGH_3[i]),
        4 => Some(&PLANES_THROUGH_4[i]),
        _ => None,
    }
}

/// The axes of every plane when the dimension is fixed at 3 or 4 (None: any other).
#[inline(always)]
fn axes_of<const N: usize>() -> Option<&'static [[usize; 2]]> {
    match N {
        3 => Some(&AXES_OF_3),
        4 => Some(&AXES_OF_4),
        _ => None,
    }
}

/// u = v + C w at a row's point, at `offset` from the centre of mass (`N` as in [`dim`];
/// in 3D and 4D C is read through the offset, as its entries that can be non-zero are
/// ±rⱼ).
#[inline(always)]
fn point_velocity<const N: usize>(
    d: &[f64],
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
    let c = &d[l.c..l.c + n * m];
    for ((ui, vi), row) in u[..n].iter_mut().zip(&v[..n]).zip(c.chunks_exact(m)) {
        *ui = vi + dot(row, w);
    }
}

/// Entry (i, p) of C (column p: r ⌋ e_p) for the offset r and an axis i of plane p =
/// (a, b), a < b: −r_b for i = a, r_a for i = b. Entry (p, j) of R (column j: r ∧ e_j) is
/// the same for j the other axis of the plane.
#[inline(always)]
fn contraction_entry(offset: &[f64], [a, b]: [usize; 2], i: usize) -> f64 {
    if i == a { -offset[b] } else { offset[a] }
}

/// y += a A x for an M × n row-major A.
#[inline(always)]
fn add_mat_vec(y: &mut [f64], a_mat: &[f64], a: f64, x: &[f64]) {
    for (yp, row) in y.iter_mut().zip(a_mat.chunks_exact(x.len())) {
        *yp += a * dot(row, x);
    }
}

/// One ball joint in a solve: the offsets of its two ends.
#[derive(Clone, Debug)]
pub(crate) struct JointRow {
    pub body: usize,
    pub r: Vector,
    pub other: Option<(usize, Vector)>,
    pub impulse: Vector,
    /// The joint's inverse mass K (set when a solve starts).
    k: Dense,
}

impl JointRow {
    pub(crate) fn new(joint: &BallJoint, bodies: &[MovingBody]) -> JointRow {
        let r = bodies[joint.body].attitude().rotate_vector(&joint.point);
        let other = match &joint.other {
            Anchor::World(_) => None,
            Anchor::Body(j, p) => Some((*j, bodies[*j].attitude().rotate_vector(p))),
        };
        JointRow {
            body: joint.body,
            r,
            other,
            impulse: Vector::zero(bodies[0].dim()),
            k: Dense::new(),
        }
    }

    /// The relative velocity of the two ends.
    fn velocity(&self, states: &[BodyState]) -> Vector {
        let mut u = states[self.body].velocity_at(&self.r);
        if let Some((j, q)) = &self.other {
            u -= &states[*j].velocity_at(q);
        }
        u
    }

    /// Applies the impulse `j` to the first end and −`j` to the second.
    fn apply(&self, states: &mut [BodyState], j: &Vector) {
        states[self.body].apply(&self.r, j);
        if let Some((b, q)) = &self.other {
            states[*b].apply(q, &(j * -1.0));
        }
    }

    /// The ends as (body, offset, sign of the impulse there).
    fn ends(&self) -> impl Iterator<Item = (usize, &Vector, f64)> {
        std::iter::once((self.body, &self.r, 1.0))
            .chain(self.other.iter().map(|(b, q)| (*b, q, -1.0)))
    }
}

/// The reusable work space of the solves.
#[derive(Clone, Debug, Default)]
pub(crate) struct Solver {
    pub contacts: Vec<ContactRow>,
    pub joints: Vec<JointRow>,
    states: Vec<BodyState>,
    work: Dense,
    rhs: Dense,
    big: Vec<f64>,
    big_rhs: Vec<f64>,
    /// Each joint end's contraction and inverse-inertia matrices (for K).
    end_c: Vec<f64>,
    end_w: Vec<f64>,
    /// The contact rows' matrices ([`RowLayout`]), slot k for row k, and what they were
    /// computed for: a row that touches again at the same placement keeps them.
    row_data: Vec<f64>,
    row_keys: Vec<RowKey>,
    /// The last generation handed to a body's inverse inertia.
    generations: u64,
    /// True while `big` holds the Cholesky factor of the joints' K at the bodies' current
    /// attitudes (the rows' offsets): a velocity solve of joints alone leaves it there, and
    /// the position solve of the same placement reuses it.
    joint_factor: bool,
    pub residuals: Vec<Vector>,
    /// The last solve's impulses of the rows that left their slots, by (body, half-space,
    /// candidate), to start the next solve from (a row that stays in its slot keeps its
    /// own): a resting contact then needs one sweep. Filled by `find_contacts` from the
    /// first slot whose point changes, before it is overwritten.
    warm: Vec<WarmImpulse>,
    /// The length of the kick before the last solve (0: none yet). A resting contact's
    /// impulse is its force times that length, so the next solve starts from the last
    /// impulses scaled by the ratio of the kicks.
    warm_kick: f64,
    /// True to use the kernels of run-time dimension in every dimension, also in 3D and 4D
    /// where the fixed-size kernels do the same arithmetic in the same order, only without
    /// the terms that are exact zeros (so that tests can compare the two).
    pub runtime_kernels: bool,
}

/// Contact rows solved together, and what their solve reads.
struct Group<'a> {
    range: std::ops::Range<usize>,
    /// True if joints couple the rows (then every joint is swept with them).
    coupled: bool,
    half_spaces: &'a [HalfSpace],
    layout: &'a RowLayout,
    /// The factor on the last solve's impulses to start from.
    warm_scale: f64,
}

/// The impulses of the last solve with the place to search them from.
type WarmList<'a> = (&'a [WarmImpulse], &'a mut usize);

/// A contact's impulses kept for the next solve: body, half-space, candidate, normal
/// impulse, friction impulse.
type WarmImpulse = (usize, usize, usize, f64, Vector);

impl Solver {
    /// Finds the contact points of `bodies` within `tolerance` × their radius of a
    /// half-space, the bodies placed by `placements`.
    pub(crate) fn find_contacts(
        &mut self,
        bodies: &[MovingBody],
        shapes: &[ContactShape],
        half_spaces: &[HalfSpace],
        tolerance: f64,
        placements: &Placements,
    ) {
        // Rows are overwritten in place (a row is large: moving it costs more than its setup).
        let mut used = 0;
        let n = bodies[0].dim();
        self.warm.clear();
        let mut listed = false;
        for (i, (b, shape)) in bodies.iter().zip(shapes).enumerate() {
            if matches!(shape, ContactShape::None) {
                continue;
            }
            let placed = placements.get(i);
            let reach = tolerance * placed.radius;
            for (k, plane) in half_spaces.iter().enumerate() {
                let nrm = plane.normal();
                let base = plane.distance(b.position());
                let mut put = |index: usize, p: &Vector, r: &[f64]| {
                    // The target is set when the solve starts, from the loaded velocities.
                    let target = 0.0;
                    let stays = self.contacts.get(used).is_some_and(|row| {
                        row.body == i && row.half_space == k && row.index == index
                    });
                    if !stays && !listed {
                        // The points change from this slot on: the rows from here keep their
                        // impulses in the list (in the order of their points) before they are
                        // overwritten.
                        self.warm.extend(self.contacts[used..].iter().map(|row| {
                            (
                                row.body,
                                row.half_space,
                                row.index,
                                row.normal_impulse,
                                row.friction_impulse.clone(),
                            )
                        }));
                        listed = true;
                    }
                    if let Some(row) = self.contacts.get_mut(used) {
                        // The same point in the same slot keeps its impulses of the last
                        // solve, to start from.
                        row.warm = row.body == i && row.half_space == k && row.index == index;
                        if !row.warm {
                            row.normal_impulse = 0.0;
                            row.friction_impulse.as_mut_slice().fill(0.0);
                        }
                        row.body = i;
                        row.half_space = k;
                        row.index = index;
                        // The same point of the same placement is there already.
                        if !(row.warm && row.placed == placed.generation) {
                            set_vector(&mut row.point, p.as_slice());
                            set_vector(&mut row.r, r);
                            row.placed = placed.generation;
                        }
                        row.target = target;
                        row.position_impulse = 0.0;
                        row.knn = 0.0;
                        row.speed = 0.0;
                    } else {
                        self.contacts.push(ContactRow {
                            body: i,
                            half_space: k,
                            index,
                            point: p.clone(),
                            r: Vector::from_storage(SmallVec::from_slice(r)),
                            target,
                            normal_impulse: 0.0,
                            friction_impulse: Vector::zero(n),
                            position_impulse: 0.0,
                            knn: 0.0,
                            speed: 0.0,
                            warm: false,
                            placed: placed.generation,
                        });
                    }
                    used += 1;
                };
                if placed.vertex(shape, 1).is_some() {
                    // Vertices: their heights are kept, and only those in reach are read.
                    placed.candidate_heights(shape, (k, nrm), |index, h| {
                        if base + h <= reach
                            && let Some((p, r)) = placed.vertex(shape, index)
                        {
                            put(index, p, r);
                        }
                    });
                } else {
                    placed.candidates(shape, (k, nrm), |index, p, r| {
                        if base + dot(nrm.as_slice(), r) <= reach {
                            put(index, p, r);
                        }
                    });
                }
            }
        }
        self.contacts.truncate(used);
    }

    /// Sets up the joint rows at the current placement.
    /// The factor of the joints' K is kept if every row is the same as before (the bodies'
    /// attitudes did not change; [`Solver::load`] checks their inertias).
    pub(crate) fn find_joints(&mut self, bodies: &[MovingBody], joints: &[BallJoint]) {
        let mut same = self.joints.len() == joints.len();
        self.joints.truncate(joints.len());
        for (k, joint) in joints.iter().enumerate() {
            let row = JointRow::new(joint, bodies);
            match self.joints.get_mut(k) {
                Some(old) => {
                    same &= old.body == row.body && old.r == row.r && old.other == row.other;
                    old.body = row.body;
                    old.r = row.r;
                    old.other = row.other;
                    old.impulse.as_mut_slice().fill(0.0);
                }
                None => self.joints.push(row),
            }
        }
        if !same {
            self.joint_factor = false;
        }
    }

    /// Loads the bodies the rows act on.
    fn load(&mut self, bodies: &[MovingBody]) {
        let n = bodies[0].dim();
        self.states
            .resize_with(bodies.len(), || BodyState::empty(n));
        let mut work = std::mem::take(&mut self.work);
        let touched = self.contacts.iter().map(|c| c.body).chain(
            self.joints
                .iter()
                .flat_map(|j| std::iter::once(j.body).chain(j.other.iter().map(|(b, _)| *b))),
        );
        let mut placed = false;
        for i in touched {
            if !self.states[i].used && self.states[i].load(&bodies[i], &mut work) {
                placed = true;
                self.generations += 1;
                self.states[i].generation = self.generations;
            }
        }
        self.work = work;
        if placed {
            // A body turned: the joints' K is another.
            self.joint_factor = false;
        }
    }

    /// Hands the impulses of the solve to the bodies.
    fn store(&mut self, bodies: &mut [MovingBody]) {
        for (s, b) in self.states.iter_mut().zip(bodies) {
            if s.used {
                s.store(b);
            }
        }
    }

    /// The velocity solve: impulses such that every joint's ends move together and every
    /// contact point leaves its half-space at its target speed or faster, with friction in
    /// Coulomb's cone. Appends the contacts and their impulses to `record` (if any).
    ///
    /// A contact's target is restitution e for a point approaching faster than
    /// `resting_speed[i]` (body i), none below (a resting contact). `kick` is the length of
    /// the kick of the forques before the solve.
    pub(crate) fn solve_velocities(
        &mut self,
        bodies: &mut [MovingBody],
        half_spaces: &[HalfSpace],
        resting_speed: &[f64],
        kick: f64,
        mut record: Option<&mut ContactLog>,
    ) {
        if self.contacts.is_empty() && self.joints.is_empty() {
            return;
        }
        let warm_scale = if self.warm_kick > 0.0 && kick > 0.0 {
            kick / self.warm_kick
        } else {
            1.0
        };
        self.warm_kick = kick;
        self.load(bodies);
        let n = bodies[0].dim();
        if self.contacts.is_empty() {
            // Equalities only: one dense solve is exact.
            let mut u = std::mem::take(&mut self.residuals);
            u.clear();
            u.extend(self.joints.iter().map(|row| row.velocity(&self.states)));
            self.solve_joints_dense_loaded(&u, 1.0);
            self.residuals = u;
            self.store(bodies);
            return;
        }
        for row in &mut self.joints {
            row.k.clear();
            row.k.resize(n * n, 0.0);
            add_inverse_mass(&self.states[row.body], &row.r, &mut row.k);
            if let Some((j, q)) = &row.other {
                add_inverse_mass(&self.states[*j], q, &mut row.k);
            }
        }
        let layout = RowLayout::new(n);
        let rows = self.contacts.len();
        if self.row_data.len() < rows * layout.stride {
            self.row_data.resize(rows * layout.stride, 0.0);
        }
        if self.row_keys.len() < rows {
            self.row_keys.resize_with(rows, RowKey::default);
        }
        // Bodies that no joint couples are solved apart (their contacts are consecutive), each
        // from setup to record while its rows' matrices are in cache; with joints,
        // everything is one problem.
        let coupled = !self.joints.is_empty();
        let last = std::mem::take(&mut self.warm);
        let mut cursor = 0;
        let mut start = 0;
        while start < rows {
            let end = if coupled {
                rows
            } else {
                let body = self.contacts[start].body;
                start
                    + self.contacts[start..]
                        .iter()
                        .take_while(|r| r.body == body)
                        .count()
            };
            let group = Group {
                range: start..end,
                coupled,
                half_spaces,
                layout: &layout,
                warm_scale,
            };
            let warm = (&last[..], &mut cursor);
            match (self.runtime_kernels, n) {
                (false, 3) => {
                    self.solve_group::<3>(&group, resting_speed, warm, record.as_deref_mut())
                }
                (false, 4) => {
                    self.solve_group::<4>(&group, resting_speed, warm, record.as_deref_mut())
                }
                _ => self.solve_group::<0>(&group, resting_speed, warm, record.as_deref_mut()),
            }
            start = end;
        }
        // Kept for its room: the next `find_contacts` clears it.
        self.warm = last;
        self.store(bodies);
    }

    /// The velocity solve of one group of contact rows (`N` as in [`dim`]): their matrices,
    /// warm start from their own impulses or from `last` (searched from `cursor` on), sweeps
    /// and the record if there is one.
    fn solve_group<const N: usize>(
        &mut self,
        group: &Group<'_>,
        resting_speed: &[f64],
        (last, cursor): WarmList<'_>,
        record: Option<&mut ContactLog>,
    ) {
        // The layout anew, so that in 3D and 4D its offsets are constants of the kernels.
        let layout = &RowLayout::new(dim::<N>(group.layout.n));
        let (range, half_spaces) = (group.range.clone(), group.half_spaces);
        self.prepare_rows::<N>(range.clone(), half_spaces, resting_speed, layout);
        self.warm_start::<N>(
            range.clone(),
            (last, cursor),
            half_spaces,
            layout,
            (group.coupled, group.warm_scale),
        );
        self.sweep_rows::<N>(range.clone(), group.coupled, half_spaces, layout);
        if let Some(record) = record {
            self.record_rows::<N>(range, half_spaces, layout, record);
        }
    }

    /// Computes (or keeps) the matrices of the contact rows `range` at the loaded states,
    /// and sets their nᵀ K n, target and speed.
    fn prepare_rows<const N: usize>(
        &mut self,
        range: std::ops::Range<usize>,
        half_spaces: &[HalfSpace],
        resting_speed: &[f64],
        layout: &RowLayout,
    ) {
        let n = dim::<N>(layout.n);
        let m = n * (n - 1) / 2;
        let (mut u_fixed, mut u_any) = ([0.0; 4], Small::new());
        let u = scratch::<N>(&mut u_fixed, &mut u_any, n);
        // The velocities of the last row's body (the rows of a body are consecutive).
        let (mut body, mut v, mut w): (usize, &[f64], &[f64]) = (usize::MAX, &[], &[]);
        for k in range {
            let row = &mut self.contacts[k];
            let plane = &half_spaces[row.half_space];
            let nrm = plane.normal();
            let st = &self.states[row.body];
            if row.body != body {
                (body, v, w) = (row.body, &st.v.as_slice()[..n], &st.w.as_slice()[..m]);
            }
            let data = &mut self.row_data[k * layout.stride..(k + 1) * layout.stride];
            let key = &mut self.row_keys[k];
            let same = key.body == row.body
                && key.half_space == row.half_space
                && key.index == row.index
                && key.placed == row.placed
                && key.generation == st.generation;
            if !same {
                row_matrices(st, &row.r, nrm, layout, data);
                *key = RowKey {
                    body: row.body,
                    half_space: row.half_space,
                    index: row.index,
                    placed: row.placed,
                    generation: st.generation,
                };
            }
            row.knn = data[layout.knn];
            let r = &row.r.as_slice()[..n];
            point_velocity::<N>(data, layout, r, v, w, u);
            let un = dot(&nrm.as_slice()[..n], u);
            row.target = if un < -resting_speed[row.body] {
                -plane.restitution() * un
            } else {
                0.0
            };
            row.speed = u
                .iter()
                .fold(0.0, |m: f64, c| m.max(c.abs()))
                .max(row.target.abs());
        }
    }

    /// Starts the contact rows `range` from the last solve's impulses times `scale` where
    /// the same points touch again: kept in the row when it is in the same slot, else looked
    /// up in `last` (sorted by point, searched from `cursor` on).
    fn warm_start<const N: usize>(
        &mut self,
        range: std::ops::Range<usize>,
        (last, cursor): (&[WarmImpulse], &mut usize),
        half_spaces: &[HalfSpace],
        layout: &RowLayout,
        (coupled, scale): (bool, f64),
    ) {
        let n = dim::<N>(layout.n);
        let (mut jt_fixed, mut jt_any) = ([0.0; 4], Small::new());
        let jt = scratch::<N>(&mut jt_fixed, &mut jt_any, n);
        let (mut total_fixed, mut total_any) = ([0.0; 4], Small::new());
        let total = scratch::<N>(&mut total_fixed, &mut total_any, n);
        // One body in 3D or 4D: the rows' starting impulses are set first, and then applied
        // in the same order to the body's velocities and impulses in locals (the rows that
        // start, one bit each).
        let apart = !coupled && N != 0 && range.len() <= 64;
        let mut started = 0u64;
        for k in range.clone() {
            let row = &mut self.contacts[k];
            let lambda = if row.warm {
                jt.copy_from_slice(&row.friction_impulse.as_slice()[..n]);
                row.normal_impulse
            } else {
                let key = (row.body, row.half_space, row.index);
                let w = &mut *cursor;
                while *w < last.len() && (last[*w].0, last[*w].1, last[*w].2) < key {
                    *w += 1;
                }
                match last.get(*w).filter(|e| (e.0, e.1, e.2) == key) {
                    Some(e) => {
                        jt.copy_from_slice(&e.4.as_slice()[..n]);
                        e.3
                    }
                    None => continue,
                }
            };
            let plane = &half_spaces[row.half_space];
            let nv = &plane.normal().as_slice()[..n];
            // Scaled to this solve's kick, into the friction disc of the normal impulse, and
            // into the plane.
            let lambda = lambda * scale;
            let limit = plane.friction() * lambda;
            let norm = dot(jt, jt).sqrt() * scale;
            let fit = if norm > limit { limit / norm } else { 1.0 };
            for x in jt.iter_mut() {
                *x *= scale * fit;
            }
            let along = dot(nv, jt);
            for ((t, x), nx) in total.iter_mut().zip(jt.iter_mut()).zip(nv) {
                *x -= nx * along;
                *t = nx * lambda + *x;
            }
            row.normal_impulse = lambda;
            row.friction_impulse.as_mut_slice().copy_from_slice(jt);
            if apart {
                started |= 1 << (k - range.start);
                continue;
            }
            let data = &self.row_data[k * layout.stride..(k + 1) * layout.stride];
            self.states[row.body].view::<N>().apply_with::<N>(
                data,
                layout,
                &row.r.as_slice()[..n],
                total,
            );
        }
        if started == 0 {
            return;
        }
        let mut st = self.states[self.contacts[range.start].body].view::<N>();
        let mut local = LocalBody::new(&st);
        let mut view = local.view();
        for k in range.clone() {
            if started & (1 << (k - range.start)) == 0 {
                continue;
            }
            let row = &self.contacts[k];
            let nv = &half_spaces[row.half_space].normal().as_slice()[..n];
            let (lambda, jt) = (row.normal_impulse, &row.friction_impulse.as_slice()[..n]);
            for ((t, x), nx) in total.iter_mut().zip(jt).zip(nv) {
                *t = nx * lambda + *x;
            }
            let data = &self.row_data[k * layout.stride..(k + 1) * layout.stride];
            view.apply_with::<N>(data, layout, &row.r.as_slice()[..n], total);
        }
        local.store(&mut st);
    }

    /// Gauss–Seidel sweeps over the contact rows `range` (and every joint when `coupled`)
    /// until no impulse changes one of their velocities by more than 1e-12 of their speeds.
    fn sweep_rows<const N: usize>(
        &mut self,
        range: std::ops::Range<usize>,
        coupled: bool,
        half_spaces: &[HalfSpace],
        layout: &RowLayout,
    ) {
        let n = layout.n;
        let (start, end) = (range.start, range.end);
        let speed = self.contacts[range]
            .iter()
            .map(|r| r.speed)
            .fold(0.0, f64::max);
        let tolerance = 1e-12 * speed.max(1e-300);
        for _ in 0..MAX_SWEEPS {
            let mut change = 0.0f64;
            if coupled {
                for row in &mut self.joints {
                    let u = row.velocity(&self.states);
                    self.work.clear();
                    self.work.extend_from_slice(&row.k);
                    self.rhs.clear();
                    self.rhs.extend(u.as_slice().iter().map(|x| -x));
                    if !cholesky_solve(&mut self.work, n, &mut self.rhs) {
                        continue;
                    }
                    let dj = Vector::from_storage(self.rhs.iter().copied().collect());
                    row.apply(&mut self.states, &dj);
                    row.impulse += &dj;
                    change = change.max(u.max_abs());
                }
            }
            if coupled {
                for (k, row) in self.contacts[start..end].iter_mut().enumerate() {
                    let at = (start + k) * layout.stride;
                    let data = &self.row_data[at..at + layout.stride];
                    let mut st = self.states[row.body].view::<N>();
                    let plane = &half_spaces[row.half_space];
                    change = change.max(sweep_contact::<N>(row, data, layout, plane, &mut st));
                }
            } else if N != 0 {
                // One body in 3D or 4D: its velocities and impulses in locals.
                let mut st = self.states[self.contacts[start].body].view::<N>();
                let mut local = LocalBody::new(&st);
                let mut view = local.view();
                for (k, row) in self.contacts[start..end].iter_mut().enumerate() {
                    let at = (start + k) * layout.stride;
                    let data = &self.row_data[at..at + layout.stride];
                    let plane = &half_spaces[row.half_space];
                    let c = sweep_contact::<N>(row, data, layout, plane, &mut view);
                    change = change.max(c);
                }
                local.store(&mut st);
            } else {
                // One body: its view serves every row.
                let mut st = self.states[self.contacts[start].body].view::<N>();
                for (k, row) in self.contacts[start..end].iter_mut().enumerate() {
                    let at = (start + k) * layout.stride;
                    let data = &self.row_data[at..at + layout.stride];
                    let plane = &half_spaces[row.half_space];
                    change = change.max(sweep_contact::<N>(row, data, layout, plane, &mut st));
                }
            }
            if change <= tolerance {
                break;
            }
        }
    }

    /// Records the contact rows `range` with their impulses and the velocities the solve
    /// leaves at their points.
    fn record_rows<const N: usize>(
        &self,
        range: std::ops::Range<usize>,
        half_spaces: &[HalfSpace],
        layout: &RowLayout,
        record: &mut ContactLog,
    ) {
        let n = dim::<N>(layout.n);
        let m = n * (n - 1) / 2;
        let (mut u_fixed, mut u_any) = ([0.0; 4], Small::new());
        let u = scratch::<N>(&mut u_fixed, &mut u_any, n);
        // The velocities of the last row's body (the rows of a body are consecutive).
        let (mut body, mut v, mut w): (usize, &[f64], &[f64]) = (usize::MAX, &[], &[]);
        for k in range {
            let row = &self.contacts[k];
            let nrm = half_spaces[row.half_space].normal();
            if row.body != body {
                let st = &self.states[row.body];
                (body, v, w) = (row.body, &st.v.as_slice()[..n], &st.w.as_slice()[..m]);
            }
            let data = &self.row_data[k * layout.stride..(k + 1) * layout.stride];
            point_velocity::<N>(data, layout, &row.r.as_slice()[..n], v, w, u);
            record.record(
                (row.body, row.half_space),
                &row.point.as_slice()[..n],
                row.normal_impulse,
                &row.friction_impulse.as_slice()[..n],
                u,
                &nrm.as_slice()[..n],
            );
        }
    }

    /// The position step of the joints at the placement the rows were found at: the
    /// impulses J (one per joint) with Σ_k K_jk J_k = −`residuals`[j]/`per`, given to the
    /// bodies. The bodies' inverse inertias and the factor of K are kept from one call to
    /// the next (the placement does not change between them: only momenta do) until
    /// [`Solver::release`]; a velocity solve of joints alone at the same placement leaves
    /// its factor for the first call.
    /// Each joint's impulse is added to `totals`.
    pub(crate) fn joint_position_step(
        &mut self,
        bodies: &mut [MovingBody],
        residuals: &[Vector],
        per: f64,
        totals: &mut [Vector],
    ) {
        self.load(bodies);
        if !self.joint_factor {
            self.factor_joints();
        }
        if self.joint_factor {
            self.apply_joint_solve(residuals, per, Some(totals));
        }
        self.store_loaded(bodies);
    }

    /// Gives the joints the impulses `impulses` (one per joint, first end; the second
    /// takes the opposite), at the placement the rows were found at; the bodies stay
    /// loaded as for [`Solver::joint_position_step`].
    pub(crate) fn joint_position_impulses(
        &mut self,
        bodies: &mut [MovingBody],
        impulses: &[Vector],
    ) {
        self.load(bodies);
        for (row, j) in self.joints.iter().zip(impulses) {
            row.apply(&mut self.states, j);
        }
        self.store_loaded(bodies);
    }

    /// Hands the impulses so far to the bodies, keeping them loaded.
    fn store_loaded(&mut self, bodies: &mut [MovingBody]) {
        for (s, b) in self.states.iter_mut().zip(bodies.iter_mut()) {
            if s.used {
                s.store(b);
                // Stay loaded for the next call.
                s.used = true;
                s.dp.as_mut_slice().fill(0.0);
                s.dl.as_mut_slice().fill(0.0);
            }
        }
    }

    /// Forgets the loaded bodies and the joints' factor (the placement is about to change).
    pub(crate) fn release(&mut self) {
        self.joint_factor = false;
        for s in &mut self.states {
            s.used = false;
        }
    }

    /// Assembles the joints' K (all joints together, n × n blocks) in `big` and factors it.
    fn factor_joints(&mut self) {
        self.joint_factor = false;
        let Some(n) = self.joints.first().map(|j| j.r.dim()) else {
            return;
        };
        let m = self.joints.len() * n;
        let planes = n * (n - 1) / 2;
        // For each joint end (joint a, end e at offset r of body b): C = (r ⌋ ·) as an
        // n × M matrix and W = I⁻¹ (r ∧ ·) as an M × n matrix; the velocity at an end of
        // joint a per impulse at an end of joint c on the same body is 1/m + C_a W_c.
        let (cs, ws) = (n * planes, planes * n);
        self.end_c.clear();
        self.end_c.resize(self.joints.len() * 2 * cs, 0.0);
        self.end_w.clear();
        self.end_w.resize(self.joints.len() * 2 * ws, 0.0);
        let mut e = Bivector::zero(n);
        for (a, row) in self.joints.iter().enumerate() {
            for (end, (b, r, _)) in row.ends().enumerate() {
                let at = a * 2 + end;
                let c = &mut self.end_c[at * cs..(at + 1) * cs];
                for p in 0..planes {
                    e.as_mut_slice().fill(0.0);
                    e.as_mut_slice()[p] = 1.0;
                    for (i, x) in r.left_contract(&e).as_slice().iter().enumerate() {
                        c[i * planes + p] = *x;
                    }
                }
                let w = &mut self.end_w[at * ws..(at + 1) * ws];
                for col in 0..n {
                    let iw = self.states[b].inverse_inertia(&r.wedge(&Vector::basis(n, col)));
                    for (p, x) in iw.as_slice().iter().enumerate() {
                        w[p * n + col] = *x;
                    }
                }
            }
        }
        self.big.clear();
        self.big.resize(m * m, 0.0);
        for (a, row) in self.joints.iter().enumerate() {
            for (ea, (ba, _, sa)) in row.ends().enumerate() {
                let c = &self.end_c[(a * 2 + ea) * cs..(a * 2 + ea + 1) * cs];
                for (k, other) in self.joints.iter().enumerate() {
                    for (ek, (bk, _, sk)) in other.ends().enumerate() {
                        if ba != bk {
                            continue;
                        }
                        let w = &self.end_w[(k * 2 + ek) * ws..(k * 2 + ek + 1) * ws];
                        let inv_mass = self.states[ba].inv_mass;
                        for i in 0..n {
                            for col in 0..n {
                                let mut x: f64 = (0..planes)
                                    .map(|p| c[i * planes + p] * w[p * n + col])
                                    .sum();
                                if i == col {
                                    x += inv_mass;
                                }
                                self.big[(a * n + i) * m + k * n + col] += sa * sk * x;
                            }
                        }
                    }
                }
            }
        }
        self.joint_factor = cholesky_factor(&mut self.big, m);
    }

    /// With the factor in `big`: the impulses J with K J = −`residuals`/`per`, applied to
    /// the loaded states.
    fn apply_joint_solve(
        &mut self,
        residuals: &[Vector],
        per: f64,
        mut totals: Option<&mut [Vector]>,
    ) {
        let Some(n) = residuals.first().map(Vector::dim) else {
            return;
        };
        let m = self.joints.len() * n;
        self.big_rhs.clear();
        for r in residuals {
            self.big_rhs.extend(r.as_slice().iter().map(|x| -x / per));
        }
        cholesky_substitute(&self.big, m, &mut self.big_rhs);
        for a in 0..self.joints.len() {
            let j =
                Vector::from_storage(self.big_rhs[a * n..(a + 1) * n].iter().copied().collect());
            let row = &mut self.joints[a];
            row.apply(&mut self.states, &j);
            if let Some(t) = totals.as_deref_mut() {
                t[a] += &j;
            }
            row.impulse += &j;
        }
    }

    fn solve_joints_dense_loaded(&mut self, residuals: &[Vector], per: f64) {
        if !self.joint_factor {
            self.factor_joints();
        }
        if self.joint_factor {
            self.apply_joint_solve(residuals, per, None);
        }
    }
}

/// One Gauss–Seidel update of a contact: the normal impulse, then the friction impulse,
/// through the row's matrices `data` laid out by `l` (`N` as in [`dim`]). Returns the
/// largest velocity change it made.
#[inline(always)]
fn sweep_contact<const N: usize>(
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
    point_velocity::<N>(data, l, offset, &st.v[..n], &st.w[..m], ut);
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
        friction_impulse(
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
type Small = SmallVec<[f64; 8]>;

/// A zero scratch vector of length n (`N` as in [`dim`]): `fixed` in 3D and 4D, where its
/// length is known and it needs no check of its storage, else `any`.
#[inline(always)]
fn scratch<'a, const N: usize>(
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
fn row_matrices(st: &BodyState, r: &Vector, nrm: &Vector, l: &RowLayout, data: &mut [f64]) {
    let (n, m) = (l.n, l.m);
    // C: column p is r ⌋ e_p (the velocity at r of a unit angular velocity in plane p).
    let mut e = Bivector::zero(n);
    for p in 0..m {
        e.as_mut_slice().fill(0.0);
        e.as_mut_slice()[p] = 1.0;
        for (i, x) in r.left_contract(&e).as_slice().iter().enumerate() {
            data[l.c + i * m + p] = *x;
        }
    }
    // R: column j is r ∧ e_j; W = I⁻¹ R.
    for j in 0..n {
        let rj = r.wedge(&Vector::basis(n, j));
        let wj = st.inverse_inertia(&rj);
        for p in 0..m {
            data[l.r + p * n + j] = rj.as_slice()[p];
            data[l.w + p * n + j] = wj.as_slice()[p];
        }
    }
    let nv = nrm.as_slice();
    for p in 0..m {
        data[l.cn + p] = (0..n).map(|i| data[l.c + i * m + p] * nv[i]).sum();
        data[l.wn + p] = dot(&data[l.w + p * n..l.w + (p + 1) * n], nv);
        data[l.rn + p] = dot(&data[l.r + p * n..l.r + (p + 1) * n], nv);
    }
    // K = 1/m + C W.
    let mut k: Dense = SmallVec::from_elem(0.0, n * n);
    for i in 0..n {
        for j in 0..n {
            let mut x: f64 = (0..m)
                .map(|p| data[l.c + i * m + p] * data[l.w + p * n + j])
                .sum();
            if i == j {
                x += st.inv_mass;
            }
            k[i * n + j] = x;
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
fn tangent_block(k: &mut [f64], nrm: &Vector) {
    let n = nrm.dim();
    let nv = nrm.as_slice();
    // k n and nᵀ k n.
    let kn: SmallVec<[f64; 8]> = (0..n)
        .map(|i| (0..n).map(|j| k[i * n + j] * nv[j]).sum())
        .collect();
    let nkn: f64 = (0..n).map(|i| nv[i] * kn[i]).sum();
    for i in 0..n {
        for j in 0..n {
            // P k P = k − n (kn)ᵀ − (kn) nᵀ + (nᵀkn) n nᵀ
            k[i * n + j] += -nv[i] * kn[j] - kn[i] * nv[j] + nkn * nv[i] * nv[j] + nv[i] * nv[j];
        }
    }
}

/// The eigen-decomposition K = V diag(d) Vᵀ of a small symmetric matrix by cyclic Jacobi
/// rotations (row-major; V's columns are the eigenvectors).
fn symmetric_eigen(k: &[f64], n: usize, d: &mut Dense, v: &mut Dense) {
    let mut a: Dense = k.iter().copied().collect();
    v.clear();
    v.resize(n * n, 0.0);
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    for _ in 0..30 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i * n + j] * a[i * n + j])
            .sum();
        let diag: f64 = (0..n).map(|i| a[i * n + i] * a[i * n + i]).sum();
        if off <= 1e-32 * diag {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p * n + q];
                if apq == 0.0 {
                    continue;
                }
                let theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
                let t = theta.signum().max(0.0) * 2.0 - 1.0;
                let t = t / (theta.abs() + (theta * theta + 1.0).sqrt());
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for r in 0..n {
                    let (arp, arq) = (a[r * n + p], a[r * n + q]);
                    a[r * n + p] = c * arp - s * arq;
                    a[r * n + q] = s * arp + c * arq;
                }
                for r in 0..n {
                    let (apr, aqr) = (a[p * n + r], a[q * n + r]);
                    a[p * n + r] = c * apr - s * aqr;
                    a[q * n + r] = s * apr + c * aqr;
                }
                for r in 0..n {
                    let (vrp, vrq) = (v[r * n + p], v[r * n + q]);
                    v[r * n + p] = c * vrp - s * vrq;
                    v[r * n + q] = s * vrp + c * vrq;
                }
            }
        }
    }
    d.clear();
    d.extend((0..n).map(|i| a[i * n + i]));
}

/// The friction impulse of maximal dissipation: with slip `ut` under the impulse `old`,
/// the sticking impulse old − K_t⁻¹ ut when |·| ≤ `limit`, else the J on the rim |J| = limit
/// with (K_t + σ) J = K_t old − ut for the σ ≥ 0 that puts it there, so that the slip left,
/// K_t (J − old) + ut = −σ J, is exactly opposite to J. K_t = V diag(d) Vᵀ is given by its
/// eigen-decomposition; σ comes from Newton's method on 1/|J(σ)| − 1/limit, which is
/// nearly linear in σ and converges from σ = 0 without overshooting (Moré–Sorensen).
fn friction_impulse(
    d: &[f64],
    v: &[f64],
    kt: &[f64],
    old: &[f64],
    ut: &[f64],
    limit: f64,
    out: &mut [f64],
) {
    let n = d.len();
    // c = Vᵀ b, b = K_t old − ut.
    let mut b: Small = SmallVec::from_elem(0.0, n);
    for (i, x) in b.iter_mut().enumerate() {
        *x = dot(&kt[i * n..(i + 1) * n], old) - ut[i];
    }
    let mut c: Small = SmallVec::from_elem(0.0, n);
    for (row, bi) in v.chunks_exact(n).zip(&b) {
        for (x, vik) in c.iter_mut().zip(row) {
            *x += vik * bi;
        }
    }
    let size = |sigma: f64| -> (f64, f64) {
        let (mut s2, mut s3) = (0.0, 0.0);
        for k in 0..n {
            let q = c[k] / (d[k] + sigma);
            s2 += q * q;
            s3 += q * q / (d[k] + sigma);
        }
        (s2.sqrt(), s3)
    };
    let (norm0, _) = size(0.0);
    let sigma = if norm0 <= limit {
        0.0
    } else {
        let mut sigma = 0.0f64;
        for _ in 0..60 {
            let (norm, s3) = size(sigma);
            let psi = 1.0 / norm - 1.0 / limit;
            let step = psi * norm * norm * norm / s3;
            sigma -= step;
            if step.abs() <= 1e-15 * sigma.abs() {
                break;
            }
        }
        sigma.max(0.0)
    };
    let (norm, _) = size(sigma);
    let scale = if sigma > 0.0 { limit / norm } else { 1.0 };
    for (k, x) in c.iter_mut().enumerate() {
        *x /= d[k] + sigma;
    }
    for (i, x) in out.iter_mut().enumerate() {
        *x = scale * dot(&v[i * n..(i + 1) * n], &c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Off the disc, the friction impulse is the trust-region step of Coulomb's law: |J| is
    /// the limit and the slip left after it, K_t (J − old) + ut, is −σ J with σ > 0 (exactly
    /// opposite to the friction), for a limit near zero, small and near the sticking size.
    #[test]
    fn rim_impulse_leaves_the_slip_opposite_to_it() {
        let n = 4;
        // K_t = V diag(d) Vᵀ, V a rotation of 4-space (two plane rotations), the normal
        // (the last axis) kept apart with eigenvalue 1 as `tangent_block` keeps it.
        let (c1, s1, c2, s2) = (0.8f64, 0.6f64, 0.28f64, 0.96f64);
        #[rustfmt::skip]
        let v = [
            c1, -s1, 0.0, 0.0,
            s1 * c2, c1 * c2, -s2, 0.0,
            s1 * s2, c1 * s2, c2, 0.0,
            0.0, 0.0, 0.0, 1.0,
        ];
        let d = [0.7, 1.9, 3.1, 1.0];
        let mut kt = [0.0; 16];
        for i in 0..n {
            for j in 0..n {
                kt[i * n + j] = (0..n).map(|k| v[i * n + k] * d[k] * v[j * n + k]).sum();
            }
        }
        let (old, ut) = ([0.3, -0.2, 0.1, 0.0], [1.1, 0.4, -0.7, 0.0]);
        let mut checked = 0;
        for limit in [1e-6, 0.05, 0.4] {
            let mut j = [0.0; 4];
            friction_impulse(&d, &v, &kt, &old, &ut, limit, &mut j);
            let norm = dot(&j, &j).sqrt();
            assert!(
                (norm - limit).abs() <= 1e-13 * limit,
                "limit {limit}: |J| = {norm}"
            );
            let slip: Vec<f64> = (0..n)
                .map(|i| (0..n).map(|k| kt[i * n + k] * (j[k] - old[k])).sum::<f64>() + ut[i])
                .collect();
            let sigma = -dot(&slip, &j) / (norm * norm);
            assert!(sigma > 0.0, "limit {limit}: σ = {sigma}");
            for i in 0..n {
                assert!(
                    (slip[i] + sigma * j[i]).abs() <= 1e-12 * (1.0 + sigma * limit),
                    "limit {limit}, row {i}: slip {slip:?}, J {j:?}"
                );
            }
            checked += 1;
        }
        assert_eq!(checked, 3);
    }
}
