//! A symmetric eigen-decomposition that never returns NaN for finite input.
//!
//! nalgebra's `SymmetricEigen` is fast and accurate, but for some well-scaled matrices whose
//! entries span hundreds of orders of magnitude (e.g. 1 beside 1e-226, which the invariant
//! decomposition meets for bivectors with components 1e150 and 1e37) its implicit QR step
//! returns ∞ and NaN eigenvalues (random bivectors spanning that range meet it).
//! This wrapper flushes entries below ε²·max|S| to zero (they move no eigenvalue by more than
//! ε² max|S|, far below round-off), checks the result, and falls back to the cyclic Jacobi
//! method, which only ever applies exact plane rotations and cannot produce NaN.

use nalgebra::{DMatrix, DVector};
use smallvec::SmallVec;

/// The result of [`symmetric_eigen`], shaped like nalgebra's `SymmetricEigen`.
pub(crate) struct RobustEigen {
    /// The eigenvalues, unsorted.
    pub eigenvalues: DVector<f64>,
    /// The eigenvectors, as columns in the order of the eigenvalues.
    pub eigenvectors: DMatrix<f64>,
}

impl RobustEigen {
    /// Decomposes the symmetric matrix `s` (see [`symmetric_eigen`]).
    pub(crate) fn new(s: DMatrix<f64>) -> Self {
        let (eigenvalues, eigenvectors) = symmetric_eigen(s);
        RobustEigen {
            eigenvalues,
            eigenvectors,
        }
    }
}

/// Returns (eigenvalues, eigenvectors as columns) of the symmetric matrix `s` (finite).
pub(crate) fn symmetric_eigen(mut s: DMatrix<f64>) -> (DVector<f64>, DMatrix<f64>) {
    let n = s.nrows();
    let scale = s.amax();
    if scale == 0.0 || !scale.is_finite() {
        let values = DVector::from_fn(n, |i, _| s[(i, i)]);
        return (values, DMatrix::identity(n, n));
    }
    let floor = negligible_below(scale);
    s.iter_mut().for_each(|x| {
        if x.abs() < floor {
            *x = 0.0;
        }
    });
    if let Some(eig) = nalgebra::SymmetricEigen::try_new(s.clone(), f64::EPSILON, 0) {
        let finite = eig.eigenvalues.iter().all(|x| x.is_finite())
            && eig.eigenvectors.iter().all(|x| x.is_finite());
        if finite {
            return (eig.eigenvalues, eig.eigenvectors);
        }
    }
    jacobi(s)
}

/// The entries of a symmetric matrix with largest magnitude `scale` that count as zero: below
/// ε² · scale they move no eigenvalue by more than that, far below round-off.
#[inline]
pub(crate) fn negligible_below(scale: f64) -> f64 {
    f64::EPSILON * f64::EPSILON * scale
}

/// The cyclic Jacobi eigenvalue method (Golub & Van Loan, *Matrix Computations*, §8.5) on the
/// symmetric n × n matrix `a` (its storage order does not matter): sweeps of exact plane
/// rotations that zero each off-diagonal entry in turn, which cannot produce NaN from finite
/// input. On return the eigenvalues are on the diagonal of `a` (the rest zero) and `v`
/// (n × n, by columns) holds the eigenvectors as columns, in the order of the diagonal.
///
/// The stopping rule: a sweep ends the iteration when it finds every a_pq below
/// ε √|a_pp a_qq| or below ε² max |aᵢⱼ| (the threshold of Demmel & Veselić, "Jacobi's method is
/// more accurate than QR", 1992); such entries are set to zero rather than rotated away, which
/// would only create round-off of their size elsewhere. Convergence is quadratic; at most 60
/// sweeps run. No allocation: callers on stack storage stay on the stack.
pub(crate) fn jacobi_eigen(a: &mut [f64], n: usize, v: &mut [f64]) {
    debug_assert!(a.len() >= n * n && v.len() >= n * n);
    v[..n * n].iter_mut().for_each(|x| *x = 0.0);
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    let scale = crate::numeric::max_abs(&a[..n * n]);
    if scale == 0.0 || !scale.is_finite() {
        return;
    }
    let floor = negligible_below(scale);
    a[..n * n].iter_mut().for_each(|x| {
        if x.abs() < floor {
            *x = 0.0;
        }
    });
    for _sweep in 0..60 {
        let mut rotated = false;
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[q * n + p];
                let (app, aqq) = (a[p * n + p], a[q * n + q]);
                if apq.abs() <= floor.max(f64::EPSILON * (app * aqq).abs().sqrt()) {
                    a[q * n + p] = 0.0;
                    a[p * n + q] = 0.0;
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
                // Rows and columns p and q outside the 2 × 2 block, kept symmetric; the block
                // becomes diag(a_pp − t a_pq, a_qq + t a_pq) (Numerical Recipes' form, which
                // needs no products of the rotation there).
                for k in 0..n {
                    if k == p || k == q {
                        continue;
                    }
                    let (akp, akq) = (a[p * n + k], a[q * n + k]);
                    let (x, y) = (c * akp - s * akq, s * akp + c * akq);
                    a[p * n + k] = x;
                    a[q * n + k] = y;
                    a[k * n + p] = x;
                    a[k * n + q] = y;
                }
                a[p * n + p] = app - t * apq;
                a[q * n + q] = aqq + t * apq;
                a[q * n + p] = 0.0;
                a[p * n + q] = 0.0;
                rotate_columns(v, n, p, q, c, s);
            }
        }
        if !rotated {
            break;
        }
    }
}

