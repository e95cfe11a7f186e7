//! Small dense real matrices with inline storage, for the decompositions and matrix functions
//! behind the versor exponential and logarithm: entries live on the stack up to `CAP` of them
//! (an 8 × 8 matrix in [`Mat8`]) and spill to the heap only beyond, so that exp and log up to
//! N = 6 never allocate while larger N keep working.
//!
//! The kernels are the textbook ones (Golub & Van Loan, *Matrix Computations*, 4th ed.): LU
//! with partial pivoting (§3.4), Householder reflections (§5.1), and for symmetric
//! eigenproblems nalgebra's symmetric QR on fixed-size matrices with the cyclic Jacobi
//! method (§8.5) as its fallback.

use smallvec::SmallVec;
use std::ops::{Index, IndexMut};

/// A dense matrix stored by columns, inline up to `CAP` entries.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Dense<const CAP: usize> {
    rows: usize,
    cols: usize,
    a: SmallVec<[f64; CAP]>,
}

/// Square matrices up to 8 × 8 inline: rotation matrices and skew matrices of N ≤ 8.
pub(crate) type Mat8 = Dense<64>;

/// Short vectors, inline up to 8 entries (N ≤ 8).
pub(crate) type Vec8 = SmallVec<[f64; 8]>;

impl<const CAP: usize> Index<(usize, usize)> for Dense<CAP> {
    type Output = f64;
    #[inline]
    fn index(&self, (i, j): (usize, usize)) -> &f64 {
        debug_assert!(i < self.rows && j < self.cols);
        &self.a[j * self.rows + i]
    }
}

impl<const CAP: usize> IndexMut<(usize, usize)> for Dense<CAP> {
    #[inline]
    fn index_mut(&mut self, (i, j): (usize, usize)) -> &mut f64 {
        debug_assert!(i < self.rows && j < self.cols);
        &mut self.a[j * self.rows + i]
    }
}

impl<const CAP: usize> Dense<CAP> {
    pub(crate) fn zeros(rows: usize, cols: usize) -> Self {
        Dense {
            rows,
            cols,
            a: SmallVec::from_elem(0.0, rows * cols),
        }
    }

    pub(crate) fn identity(n: usize) -> Self {
        let mut m = Self::zeros(n, n);
        for i in 0..n {
            m[(i, i)] = 1.0;
        }
        m
    }

    pub(crate) fn from_fn(
        rows: usize,
        cols: usize,
        mut f: impl FnMut(usize, usize) -> f64,
    ) -> Self {
        let mut m = Self::zeros(rows, cols);
        for j in 0..cols {
            for i in 0..rows {
                m[(i, j)] = f(i, j);
            }
        }
        m
    }

    #[inline]
    pub(crate) fn nrows(&self) -> usize {
        self.rows
    }

    #[inline]
    pub(crate) fn ncols(&self) -> usize {
        self.cols
    }

    /// The entries, by columns.
    #[inline]
    pub(crate) fn as_slice(&self) -> &[f64] {
        &self.a
    }

