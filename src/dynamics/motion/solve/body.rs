//! A body as the solves see it.

use super::Dense;
use super::contact_row::{RowLayout, add_mat_vec, axes_of, contraction_entry, dim};
use crate::algebra::{Bivector, Vector};
use crate::dynamics::Attitude;
use crate::dynamics::motion::MovingBody;
use crate::dynamics::motion::placement::{attitudes_close, dot, set_vector};
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
    pub(super) v: Vector,
    pub(super) w: Bivector,
    pub(super) dp: Vector,
    pub(super) dl: Bivector,
    pub used: bool,
    /// The attitude of the principal frame, the mass and the inverse plane moments that
    /// `frame` and `inv_inertia` were computed for (None when they must be computed anew):
    /// a body at the same placement as at the last solve reuses them.
    pub(super) key: Option<(Attitude, f64)>,
    pub(super) key_moments: SmallVec<[f64; 28]>,
    /// Changes whenever `frame` and `inv_inertia` are computed anew.
    pub(super) generation: u64,
}

impl BodyState {
    pub(super) fn empty(n: usize) -> BodyState {
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
    pub(super) fn load(&mut self, b: &MovingBody, work: &mut Dense) -> bool {
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
            if b.is_fixed() {
                // Infinite inertia: no impulse turns it.
                self.inv_inertia.iter_mut().for_each(|x| *x = 0.0);
            }
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
    pub(super) fn place(&mut self, b: &MovingBody, work: &mut Dense) {
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

    /// The velocity change at offset `q` for an impulse `j` at offset `r`.
    pub(super) fn response(&self, r: &Vector, j: &Vector, q: &Vector) -> Vector {
        let mut du = j * self.inv_mass;
        du += &q.left_contract(&self.inverse_inertia(&r.wedge(j)));
        du
    }

    /// The velocity of the point at offset `r`.
    pub(super) fn velocity_at(&self, r: &Vector) -> Vector {
        let mut u = self.v.clone();
        u += &r.left_contract(&self.w);
        u
    }

    /// Takes an impulse `j` at offset `r`.
    pub(super) fn apply(&mut self, r: &Vector, j: &Vector) {
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
    pub(super) fn view<const N: usize>(&mut self) -> BodyView<'_> {
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
    pub(super) fn store(&mut self, b: &mut MovingBody) {
        self.used = false;
        if b.is_fixed() {
            // The world takes the impulses without moving.
            return;
        }
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
pub(super) fn frame_diagonal<const M: usize>(frame: &[f64], inv: &[f64], l: &[f64], w: &mut [f64]) {
    let m = if M == 0 { w.len() } else { M };
    let (frame, inv, l) = (&frame[..m * m], &inv[..m], &l[..m]);
    for (i, w) in w[..m].iter_mut().enumerate() {
        *w = (0..m).map(|k| frame[i * m + k] * inv[k] * l[k]).sum();
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
        let r = &data[l.r..l.r + m * n];
        for (d, row) in self.dl[..m].iter_mut().zip(r.chunks_exact(n)) {
            *d += dot(row, j);
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
        for (d, x) in self.dl[..m].iter_mut().zip(&data[l.rn..l.rn + m]) {
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

/// The effective inverse mass of a body state at offset `r`, added to `k` (n × n, row-major).
pub(super) fn add_inverse_mass(b: &BodyState, r: &Vector, k: &mut [f64]) {
    let n = r.dim();
    for c in 0..n {
        let col = b.response(r, &Vector::basis(n, c), r);
        for (row, x) in col.as_slice().iter().enumerate() {
            k[row * n + c] += x;
        }
    }
}
