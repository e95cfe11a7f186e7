//! Small dense real matrices with inline storage, for the decompositions and matrix functions
//! behind the versor exponential and logarithm: entries live on the stack up to `CAP` of them
//! (an 8 × 8 matrix in [`Mat8`]) and spill to the heap only beyond, so that exp and log up to
//! N = 6 never allocate while larger N keep working.
//!
//! The matrix kernels are the slice kernels of this module's siblings: LU with partial
//! pivoting ([`super::solve`]), the Householder complement ([`super::householder`]), and for
//! symmetric eigenproblems nalgebra's symmetric QR on fixed-size matrices with the cyclic
//! Jacobi method ([`super::eigen`]) as its fallback.

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
        let floor = super::eigen::negligible_below(scale);
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
    /// matrix, by the cyclic Jacobi method ([`super::eigen::jacobi_eigen`]).
    pub(crate) fn jacobi_eigen(&self) -> (Vec8, Self) {
        let n = self.rows;
        let mut a = self.clone();
        let mut v = Self::zeros(n, n);
        super::eigen::jacobi_eigen(&mut a.a, n, &mut v.a);
        ((0..n).map(|i| a[(i, i)]).collect(), v)
    }

    /// The inverse of a square matrix and log |det|, by LU with partial pivoting; None if a
    /// pivot is zero or the inverse is not finite.
    pub(crate) fn inverse_and_log_det(&self) -> Option<(Self, f64)> {
        let n = self.rows;
        let mut lu = self.clone();
        let mut pivots: SmallVec<[usize; 32]> = SmallVec::from_elem(0, n);
        if !super::solve::lu_factor(n, &mut lu.a, &mut pivots) {
            return None;
        }
        // |det| is the product of |uₖₖ|, summed as logarithms so that it cannot overflow.
        let log_det = (0..n).map(|k| lu[(k, k)].abs().ln()).sum();
        let mut inv = Self::identity(n);
        super::solve::lu_apply(n, &lu.a, &pivots, &mut inv.a, n);
        inv.a
            .iter()
            .all(|x| x.is_finite())
            .then_some((inv, log_det))
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
    use crate::numeric::tests::random;
    use nalgebra::DMatrix;

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
}
