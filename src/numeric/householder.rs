//! Householder reflections: an orthonormal basis of the complement of two orthonormal
//! vectors, stable even when they are near basis vectors.

use nalgebra::{DMatrix, DVector};

/// Returns an m×(m−2) matrix whose orthonormal columns span the complement of the orthonormal
/// pair (w, u), from two Householder reflections (stable even when w, u are near basis vectors).
pub(crate) fn householder_complement(w: &DVector<f64>, u: &DVector<f64>) -> DMatrix<f64> {
    let m = w.len();
    let mut q = DMatrix::<f64>::identity(m, m);
    // H1 maps w to ±e1.
    let h1 = householder(w.as_slice(), 0);
    // H2 acts on coordinates 1.. and maps (H1 u)[1..] to ±e2.
    let mut hu: Vec<f64> = u.iter().copied().collect();
    apply_householder(&h1, &mut hu);
    let h2 = householder(&hu, 1);
    // Q = H1 H2: apply H2 then H1 to each column of the identity.
    for c in 0..m {
        let mut col: Vec<f64> = q.column(c).iter().copied().collect();
        apply_householder(&h2, &mut col);
        apply_householder(&h1, &mut col);
        q.column_mut(c).copy_from_slice(&col);
    }
    q.columns(2, m - 2).into_owned()
}

/// A Householder reflection I − 2 h hᵀ (|h| = 1, h zero before `start`); identity if h = 0.
struct Householder {
    h: Vec<f64>,
}

fn householder(x: &[f64], start: usize) -> Householder {
    let m = x.len();
    let mut h = vec![0.0; m];
    let tail_norm = x[start..].iter().map(|a| a * a).sum::<f64>().sqrt();
    if tail_norm == 0.0 {
        return Householder { h };
    }
    // h ∝ x − σ|x| e_start with σ = −sign(x_start), avoiding cancellation.
    let sigma = if x[start] >= 0.0 { -1.0 } else { 1.0 };
    h[start..].copy_from_slice(&x[start..]);
    h[start] -= sigma * tail_norm;
    let hn = h.iter().map(|a| a * a).sum::<f64>().sqrt();
    if hn > 0.0 {
        h.iter_mut().for_each(|a| *a /= hn);
    }
    Householder { h }
}

fn apply_householder(hh: &Householder, x: &mut [f64]) {
    let d: f64 = hh.h.iter().zip(x.iter()).map(|(a, b)| a * b).sum();
    if d != 0.0 {
        x.iter_mut()
            .zip(hh.h.iter())
            .for_each(|(xi, hi)| *xi -= 2.0 * d * hi);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The columns are orthonormal and orthogonal to w and u, also when w and u are basis
    /// vectors (where a naive reflection divides by zero).
    #[test]
    fn complement_is_orthonormal_and_orthogonal_to_the_pair() {
        let m = 5;
        let c = std::f64::consts::FRAC_1_SQRT_2;
        let pairs = [
            (DVector::from_element(m, 1.0).normalize(), {
                let mut u = DVector::zeros(m);
                u[0] = c;
                u[1] = -c;
                u
            }),
            (
                DVector::from_fn(m, |i, _| if i == 0 { 1.0 } else { 0.0 }),
                DVector::from_fn(m, |i, _| if i == 1 { 1.0 } else { 0.0 }),
            ),
        ];
        for (w, u) in pairs {
            let q = householder_complement(&w, &u);
            assert_eq!(q.shape(), (m, m - 2));
            let gram = q.transpose() * &q;
            assert!((gram - DMatrix::<f64>::identity(m - 2, m - 2)).amax() < 1e-15);
            assert!((q.transpose() * &w).amax() < 1e-15);
            assert!((q.transpose() * &u).amax() < 1e-15);
        }
    }
}