    #[inline]
    pub(crate) fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.a
    }

    /// Column j, contiguous.
    #[inline]
    pub(crate) fn column(&self, j: usize) -> &[f64] {
        &self.a[j * self.rows..(j + 1) * self.rows]
    }

    #[inline]
    pub(crate) fn column_mut(&mut self, j: usize) -> &mut [f64] {
        let r = self.rows;
        &mut self.a[j * r..(j + 1) * r]
    }

    pub(crate) fn transpose(&self) -> Self {
        Self::from_fn(self.cols, self.rows, |i, j| self[(j, i)])
    }

    /// The product self · other.
    pub(crate) fn mul(&self, other: &Self) -> Self {
        debug_assert_eq!(self.cols, other.rows);
        let r = self.rows;
        let mut out = Self::zeros(r, other.cols);
        let a = self.a.as_slice();
        for (j, oc) in out.a.chunks_exact_mut(r.max(1)).enumerate() {
            for (k, &b) in other.column(j).iter().enumerate() {
                if b == 0.0 {
                    continue;
                }
                for (o, &x) in oc.iter_mut().zip(&a[k * r..(k + 1) * r]) {
                    *o += x * b;
                }
            }
        }
        out
    }

    /// The product self · x.
    pub(crate) fn mul_vec(&self, x: &[f64]) -> Vec8 {
        debug_assert_eq!(self.cols, x.len());
        let mut out: Vec8 = SmallVec::from_elem(0.0, self.rows);
        for (k, &b) in x.iter().enumerate() {
            for (o, &a) in out.iter_mut().zip(self.column(k)) {
                *o += a * b;
            }
        }
        out
    }

    /// self + s · other.
    pub(crate) fn add_scaled(&self, other: &Self, s: f64) -> Self {
        let mut out = self.clone();
        for (x, y) in out.a.iter_mut().zip(&other.a) {
            *x += s * y;
        }
        out
    }

    /// s · self.
    pub(crate) fn scaled(&self, s: f64) -> Self {
        let mut out = self.clone();
        out.a.iter_mut().for_each(|x| *x *= s);
        out
    }

    /// max |aᵢⱼ|.
    pub(crate) fn amax(&self) -> f64 {
        self.a.iter().fold(0.0f64, |m, x| m.max(x.abs()))
    }

    /// The largest absolute column sum ‖A‖₁ of A − I.
    pub(crate) fn norm1_minus_identity(&self) -> f64 {
        (0..self.cols)
            .map(|j| {
                self.column(j)
                    .iter()
                    .enumerate()
                    .map(|(i, x)| if i == j { (x - 1.0).abs() } else { x.abs() })
                    .sum::<f64>()
            })
            .fold(0.0f64, f64::max)
    }

    /// The leading m × m block.
    pub(crate) fn leading(&self, m: usize) -> Self {
        Self::from_fn(m, m, |i, j| self[(i, j)])
    }

    /// The eigenvalues and eigenvectors (columns, in the order of the values) of a symmetric
    /// matrix, as `crate::numeric::symmetric_eigen` computes them (nalgebra's symmetric QR
    /// after flushing entries below ε² max |aᵢⱼ| to zero, and the cyclic Jacobi method where
    /// that returns NaN), on fixed-size nalgebra matrices up to 8 × 8 so that nothing is
    /// allocated there.
    pub(crate) fn symmetric_eigen(&self) -> (Vec8, Self) {
        let n = self.rows;
        let scale = self.amax();
        if scale == 0.0 || !scale.is_finite() {
            return ((0..n).map(|i| self[(i, i)]).collect(), Self::identity(n));
        }
        let floor = f64::EPSILON * f64::EPSILON * scale;
        let entry = |i: usize, j: usize| {
            let x = self[(i, j)];
            if x.abs() < floor { 0.0 } else { x }
        };
        // One arm per size, each on a fixed-size matrix (no heap).
        macro_rules! fixed {
            ($($size:literal),*) => {
                match n {
                    $($size => {
                        let s = nalgebra::SMatrix::<f64, $size, $size>::from_fn(entry);
                        if let Some(eig) = nalgebra::SymmetricEigen::try_new(s, f64::EPSILON, 0) {
                            let finite = eig.eigenvalues.iter().all(|x| x.is_finite())
                                && eig.eigenvectors.iter().all(|x| x.is_finite());
                            if finite {
                                return (
                                    eig.eigenvalues.iter().copied().collect(),
                                    Self::from_fn(n, n, |i, j| eig.eigenvectors[(i, j)]),
                                );
                            }
                        }
                        return Self::from_fn(n, n, entry).jacobi_eigen();
                    })*
                    _ => {}
                }
            };
        }
        fixed!(1, 2, 3, 4, 5, 6, 7, 8);
        let (values, vectors) =
            crate::numeric::symmetric_eigen(nalgebra::DMatrix::from_fn(n, n, |i, j| self[(i, j)]));
        (
            values.iter().copied().collect(),
            Self::from_fn(n, n, |i, j| vectors[(i, j)]),
        )
    }

    /// The eigenvalues and eigenvectors (columns, in the order of the values) of a symmetric
    /// matrix, by the cyclic Jacobi method: sweeps of exact plane rotations that zero each
    /// off-diagonal entry in turn, until a sweep finds every a_pq below ε √|a_pp a_qq| (the
    /// threshold of Demmel & Veselić, "Jacobi's method is more accurate than QR", 1992;
    /// quadratic convergence, at most 60 sweeps). Entries below ε² max |aᵢⱼ| count as zero:
    /// they move no eigenvalue by more than that, far below round-off, and would only cost
    /// rotations.
    pub(crate) fn jacobi_eigen(&self) -> (Vec8, Self) {
        let n = self.rows;
        let mut a = self.clone();
        let mut v = Self::identity(n);
        let scale = a.amax();
        if scale == 0.0 || !scale.is_finite() {
            return ((0..n).map(|i| a[(i, i)]).collect(), v);
        }
        let floor = f64::EPSILON * f64::EPSILON * scale;
        a.a.iter_mut().for_each(|x| {
            if x.abs() < floor {
                *x = 0.0;
            }
        });
        let (am, vm) = (a.a.as_mut_slice(), v.a.as_mut_slice());
        for _sweep in 0..60 {
            let mut rotated = false;
            for p in 0..n {
                for q in p + 1..n {
                    let apq = am[q * n + p];
                    // An entry below ε √|a_pp a_qq| (or the floor) moves no eigenvalue beyond
                    // round-off: it is dropped rather than rotated away, which would only
                    // create round-off of the same size elsewhere.
                    let (app, aqq) = (am[p * n + p], am[q * n + q]);
                    if apq.abs() <= floor.max(f64::EPSILON * (app * aqq).abs().sqrt()) {
                        am[q * n + p] = 0.0;
                        am[p * n + q] = 0.0;
                        continue;
                    }
                    rotated = true;
                    // The rotation angle that annihilates a_pq, in the stable tangent form
                    // (|t| ≤ 1; a θ whose square overflows gives t = 0, no rotation).
                    let theta = (aqq - app) / (2.0 * apq);
                    let t = if theta == 0.0 {
                        1.0
                    } else {
                        theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt())
                    };
                    let c = 1.0 / (t * t + 1.0).sqrt();
                    let s = t * c;
                    // Rows and columns p and q outside the 2 × 2 block, kept symmetric; the
                    // block becomes diag(a_pp − t a_pq, a_qq + t a_pq) (Numerical Recipes'
                    // form, which needs no products of the rotation there).
                    for k in 0..n {
                        if k == p || k == q {
                            continue;
                        }
                        let (akp, akq) = (am[p * n + k], am[q * n + k]);
                        let (x, y) = (c * akp - s * akq, s * akp + c * akq);
                        am[p * n + k] = x;
                        am[q * n + k] = y;
                        am[k * n + p] = x;
                        am[k * n + q] = y;
                    }
                    am[p * n + p] = app - t * apq;
                    am[q * n + q] = aqq + t * apq;
                    am[q * n + p] = 0.0;
                    am[p * n + q] = 0.0;
                    rotate_columns(vm, n, p, q, c, s);
                }
            }
            if !rotated {
                break;
            }
        }
        ((0..n).map(|i| a[(i, i)]).collect(), v)
    }

    /// The inverse of a square matrix and log |det|, by LU with partial pivoting; None if a
    /// pivot is zero or the inverse is not finite.
    pub(crate) fn inverse_and_log_det(&self) -> Option<(Self, f64)> {
        let n = self.rows;
        let mut lu = self.clone();
        let l = lu.a.as_mut_slice();
        let mut perm: SmallVec<[usize; 32]> = (0..n).collect();
        let mut log_det = 0.0;
        // Entry (i, j) is l[j * n + i].
        for k in 0..n {
            let (p, pivot) = (k..n)
                .map(|i| (i, l[k * n + i].abs()))
                .fold((k, -1.0), |best, x| if x.1 > best.1 { x } else { best });
            if pivot == 0.0 || !pivot.is_finite() {
                return None;
            }
            if p != k {
                perm.swap(p, k);
                for j in 0..n {
                    l.swap(j * n + p, j * n + k);
                }
            }
            log_det += pivot.ln();
            let (left, right) = l.split_at_mut((k + 1) * n);
            let col_k = &mut left[k * n..];
            let d = col_k[k];
            for x in &mut col_k[k + 1..] {
                *x /= d;
            }
            for cj in right.chunks_exact_mut(n) {
                let ukj = cj[k];
                if ukj == 0.0 {
                    continue;
                }
                for (x, &lik) in cj[k + 1..].iter_mut().zip(&col_k[k + 1..]) {
                    *x -= lik * ukj;
                }
            }
        }
        // Solve L U X = P I column by column: column perm[c] of the inverse has the unit
        // vector e_c on the right.
        let mut inv = Self::zeros(n, n);
        for (c, &pc) in perm.iter().enumerate() {
            let col = inv.column_mut(pc);
            col[c] = 1.0;
            for i in 0..n {
                let mut s = col[i];
                for k in 0..i {
                    s -= l[k * n + i] * col[k];
                }
                col[i] = s;
            }
            for i in (0..n).rev() {
                let mut s = col[i];
                for k in i + 1..n {
                    s -= l[k * n + i] * col[k];
                }
                col[i] = s / l[i * n + i];
            }
        }
        inv.a
            .iter()
            .all(|x| x.is_finite())
            .then_some((inv, log_det))
    }
}

