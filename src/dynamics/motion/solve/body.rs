//! A body as the solves see it.

use super::Dense;
use super::contact_row::{
    Angular, Linear, RowLayout, add_contraction, add_mat_vec, axes_of, contraction_entry, dim,
};
use crate::algebra::{Bivector, Vector};
use crate::dynamics::motion::MovingBody;
use crate::dynamics::motion::placement::{AttitudeKey, dot};
use smallvec::SmallVec;

/// One body during a solve: its velocity and angular velocity (space) as the impulses so
/// far leave them, its inverse mass and inverse inertia in space, and the impulses to hand
/// back to its momenta when the solve ends.
#[derive(Clone, Debug)]
pub(crate) struct BodyState {
    pub(super) inv_mass: f64,
    /// I⁻¹ in space, M × M row-major on the bivector components.
    pub(super) inv_inertia: Vec<f64>,
    /// The rotation of the principal frame on bivectors, M × M row-major (columns: the
    /// images of the basis planes).
    pub(super) frame: Vec<f64>,
    pub(super) v: Linear,
    pub(super) w: Angular,
    pub(super) dp: Linear,
    pub(super) dl: Angular,
    pub used: bool,
    /// The attitude of the principal frame, the mass and the inverse plane moments that
    /// `frame` and `inv_inertia` were computed for (None when they must be computed anew):
    /// a body at the same placement as at the last solve reuses them.
    pub(super) key: AttitudeKey,
    pub(super) key_mass: f64,
    pub(super) key_moments: SmallVec<[f64; 6]>,
    /// Changes whenever `frame` and `inv_inertia` are computed anew.
    pub(super) generation: u64,
}

impl BodyState {
    pub(super) fn empty(n: usize) -> BodyState {
        BodyState {
            inv_mass: 0.0,
            inv_inertia: Vec::new(),
            frame: Vec::new(),
            v: Linear::from_elem(0.0, n),
            w: Angular::from_elem(0.0, n * (n - 1) / 2),
            dp: Linear::from_elem(0.0, n),
            dl: Angular::from_elem(0.0, n * (n - 1) / 2),
            used: false,
            key: AttitudeKey::default(),
            key_mass: 0.0,
            key_moments: SmallVec::new(),
            generation: 0,
        }
    }

    /// Loads body `b`: the rotation of the planes by its principal frame P, I⁻¹ in space
    /// (P I⁻¹ Pᵀ on bivectors), its velocities, no impulse yet. Returns true if the inverse
    /// inertia was computed anew (false: it is the last solve's, as the body has not turned
    /// since, or its inertia is the same in every frame, as a ball's or a cube's).
    pub(super) fn load(&mut self, b: &MovingBody, work: &mut Dense) -> bool {
        self.load_placed(b, AttitudeMatrix::Into(work))
    }