/// The eigen-decomposition K = V diag(d) Vᵀ of a small symmetric n × n matrix `k`
/// (row-major) by [`jacobi_eigen`]: `d` receives the n eigenvalues and `v` the eigenvectors
/// as its columns, row-major (`v[i * n + j]` is component i of eigenvector j). No heap for
/// n ≤ 8.
pub(crate) fn symmetric_eigen_rows(
    k: &[f64],
    n: usize,
    d: &mut SmallVec<[f64; 64]>,
    v: &mut SmallVec<[f64; 64]>,
) {
    let mut a: SmallVec<[f64; 64]> = SmallVec::from_slice(&k[..n * n]);
    v.clear();
    v.resize(n * n, 0.0);
    jacobi_eigen(&mut a, n, v);
    // The kernel leaves V by columns; by rows it is the transpose.
    for i in 0..n {
        for j in i + 1..n {
            v.swap(i * n + j, j * n + i);
        }
    }
    d.clear();
    d.extend((0..n).map(|i| a[i * n + i]));
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

/// [`jacobi_eigen`] on a heap matrix: (eigenvalues, eigenvectors as columns).
fn jacobi(mut a: DMatrix<f64>) -> (DVector<f64>, DMatrix<f64>) {
    let n = a.nrows();
    let mut v = DMatrix::<f64>::zeros(n, n);
    jacobi_eigen(a.as_mut_slice(), n, v.as_mut_slice());
    (DVector::from_fn(n, |i, _| a[(i, i)]), v)
}

/// Sorted (ascending) eigen-decomposition of a symmetric matrix, eigenvectors as columns in
/// the same order (robust as [`RobustEigen`]).
pub(crate) fn sorted_symmetric_eigen(m: &DMatrix<f64>) -> (DVector<f64>, DMatrix<f64>) {
    let n = m.nrows();
    let eig = RobustEigen::new(m.clone());
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let values = DVector::from_iterator(n, order.iter().map(|&k| eig.eigenvalues[k]));
    let mut vectors = DMatrix::zeros(n, n);
    for (col, &k) in order.iter().enumerate() {
        vectors.set_column(col, &eig.eigenvectors.column(k));
    }
    (values, vectors)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The matrix on which nalgebra returned NaN: the wrapper's answer is finite and
    /// reconstructs S; Jacobi alone agrees with it.
    #[test]
    fn wide_range_matrix_decomposes_without_nan() {
        // The non-zero components of the bivector, by their index in lexicographic pair order.
        let nonzero = [
            (5, 1e38),
            (6, 2.892761935129748e148),
            (7, 2.412037944016982e150),
            (16, 1e37),
            (17, -6.369184931809316e150),
            (24, 9.78176666059664e50),
        ];
        let n = 8;
        let mut c = [0.0; 28];
        for (k, x) in nonzero {
            c[k] = x;
        }
        let mut a = DMatrix::<f64>::zeros(n, n);
        let s0 = 2f64.powi(-501);
        let pairs = (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j)));
        for ((i, j), &x) in pairs.zip(c.iter()) {
            a[(i, j)] = x * s0;
            a[(j, i)] = -x * s0;
        }
        let s = a.transpose() * &a;
        for (values, vectors) in [symmetric_eigen(s.clone()), jacobi(s.clone())] {
            assert!(values.iter().all(|x| x.is_finite()));
            let back = &vectors * DMatrix::from_diagonal(&values) * vectors.transpose();
            assert!((back - &s).amax() < 1e-14, "reconstruction");
        }
    }

    /// The sorted form: ascending values, columns that are their eigenvectors, and S rebuilt.
    #[test]
    fn sorted_symmetric_eigen_orders_values_and_vectors_together() {
        let s = DMatrix::from_row_slice(3, 3, &[3.0, 1.0, 0.0, 1.0, 2.0, 0.5, 0.0, 0.5, -1.0]);
        let (values, vectors) = sorted_symmetric_eigen(&s);
        assert!(values[0] <= values[1] && values[1] <= values[2]);
        for k in 0..3 {
            let v = vectors.column(k);
            assert!((&s * v - v * values[k]).amax() < 1e-14, "column {k}");
        }
        let back = &vectors * DMatrix::from_diagonal(&values) * vectors.transpose();
        assert!((back - &s).amax() < 1e-14);
    }

    /// The Jacobi kernel on symmetric matrices of sizes 1 … 9 (random entries, and one with a
    /// repeated eigenvalue): nalgebra's eigenvalues, orthonormal eigenvectors, and S rebuilt.
    #[test]
    fn jacobi_matches_nalgebra_and_reconstructs() {
        let mut checked = 0;
        for n in 1..=9 {
            let random = DMatrix::from_fn(n, n, |i, j| {
                ((i * 7 + j * 3) as f64).sin() + ((j * 7 + i * 3) as f64).sin()
            });
            // Q diag(1, 1, 2, 3, …) Qᵀ with Q from the random matrix's eigenvectors.
            let q = nalgebra::SymmetricEigen::new(random.clone()).eigenvectors;
            let d = DMatrix::from_fn(n, n, |i, j| if i == j { i.max(1) as f64 } else { 0.0 });
            let repeated = &q * d * q.transpose();
            for m in [random, repeated] {
                let (values, vectors) = jacobi(m.clone());
                let mut a = values.clone();
                let mut b = nalgebra::SymmetricEigen::new(m.clone()).eigenvalues;
                a.as_mut_slice().sort_by(f64::total_cmp);
                b.as_mut_slice().sort_by(f64::total_cmp);
                assert!((a - b).amax() < 1e-13, "n = {n}");
                let identity = DMatrix::<f64>::identity(n, n);
                assert!((vectors.transpose() * &vectors - identity).amax() < 1e-14);
                let back = &vectors * DMatrix::from_diagonal(&values) * vectors.transpose();
                assert!((back - &m).amax() < 1e-13, "n = {n}");
                checked += 1;
            }
        }
        assert_eq!(checked, 18);
    }

    /// The row-major form: K v_j = d_j v_j for every column j of V read by rows, against a
    /// matrix with known eigenvalues, sizes 1 … 8.
    #[test]
    fn row_major_form_gives_eigenpairs_by_columns() {
        let mut checked = 0;
        for n in 1..=8 {
            let q = nalgebra::SymmetricEigen::new(DMatrix::from_fn(n, n, |i, j| {
                ((i * 5 + j * 2) as f64).cos() + ((j * 5 + i * 2) as f64).cos()
            }))
            .eigenvectors;
            let want: Vec<f64> = (0..n).map(|i| 0.5 + i as f64).collect();
            let m = &q * DMatrix::from_diagonal(&DVector::from_vec(want.clone())) * q.transpose();
            let k: Vec<f64> = (0..n * n).map(|x| m[(x / n, x % n)]).collect();
            let (mut d, mut v) = (SmallVec::new(), SmallVec::new());
            symmetric_eigen_rows(&k, n, &mut d, &mut v);
            for j in 0..n {
                for i in 0..n {
                    let kv: f64 = (0..n).map(|c| k[i * n + c] * v[c * n + j]).sum();
                    assert!((kv - d[j] * v[i * n + j]).abs() < 1e-13, "n = {n}");
                }
            }
            let mut sorted = d.to_vec();
            sorted.sort_by(f64::total_cmp);
            for (x, y) in sorted.iter().zip(&want) {
                assert!((x - y).abs() < 1e-13, "n = {n}");
            }
            checked += 1;
        }
        assert_eq!(checked, 8);
    }
}
