//! Small dense real matrices with inline storage, for the decompositions and matrix functions
//! behind the versor exponential and logarithm: entries live on the stack up to `CAP` of them
//! (an 8 × 8 matrix in [`Mat8`]) and spill to the heap only beyond, so that exp and log up to
//! N = 6 never allocate while larger N keep working.
//!
//! The kernels are the textbook ones (Golub & Van Loan, *Matrix Computations*, 4th ed.): the
//! cyclic Jacobi method for symmetric eigenproblems (§8.5), the one-sided Jacobi SVD (§8.6.3),
//! LU with partial pivoting (§3.4) and Householder reflections (§5.1).

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
        let mut out = Self::zeros(self.rows, other.cols);
        for j in 0..other.cols {
            for k in 0..self.cols {
                let b = other[(k, j)];
                if b == 0.0 {
                    continue;
                }
                for i in 0..self.rows {
                    out.a[j * self.rows + i] += self.a[k * self.rows + i] * b;
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
    /// matrix, by the cyclic Jacobi method: sweeps of exact plane rotations that zero each
    /// off-diagonal entry in turn, until the off-diagonal mass is below ε² of the total
    /// (quadratic convergence; at most 60 sweeps). Entries below ε² max |aᵢⱼ| are flushed to
    /// zero first: they move no eigenvalue by more than that, far below round-off, and would
    /// only cost rotations.
    pub(crate) fn symmetric_eigen(&self) -> (Vec8, Self) {
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
        for _sweep in 0..60 {
            let mut off = 0.0;
            let mut total = 0.0;
            for j in 0..n {
                for i in 0..n {
                    let x = a[(i, j)] * a[(i, j)];
                    total += x;
                    if i != j {
                        off += x;
                    }
                }
            }
            if off <= f64::EPSILON * f64::EPSILON * total {
                break;
            }
            for p in 0..n {
                for q in p + 1..n {
                    let apq = a[(p, q)];
                    if apq == 0.0 {
                        continue;
                    }
                    // The rotation angle that annihilates a_pq, in the stable tangent form.
                    let theta = (a[(q, q)] - a[(p, p)]) / (2.0 * apq);
                    let t = if theta == 0.0 {
                        1.0
                    } else {
                        theta.signum() / (theta.abs() + theta.hypot(1.0))
                    };
                    let c = 1.0 / t.hypot(1.0);
                    let s = t * c;
                    for k in 0..n {
                        let (akp, akq) = (a[(k, p)], a[(k, q)]);
                        a[(k, p)] = c * akp - s * akq;
                        a[(k, q)] = s * akp + c * akq;
                    }
                    for k in 0..n {
                        let (apk, aqk) = (a[(p, k)], a[(q, k)]);
                        a[(p, k)] = c * apk - s * aqk;
                        a[(q, k)] = s * apk + c * aqk;
                    }
                    for k in 0..n {
                        let (vkp, vkq) = (v[(k, p)], v[(k, q)]);
                        v[(k, p)] = c * vkp - s * vkq;
                        v[(k, q)] = s * vkp + c * vkq;
                    }
                }
            }
        }
        ((0..n).map(|i| a[(i, i)]).collect(), v)
    }

    /// The inverse of a square matrix and log |det|, by LU with partial pivoting; None if a
    /// pivot is zero or the inverse is not finite.
    pub(crate) fn inverse_and_log_det(&self) -> Option<(Self, f64)> {
        let n = self.rows;
        let mut lu = self.clone();
        let mut perm: SmallVec<[usize; 32]> = (0..n).collect();
        let mut log_det = 0.0;
        for k in 0..n {
            let (p, pivot) = (k..n)
                .map(|i| (i, lu[(i, k)].abs()))
                .fold((k, -1.0), |best, x| if x.1 > best.1 { x } else { best });
            if pivot == 0.0 || !pivot.is_finite() {
                return None;
            }
            if p != k {
                perm.swap(p, k);
                for j in 0..n {
                    let t = lu[(p, j)];
                    lu[(p, j)] = lu[(k, j)];
                    lu[(k, j)] = t;
                }
            }
            log_det += pivot.ln();
            let d = lu[(k, k)];
            for i in k + 1..n {
                lu[(i, k)] /= d;
            }
            for j in k + 1..n {
                let ukj = lu[(k, j)];
                if ukj == 0.0 {
                    continue;
                }
                for i in k + 1..n {
                    let l = lu[(i, k)];
                    lu[(i, j)] -= l * ukj;
                }
            }
        }
        // Solve L U X = P I column by column.
        let mut inv = Self::zeros(n, n);
        for (c, &pc) in perm.iter().enumerate() {
            // Column pc of the inverse solves with the unit vector e_pc permuted to row c.
            let col = inv.column_mut(pc);
            col[c] = 1.0;
            for i in 0..n {
                let mut s = col[i];
                for k in 0..i {
                    s -= lu[(i, k)] * col[k];
                }
                col[i] = s;
            }
            for i in (0..n).rev() {
                let mut s = col[i];
                for k in i + 1..n {
                    s -= lu[(i, k)] * col[k];
                }
                col[i] = s / lu[(i, i)];
            }
        }
        inv.a
            .iter()
            .all(|x| x.is_finite())
            .then_some((inv, log_det))
    }

    /// The least-squares solution x of min |A x − b| through the singular value
    /// decomposition, with the directions whose singular value is at most `cut_relative`
    /// times the largest left out (they would only fit round-off). One-sided Jacobi
    /// (Hestenes): plane rotations of pairs of columns until every pair is orthogonal to ε,
    /// then σⱼ = |aⱼ| and x = Σ vⱼ (aⱼ · b)/σⱼ². None if b or A is not finite.
    pub(crate) fn least_squares_svd<const V: usize>(
        &self,
        b: &[f64],
        cut_relative: f64,
    ) -> Option<SmallVec<[f64; V]>> {
        let (m, n) = (self.rows, self.cols);
        if !(self.a.iter().all(|x| x.is_finite()) && b.iter().all(|x| x.is_finite())) {
            return None;
        }
        let mut a = self.clone();
        let mut v: Dense<V> = Dense::identity(n);
        for _sweep in 0..60 {
            let mut rotated = false;
            for p in 0..n {
                for q in p + 1..n {
                    let (mut alpha, mut beta, mut gamma) = (0.0, 0.0, 0.0);
                    for i in 0..m {
                        let (x, y) = (a[(i, p)], a[(i, q)]);
                        alpha += x * x;
                        beta += y * y;
                        gamma += x * y;
                    }
                    if gamma == 0.0 || gamma.abs() <= f64::EPSILON * (alpha * beta).sqrt() {
                        continue;
                    }
                    rotated = true;
                    let zeta = (beta - alpha) / (2.0 * gamma);
                    let t = if zeta == 0.0 {
                        1.0
                    } else {
                        zeta.signum() / (zeta.abs() + zeta.hypot(1.0))
                    };
                    let c = 1.0 / t.hypot(1.0);
                    let s = c * t;
                    for i in 0..m {
                        let (x, y) = (a[(i, p)], a[(i, q)]);
                        a[(i, p)] = c * x - s * y;
                        a[(i, q)] = s * x + c * y;
                    }
                    for i in 0..n {
                        let (x, y) = (v[(i, p)], v[(i, q)]);
                        v[(i, p)] = c * x - s * y;
                        v[(i, q)] = s * x + c * y;
                    }
                }
            }
            if !rotated {
                break;
            }
        }
        let sigma: SmallVec<[f64; V]> = (0..n)
            .map(|j| crate::numeric::scaled_norm(a.column(j)))
            .collect();
        let cut = cut_relative * sigma.iter().fold(0.0f64, |s, x| s.max(*x));
        let mut x: SmallVec<[f64; V]> = SmallVec::from_elem(0.0, n);
        for j in 0..n {
            if sigma[j] <= cut || sigma[j] == 0.0 {
                continue;
            }
            let ub: f64 = a.column(j).iter().zip(b).map(|(u, y)| u * y).sum();
            let k = ub / sigma[j] / sigma[j];
            for (xi, vi) in x.iter_mut().zip(v.column(j)) {
                *xi += k * vi;
            }
        }
        x.iter().all(|c| c.is_finite()).then_some(x)
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
            // Symmetric eigen: A = V diag(λ) Vᵀ with V orthogonal.
            let s = a.transpose().mul(&a);
            let (values, vectors) = s.symmetric_eigen();
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

    #[test]
    fn least_squares_matches_nalgebra_svd_and_cuts_null_directions() {
        let mut seed = 11u64;
        let (m, n) = (12, 5);
        let mut a = Dense::<64>::from_fn(m, n, |_, _| random(&mut seed));
        // Column 4 a multiple of column 0: a null direction the cut must leave out.
        for i in 0..m {
            a[(i, 4)] = 2.0 * a[(i, 0)];
        }
        let b: Vec<f64> = (0..m).map(|_| random(&mut seed)).collect();
        let x = a.least_squares_svd::<8>(&b, 1e-10).unwrap();
        let da = DMatrix::from_fn(m, n, |i, j| a[(i, j)]);
        let svd = da.svd(true, true);
        let cut = 1e-10 * svd.singular_values.max();
        let want = svd
            .solve(&nalgebra::DVector::from_column_slice(&b), cut)
            .unwrap();
        for j in 0..n {
            assert!((x[j] - want[j]).abs() < 1e-12, "{x:?} vs {want}");
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