/// Columns p < q of a matrix stored by columns of `rows` entries:
/// (x, y) ← (c x − s y, s x + c y).
#[inline]
fn rotate_columns(a: &mut [f64], rows: usize, p: usize, q: usize, c: f64, s: f64) {
    let (left, right) = a.split_at_mut(q * rows);
    let (x, y) = (&mut left[p * rows..(p + 1) * rows], &mut right[..rows]);
    for (x, y) in x.iter_mut().zip(y.iter_mut()) {
        let (a, b) = (*x, *y);
        *x = c * a - s * b;
        *y = s * a + c * b;
    }
}

/// Returns an m × (m − 2) matrix whose orthonormal columns span the complement of the
/// orthonormal pair (w, u), from two Householder reflections (stable even when w and u are
/// near basis vectors).
pub(crate) fn householder_complement(w: &[f64], u: &[f64]) -> Mat8 {
    let m = w.len();
    // H1 maps w to ±e1.
    let h1 = householder(w, 0);
    // H2 acts on coordinates 1.. and maps (H1 u)[1..] to ±e2.
    let mut hu: Vec8 = SmallVec::from_slice(u);
    apply_householder(&h1, &mut hu);
    let h2 = householder(&hu, 1);
    // Q = H1 H2: apply H2 then H1 to each column of the identity; keep columns 2...
    let mut q = Mat8::zeros(m, m - 2);
    for c in 2..m {
        let col = q.column_mut(c - 2);
        col[c] = 1.0;
        apply_householder(&h2, col);
        apply_householder(&h1, col);
    }
    q
}

