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
    let floor = f64::EPSILON * f64::EPSILON * scale;
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

/// The cyclic Jacobi eigenvalue method (Golub & Van Loan, Matrix Computations, §8.5):
/// sweeps of exact plane rotations that zero each off-diagonal entry in turn, until the
/// off-diagonal mass is below ε² of the total (quadratic convergence; ≤ 60 sweeps).
fn jacobi(mut a: DMatrix<f64>) -> (DVector<f64>, DMatrix<f64>) {
    let n = a.nrows();
    let mut v = DMatrix::<f64>::identity(n, n);
    for _sweep in 0..60 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[(i, j)] * a[(i, j)])
            .sum();
        let total: f64 = a.iter().map(|x| x * x).sum();
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
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
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
        let c = [
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            1e38,
            2.892761935129748e148,
            2.412037944016982e150,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            1e37,
            -6.369184931809316e150,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            9.78176666059664e50,
            0.0,
            0.0,
            0.0,
        ];
        let n = 8;
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

    /// Jacobi on a random symmetric matrix matches nalgebra's eigenvalues.
    #[test]
    fn jacobi_matches_nalgebra() {
        let n = 6;
        let m = DMatrix::from_fn(n, n, |i, j| {
            ((i * 7 + j * 3) as f64).sin() + ((j * 7 + i * 3) as f64).sin()
        });
        let (mut a, _) = jacobi(m.clone());
        let mut b = nalgebra::SymmetricEigen::new(m).eigenvalues;
        a.as_mut_slice().sort_by(f64::total_cmp);
        b.as_mut_slice().sort_by(f64::total_cmp);
        assert!((a - b).amax() < 1e-13);
    }
}