    /// [`Self::load`], the attitude matrix of the body's principal frame given by the
    /// caller or computed when it is needed.
    pub(super) fn load_placed(&mut self, b: &MovingBody, matrix: AttitudeMatrix<'_>) -> bool {
        let n = b.dim();
        let m = n * (n - 1) / 2;
        let attitude = b.rotation().principal_frame_attitude();
        let inertia = b.rotation().inertia();
        let diagonal = inertia.diagonal_inverse_plane_moments();
        let same_inertia = match diagonal {
            Some(inv) if self.key.is_set() => {
                self.key_mass == b.mass() && self.key_moments[..] == inv[..]
            }
            _ => false,
        };
        // Equal plane moments: I⁻¹ is the same multiple of the identity in every frame. Such
        // a body's frame is taken anew at every load, which costs about what comparing its
        // attitude with the last one would.
        let isotropic = diagonal.is_some_and(|inv| inv.iter().all(|x| *x == inv[0]));
        let turned = !(same_inertia && !isotropic && self.key.close_to(attitude));
        let anew = !same_inertia || (turned && !isotropic);
        if turned {
            self.place_frame(b, matrix);
        }
        if anew {
            self.place_inverse_inertia(b);
            if b.is_fixed() {
                // Infinite inertia: no impulse turns it.
                self.inv_inertia.iter_mut().for_each(|x| *x = 0.0);
            }
            match diagonal {
                Some(inv) => {
                    self.key.set(attitude);
                    self.key_mass = b.mass();
                    self.key_moments.clear();
                    self.key_moments.extend_from_slice(inv);
                }
                None => self.key.clear(),
            }
        }
        self.inv_mass = 1.0 / b.mass();
        self.v.clear();
        let inv_mass = self.inv_mass;
        self.v
            .extend(b.linear_momentum().as_slice().iter().map(|p| p * inv_mass));
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
            None => {
                self.w.clear();
                self.w.extend_from_slice(b.space_omega().as_slice());
            }
        }
        self.dp.as_mut_slice().fill(0.0);
        self.dl.as_mut_slice().fill(0.0);
        self.used = true;
        anew
    }

    /// Loads body `b`'s velocities for a solve that needs no inverse inertia in space (the
    /// soft step's substeps, whose rows keep the arms of the step's start): v = p / m and
    /// ω = P I⁻¹ L in space into `vel` (N, then M numbers), for
    /// [`Self::store_velocity_change`] to hand back what the solve changed. The rotation P
    /// of the planes is computed anew from `matrix` (the attitude matrix of the principal
    /// frame, as in [`Self::load_placed`]) if it is given, and is the last load's otherwise
    /// (the body has not turned since).
    pub(super) fn load_velocities(
        &mut self,
        b: &MovingBody,
        matrix: Option<&[f64]>,
        vel: &mut [f64],
    ) {
        let n = b.dim();
        let m = n * (n - 1) / 2;
        if let Some(matrix) = matrix {
            self.place_frame(b, AttitudeMatrix::Given(matrix));
            // The inverse inertia in space is that of another frame now.
            self.key.clear();
        }
        self.inv_mass = 1.0 / b.mass();
        for (x, p) in vel[..n].iter_mut().zip(b.linear_momentum().as_slice()) {
            *x = p * self.inv_mass;
        }
        let w = &mut vel[n..n + m];
        match b.rotation().inertia().diagonal_inverse_plane_moments() {
            Some(inv) => {
                let l = b.rotation().momentum().as_slice();
                match m {
                    3 => frame_diagonal::<3>(&self.frame, inv, l, w),
                    6 => frame_diagonal::<6>(&self.frame, inv, l, w),
                    _ => frame_diagonal::<0>(&self.frame, inv, l, w),
                }
            }
            None => w.copy_from_slice(b.space_omega().as_slice()),
        }
        self.used = true;
    }

    /// Hands body `b` what a solve did to its velocities, `change` (Δv, then Δω in space,
    /// laid out as [`Self::load_velocities`] writes them): Δp = m Δv, and ΔL = I Pᵀ Δω in
    /// the principal frame, so that the body then moves with the velocities the solve left
    /// (the frame P is the last load's). Where the solve's rows used the inverse inertia of
    /// another frame (the soft step's, of the step's start), ΔL differs from the moment of
    /// the impulses by as much as the body turned since. `work` is room for 2M numbers.
    pub(super) fn store_velocity_change(
        &mut self,
        b: &mut MovingBody,
        change: &[f64],
        work: &mut [f64],
    ) {
        self.used = false;
        if b.is_fixed() {
            return;
        }
        let n = b.dim();
        let m = n * (n - 1) / 2;
        let (turned, dl) = work[..2 * m].split_at_mut(m);
        turned.fill(0.0);
        let dw = &change[n..n + m];
        match m {
            3 => add_frame_transpose::<3>(&self.frame, dw, turned),
            6 => add_frame_transpose::<6>(&self.frame, dw, turned),
            _ => add_frame_transpose::<0>(&self.frame, dw, turned),
        }
        b.rotation().inertia().apply_into(turned, dl);
        let mass = b.mass();
        let (_, p, rotation) = b.state_mut();
        for (x, dv) in p.as_mut_slice().iter_mut().zip(&change[..n]) {
            *x += mass * dv;
        }
        let (_, l) = rotation.state_mut();
        for (x, d) in l.as_mut_slice().iter_mut().zip(dl.iter()) {
            *x += d;
        }
    }

    /// Computes the rotation of the planes by the principal frame from its attitude matrix.
    fn place_frame(&mut self, b: &MovingBody, matrix: AttitudeMatrix<'_>) {
        let n = b.dim();
        let m = n * (n - 1) / 2;
        let p = match matrix {
            AttitudeMatrix::Given(p) => p,
            AttitudeMatrix::Into(work) => {
                // `write_matrix` writes every entry.
                work.resize(n * n, 0.0);
                b.rotation()
                    .principal_frame_attitude()
                    .write_matrix(&mut work[..n * n]);
                &work[..n * n]
            }
        };
        self.frame.resize(m * m, 0.0);
        match n {
            3 => plane_rotation::<3>(p, n, &mut self.frame),
            4 => plane_rotation::<4>(p, n, &mut self.frame),
            _ => plane_rotation::<0>(p, n, &mut self.frame),
        }
    }

    /// Computes I⁻¹ in space from the rotation of the planes.
    fn place_inverse_inertia(&mut self, b: &MovingBody) {
        let n = b.dim();
        let m = n * (n - 1) / 2;
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
    pub(super) fn inverse_inertia(&self, b: &Bivector) -> Bivector {
        let m = b.as_slice().len();
        let mut out = Bivector::zero(b.dim());
        for (i, o) in out.as_mut_slice().iter_mut().enumerate() {
            *o = (0..m)
                .map(|k| self.inv_inertia[i * m + k] * b.as_slice()[k])
                .sum();
        }
        out
    }

    /// The velocity change at offset `q` for an impulse `j` at offset `r`, by the algebra's
    /// products (the reference of [`add_inverse_mass`]).
    #[cfg(test)]
    pub(super) fn response(&self, r: &Vector, j: &Vector, q: &Vector) -> Vector {
        let mut du = j * self.inv_mass;
        du += &q.left_contract(&self.inverse_inertia(&r.wedge(j)));
        du
    }

    /// The velocity of the point at offset `r`.
    pub(super) fn velocity_at(&self, r: &Vector) -> Vector {
        let mut u = Vector::zero(r.dim());
        self.velocity_at_into::<0>(r.as_slice(), u.as_mut_slice());
        u
    }

    /// The velocity v + r ⌋ ω of the point at offset `r`, written to `u` (`N` as in
    /// [`dim`]).
    #[inline(always)]
    pub(super) fn velocity_at_into<const N: usize>(&self, r: &[f64], u: &mut [f64]) {
        let n = dim::<N>(r.len());
        let (r, w) = (&r[..n], self.w.as_slice());
        u[..n].copy_from_slice(&self.v.as_slice()[..n]);
        add_contraction(r, w, u);
    }

    /// Takes an impulse `j` at offset `r`.
    pub(super) fn apply(&mut self, r: &Vector, j: &Vector) {
        self.apply_scaled::<0>(r.as_slice(), j.as_slice(), 1.0);
    }

    /// Takes the impulse s j at offset `r`: v += s j / m, ω += I⁻¹ (r ∧ s j) (`N` as in
    /// [`dim`]).
    #[inline(always)]
    pub(super) fn apply_scaled<const N: usize>(&mut self, r: &[f64], j: &[f64], s: f64) {
        let n = dim::<N>(r.len());
        let m = n * (n - 1) / 2;
        let (r, j) = (&r[..n], &j[..n]);
        // On the stack up to N = 8 (a SmallVec would be moved out of its constructor).
        let (mut fixed, mut any) = ([0.0f64; 28], Vec::new());
        let dl: &mut [f64] = if m <= 28 {
            &mut fixed[..m]
        } else {
            any.resize(m, 0.0);
            &mut any
        };
        let mut p = 0;
        for a in 0..n {
            for b in a + 1..n {
                dl[p] = s * (r[a] * j[b] - r[b] * j[a]);
                p += 1;
            }
        }
        let (v, dp) = (
            &mut self.v.as_mut_slice()[..n],
            &mut self.dp.as_mut_slice()[..n],
        );
        for ((v, dp), x) in v.iter_mut().zip(dp.iter_mut()).zip(j) {
            *v += s * x * self.inv_mass;
            *dp += s * x;
        }
        let inv = &self.inv_inertia[..m * m];
        for (w, row) in self.w.as_mut_slice()[..m]
            .iter_mut()
            .zip(inv.chunks_exact(m))
        {
            *w += dot(row, dl);
        }
        for (d, x) in self.dl.as_mut_slice()[..m].iter_mut().zip(dl.iter()) {
            *d += x;
        }
    }

    /// Its velocities and impulses as slices of length N and M (`N` as in [`dim`]): taken
    /// once for all the rows of a body, they spare each row the checks of the vectors'
    /// storage.
    #[inline(always)]
    pub(super) fn view<const N: usize>(&mut self) -> BodyView<'_> {
        let n = dim::<N>(self.v.len());
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
    pub(super) fn store(&mut self, b: &mut MovingBody) {
        self.used = false;
        if b.is_fixed() {
            // The world takes the impulses without moving.
            return;
        }
        let m = self.dl.as_slice().len();
        let (_, p, rotation) = b.state_mut();
        for (x, d) in p.as_mut_slice().iter_mut().zip(&self.dp) {
            *x += d;
        }
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

/// Where [`BodyState::load_placed`] takes a body's attitude matrix (of its principal frame,
/// row-major, own axes → space) from.
pub(super) enum AttitudeMatrix<'a> {
    /// The caller has it.
    Given(&'a [f64]),
    /// Written here if the load needs it.
    Into(&'a mut Dense),
}

/// w = F diag(`inv`) `l` for the rotation F of the planes (M × M row-major; `M` fixed, or 0
/// for `w.len()`).
#[inline(always)]
pub(super) fn frame_diagonal<const M: usize>(frame: &[f64], inv: &[f64], l: &[f64], w: &mut [f64]) {
    let m = if M == 0 { w.len() } else { M };
    let (frame, inv, l) = (&frame[..m * m], &inv[..m], &l[..m]);
    for (i, w) in w[..m].iter_mut().enumerate() {
        *w = (0..m).map(|k| frame[i * m + k] * inv[k] * l[k]).sum();
    }
}

/// The rotation F of the planes (M × M row-major, column k the image of the k-th plane
/// eₐ ∧ e_b, a < b in order) by the N × N matrix `p` (row-major; `N` fixed, or 0 for `n`):
/// F_(cd),(ab) = p_ca p_db − p_da p_cb.
#[inline(always)]
fn plane_rotation<const N: usize>(p: &[f64], n: usize, frame: &mut [f64]) {
    let n = if N == 0 { n } else { N };
    let m = n * (n - 1) / 2;
    let (p, frame) = (&p[..n * n], &mut frame[..m * m]);
    let mut k = 0;
    for a in 0..n {
        for b in a + 1..n {
            let mut row = 0;
            for c in 0..n {
                for d in c + 1..n {
                    frame[row * m + k] = p[c * n + a] * p[d * n + b] - p[d * n + a] * p[c * n + b];
                    row += 1;
                }
            }
            k += 1;
        }
    }
}

/// l += Fᵀ `dl` for the rotation F of the planes (M × M row-major; `M` fixed, or 0 for
/// `l.len()`).
#[inline(always)]
pub(super) fn add_frame_transpose<const M: usize>(frame: &[f64], dl: &[f64], l: &mut [f64]) {
    let m = if M == 0 { l.len() } else { M };
    let (frame, dl) = (&frame[..m * m], &dl[..m]);
    for (i, x) in l[..m].iter_mut().enumerate() {
        *x += (0..m).map(|k| frame[k * m + i] * dl[k]).sum::<f64>();
    }
}

/// A body's velocities and impulses during a contact solve ([`BodyState::view`]).
pub(super) struct BodyView<'a> {
    pub(super) inv_mass: f64,
    pub(super) v: &'a mut [f64],
    pub(super) w: &'a mut [f64],
    pub(super) dp: &'a mut [f64],
    pub(super) dl: &'a mut [f64],
}

impl BodyView<'_> {
    /// Takes an impulse `j` at the point of a contact row with matrices `data` (`N` as in
    /// [`dim`]).
    #[inline(always)]
    pub(super) fn apply_with<const N: usize>(
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
        let mut p = 0;
        for a in 0..n {
            for b in a + 1..n {
                self.dl[p] += offset[b] * -j[a] + offset[a] * j[b];
                p += 1;
            }
        }
    }

    /// Takes the normal impulse λ n at the point of a contact row with matrices `data`
    /// (`N` as in [`dim`]).
    #[inline(always)]
    pub(super) fn apply_normal<const N: usize>(
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
        // R n = Cᵀn = r ∧ n.
        for (d, x) in self.dl[..m].iter_mut().zip(&data[l.cn..l.cn + m]) {
            *d += lambda * x;
        }
    }
}

/// A body's velocities and impulses copied out of its state in 3D or 4D, so that over the
/// rows of a one-body group they stay in registers instead of going through the state's
/// storage after every impulse.
pub(super) struct LocalBody {
    pub(super) inv_mass: f64,
    pub(super) n: usize,
    pub(super) m: usize,
    pub(super) v: [f64; 4],
    pub(super) w: [f64; 6],
    pub(super) dp: [f64; 4],
    pub(super) dl: [f64; 6],
}

impl LocalBody {
    #[inline(always)]
    pub(super) fn new(st: &BodyView<'_>) -> LocalBody {
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
    pub(super) fn view(&mut self) -> BodyView<'_> {
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
    pub(super) fn store(&self, st: &mut BodyView<'_>) {
        st.v.copy_from_slice(&self.v[..self.n]);
        st.w.copy_from_slice(&self.w[..self.m]);
        st.dp.copy_from_slice(&self.dp[..self.n]);
        st.dl.copy_from_slice(&self.dl[..self.m]);
    }
}

/// The effective inverse mass of a body state at offset `r`, added to `k` (n × n, row-major):
/// column c is the velocity change at r for a unit impulse e_c there, e_c / m + r ⌋ I⁻¹(r ∧ e_c)
/// (as [`BodyState::response`] gives it), written without temporaries: a pair's rows set up
/// two of these per solve.
pub(super) fn add_inverse_mass(b: &BodyState, r: &Vector, k: &mut [f64]) {
    // In 3D and 4D the loops have constant bounds: unrolled, the wedges' zeros and signs
    // are known where they are written (the same products and sums, in the same order).
    let r = r.as_slice();
    match r.len() {
        3 => add_inverse_mass_n::<3>(b, r, k, &mut [0.0; 6]),
        4 => add_inverse_mass_n::<4>(b, r, k, &mut [0.0; 12]),
        n => {
            let m = n * (n - 1) / 2;
            // r ∧ e_c and its image under I⁻¹, on the stack up to N = 8.
            let (mut fixed, mut any) = ([0.0f64; 56], Vec::new());
            let room: &mut [f64] = if 2 * m <= fixed.len() {
                &mut fixed[..2 * m]
            } else {
                any.resize(2 * m, 0.0);
                &mut any
            };
            add_inverse_mass_n::<0>(b, r, k, room);
        }
    }
}

/// [`add_inverse_mass`] in dimension `N` (0: any), with `room` for 2M numbers.
#[inline(always)]
fn add_inverse_mass_n<const N: usize>(b: &BodyState, r: &[f64], k: &mut [f64], room: &mut [f64]) {
    let n = super::contact_row::dim::<N>(r.len());
    let m = n * (n - 1) / 2;
    let r = &r[..n];
    let k = &mut k[..n * n];
    let (wedge, w) = room[..2 * m].split_at_mut(m);
    let inv = &b.inv_inertia[..m * m];
    for c in 0..n {
        // The planes (a, b), a < b, in order: r ∧ e_c has r_a in the planes (a, c) and −r_b
        // in the planes (c, b).
        let mut p = 0;
        for a in 0..n {
            for bb in a + 1..n {
                wedge[p] = if bb == c {
                    r[a]
                } else if a == c {
                    -r[bb]
                } else {
                    0.0
                };
                p += 1;
            }
        }
        for (x, row) in w.iter_mut().zip(inv.chunks_exact(m)) {
            *x = row.iter().zip(wedge.iter()).map(|(i, y)| i * y).sum();
        }
        k[c * n + c] += b.inv_mass;
        // r ⌋ w into column c, as `add_contraction` adds it to a velocity.
        let mut p = 0;
        for a in 0..n {
            for bb in a + 1..n {
                k[bb * n + c] += r[a] * w[p];
                k[a * n + c] -= r[bb] * w[p];
                p += 1;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::Rotor;
    use crate::inertia::spec::parse_body;

    /// A body loaded at one attitude, then turned and loaded again: a ball or a cube (equal
    /// plane moments) keeps its inverse inertia, a box recomputes it, and both give the
    /// angular velocity in space and the inverse inertia of a state loaded afresh.
    #[test]
    fn a_turned_body_keeps_its_inverse_inertia_only_when_it_is_the_same_in_every_frame() {
        let mut cases = 0;
        for (spec, kept) in [
            ("ball:3,0.5+mass=1", true),
            ("cuboid:0.5,0.5,0.5+mass=2", true),
            ("ball:4,0.5+mass=1", true),
            ("cuboid:0.5,1,1.5+mass=1", false),
            ("cuboid:0.5,1,1.5,2+mass=1", false),
        ] {
            let parsed = parse_body(spec).unwrap();
            let n = parsed.dim;
            let omega = Bivector::from_components(n, &vec![0.3; n * (n - 1) / 2]).unwrap();
            let at = |angle: f64| {
                MovingBody::new(
                    parsed.mass,
                    parsed.inertia.clone(),
                    Rotor::from_plane_angle(n, 0, 1, angle).unwrap(),
                    &Vector::zero(n),
                    &Vector::zero(n),
                    &omega,
                )
                .unwrap()
            };
            let (before, after) = (at(0.2), at(1.1));
            let mut work = Dense::new();
            let mut st = BodyState::empty(n);
            assert!(st.load(&before, &mut work), "{spec}: first load");
            st.used = false;
            assert_eq!(st.load(&after, &mut work), !kept, "{spec}: turned");
            let mut fresh = BodyState::empty(n);
            assert!(fresh.load(&after, &mut work));
            let w = after.space_omega();
            for (x, y) in st.w.as_slice().iter().zip(w.as_slice()) {
                assert!(
                    (x - y).abs() <= 1e-14 * y.abs().max(1.0),
                    "{spec}: ω {x} against {y}"
                );
            }
            for (x, y) in st.inv_inertia.iter().zip(&fresh.inv_inertia) {
                assert!(
                    (x - y).abs() <= 1e-14 * y.abs().max(1.0),
                    "{spec}: I⁻¹ {x} against {y}"
                );
            }
            cases += 1;
        }
        assert_eq!(cases, 5);
    }

    /// The effective inverse mass written without temporaries against the columns of
    /// [`BodyState::response`] (the algebra's wedge, inverse inertia and contraction), for
    /// turned boxes in N = 2 … 8 at random offsets.
    #[test]
    fn effective_inverse_mass_is_the_response_to_unit_impulses() {
        let mut cases = 0;
        for n in 2..=8usize {
            let lengths: Vec<String> = (0..n)
                .map(|i| format!("{}", 0.3 + 0.17 * i as f64))
                .collect();
            let parsed = parse_body(&format!("cuboid:{}+mass=1.7", lengths.join(","))).unwrap();
            let body = MovingBody::new(
                parsed.mass,
                parsed.inertia.clone(),
                Rotor::from_plane_angle(n, 0, n - 1, 0.7).unwrap(),
                &Vector::zero(n),
                &Vector::zero(n),
                &Bivector::zero(n),
            )
            .unwrap();
            let mut work = Dense::new();
            let mut st = BodyState::empty(n);
            assert!(st.load(&body, &mut work));
            let r = Vector::from_components(
                &(0..n)
                    .map(|i| (1.3 * i as f64 + 0.4).sin())
                    .collect::<Vec<_>>(),
            )
            .unwrap();
            let mut k = vec![0.25; n * n];
            add_inverse_mass(&st, &r, &mut k);
            for c in 0..n {
                let col = st.response(&r, &Vector::basis(n, c), &r);
                for (row, x) in col.as_slice().iter().enumerate() {
                    let y = k[row * n + c] - 0.25;
                    assert!(
                        (x - y).abs() <= 1e-14 * x.abs().max(1.0),
                        "N = {n}: {x} against {y}"
                    );
                }
            }
            cases += 1;
        }
        assert_eq!(cases, 7);
    }

    /// The allocation-free kernels against the algebra's products: the point velocity
    /// v + r ⌋ ω and an impulse's v += j/m, ω += I⁻¹ (r ∧ j), for N = 2 … 8 with a full
    /// symmetric I⁻¹ and pseudo-random data; in 3D and 4D the fixed-size kernels give the
    /// run-time ones' results to the bit.
    #[test]
    fn point_velocity_and_impulse_kernels_agree_with_the_algebra() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut cases = 0;
        for n in 2..=8 {
            let m = n * (n - 1) / 2;
            let mut st = BodyState::empty(n);
            st.inv_mass = 0.7;
            st.inv_inertia = vec![0.0; m * m];
            for i in 0..m {
                for k in 0..=i {
                    let x = next();
                    st.inv_inertia[i * m + k] = x;
                    st.inv_inertia[k * m + i] = x;
                }
            }
            let vector = |f: &mut dyn FnMut() -> f64| {
                Vector::from_components(&(0..n).map(|_| f()).collect::<Vec<_>>()).unwrap()
            };
            let v = vector(&mut next);
            let w =
                Bivector::from_components(n, &(0..m).map(|_| next()).collect::<Vec<_>>()).unwrap();
            st.v = Linear::from_slice(v.as_slice());
            st.w = Angular::from_slice(w.as_slice());
            let (r, j) = (vector(&mut next), vector(&mut next));
            let mut want = v.clone();
            want += &r.left_contract(&w);
            let got = st.velocity_at(&r);
            for (x, y) in got.as_slice().iter().zip(want.as_slice()) {
                assert!((x - y).abs() <= 1e-15, "N = {n}: u {x} against {y}");
            }
            let (v0, w0) = (v, w);
            // The fixed-size kernels of 3D and 4D take the same steps as the run-time ones.
            let mut fixed = st.clone();
            let mut u = vec![0.0; n];
            match n {
                3 => {
                    st.velocity_at_into::<3>(r.as_slice(), &mut u);
                    fixed.apply_scaled::<3>(r.as_slice(), j.as_slice(), -2.0);
                }
                4 => {
                    st.velocity_at_into::<4>(r.as_slice(), &mut u);
                    fixed.apply_scaled::<4>(r.as_slice(), j.as_slice(), -2.0);
                }
                _ => {
                    st.velocity_at_into::<0>(r.as_slice(), &mut u);
                    fixed.apply_scaled::<0>(r.as_slice(), j.as_slice(), -2.0);
                }
            }
            assert_eq!(u, got.as_slice(), "N = {n}: fixed-size u");
            st.apply_scaled::<0>(r.as_slice(), j.as_slice(), -2.0);
            assert_eq!(fixed.v.as_slice(), st.v.as_slice(), "N = {n}: fixed-size v");
            assert_eq!(fixed.w.as_slice(), st.w.as_slice(), "N = {n}: fixed-size ω");
            let j2 = &j * -2.0;
            let dl = r.wedge(&j2);
            let mut want_v = v0;
            want_v += &(&j2 * st.inv_mass);
            let mut want_w = w0;
            want_w += &st.inverse_inertia(&dl);
            let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-14);
            assert!(close(st.v.as_slice(), want_v.as_slice()), "N = {n}: v");
            assert!(close(st.w.as_slice(), want_w.as_slice()), "N = {n}: ω");
            assert!(close(st.dl.as_slice(), dl.as_slice()), "N = {n}: ΔL");
            assert!(close(st.dp.as_slice(), j2.as_slice()), "N = {n}: Δp");
            cases += 1;
        }
        assert_eq!(cases, 7);
    }
}