/// The unit vector h of the reflection I − 2 h hᵀ (h zero before `start`) that maps x to a
/// multiple of e_start; zero (the identity) if x vanishes from `start` on.
fn householder(x: &[f64], start: usize) -> Vec8 {
    let m = x.len();
    let mut h: Vec8 = SmallVec::from_elem(0.0, m);
    let tail_norm = x[start..].iter().map(|a| a * a).sum::<f64>().sqrt();
    if tail_norm == 0.0 {
        return h;
    }
    // h ∝ x − σ|x| e_start with σ = −sign(x_start), avoiding cancellation.
    let sigma = if x[start] >= 0.0 { -1.0 } else { 1.0 };
    h[start..].copy_from_slice(&x[start..]);
    h[start] -= sigma * tail_norm;
    let hn = h.iter().map(|a| a * a).sum::<f64>().sqrt();
    if hn > 0.0 {
        h.iter_mut().for_each(|a| *a /= hn);
    }
    h
}

fn apply_householder(h: &[f64], x: &mut [f64]) {
    let d: f64 = h.iter().zip(x.iter()).map(|(a, b)| a * b).sum();
    if d != 0.0 {
        x.iter_mut().zip(h).for_each(|(xi, hi)| *xi -= 2.0 * d * hi);
    }
}

/// Euclidean norm of a short vector (plain sum of squares).
pub(crate) fn norm(x: &[f64]) -> f64 {
    x.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// Dot product.
pub(crate) fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    fn random(seed: &mut u64) -> f64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    #[test]
    fn kernels_match_nalgebra() {
        let mut seed = 7u64;
        for n in 1..=9 {
            let a = Mat8::from_fn(n, n, |_, _| random(&mut seed));
            let b = Mat8::from_fn(n, n, |_, _| random(&mut seed));
            let da = DMatrix::from_fn(n, n, |i, j| a[(i, j)]);
            let db = DMatrix::from_fn(n, n, |i, j| b[(i, j)]);
            let p = a.mul(&b);
            let dp = &da * &db;
            for i in 0..n {
                for j in 0..n {
                    assert!((p[(i, j)] - dp[(i, j)]).abs() < 1e-14);
                }
            }
            let (inv, log_det) = a.inverse_and_log_det().unwrap();
            let dinv = da.clone().try_inverse().unwrap();
            let scale = dinv.amax();
            for i in 0..n {
                for j in 0..n {
                    assert!(
                        (inv[(i, j)] - dinv[(i, j)]).abs() < 1e-11 * scale,
                        "n = {n}"
                    );
                }
            }
            assert!(
                (log_det - da.determinant().abs().ln()).abs() < 1e-12,
                "n = {n}"
            );
            // Symmetric eigen: A = V diag(λ) Vᵀ with V orthogonal, both routes.
            let s = a.transpose().mul(&a);
            for (values, vectors) in [s.symmetric_eigen(), s.jacobi_eigen()] {
                for i in 0..n {
                    for j in 0..n {
                        let r: f64 = (0..n)
                            .map(|k| vectors[(i, k)] * values[k] * vectors[(j, k)])
                            .sum();
                        assert!((r - s[(i, j)]).abs() < 1e-13 * s.amax(), "n = {n}");
                        let o: f64 = (0..n).map(|k| vectors[(k, i)] * vectors[(k, j)]).sum();
                        let want = if i == j { 1.0 } else { 0.0 };
                        assert!((o - want).abs() < 1e-14, "n = {n}");
                    }
                }
            }
        }
    }

    #[test]
    fn householder_complement_is_orthonormal_and_orthogonal_to_the_pair() {
        let c = std::f64::consts::FRAC_1_SQRT_2;
        let m = 6;
        let w: Vec8 = (0..m).map(|_| 1.0 / (m as f64).sqrt()).collect();
        let mut u: Vec8 = SmallVec::from_elem(0.0, m);
        u[0] = c;
        u[1] = -c;
        let e = |k: usize| -> Vec8 { (0..m).map(|i| f64::from(u8::from(i == k))).collect() };
        for (w, u) in [(w, u), (e(0), e(1)), (e(3), e(5))] {
            let q = householder_complement(&w, &u);
            for j in 0..m - 2 {
                assert!(dot(q.column(j), &w).abs() < 1e-15);
                assert!(dot(q.column(j), &u).abs() < 1e-15);
                for k in 0..m - 2 {
                    let want = if j == k { 1.0 } else { 0.0 };
                    assert!((dot(q.column(j), q.column(k)) - want).abs() < 1e-15);
                }
            }
        }
    }
}
